"""FC280_PARAMETER and FC280_STORE (fblocks/vendor/fc280_parameter.st) and
CANOPEN_ABORT_TEXT (fblocks/comm/sdo.st), driven cycle by cycle in virtual
time through a small ST program, with digest 003's SDO vectors.

SDO traffic goes through the CANopen master's own READ_VAR / WRITE_VAR
service (SchneiderSdoService), bound under the native function's service
name as the master binds it; the test holds each transfer, checks the CAN
frame CiA 301 makes of it (expedited: CS 2Fh/2Bh/23h by size, 40h for an
upload, digest 003 §1.10) and answers it."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.fc280 import parameters as params
from softplc.runtime.io.canopen.cia301 import ABORT_CODES
from softplc.runtime.io.canopen.sdo import SERVICE as SDO_SERVICE
from softplc.runtime.io.canopen.sdo import SchneiderSdoService, SdoJob

from .st_bench import Bench


class Master:
    """The CANopen master's READ_VAR / WRITE_VAR service, its transfers held
    for the test to answer (the worker thread's part)."""

    def __init__(self, bench: Bench) -> None:
        self.jobs: list[SdoJob] = []
        self.service = SchneiderSdoService(self.jobs.append, default_timeout_s=1.0)
        bench.runner.ctx.services[SDO_SERVICE] = self.service

    def frame(self) -> tuple[int, str]:
        """The request the last transfer puts on the bus (CiA 301 expedited)."""
        job = self.jobs[-1]
        if job.data is None:
            cs, payload = 0x40, bytes(4)
        else:
            cs, payload = 0x23 | (4 - len(job.data)) << 2, job.data.ljust(4, b"\0")
        data = bytes([cs]) + job.index.to_bytes(2, "little") + bytes([job.subindex]) + payload
        return 0x600 + job.node_id, data.hex(" ").upper()

    def answer(self, received: bytes = b"", abort: int = 0, timed_out: bool = False) -> None:
        """The node answered (before the next cycle starts)."""
        job = self.jobs[-1]
        job.received, job.abort_code, job.timed_out, job.done = received, abort, timed_out, True
        self.service.collect()


PARAM_DECLS = """
    p : FC280_PARAMETER;
    execute : BOOL; node : USINT := 5; parameter : STRING[16]; group : USINT; number : USINT;
    subindex : BYTE; write : BOOL; value : LREAL;
"""
PARAM_BODY = """
p(EXECUTE := execute, NODE := node, PARAMETER := parameter, GROUP := group, NUMBER := number,
  SUBINDEX := subindex, WRITE := write, VALUE := value);
"""


def param() -> tuple[Bench, Master]:
    b = Bench(PARAM_DECLS, PARAM_BODY)
    return b, Master(b)


def outputs(b: Bench, fb: str = "p") -> tuple:
    return b[f"{fb}.BUSY"], b[f"{fb}.DONE"], b[f"{fb}.ERROR"]


def request(b: Bench, **inputs) -> Bench:
    defaults = dict(parameter="", group=0, number=0, subindex=0, write=False, value=0.0)
    return b.step(execute=False).step(execute=True, **{**defaults, **inputs})


def test_d7_write_8_03_one_second():
    b, master = param()
    request(b, parameter="8-03", write=True, value=1.0)
    assert master.frame() == (0x605, "2B 23 23 00 0A 00 00 00")  # D7
    assert outputs(b) == (True, False, False) and b["p.INDEX"] == 0x2323
    master.answer()  # D8: 585 60 23 23 00 ...
    b.step()
    assert outputs(b) == (False, True, False)
    assert b["p.VALUE_READ"] == 1.0 and b["p.RAW"] == 10 and b["p.ERROR_TEXT"] == ""


@pytest.mark.parametrize(
    "number, value, frame",
    [
        ("8-04", 5, "2F 24 23 00 05 00 00 00"),  # D9: [5] Stopp und Alarm
        ("8-10", 0, "2F 2A 23 00 00 00 00 00"),  # D10: [0] FC profile
        ("8-01", 2, "2F 21 23 00 02 00 00 00"),  # D11: [2] Nur Steuerwort
        ("8-54", 1, "2F 56 23 00 01 00 00 00"),  # D12: [1] Bus
        ("16-80", 0x047C, "2B 90 26 00 7C 04 00 00"),  # D18: CTW 047C
        ("16-82", 0x2000, "2B 92 26 00 00 20 00 00"),  # D19: REF 50 %
        ("8-90", 100, "2B 7A 23 00 70 17 00 00"),  # 100 RPM x 60 = 6000 (index 67, A34)
        ("3-41", 3.0, "23 55 21 00 2C 01 00 00"),  # 3 s at index -2: 300, UInt32
        ("3-02", -12.5, "23 2E 21 00 2C CF FF FF"),  # Int32, index -3: -12500
    ],
)
def test_write_frames_of_the_digest(number, value, frame):
    b, master = param()
    request(b, parameter=number, write=True, value=value)
    assert master.frame() == (0x605, frame)
    master.answer()
    b.step()
    assert b["p.DONE"] and b["p.VALUE_READ"] == value


def test_a_negative_value_of_an_array_element():
    b, master = param()
    request(b, parameter="3-10", subindex=1, write=True, value=-12.5)  # Int16, index -2: -1250
    assert master.frame() == (0x605, "2B 36 21 01 1E FB 00 00")
    master.answer()
    assert b.step()["p.RAW"] == -1250


def test_group_and_number_when_parameter_is_empty_and_the_string_wins():
    b, master = param()
    request(b, group=8, number=3, write=True, value=1.0)
    assert master.frame() == (0x605, "2B 23 23 00 0A 00 00 00")
    master.answer()
    request(b.step(), parameter="8-04", group=8, number=3)
    assert master.frame() == (0x605, "40 24 23 00 00 00 00 00")  # '8-04' wins over 8/3


@pytest.mark.parametrize(
    "number, received, value, raw",
    [
        ("8-03", "0A 00", 1.0, 10),  # index -1
        ("0-01", "00", 0, 0),  # D6's object
        ("8-90", "70 17", 100.0, 6000),  # index 67: 1/60
        ("3-10", "1E FB", -12.5, -1250),  # Int16
        ("16-03", "07 0F", 0x0F07, 0x0F07),  # D21: status word 0F07
        ("16-90", "00 00 00 80", 2147483648.0, -(2**31)),  # UInt32 above 7FFFFFFFh: RAW wraps
        ("99-99", "01 02 03", 0x030201, 0x030201),  # not in the table: bytes as they came
    ],
)
def test_read_direction(number, received, value, raw):
    b, master = param()
    request(b, parameter=number)
    node, frame = master.frame()
    assert frame.startswith("40 ") and frame.endswith(" 00 00 00 00")  # D6, D20: read request
    master.answer(bytes.fromhex(received))
    b.step()
    assert outputs(b) == (False, True, False)
    assert b["p.VALUE_READ"] == value and b["p.RAW"] == raw


def test_d6_read_0_01():
    b, master = param()
    request(b, parameter="0-01")
    assert master.frame() == (0x605, "40 01 20 00 00 00 00 00")


@pytest.mark.parametrize(
    "number, index",
    [("8-03", 0x2323), ("16-80", 0x2690), ("10-01", 0x23E9), ("0-01", 0x2001), ("3-41", 0x2155), ("99-99", 0x470F)],
)
def test_index_rule(number, index):
    b = Bench("i : UINT;", f"i := FC280_PARAMETER_INDEX('{number}', 0, 0);").step()
    assert b["i"] == index == params.index_of(number)


@pytest.mark.parametrize("text", ["8", "8-", "-3", "100-1", "8-003", "a-03", " 8-03", "8-03 ", "8--3", "8-3-"])
def test_index_of_something_else_is_zero(text):
    b = Bench("i : UINT;", f"i := FC280_PARAMETER_INDEX('{text}', 8, 3);").step()
    assert b["i"] == 0
    b = Bench("i : UINT;", "i := FC280_PARAMETER_INDEX('', 100, 3);").step()
    assert b["i"] == 0


def test_a_bad_parameter_sends_nothing():
    b, master = param()
    request(b, parameter="8/03")
    assert outputs(b) == (False, False, True) and master.jobs == []
    assert b["p.ERRORINFO"] == 0x08000000 and "g-nn" in b["p.ERROR_TEXT"]


@pytest.mark.parametrize("value", [6553.6, -0.1, float("nan"), float("inf")])
def test_a_value_outside_the_type_is_not_sent(value):
    b, master = param()
    request(b, parameter="8-03", write=True, value=value)  # UInt16, index -1: 0..6553.5 s (A27)
    assert outputs(b) == (False, False, True) and master.jobs == []
    assert b["p.ERRORINFO"] == 0x06090030
    assert b["p.ERROR_TEXT"] == "Value range of parameter exceeded (only for write access)"


def test_the_largest_value_is_sent():
    b, master = param()
    request(b, parameter="8-03", write=True, value=6553.5)
    assert master.frame() == (0x605, "2B 23 23 00 FF FF 00 00")


def test_a_parameter_of_unknown_size_is_not_written():
    b, master = param()
    request(b, parameter="99-99", write=True, value=1)
    assert outputs(b) == (False, False, True) and master.jobs == []
    assert b["p.ERRORINFO"] == 0x06070010


def test_the_drive_refuses_abort_code_and_text():
    b, master = param()
    request(b, parameter="8-04", write=True, value=9)
    master.answer(abort=0x06090030)
    b.step()
    assert outputs(b) == (False, False, True) and b["p.ERRORINFO"] == 0x06090030
    assert b["p.ERROR_TEXT"] == "Value range of parameter exceeded (only for write access)"


def test_no_answer_is_the_sdo_timeout():
    b, master = param()
    request(b, parameter="8-03")
    master.answer(timed_out=True)
    b.step()
    assert b["p.ERRORINFO"] == 0x05040000 and b["p.ERROR_TEXT"] == "SDO protocol timed out"


def test_plcopen_outputs():
    b, master = param()
    request(b, parameter="8-03")
    b.step()
    assert outputs(b) == (True, False, False)
    b.step(execute=False, parameter="8-04")  # an edge while busy is ignored
    b.step(execute=True)
    master.answer(bytes.fromhex("0A 00"))
    b.step(3)
    assert outputs(b) == (False, True, False) and len(master.jobs) == 1  # DONE stays with EXECUTE
    b.step(execute=False)
    assert outputs(b) == (False, False, False)
    request(b, parameter="8-03")
    b.step(execute=False)
    master.answer(bytes.fromhex("0A 00"))
    assert outputs(b.step()) == (False, True, False)  # EXECUTE already fell: one call
    assert outputs(b.step()) == (False, False, False)


def test_without_a_canopen_master_the_read_ends_in_error():
    b = Bench(PARAM_DECLS, PARAM_BODY)  # READ_VAR's fallback: no network
    request(b, parameter="8-03")
    assert outputs(b) == (False, False, True) and b["p.ERRORINFO"] == 0x08000000
    assert b["p.ERROR_TEXT"] == "General error"


STORE_DECLS = "s : FC280_STORE; save : BOOL; restore : BOOL; sub : BYTE := 1;"
STORE_BODY = "s(NODE := 5, SAVE := save, RESTORE := restore, SUBINDEX := sub);"


def test_d13_save_and_d14_restore():
    b = Bench(STORE_DECLS, STORE_BODY)
    master = Master(b)
    b.step(save=True)
    assert master.frame() == (0x605, "23 10 10 01 73 61 76 65")  # D13: 'save'
    assert outputs(b, "s") == (True, False, False)
    master.answer()
    b.step(2)
    assert outputs(b, "s") == (False, True, False)
    b.step(save=False)
    assert outputs(b, "s") == (False, False, False)
    b.step(restore=True)
    assert master.frame() == (0x605, "23 11 10 01 6C 6F 61 64")  # D14: 'load'
    master.answer(abort=0x08000022)
    b.step()
    assert outputs(b, "s") == (False, False, True) and b["s.ERRORINFO"] == 0x08000022
    b.step(restore=False, save=True, sub=4)
    assert master.frame() == (0x605, "23 10 10 04 73 61 76 65")  # sub 4: the drive parameters


def test_save_and_restore_at_once_send_nothing():
    b = Bench(STORE_DECLS, STORE_BODY)
    master = Master(b)
    b.step(save=True, restore=True)
    assert outputs(b, "s") == (False, False, True) and master.jobs == []


# ---------------------------------------------------------------- CANOPEN_ABORT_TEXT (sdo.st)

TABELLE_8_8 = [
    0x05030000,
    0x05040000,
    0x05040001,
    0x05040002,
    0x05040003,
    0x05040004,
    0x05040005,
    0x06010000,
    0x06010001,
    0x06010002,
    0x06020000,
    0x06040041,
    0x06040042,
    0x06040043,
    0x06040047,
    0x06060000,
    0x06070010,
    0x06070012,
    0x06070013,
    0x06090011,
    0x06090030,
    0x06090031,
    0x06090032,
    0x06090036,
    0x08000000,
    0x08000020,
    0x08000021,
    0x08000022,
    0x08000023,
]


def test_every_abort_code_has_a_text():
    codes = sorted(set(TABELLE_8_8) | set(ABORT_CODES)) + [0, 0x12345678]
    decls = "".join(f"t{i} : STRING[80];\n" for i in range(len(codes)))
    body = "".join(f"t{i} := CANOPEN_ABORT_TEXT(16#{c:08X});\n" for i, c in enumerate(codes))
    b = Bench(decls, body).step()
    texts = {c: b[f"t{i}"] for i, c in enumerate(codes)}
    assert texts.pop(0) == "" and texts.pop(0x12345678) == "Unknown SDO abort code"
    assert all(t and t != "Unknown SDO abort code" for t in texts.values()), texts
    assert texts[0x06020000] == "Object does not exist in the object dictionary"
