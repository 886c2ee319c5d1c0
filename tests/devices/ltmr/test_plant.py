"""The LTMR motor end to end: st_programs/ltmr_motor.st through the CANopen
master to the simulated LTMR on the virtual bus, in virtual time."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.devices.ltmr import bits as ltmr_bits
from softplc.runtime.devices.ltmr import codes as ltmr_codes
from softplc.runtime.devices.ltmr import registers as ltmr

# whole plants over seconds of virtual time, answers crossing sockets in real time
pytestmark = pytest.mark.slow

ROOT = Path(__file__).resolve().parents[3]
MOTOR = (ROOT / "st_programs" / "ltmr_motor.st").read_text()


def _motor(plants, **kwargs):
    plant = plants(MOTOR, program="LtmrMotor", **kwargs)
    plant.run_until(lambda: plant.get("LtmrMotor.ltmr.Running"), 3000, "motor running")
    return plant


def test_the_motor_sequence_forward_pause_reverse_pause(plants):
    plant = _motor(plants)
    sim = plant.sims[40]
    assert sim.lo1 and not sim.lo2  # reverser mode: LO1 forward
    # RPDO1 as the manual lays it out (digest 001 §7.2): 704 = 0x0001, 703 = 0, 700 = 0
    assert plant.frames_with(0x228)[-1] == bytes.fromhex("01 00 00 00 00 00")
    status1 = plant.get("LtmrMotor.status1")
    assert status1 & ltmr_bits.Status1.RUNNING and status1 & ltmr_bits.Status1.READY
    assert plant.get("LtmrMotor.ltmr.CurrentRatio") > 10.0
    plant.run_until(lambda: not sim.lo1, 3200, "forward ends after 3 s")
    assert plant.frames_with(0x228)[-1] == bytes.fromhex("00 00 00 00 00 00")
    plant.run_until(lambda: sim.lo2, 1200, "reverse after the 1 s pause")
    assert plant.frames_with(0x228)[-1] == bytes.fromhex("02 00 00 00 00 00")
    plant.run_until(lambda: plant.get("LtmrMotor.ltmr.Running"), 1000, "running in reverse")
    assert plant.get("LtmrMotor.starts") == 2


def test_an_overload_trips_the_motor_with_the_thermal_code_and_the_program_resets_it(plants):
    plant = _motor(plants)
    sim = plant.sims[40]
    sim.set_load(400)  # % FLC: a jammed machine
    plant.run_until(lambda: plant.get("LtmrMotor.ltmr.Tripped"), 60_000, "thermal trip")
    assert plant.get("LtmrMotor.tripCode") == ltmr_codes.TRIP_THERMAL_OVERLOAD  # 451 via TPDO2
    assert plant.get("LtmrMotor.ltmr.TripText") == ltmr_codes.trip_text(ltmr_codes.TRIP_THERMAL_OVERLOAD)
    assert not sim.lo1 and not sim.lo2
    assert sim.register(ltmr.REG_TRIP_REGISTER_1) & ltmr_bits.TripRegister1.THERMAL_OVERLOAD
    # The LTMR's EMCY reaches the program (manual gives no payload; the simulator's choice, A22)
    assert plant.node_diag(40, "Emergencies") >= 1
    assert plant.node_diag(40, "EmcyCode") == 0x1000
    sim.set_load(80)
    # READ_VAR of trip register 1 (452) shows the cause, bit 3 thermal overload
    plant.run_until(
        lambda: plant.get("LtmrMotor.tripRegister1") & ltmr_bits.TripRegister1.THERMAL_OVERLOAD,
        3000,
        "trip register read by SDO",
    )
    # cooling below the reset threshold authorizes the reset; the program resets (remote reset mode)
    plant.run_until(lambda: plant.get("LtmrMotor.ltmr.Running"), 600_000, "running again after reset")
    assert plant.get("LtmrMotor.trips") == 1
    assert sim.register(ltmr.REG_TRIP_CODE) == 0


def test_communication_loss_applies_the_ltmr_fallback_then_recovers(plants):
    plant = _motor(plants)
    sim = plant.sims[40]
    plant.run_ms(200)  # CiA 301: the LTMR watches the master from the first heartbeat it gets
    sim.unplug()  # the cable between PLC and LTMR is cut
    plant.run_ms(700)  # > 500 ms master_timeout in the LTMR
    assert not sim.lo1 and not sim.lo2  # fallback 682 = 2: LO1, LO2 off
    assert sim.register(ltmr.REG_STATUS_2) & ltmr_bits.Status2.NETWORK_COMM_LOSS
    assert plant.get("LtmrMotor.ltmr.CommLoss")
    sim.plug()
    plant.run_until(lambda: plant.get("LtmrMotor.ltmr.Running"), 10_000, "running again")
    assert not sim.register(ltmr.REG_STATUS_2) & ltmr_bits.Status2.NETWORK_COMM_LOSS
    assert not plant.get("LtmrMotor.ltmr.CommLoss")
