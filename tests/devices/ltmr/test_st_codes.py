"""fblocks/vendor/ltmr_codes.st: generated from ltmr.py/pkw.py, up to date, and
usable from a running ST program (the vendor library is compiled into every
program)."""

from __future__ import annotations

from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr import st_codes
from softplc.runtime.program import compile_files

PROGRAM = """
PROGRAM main
VAR
    status1 : WORD := 16#6083;          (* digest 001 §6.3: ready, on, running, 100 % FLC, in remote *)
    ready, running, tripped : BOOL;
    ratio : UINT;
    tripText, alarmText, rangeText, unknownText : STRING[80];
    control : WORD;
    statusReg : UINT;
    pkwRead : BYTE;
END_VAR
ready := (status1 AND LTMR_STATUS1_READY) <> 0;
running := (status1 AND LTMR_STATUS1_RUNNING) <> 0;
tripped := (status1 AND LTMR_STATUS1_TRIPPED) <> 0;
ratio := WORD_TO_UINT(SHR(status1, LTMR_STATUS1_CURRENT_SHIFT) AND LTMR_STATUS1_CURRENT_MASK);
tripText := LTMR_TRIP_TEXT(4);
alarmText := LTMR_ALARM_TEXT(LTMR_ALARM_NETWORK_COMM);
rangeText := LTMR_TRIP_TEXT(103);
unknownText := LTMR_TRIP_TEXT(1);
control := LTMR_CONTROL1_RUN_FORWARD OR LTMR_CONTROL1_TRIP_RESET;
statusReg := LTMR_REG_STATUS_1;
pkwRead := LTMR_PKW_R_REG_16;
END_PROGRAM
"""


def test_shipped_file_is_up_to_date():
    # regenerate with: python -m softplc.runtime.devices
    assert st_codes.ST_FILE.read_text(encoding="utf-8") == st_codes.render()


def test_the_constants_the_function_blocks_use():
    text = st_codes.render()
    for line in (
        "LTMR_STATUS1_READY : WORD := 16#0001;",
        "LTMR_STATUS1_RUNNING : WORD := 16#0080;",
        "LTMR_STATUS2_NETWORK_COMM_LOSS : WORD := 16#0100;",
        "LTMR_CONTROL1_RUN_FORWARD : WORD := 16#0001;",
        "LTMR_CONTROL1_TRIP_RESET : WORD := 16#0008;",
        "LTMR_CONTROL2_CLEAR_ALL : WORD := 16#0001;",
        "LTMR_TRIPREGISTER1_THERMAL_OVERLOAD : WORD := 16#0008;",
        "LTMR_STATUS1_CURRENT_SHIFT : UINT := 8;",
        "LTMR_STATUS1_CURRENT_MASK : WORD := 16#003F;",
        "LTMR_PKW_R_REG_16 : BYTE := 16#25;",
        "LTMR_PKW_ERROR : BYTE := 16#4E;",
        "LTMR_REG_STATUS_1 : UINT := 455;",
        "LTMR_REG_CONTROL_1 : UINT := 704;",
        "LTMR_TRIP_THERMAL_OVERLOAD : UINT := 4;",
        "LTMR_TRIP_TEST : UINT := 10;",
        "LTMR_TRIP_NETWORK_COMM : UINT := 109;",
        "100..104: LTMR_TRIP_TEXT := 'Network port internal detected error';",
    ):
        assert line in text, line
    assert text.count("LTMR_REG_") >= len([n for n in vars(ltmr) if n.startswith("REG_")])
    assert "GENERATED" in text and "python -m softplc.runtime.devices\n" in text


def test_a_program_reads_the_constants_and_texts():
    runner = compile_files([], texts={"ltmr_use.st": PROGRAM}).runner("main")
    runner.run(1)
    assert runner.get("ready") is True and runner.get("running") is True and runner.get("tripped") is False
    assert runner.get("ratio") == 32  # 100 % FLC
    assert runner.get("tripText") == "Thermal overload"
    assert runner.get("alarmText") == "Network port comm loss"
    assert runner.get("rangeText") == "Network port internal detected error"
    assert runner.get("unknownText") == "unknown trip code"
    assert runner.get("control") == 0x0009
    assert runner.get("statusReg") == 455 and runner.get("pkwRead") == 0x25
