"""The LTMR in its safe state (README, "Safe outputs"): on a task fault and
at the stop the RPDO carries register 704 = 0 (no run command) and the
simulated LTMR opens LO1 and LO2, whether [outputs] safe says so or the
device does (Device.safe_objects)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.ltmr import registers as ltmr

from ..safe_support import fault_the_task, safe_plant

pytestmark = pytest.mark.slow


def _running(tmp_path, configured_safe: bool):
    plc = safe_plant(tmp_path, "canopen.toml", "Main", configured_safe=configured_safe)
    plc.write("Motor.Auto", False)
    plc.force("Motor.CmdForward", True)
    ltmr40 = plc.sim("ltmr40")
    plc.run_until(lambda: ltmr40.lo1, timeout="3s", what="LO1 closed: the motor runs forward")
    assert ltmr40.register(ltmr.REG_CONTROL_1) == 1 and ltmr40.motor_running
    return plc, ltmr40


@pytest.mark.parametrize("configured_safe", [True, False], ids=["[outputs] safe", "the device's"])
def test_a_task_fault_opens_lo1_and_lo2(tmp_path, configured_safe):
    plc, ltmr40 = _running(tmp_path, configured_safe)
    try:
        fault_the_task(plc)
        plc.run_until(lambda: not ltmr40.lo1, timeout="200ms", what="LO1 open")
        plc.run_for("2s")  # and it stays so: the forced command reaches no wire
        assert ltmr40.register(ltmr.REG_CONTROL_1) == 0
        assert not ltmr40.lo1 and not ltmr40.lo2 and not ltmr40.motor_running
        assert not ltmr40.fallback_applied  # the bus is fine: the PLC, not a fallback, stopped it
    finally:
        plc.stop()


@pytest.mark.parametrize("configured_safe", [True, False], ids=["[outputs] safe", "the device's"])
def test_the_stop_opens_lo1_and_lo2(tmp_path, configured_safe):
    plc, ltmr40 = _running(tmp_path, configured_safe)
    plc.stop()
    assert ltmr40.register(ltmr.REG_CONTROL_1) == 0
    assert not ltmr40.lo1 and not ltmr40.lo2 and not ltmr40.motor_running
