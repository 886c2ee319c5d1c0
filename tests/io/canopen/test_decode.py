"""`softplc log` (io/can/readlog.py, io/canopen/decode.py,
io/modbus/readlog.py): the default plant's wire, recorded with
--bus-log, printed in the configuration's words: its nodes by name, their
objects by the names of their EDS (the LTMR's register numbers, the
FC 280's parameter numbers), the PDOs' mapped objects, the DA1 line's
requests and answers (Modbus Application Protocol V1.1b3, 6)."""

from __future__ import annotations

import re

import pytest

from softplc.runtime.config import default_config_path, load_config
from softplc.testing import PLC

from ...test_cli import softplc


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    path = tmp_path_factory.mktemp("wire") / "plant.asc"
    plc = PLC.from_config(bus_log=path)
    try:
        plc.run_for("1s")
    finally:
        plc.stop()
    return path


@pytest.fixture(scope="module")
def can_lines(recorded) -> list[str]:
    done = softplc("log", recorded)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


def test_every_frame_is_a_line_with_its_engine_time_bus_and_direction(recorded, can_lines):
    import can

    assert len(can_lines) == len(list(can.LogReader(recorded)))
    assert all(re.match(r" *\d+\.\d{6} can0 [TR]x [0-9A-F]{3} \[\d\]", line) for line in can_lines)


def test_the_boot_in_the_configuration_s_words(can_lines):
    motor = next(n for n in load_config(default_config_path()).canopen.nodes if n.name == "motor")
    text = "\n".join(can_lines)
    assert "Tx 000 [2] 01 28" in text and "NMT start: motor (40)" in text
    assert "NMT start: pump (20)" in text
    assert "motor (40) boot-up" in text and "pump (20) boot-up" in text
    # the heartbeat the file gives the LTMR, written to its 1017h (CiA 301), named by its EDS
    assert f"SDO request to motor (40): write 1017:00 Producer heartbeat time = {motor.heartbeat_ms}" in text
    assert "pump (20) node guarding request" in text  # guard_time: the FC 280 has no heartbeat consumer
    assert re.search(r"pump \(20\) guarding answer: operational", text)


def test_pdos_name_their_mapped_objects(can_lines):
    text = "\n".join(can_lines)
    # the FC 280's TPDO1 of the file: 16-03 status word, 16-05 main actual value (manual 003)
    assert re.search(r"pump \(20\) TPDO1: 2643:00 Status word \(16-03\) = \d+", text)
    assert "2645:00 Main actual value (16-05) = " in text
    # the LTMR's RPDO1: 704 control register 1 (manual 001)
    assert re.search(r"motor \(40\) RPDO1: 2008:05 Control register 1 \[704\] = \d", text)


def test_device_words_for_their_objects(can_lines):
    text = "\n".join(can_lines)
    # the program runs the pump: 16-80 = 047C, "start" in the FC profile (manual 003 Tabelle 4.7)
    assert "2690:00 Fieldbus CTW 1 (16-80) = 1148 (0x47C): start; preset 1" in text
    assert re.search(r"2643:00 Status word \(16-03\) = \d+ \(0x[0-9A-F]+\): control ready, drive ready", text)
    assert "2004:02 Trip code [451] = 0: No detected error" in text  # the LTMR's DT_FaultCode 0


def test_the_modbus_log_in_words(recorded):
    done = softplc("log", recorded.with_name("plant.modbus.log"))
    assert done.returncode == 0, done.stderr
    lines = done.stdout.splitlines()
    assert lines[0].endswith("unit 1: read holding registers 5..9")  # drive_monitor: IDs 6..10
    assert re.search(r"RX .*unit 1: holding registers 5\.\.9 = \d+, \d+, \d+, \d+, \d+$", lines[1])


def test_a_file_no_bus_reads_exits_2(tmp_path):
    notes = tmp_path / "notes.txt"
    notes.write_text("not a log\n")
    done = softplc("log", notes)
    assert done.returncode == 2
    assert "no bus reads such a log" in done.stderr and "Traceback" not in done.stderr
