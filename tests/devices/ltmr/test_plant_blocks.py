"""LTMR_PKW over PDO4 and the CiA-405-style SDO_READ / SDO_WRITE, end to end
through the CANopen master and the simulated LTMR (node 40)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.ltmr import pkw
from softplc.runtime.devices.ltmr import registers as ltmr

# whole plants over seconds of virtual time, answers crossing sockets in real time
pytestmark = pytest.mark.slow

# PDO4 carries the PKW objects 0x3000:01..04 (U32 each; manual 001 §2.5). CANopen
# and the image are both little-endian, so 3000:01 in %QD55 is word 1 in %QW110 and
# word 2 in %QW111 (the byte layout of ambiguity A6's default).
PKW_NODE = {
    "name": "motor",
    "id": 40,
    "eds": "ltmr",
    "heartbeat": "100ms",
    "tpdo": [
        {
            "number": 4,
            "configure": False,
            "map": [{"object": "3000:03", "address": "%ID55"}, {"object": "3000:04", "address": "%ID56"}],
        }
    ],
    "rpdo": [
        {
            "number": 4,
            "configure": False,
            "map": [{"object": "3000:01", "address": "%QD55"}, {"object": "3000:02", "address": "%QD56"}],
        }
    ],
}

PKW = """
PROGRAM Pkw
VAR
    go : BOOL;
    write : BOOL;
    register : UINT;
    value : UDINT;
    in1 AT %IW110 : WORD; in2 AT %IW111 : WORD; in3 AT %IW112 : WORD; in4 AT %IW113 : WORD;
    out1 AT %QW110 : WORD; out2 AT %QW111 : WORD; out3 AT %QW112 : WORD; out4 AT %QW113 : WORD;
    pkw : LTMR_PKW;
END_VAR
pkw(Execute := go, Write := write, Register := register, Value := value,
    In1 := in1, In2 := in2, In3 := in3, In4 := in4);
out1 := pkw.Out1; out2 := pkw.Out2; out3 := pkw.Out3; out4 := pkw.Out4;
END_PROGRAM
"""


def _pkw(plant, register: int, *, write: bool = False, value: int = 0):
    plant.set("Pkw.go", False)
    plant.scan()
    plant.set("Pkw.register", register)
    plant.set("Pkw.write", write)
    plant.set("Pkw.value", value)
    plant.set("Pkw.go", True)
    plant.run_until(lambda: plant.get("Pkw.pkw.Done") or plant.get("Pkw.pkw.Error"), 1500, "PKW answer")
    return plant.get("Pkw.pkw.Done"), plant.get("Pkw.pkw.ReadValue"), plant.get("Pkw.pkw.ErrorCode")


def test_pkw_reads_and_writes_registers_over_pdo4(plants):
    plant = plants(PKW, program="Pkw", nodes=[PKW_NODE])
    plant.run_until(lambda: plant.master.status().ok, 500, "node 40 booted")
    sim = plant.sims[40]
    sim.set_register(ltmr.REG_FLC1, 35)
    assert _pkw(plant, ltmr.REG_FLC1)[:2] == (True, 35)  # R_REG_16 652
    # the request on the wire, RPDO4 (0x528): word 1 = 652, word 2 = toggle | 0x25 << 8
    request = pkw.decode_frame(plant.frames_with(0x528)[-1])
    assert (request.w1, request.function) == (652, pkw.R_REG_16)
    answer = pkw.decode_frame(plant.frames_with(0x4A8)[-1])
    assert (answer.w1, answer.function, answer.toggle, answer.w3) == (652, pkw.R_REG_16, request.toggle, 35)
    assert _pkw(plant, ltmr.REG_FLC1, write=True, value=60)[0]  # W_REG_16 652 := 60
    assert sim.register(ltmr.REG_FLC1) == 60
    second = pkw.decode_frame(plant.frames_with(0x528)[-1])
    assert second.function == pkw.W_REG_16 and second.toggle != request.toggle  # a new request flips it


def test_pkw_error_path_returns_the_abort_code(plants):
    plant = plants(PKW, program="Pkw", nodes=[PKW_NODE])
    plant.run_until(lambda: plant.master.status().ok, 500, "node 40 booted")
    done, _value, code = _pkw(plant, ltmr.REG_STATUS_1, write=True, value=1)  # 455 is read-only
    assert not done and plant.get("Pkw.pkw.Error")
    assert code == 0x06010002  # manual 001 §3.3, in words 3-4
    answer = pkw.decode_frame(plant.frames_with(0x4A8)[-1])
    assert answer.function == pkw.ERROR and answer.value32 == 0x06010002
    done, _value, code = _pkw(plant, 800)  # no such register (not mapped)
    assert not done and code != 0


SDO_BLOCKS = """
PROGRAM Sdo
VAR
    goRead : BOOL;
    goWrite : BOOL;
    index : WORD := 16#2007;
    subindex : BYTE := 16#03;
    rd : SDO_READ;
    wr : SDO_WRITE;
END_VAR
wr(EXECUTE := goWrite, NODE := 40, INDEX := index, SUBINDEX := subindex, LENGTH := 2);
rd(EXECUTE := goRead, NODE := 40, INDEX := index, SUBINDEX := subindex);
END_PROGRAM
"""


def test_sdo_read_and_sdo_write_blocks(plants):
    plant = plants(SDO_BLOCKS, program="Sdo", nodes=[{"name": "motor", "id": 40, "eds": "ltmr"}])
    plant.run_until(lambda: plant.master.status().ok, 500, "node 40 booted")
    sim = plant.sims[40]
    data = plant.get("Sdo.wr.DATA")
    data[0], data[1] = 45, 0  # FLC1 := 45 %
    plant.set("Sdo.goWrite", True)
    plant.run_until(lambda: plant.get("Sdo.wr.DONE") or plant.get("Sdo.wr.ERROR"), 100, "SDO_WRITE done")
    assert plant.get("Sdo.wr.DONE") and sim.register(ltmr.REG_FLC1) == 45
    plant.set("Sdo.goRead", True)
    plant.run_until(lambda: plant.get("Sdo.rd.DONE") or plant.get("Sdo.rd.ERROR"), 100, "SDO_READ done")
    assert (plant.get("Sdo.rd.VALUE"), plant.get("Sdo.rd.LENGTH")) == (45, 2)
    # an abort: write the read-only status register 455 (2004:06)
    plant.set("Sdo.goWrite", False)
    plant.set("Sdo.index", 0x2004)
    plant.set("Sdo.subindex", 0x06)
    plant.scan()
    plant.set("Sdo.goWrite", True)
    plant.run_until(lambda: plant.get("Sdo.wr.ERROR"), 100, "SDO_WRITE error")
    assert plant.get("Sdo.wr.ERRORINFO") == 0x06010002 and not plant.get("Sdo.wr.DONE")
