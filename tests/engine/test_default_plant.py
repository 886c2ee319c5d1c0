"""The embedded default (io_config/default.toml): the Eaton drive on Modbus
RTU runs its sequence beside the LTMR on CANopen, in one engine."""

from __future__ import annotations

import pytest

from softplc.runtime.config import default_config_path, load_config
from softplc.runtime.engine.build import build_engine

from ..io.modbus.plant import MS

# whole plants over seconds of virtual time, answers crossing sockets in real time
pytestmark = pytest.mark.slow


def test_drive_and_motor_run_side_by_side():
    engine = build_engine(load_config(default_config_path()), virtual_time=True)
    engine.start()
    try:
        drive_at_speed = motor_ran = False
        while engine.clock.now_ns() < 6000 * MS and not (drive_at_speed and motor_ran):
            engine.run(duration_ns=20 * MS)
            drive_at_speed |= engine.get("Drive.drive.AT_SETPOINT") and engine.get("Drive.drive.RUNNING")
            motor_ran |= engine.get("Motor.ltmr.Running")
        assert drive_at_speed and motor_ran
        assert engine.get("Drive.drive.ACTUAL_HZ") == pytest.approx(40.0)
        assert engine.get("Drive.drive.MODEL") == "DA1"
        assert engine.get("Drive.MonitorOk")
        assert all(d.status().ok for d in engine.drivers)
        assert engine.faults == []
    finally:
        engine.stop()
