"""The embedded default (io_config/default.toml): the Eaton drive on Modbus
RTU runs its sequence beside the LTMR on CANopen, in one engine (the
default plant of the softplc pytest plugin's `plc` fixture)."""

from __future__ import annotations

import pytest

# whole plants over seconds of virtual time, answers crossing sockets in real time
pytestmark = pytest.mark.slow


def test_drive_and_motor_run_side_by_side(plc):
    plc.watch("Motor.ltmr.Running")
    plc.run_until(
        lambda: plc["Drive.drive.AT_SETPOINT"] and plc["Drive.drive.RUNNING"], timeout="6s", what="drive at speed"
    )
    assert True in plc.trace.values("Motor.ltmr.Running")
    assert plc["Drive.drive.ACTUAL_HZ"] == pytest.approx(40.0)
    assert plc["Drive.drive.MODEL"] == "DA1"
    assert plc["Drive.MonitorOk"]
    assert all(d.status().ok for d in plc.engine.drivers)
    assert plc.engine.faults == []
