"""st_programs/eaton_drive.st against a simulated drive, over TCP and over
RTU on a pseudo-terminal, in virtual time: start, ramp to the setpoint,
reverse through zero, stop, and a fault reset by the program."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import registers as eaton

from ...io.modbus.plant import DRIVE_PROGRAM, WIRES, plant_config

# whole plants over seconds of virtual time, answers crossing sockets in real time
pytestmark = pytest.mark.slow

MONITOR = {
    "name": "drive_monitor",
    "unit": 1,
    "function": 3,
    "offset": 5,
    "count": 5,
    "read_to": "%IW200",
    "period": "100ms",
}


def drive_plant(plants, tmp_path, transport, sim_type="da1", **extra):
    return plants(
        plant_config(
            tmp_path,
            [DRIVE_PROGRAM],
            transport=transport,
            program={"instance": "Drive", "program": "EatonDrive"},
            sims=[{"type": sim_type, "unit": 1}],
            channels=[MONITOR],
            **extra,
        )
    )


@pytest.mark.parametrize("wire", WIRES)
@pytest.mark.parametrize("transport", ["tcp", "rtu"])
def test_start_ramp_reverse_stop(plants, tmp_path, transport, wire):
    # on a port RTU costs a few ms of real time per transaction: a slower task keeps the test short
    tick = 50 if (transport, wire) == ("rtu", "port") else 10
    plant = drive_plant(plants, tmp_path, transport, interval=f"{tick}ms", wire=wire)
    drive = plant.drive(1)
    plant.run_until(lambda: plant["Drive.state"] == "RunForward", 500)
    assert plant["Drive.drive.MODEL"] == "DA1" and plant["Drive.drive.FAMILY"] == eaton.Family.DA1
    # The simulator's 5 s ramp runs from 0 to f-max 50 Hz: 40 Hz takes 4 s.
    took = plant.run_until(lambda: plant["Drive.state"] == "HoldForward", 6000, step_ms=tick)
    assert 4000 <= took <= 4000 + 4 * tick  # the command goes out and the status comes back a few cycles later
    assert drive.actual_hz == pytest.approx(40.0)
    assert plant["Drive.drive.ACTUAL_HZ"] == pytest.approx(40.0)
    assert plant["Drive.drive.RUNNING"] and plant["Drive.drive.AT_SETPOINT"]
    assert plant["Drive.drive.CURRENT_A"] > 0
    # the HMI channel reads the same speed, in 0.1 Hz
    plant.run_ms(200)
    assert plant["%IW201"] == 400 and plant["Drive.MonitorOk"]
    # reverse: down through zero and up to 40 Hz the other way, 80 Hz at 10 Hz/s
    plant.run_until(lambda: plant["Drive.state"] == "RunReverse", 2100)
    seen_zero = []
    plant.run_until(lambda: seen_zero.append(drive.actual_hz) or plant["Drive.state"] == "HoldReverse", 9000)
    assert min(seen_zero) == pytest.approx(-40.0) and any(abs(hz) < 0.5 for hz in seen_zero)
    assert plant["Drive.drive.ACTUAL_HZ"] == pytest.approx(-40.0) and plant["Drive.drive.REVERSED"]
    # stop on the deceleration ramp
    plant.run_until(lambda: plant["Drive.state"] == "Stopping", 2100)
    plant.run_until(lambda: plant["Drive.state"] == "Rest", 5000)
    assert drive.actual_hz == 0 and not plant["Drive.drive.RUNNING"]
    assert plant["Drive.cycles"] == 1
    assert plant["Drive.AccelRamp"] == 50  # P1-03 read by name: 5.0 s in 0.1 s
    assert plant.engine.faults == []
    assert [ch.stats.errors for ch in plant.master.channels] == [0]


def test_a_drive_fault_is_shown_and_reset_by_the_program(plants, tmp_path):
    plant = drive_plant(plants, tmp_path, "tcp")
    plant.run_until(lambda: plant["Drive.state"] == "HoldForward", 6000)
    plant.drive(1).trip(4)  # I.t-trP, motor overload
    plant.run_until(lambda: plant["Drive.state"] == "Faulted", 100)
    assert plant["Drive.drive.FAULT"] and plant["Drive.drive.FAULT_CODE"] == 4
    assert plant["Drive.drive.FAULT_TEXT"] == "Motor overload"
    assert not plant["Drive.drive.RUNNING"]  # a fault switches the output off
    took = plant.run_until(lambda: plant["Drive.state"] == "Idle", 2000)
    assert 1000 <= took <= 1100  # AutoReset after 1 s
    assert not plant["Drive.drive.FAULT"] and plant["Drive.faults"] == 1
    plant.run_until(lambda: plant["Drive.drive.RUNNING"], 200)  # and it starts again


@pytest.mark.parametrize(
    "sim_type, model", [("da1", "DA1"), ("db1", "DB1"), ("dc1", "DC1"), ("de1", "DE1"), ("de11", "DE11")]
)
def test_the_program_runs_every_family(plants, tmp_path, sim_type, model):
    """DA1_DRIVE reads ID 17 and adapts; the DE1 has no ID 4, 9, 10."""
    plant = drive_plant(plants, tmp_path, "tcp", sim_type=sim_type)
    plant.run_until(lambda: plant["Drive.state"] == "HoldForward", 6000)
    family, printed = next((f, m) for v, (f, m) in eaton.DEVICE_IDENTIFICATION.items() if m == model)
    assert plant["Drive.drive.MODEL"] == printed and plant["Drive.drive.FAMILY"] == family
    assert plant["Drive.drive.DEVICE_ID"] == next(v for v, (_f, m) in eaton.DEVICE_IDENTIFICATION.items() if m == model)
    assert plant["Drive.drive.ACTUAL_HZ"] == pytest.approx(40.0)
