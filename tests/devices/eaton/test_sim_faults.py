"""Faults scheduled in the configuration ([[sim]] faults = [...]) for a
simulated Eaton drive: the unit falls silent (its own watchdog then trips it
with fault 50), it trips with a fault of Tabelle 11, its hardware enable
opens; the program of st_programs/eaton_drive.st sees each and recovers."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import faults as eaton_faults

from ...io.modbus.plant import DRIVE_PROGRAM, SILENT_TIMEOUT, plant_config

# whole plants over seconds of virtual time, answers crossing sockets in real time
pytestmark = pytest.mark.slow

OVERCURRENT = 3  # Tabelle 11 (L862): "O-I", overcurrent at the output


def test_faults_on_schedule(plants, tmp_path):
    # P5-05 = 20: 2.0 s comm-loss timeout, P5-06 = 0: trip (the DA1's factory setting, L387-388)
    faults = [
        {"at": "3s", "fault": "silent", "for": "2500ms"},
        {"at": "12s", "fault": "trip", "value": OVERCURRENT},
        {"at": "20s", "fault": "enable_off", "for": "1s"},
    ]
    plant = plants(
        plant_config(
            tmp_path,
            [DRIVE_PROGRAM],
            transport="tcp",
            program={"instance": "Drive", "program": "EatonDrive"},
            sims=[{"type": "da1", "unit": 1, "registers": {"505": 20, "506": 0}, "faults": faults}],
            interval="50ms",
            timeout=SILENT_TIMEOUT,
        )
    )
    drive = plant.drive(1)
    assert plant.engine.simulators["da1_1"].model is drive  # by its default name: type and unit
    # (a real-time answer late on a loaded machine may cost one exchange before 3 s; the
    # drive's own view, telegrams received, does not depend on it)
    plant.run_ms(3000)
    assert drive.fault == 0
    plant.run_until(lambda: not plant["Drive.drive.CONNECTED"], 300, step_ms=50)
    # the unit is silent, not the line: the drive's own watchdog trips it 2 s later (L906)
    plant.run_until(lambda: drive.fault == eaton_faults.COMM_LOSS_FAULT, 2200, step_ms=50)
    assert 5000 <= plant.now_ms <= 5150
    plant.run_until(lambda: plant.now_ms >= 5500 and plant["Drive.drive.CONNECTED"], 1500, step_ms=50)
    plant.run_until(lambda: plant["Drive.faults"] == 1 and plant["Drive.state"] == "RunForward", 3000, step_ms=50)
    plant.run_until(lambda: plant["Drive.drive.FAULT_CODE"] == OVERCURRENT, 7000, step_ms=50)
    assert 12_000 <= plant.now_ms <= 12_300
    assert plant["Drive.drive.FAULT_TEXT"] == eaton_faults.fault_text(OVERCURRENT) == "Overcurrent at the output"
    plant.run_until(lambda: plant["Drive.faults"] == 2 and drive.fault == 0, 3000, step_ms=50)
    plant.run_until(lambda: drive.running, 6000, step_ms=50)
    plant.run_until(lambda: not drive.di1, 8000, step_ms=50)
    assert plant.now_ms >= 20_000 and not drive.running  # the enable open: the motor coasts
    plant.run_until(lambda: drive.di1, 1100, step_ms=50)
    assert plant.engine.faults == []
