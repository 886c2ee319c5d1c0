"""The Eaton drive in its safe state (README, "Safe outputs"): DA1_DRIVE
declares it to the Modbus master once it has identified the drive
(MODBUS_SAFE_WRITE: ID 1 = 0, stop; ID 2 = 0 Hz); on a task fault and at
the stop the master writes it, through pymodbus's RTU framing, to the
simulated drive, which stops on its ramp. Before, the drive's block simply
stopped sending: the monitoring channel's reads kept the drive's
comm-loss watchdog (P5-05) fed, and the drive ran on at 40 Hz."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import registers as eaton

from ..safe_support import fault_the_task, safe_plant

pytestmark = pytest.mark.slow


def _faulted(model) -> bool:
    return bool(eaton.status_flags(model.status()) & eaton.StatusWord.FAULT)


def _running(plc, drive: str = "da1_1"):
    model = plc.sim(drive).model
    plc.run_until(lambda: model.actual_hz > 20, timeout="10s", what="the drive running above 20 Hz")
    assert model.register(eaton.REG_CONTROL_WORD) & eaton.ControlWord.RUN
    return model


def _stopped_by_the_plc(model) -> None:
    """IDs 1-2 as the safe write left them, the drive at rest, no fault."""
    assert model.register(eaton.REG_CONTROL_WORD) == int(eaton.SAFE_CONTROL_WORD) == 0
    assert model.register(eaton.REG_SPEED_SETPOINT) == 0
    assert model.actual_hz == 0 and not model.running
    assert not _faulted(model) and not model.comm_lost  # stopped, not tripped by a lost telegram


def test_a_task_fault_stops_the_drive(tmp_path):
    plc = safe_plant(tmp_path, "modbus_rtu.toml", "DriveTask")
    try:
        model = _running(plc)
        fault_the_task(plc)
        plc.run_for("100ms")
        assert model.register(eaton.REG_CONTROL_WORD) == 0  # written at once
        plc.run_for("5s")  # the ramp; P5-05 (2 s) would have tripped a drive no telegram reached
        _stopped_by_the_plc(model)
        assert plc["Drive.drive.CONNECTED"]  # the block stopped with its task: it shows the last state
    finally:
        plc.stop()


def test_the_stop_stops_the_drive(tmp_path):
    plc = safe_plant(tmp_path, "modbus_rtu.toml", "DriveTask")
    model = _running(plc)
    plc.stop()
    assert model.register(eaton.REG_CONTROL_WORD) == 0 and model.register(eaton.REG_SPEED_SETPOINT) == 0
    model.advance(plc.now_ns + 10_000_000_000)  # the drive, left alone, ramps down
    assert model.actual_hz == 0 and not model.running


@pytest.mark.realtime
def test_the_stop_on_the_real_clock_writes_through_the_serial_cable(tmp_path):
    """The RTU worker thread and a pseudo-terminal cable to the drive's
    pymodbus server: the stop sends the safe write before it closes."""
    plc = safe_plant(tmp_path, "modbus_rtu.toml", "DriveTask", virtual_time=False)
    model = plc.sim("da1_1").model
    plc.run_until(lambda: model.register(eaton.REG_CONTROL_WORD) & eaton.ControlWord.RUN, timeout="10s")
    plc.stop()
    assert model.register(eaton.REG_CONTROL_WORD) == 0 and model.register(eaton.REG_SPEED_SETPOINT) == 0


def test_a_fault_elsewhere_stops_it_though_its_block_runs_on(tmp_path):
    """The default plant, a fault in the pump's task: the drive's task still
    runs DA1_DRIVE, which reads the drive (the master puts the safe values in
    place of what it writes) until a restart brings the outputs back."""
    plc = safe_plant(tmp_path, None, "PumpTask")
    try:
        model = _running(plc)
        fault_the_task(plc)
        exchanges = plc["Drive.drive.EXCHANGES"]
        plc.run_for("10s")
        _stopped_by_the_plc(model)
        assert plc["Drive.drive.CONNECTED"] and plc["Drive.drive.EXCHANGES"] > exchanges + 100
        assert plc["Drive.drive.ACTUAL_HZ"] == 0 and not plc["Drive.drive.RUNNING"]
        assert plc.engine.restart()
        plc.run_until(lambda: model.actual_hz > 20, timeout="10s", what="the drive running again")
    finally:
        plc.stop()
