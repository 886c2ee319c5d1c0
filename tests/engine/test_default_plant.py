"""The embedded default (io_config/default.toml): the Eaton drive on Modbus
RTU runs its sequence beside the LTMR on CANopen, in one engine (the
default plant of the softplc pytest plugin's `plc` fixture)."""

from __future__ import annotations

from datetime import timedelta

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


@pytest.mark.parametrize(
    "program,step,sim,fault,value",
    [("Pump", "High", "fc28020", "alarm", 0x08), ("Drive", "HoldForward", "da1_1", "trip", 2)],
)
def test_a_trip_late_in_a_timed_step_is_reset_a_second_later(plc, program, step, sim, fault, value):
    """Found by the soak benchmark (benchmarks/bench_soak.py): a drive that
    tripped late in a timed step (the pump at high speed, the conveyor drive
    holding its speed) was reset in the next scan, not a second later: the
    step's timer had run past the Faulted state's 1 s before the trip."""
    plc.run_until(lambda: plc[f"{program}.state"] == step, timeout="20s")
    plc.run_for("1500ms")
    assert plc[f"{program}.state"] == step
    plc.fault(sim, fault, value)
    tripped = plc.now
    plc.watch(f"{program}.state")
    reset = plc.run_until(lambda: plc[f"{program}.state"] == "FaultReset", timeout="3s")
    assert "Faulted" in plc.trace.values(f"{program}.state")
    assert reset - tripped >= timedelta(seconds=1)
