"""The LTMR's emergencies in the log, in the manuals' words (runtime/devices/
ltmr/emcy.py): manuals 000/001 give only the error register 1001h ("Detected
error (1) or no detected error (0)") and 1003h ("code of the detected error");
the EMCY code and the manufacturer bytes are the simulator's (A22): CiA 301
1000h, the trip code (register 451, DT_FaultCode) in bytes 3-4."""

from __future__ import annotations

import logging

import pytest

from softplc.runtime.devices.ltmr import DEVICE
from softplc.testing import PLC

EMCY_LOG = "softplc.runtime.io.canopen.emcy_log"


def _line(data: str) -> str:
    frame = bytes.fromhex(data)
    assert DEVICE.emcy_text is not None
    return DEVICE.emcy_text(int.from_bytes(frame[:2], "little"), frame[2], frame[3:])


@pytest.mark.parametrize(
    "frame, line",
    [
        (
            "00 10 01 04 00 00 00 00",
            "EMCY 1000h generic error, error register 01h detected error; trip code 4 Thermal overload (register 451)",
        ),
        (
            "00 10 01 6D 00 00 00 00",
            "EMCY 1000h generic error, error register 01h detected error;"
            " trip code 109 Network port comm detected error (register 451)",
        ),
        ("00 00 00 00 00 00 00 00", "EMCY 0000h error reset or no error: no detected error"),
        (
            "00 10 01 07 02 00 00 00",
            "EMCY 1000h generic error, error register 01h detected error;"
            " trip code 519 not in DT_FaultCode (register 451)",
        ),
        ("10 23 00 00 00 00 00 00", "EMCY 2310h not a code the LTMR sends, error register 00h no detected error"),
    ],
)
def test_an_emcy_in_the_words_of_the_manual(frame, line):
    assert _line(frame) == line


@pytest.mark.slow  # the default plant over a minute of virtual time
def test_the_default_plants_thermal_trip_is_logged_by_its_name(caplog):
    # issue 33: the motor of io_config/default.toml trips thermally at about 57 s; the log
    # said "emergency 0x1000, error register 0x01, data 04 00 00 00 00" and no more
    plc = PLC.from_config()
    try:
        with caplog.at_level(logging.WARNING, logger=EMCY_LOG):
            plc.run_until(lambda: plc["Motor.state"] == "Tripped", timeout="90s", what="the thermal trip")
            plc.run_for("100ms")
    finally:
        plc.stop()
    assert plc["Motor.tripCode"] == 4
    lines = [r.getMessage() for r in caplog.records if r.name == EMCY_LOG]
    assert lines == [
        "canopen: node motor (40) emergency 0x1000, error register 0x01, data 04 00 00 00 00:"
        " EMCY 1000h generic error, error register 01h detected error; trip code 4 Thermal overload (register 451)"
    ]
