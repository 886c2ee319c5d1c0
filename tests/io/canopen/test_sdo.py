"""READ_VAR / WRITE_VAR over SDO: the LTMR manual's two ST examples run
verbatim against the simulated LTMR (node 40), byte for byte on the wire;
SDO aborts and timeouts surface as Schneider report codes."""

from __future__ import annotations

import struct
from pathlib import Path

from softplc.runtime.devices.ltmr import registers as ltmr

ROOT = Path(__file__).resolve().parents[3]
EXAMPLES = [ROOT / "st_programs" / "ltmr_write_sdo.st", ROOT / "st_programs" / "ltmr_read_sdo.st"]
NO_PDOS = [{"name": "motor", "id": 40, "eds": "ltmr", "heartbeat": "100ms"}]


def _word(plant, index: int) -> int:
    """%MW<index> as the Schneider model stores it (word index, little-endian)."""
    return struct.unpack_from("<H", plant.engine.image.areas["M"], 2 * index)[0]


def _examples(plants):
    plant = plants(EXAMPLES, program=["ltmr_write_sdo", "ltmr_read_sdo"], profile="schneider", nodes=NO_PDOS)
    plant.run_until(lambda: plant.master.status().ok, 500, "node 40 booted")
    return plant


def test_the_manuals_write_example_writes_50_to_2007_03_of_node_40(plants):
    plant = _examples(plants)
    sim = plant.sims[40]
    sim.set_register(ltmr.REG_FLC1, 35)  # as set on the LTMR's HMI
    plant.frames.clear()
    plant.engine.image.mbits[100] = 1  # %M100: the example's write command
    plant.run_until(lambda: not _word(plant, 3250) & 1 and _word(plant, 3250) >> 8 == 1, 100, "exchange done")
    assert sim.register(ltmr.REG_FLC1) == 50  # register 652, FLC1 = 50 % FLCmax
    assert _word(plant, 3251) == 0x0000  # operation and communication report: positive, done
    assert plant.engine.image.mbits[100] == 0  # RESET %M100
    # CiA 301 expedited download of 2 bytes (digest 001 §3.4), and its confirmation
    assert plant.frames_with(0x628) == [bytes.fromhex("2B 07 20 03 32 00 00 00")]
    assert plant.frames_with(0x5A8) == [bytes.fromhex("60 07 20 03 00 00 00 00")]


def test_the_manuals_read_example_reads_2004_03_of_node_40(plants):
    plant = _examples(plants)
    sim = plant.sims[40]
    sim.set_register(ltmr.REG_TRIP_REGISTER_1, 0x0008)  # thermal overload trip bit
    plant.frames.clear()
    plant.engine.image.mbits[101] = 1
    plant.run_until(lambda: not _word(plant, 3260) & 1 and _word(plant, 3260) >> 8 == 1, 100, "exchange done")
    assert _word(plant, 3222) == 0x0008  # the value read
    assert _word(plant, 3261) == 0x0000  # reports: positive
    assert _word(plant, 3263) == 2  # length word: 2 bytes received
    assert plant.frames_with(0x628) == [bytes.fromhex("40 04 20 03 00 00 00 00")]
    assert plant.frames_with(0x5A8) == [bytes.fromhex("4B 04 20 03 08 00 00 00")]


ABORTS = """
PROGRAM Aborts
VAR
    go : BOOL;
    data : ARRAY[0..1] OF INT;
    mgmtRo : ARRAY[0..5] OF INT;
    mgmtNone : ARRAY[0..5] OF INT;
    mgmtRange : ARRAY[0..5] OF INT;
    mgmtAbsent : ARRAY[0..5] OF INT;
    mgmtShort : ARRAY[0..3] OF INT;
END_VAR
IF go THEN
    go := FALSE;
    data[0] := 1;
    WRITE_VAR(ADR#0.1.SYS, 'SDO', 16#00062004, 40, data, mgmtRo);     (* 455 is read-only *)
    READ_VAR(ADR#0.1.SYS, 'SDO', 16#00012009, 40, data, mgmtNone);    (* no object 2009 *)
    mgmtShort[3] := 8;                                                  (* 8 bytes from a 2-word table *)
    WRITE_VAR(ADR#0.1.SYS, 'SDO', 16#00032007, 40, data, mgmtShort);
    READ_VAR(ADR#0.1.SYS, 'SDO', 16#00062004, 41, data, mgmtAbsent);  (* node 41 is not on the bus *)
END_IF;
END_PROGRAM
"""


def test_sdo_aborts_and_timeouts_surface_as_report_codes_with_the_abort_code(plants):
    plant = plants(ABORTS, program="Aborts", nodes=NO_PDOS)
    plant.run_until(lambda: plant.master.status().ok, 500, "node 40 booted")
    plant.set("Aborts.go", True)

    def table(name):
        return [w & 0xFFFF for w in plant.get(f"Aborts.{name}")]

    plant.run_until(lambda: not plant.get("Aborts.go"), 100, "the cycle that calls them")
    assert all(table(t)[0] == 0x0101 for t in ("mgmtRo", "mgmtNone", "mgmtAbsent"))  # exchange 1, active
    plant.run_until(
        lambda: all(not table(t)[0] & 1 for t in ("mgmtRo", "mgmtNone", "mgmtAbsent")), 2000, "all exchanges over"
    )
    ro, none, absent, short = table("mgmtRo"), table("mgmtNone"), table("mgmtAbsent"), table("mgmtShort")
    # device refused: communication report 16#00, operation report 16#01, abort code in words 4-5
    assert ro[1] == 0x0100 and (ro[5] << 16 | ro[4]) == 0x06010002  # write to a read-only object
    assert none[1] == 0x0100 and (none[5] << 16 | none[4]) == 0x06020000  # object does not exist
    assert short[1] == 0x0005  # bad management parameters
    assert absent[1] == 0x0001 and (absent[5] << 16 | absent[4]) == 0x05040000  # timeout
    assert plant.sims[40].register(ltmr.REG_STATUS_1) != 1  # nothing was written


def test_in_virtual_time_sdo_runs_in_the_engine_thread_without_waiting(plants):
    """No SDO worker thread; every exchange, the one to a node that is not
    on the bus included, is over at the start of the next cycle: the engine
    ran the transfers itself, pumping the bus for the answers."""
    import threading

    before = set(threading.enumerate())
    plant = plants(ABORTS, program="Aborts", nodes=NO_PDOS)
    plant.run_until(lambda: plant.master.status().ok, 500, "node 40 booted")
    assert not [t for t in set(threading.enumerate()) - before if t.name == "canopen sdo"]
    plant.set("Aborts.go", True)
    plant.run_until(lambda: not plant.get("Aborts.go"), 100, "the cycle that calls them")
    called_ms = plant.now_ms
    plant.run_until(
        lambda: all(not plant.get(f"Aborts.{t}")[0] & 1 for t in ("mgmtRo", "mgmtNone", "mgmtAbsent")),
        100,
        "all exchanges over",
    )
    assert plant.now_ms - called_ms <= 10  # one 10 ms cycle
    absent = [w & 0xFFFF for w in plant.get("Aborts.mgmtAbsent")]
    assert absent[1] == 0x0001 and (absent[5] << 16 | absent[4]) == 0x05040000  # timeout
