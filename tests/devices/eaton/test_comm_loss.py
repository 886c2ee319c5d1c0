"""A drive that stops answering: the master reports it per channel and in
DA1_DRIVE, never stops the engine; the drive's own watchdog trips it (fault
50, manual 002 L906) after its timeout; when the line is back the master
recovers by itself and the program resets the fault."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import faults as eaton_faults
from softplc.runtime.io.modbus.link import ModbusError

from ...io.modbus.plant import DRIVE_PROGRAM, SILENT_TIMEOUT, WIRES, plant_config
from .test_drive_sequence import MONITOR

# whole plants over seconds of virtual time; on a port, answers cross sockets in real time
pytestmark = pytest.mark.slow

SIGNAL_LOST = "No valid Modbus telegram received within the set time"


def silent_line(plant, transport):
    """Cut the cable (RTU) or make the server deaf (TCP); returns the undo."""
    if transport == "rtu":
        plant.line.cable.cut()
        return plant.line.cable.mend
    plant.line.silent = True
    return lambda: setattr(plant.line, "silent", False)


@pytest.mark.parametrize("wire", WIRES)
@pytest.mark.parametrize("transport", ["rtu", "tcp"])
def test_line_lost_drive_trips_master_recovers(plants, tmp_path, transport, wire):
    # P5-05 = 20: 2.0 s, P5-06 = 0: trip (the DA1's factory setting, L387-388)
    plant = plants(
        plant_config(
            tmp_path,
            [DRIVE_PROGRAM],
            transport=transport,
            program={"instance": "Drive", "program": "EatonDrive"},
            sims=[{"type": "da1", "unit": 1, "registers": {"505": 20, "506": 0}}],
            channels=[MONITOR],
            interval="50ms",
            timeout=SILENT_TIMEOUT,
            wire=wire,
        )
    )
    drive = plant.drive(1)
    plant.run_until(lambda: plant["Drive.state"] == "HoldForward", 6000, step_ms=50)
    mend = silent_line(plant, transport)
    lost_at = plant.now_ms
    plant.run_until(lambda: plant.channel(0, "Error"), 300, step_ms=50)
    # RTU: every request times out. TCP: the first one does, then the master
    # closes the socket (a late answer must not be taken for the next one) and
    # reconnects after its back-off; meanwhile requests fail at once.
    expected = (
        {ModbusError.RESPONSE_TIMEOUT}
        if transport == "rtu"
        else {ModbusError.RESPONSE_TIMEOUT, ModbusError.REQUEST_FAILED_TO_SEND}
    )
    assert plant.channel(0, "LastError") in expected
    assert plant["Drive.drive.ERROR"] and plant["Drive.drive.ERRORID"] in expected
    assert not plant["Drive.drive.CONNECTED"] and not plant.master.status().ok
    # the drive runs on for its 2.0 s, then trips with fault 50
    plant.run_until(lambda: drive.fault != 0, 2500, step_ms=50)
    assert 1950 <= plant.now_ms - lost_at <= 2100
    assert drive.fault == eaton_faults.COMM_LOSS_FAULT and not drive.running
    assert plant.engine.faults == []  # the engine never stopped
    errors_before = plant.channel(0, "Errors")
    assert errors_before >= 10
    mend()
    plant.run_until(lambda: plant.channel(0, "Ok") and plant["Drive.drive.CONNECTED"], 2000, step_ms=50)
    assert plant.channel(0, "ConnectionOk")
    # the program sees fault 50 and resets it, then the sequence starts again
    plant.run_until(lambda: plant["Drive.drive.FAULT_CODE"] == eaton_faults.COMM_LOSS_FAULT, 500, step_ms=50)
    assert plant["Drive.drive.FAULT_TEXT"] == SIGNAL_LOST
    plant.run_until(lambda: plant["Drive.state"] == "RunForward", 3000, step_ms=50)
    assert drive.fault == 0 and plant["Drive.faults"] == 1
    plant.run_until(lambda: drive.running, 500, step_ms=50)
    assert plant.master.status().ok


def test_no_answer_before_the_timeout_is_no_trip(plants, tmp_path):
    """P5-05 = 5 (0.5 s): a line silent for 0.4 s leaves the drive running."""
    plant = plants(
        plant_config(
            tmp_path,
            [DRIVE_PROGRAM],
            transport="tcp",
            program={"instance": "Drive", "program": "EatonDrive"},
            sims=[{"type": "da1", "unit": 1, "registers": {"505": 5}}],
            interval="50ms",
            timeout=SILENT_TIMEOUT,
        )
    )
    plant.run_until(lambda: plant["Drive.state"] == "HoldForward", 6000, step_ms=50)
    mend = silent_line(plant, "tcp")
    plant.run_ms(400)
    mend()
    plant.run_until(lambda: plant["Drive.drive.CONNECTED"], 1500, step_ms=50)
    assert plant.drive(1).fault == 0 and plant.drive(1).running
