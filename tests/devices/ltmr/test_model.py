"""The LTMR device model alone (no bus): commands in register 704, what the
registers show, the thermal image and its trip, reset modes, operating
modes, communication-loss fallback. Expected values come from manual 001
(register meanings, bit numbers) and from the IEC class definition, worked
out here independently of the model."""

from __future__ import annotations

import math

import pytest

from softplc.runtime.devices.ltmr import codes as ltmr_codes
from softplc.runtime.devices.ltmr import datatypes as ltmr_datatypes
from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr.bits import (
    AlarmEnable1,
    AlarmRegister1,
    Control1,
    Control2,
    Status1,
    Status2,
    TripEnable1,
    TripRegister1,
)
from softplc.runtime.devices.ltmr.codes import FallbackStrategy, OperatingMode, ResetMode
from softplc.runtime.devices.ltmr.model import LtmrModel

S = 1_000_000_000
FORWARD, REVERSE, RESET, SELF_TEST, LOW_SPEED = (
    Control1.RUN_FORWARD,
    Control1.RUN_REVERSE,
    Control1.TRIP_RESET,
    Control1.SELF_TEST,
    Control1.LOW_SPEED,
)


class Clock:
    """Moves a model in seconds of virtual time."""

    def __init__(self, model: LtmrModel) -> None:
        self.model = model
        self.t = 0
        model.advance_to(0)

    def run(self, seconds: float) -> None:
        self.t += round(seconds * S)
        self.model.advance_to(self.t)

    def run_until(self, predicate, limit_s: float, step_s: float = 0.01) -> float:
        start = self.t
        while not predicate():
            if self.t - start > limit_s * S:
                raise AssertionError(f"not within {limit_s} s")
            self.run(step_s)
        return (self.t - start) / S


def _model(registers=None, load=80.0):
    model = LtmrModel(registers, load_percent=load)
    return model, Clock(model)


def _command(model, bits):
    model.registers[ltmr.REG_CONTROL_1] = int(bits)


def _status1(model) -> int:
    return model.registers[ltmr.REG_STATUS_1]


def _udint(model, reg) -> int:
    return ltmr_datatypes.udint_from_registers(model.registers[reg], model.registers[reg + 1])


def _class_trip_seconds(trip_class: int, multiple: float, iu: float = 1.125) -> float:
    """IEC class N: N s at 7.2 x FLC from cold, so tau = -N / ln(1 - (Iu/7.2)^2);
    at another current t = -tau ln(1 - (Iu/I)^2) (Iu = 1.125, the simulator's choice)."""
    tau = -trip_class / math.log(1 - (iu / 7.2) ** 2)
    return -tau * math.log(1 - (iu / multiple) ** 2)


# ---------------------------------------------------------------------------- what 455 and the currents show


def test_flc1_is_a_percentage_of_flc_max_and_currents_are_in_centiamps():
    # digest 001 §6.4: 96 = 80 (8.0 A) and 652 = 50 -> FLC1 = 4.0 A
    model, clock = _model({ltmr.REG_FLC_MAX: 80, ltmr.REG_FLC1: 50}, load=80)
    _command(model, FORWARD)
    clock.run(2)
    assert _udint(model, ltmr.REG_AVERAGE_CURRENT) == 320  # 80 % of 4.0 A = 3.20 A, x 0.01 A
    for reg in (ltmr.REG_L1_CURRENT, ltmr.REG_L2_CURRENT, ltmr.REG_L3_CURRENT):
        assert _udint(model, reg) == 320
    assert model.registers[ltmr.REG_AVERAGE_CURRENT] == 0  # lower register = MSW (A5)
    assert model.registers[ltmr.REG_AVERAGE_CURRENT_RATIO] == 80  # 466, % FLC
    assert (_status1(model) >> 8) & 0x3F == 26  # 80 % x 32 / 100, rounded (A14)


def test_status_register_1_of_a_motor_running_at_full_load():
    # digest 001 §6.3: ready + on + running + ratio 32 (100 %) + in remote = 0x6083; bit 6
    # "controller power" is set too (A13)
    model, clock = _model(load=100)
    _command(model, FORWARD)
    clock.run(0.5)
    assert _status1(model) & Status1.STARTING  # bit 15 during the start
    assert _status1(model) & Status1.RUNNING
    clock.run(1)
    assert _status1(model) == 0x6083 | Status1.CONTROLLER_POWER
    _command(model, 0)
    clock.run(0.01)
    assert _status1(model) == Status1.READY | Status1.CONTROLLER_POWER | Status1.IN_REMOTE


@pytest.mark.parametrize("load, running", [(8, False), (12, True)])
def test_running_means_more_than_10_percent_flc(load, running):
    model, clock = _model(load=load)  # 455 bit 7 (manual 001 L3533)
    _command(model, FORWARD)
    clock.run(2)
    assert model.lo1
    assert bool(_status1(model) & Status1.RUNNING) is running


def test_outputs_show_in_458_and_459():
    model, clock = _model({ltmr.REG_LOGIC_INPUTS: 0x0005})
    _command(model, FORWARD)
    clock.run(2)
    assert model.registers[ltmr.REG_LOGIC_OUTPUTS] & 0b11 == 0b01  # 458 bit 0: LO1
    assert model.registers[ltmr.REG_IO_STATUS] == 0x1005  # 459: inputs 1, 3 and output 1 (13-14)


def test_starts_are_counted():
    model, clock = _model()
    for _ in range(3):
        _command(model, FORWARD)
        clock.run(2)
        _command(model, 0)
        clock.run(1)
    assert _udint(model, ltmr.REG_MOTOR_STARTS_COUNT) == 3  # 117-118


# ---------------------------------------------------------------------------- thermal image


@pytest.mark.parametrize("trip_class", [10, 20])
def test_a_class_n_relay_trips_after_n_seconds_at_7_2_flc_from_cold(trip_class):
    model, clock = _model({ltmr.REG_TRIP_CLASS: trip_class}, load=720)  # a locked rotor
    _command(model, FORWARD)
    clock.run(trip_class - 0.01)
    assert not model.tripped
    clock.run(0.01)
    assert model.tripped  # at N s (10 ms resolution)
    assert model.registers[ltmr.REG_THERMAL_CAPACITY] == 100
    assert model.registers[ltmr.REG_TRIP_CODE] == ltmr_codes.TRIP_THERMAL_OVERLOAD  # 451 = 4
    assert model.registers[ltmr.REG_TRIP_REGISTER_1] & TripRegister1.THERMAL_OVERLOAD  # 452 bit 3
    assert _status1(model) & (Status1.TRIP | Status1.TRIPPED) == Status1.TRIP | Status1.TRIPPED
    assert not _status1(model) & Status1.READY
    assert not model.lo1 and not model.motor_running


def test_four_times_flc_trips_when_the_class_10_curve_says():
    model, clock = _model(load=80)
    _command(model, FORWARD)
    clock.run(1)  # the start: 1 s at 6 x FLC
    model.set_load(400)
    took = clock.run_until(lambda: model.tripped, 60)
    start = 1 - math.exp(-1 / (-10 / math.log(1 - (1.125 / 7.2) ** 2)))
    theta_after_start = (6 / 1.125) ** 2 * start
    tau = -10 / math.log(1 - (1.125 / 7.2) ** 2)
    steady = (4 / 1.125) ** 2
    expected = -tau * math.log((steady - 1) / (steady - theta_after_start))
    assert abs(took - expected) < 0.02
    assert _class_trip_seconds(10, 4) > took  # from cold it would take longer


def test_time_to_trip_counts_down():
    model, clock = _model(load=400)
    _command(model, FORWARD)
    clock.run(5)
    first = model.registers[ltmr.REG_TIME_TO_TRIP]
    clock.run(10)
    assert first - 11 <= model.registers[ltmr.REG_TIME_TO_TRIP] <= first - 9
    model.set_load(80)
    clock.run(0.01)
    assert model.registers[ltmr.REG_TIME_TO_TRIP] == 0xFFFF  # no trip ahead (simulator's "never")


def test_a_disabled_thermal_trip_does_not_trip():
    model, clock = _model({ltmr.REG_TRIP_ENABLE_1: TripEnable1.SELF_TEST}, load=720)  # 631 bit 3 off
    _command(model, FORWARD)
    clock.run(30)
    assert not model.tripped and model.lo1
    assert model.registers[ltmr.REG_THERMAL_CAPACITY] > 100


def test_the_thermal_alarm_comes_at_the_alarm_threshold_when_enabled():
    model, clock = _model(load=400)
    _command(model, FORWARD)
    clock.run_until(lambda: model.registers[ltmr.REG_THERMAL_CAPACITY] >= 85, 60)  # 609 = 85 %
    clock.run(0.01)
    assert model.registers[ltmr.REG_ALARM_CODE] == ltmr_codes.ALARM_THERMAL_OVERLOAD  # 460 = 4
    assert model.registers[ltmr.REG_ALARM_REGISTER_1] & AlarmRegister1.THERMAL_OVERLOAD  # 461 bit 3
    assert _status1(model) & Status1.ALARM
    assert not model.tripped

    quiet, clock2 = _model({ltmr.REG_ALARM_ENABLE_1: AlarmEnable1.NETWORK_PORT}, load=400)  # 632 bit 3 off
    _command(quiet, FORWARD)
    clock2.run_until(lambda: quiet.registers[ltmr.REG_THERMAL_CAPACITY] >= 90, 60)
    assert quiet.registers[ltmr.REG_ALARM_CODE] == 0 and not _status1(quiet) & Status1.ALARM


def test_705_bit_2_clears_the_thermal_capacity_level():
    model, clock = _model(load=300)
    _command(model, FORWARD)
    clock.run(20)
    assert model.registers[ltmr.REG_THERMAL_CAPACITY] > 30
    model.registers[ltmr.REG_CONTROL_2] = Control2.CLEAR_THERMAL_CAPACITY
    clock.run(0.01)
    assert model.registers[ltmr.REG_THERMAL_CAPACITY] < 1


# ---------------------------------------------------------------------------- reset


def _tripped(registers=None):
    model, clock = _model(registers, load=720)
    _command(model, FORWARD)
    clock.run_until(lambda: model.tripped, 20)
    return model, clock


def test_the_reset_is_authorized_once_the_thermal_capacity_fell_below_the_reset_threshold():
    model, clock = _tripped()
    assert not _status1(model) & Status1.RESET_AUTHORIZED
    wait = model.registers[ltmr.REG_MIN_WAIT_TIME]  # 450, s
    tau = -10 / math.log(1 - (1.125 / 7.2) ** 2)
    assert abs(wait - tau * math.log(1 / 0.75)) <= 1  # cooling from 100 % to 75 % (608)
    clock.run(wait - 2)
    assert not _status1(model) & Status1.RESET_AUTHORIZED
    clock.run(2)
    assert _status1(model) & Status1.RESET_AUTHORIZED  # 455 bit 5
    assert model.registers[ltmr.REG_THERMAL_CAPACITY] <= 75
    assert model.registers[ltmr.REG_MIN_WAIT_TIME] == 0


def test_remote_reset_on_a_rising_edge_of_704_bit_3_once_authorized():
    model, clock = _tripped({ltmr.REG_GENERAL_CONFIG_2: ResetMode.REMOTE})
    _command(model, RESET)  # too early: not authorized
    clock.run(1)
    _command(model, 0)
    assert model.tripped
    clock.run_until(lambda: model.reset_authorized, 300)
    _command(model, RESET)
    clock.run(0.01)
    assert not model.tripped
    assert model.registers[ltmr.REG_TRIP_CODE] == 0 and model.registers[ltmr.REG_TRIP_REGISTER_1] == 0
    assert _status1(model) & Status1.READY


def test_manual_reset_mode_ignores_the_network_and_takes_the_button():
    model, clock = _tripped({ltmr.REG_GENERAL_CONFIG_2: ResetMode.MANUAL})
    clock.run_until(lambda: model.reset_authorized, 300)
    _command(model, RESET)
    clock.run(0.01)
    assert model.tripped
    model.press_reset()
    clock.run(0.01)
    assert not model.tripped


def test_automatic_reset_mode_resets_by_itself_once_authorized():
    model, clock = _tripped({ltmr.REG_GENERAL_CONFIG_2: ResetMode.AUTOMATIC})
    took = clock.run_until(lambda: not model.tripped, 300)
    tau = -10 / math.log(1 - (1.125 / 7.2) ** 2)
    assert abs(took - tau * math.log(1 / 0.75)) < 0.1


def test_two_wire_restarts_after_the_reset_three_wire_needs_a_new_start():
    model, clock = _tripped()  # REVERSER_2W, run bit still set
    model.set_load(80)
    clock.run_until(lambda: model.reset_authorized, 300)
    model.press_reset()
    clock.run(0.01)
    assert model.lo1  # 2-wire: the level is the command

    model, clock = _tripped({ltmr.REG_OPERATING_MODE: OperatingMode.REVERSER_3W})
    model.set_load(80)
    clock.run_until(lambda: model.reset_authorized, 300)
    model.press_reset()
    clock.run(1)
    assert not model.tripped and not model.lo1
    _command(model, 0)
    clock.run(0.01)
    _command(model, FORWARD)
    clock.run(0.01)
    assert model.lo1


# ---------------------------------------------------------------------------- self test


def test_self_test_trips_with_code_10_when_enabled():
    model, clock = _model()
    _command(model, FORWARD)
    clock.run(2)
    _command(model, FORWARD | SELF_TEST)
    clock.run(0.01)
    assert model.registers[ltmr.REG_TRIP_CODE] == ltmr_codes.TRIP_TEST  # 10
    assert model.registers[ltmr.REG_TRIP_REGISTER_1] & TripRegister1.TEST  # 452 bit 9
    assert not model.lo1
    assert model.reset_authorized

    disabled, clock2 = _model({ltmr.REG_TRIP_ENABLE_1: TripEnable1.THERMAL_OVERLOAD})  # 631 bit 9 off
    _command(disabled, SELF_TEST)
    clock2.run(0.01)
    assert not disabled.tripped


# ---------------------------------------------------------------------------- operating modes


def test_reverser_forward_reverse_and_both_is_stop():
    model, clock = _model()
    _command(model, FORWARD)
    clock.run(0.01)
    assert (model.lo1, model.lo2) == (True, False)
    _command(model, FORWARD | REVERSE)
    clock.run(0.01)
    assert (model.lo1, model.lo2) == (False, False)
    _command(model, 0)
    clock.run(0.01)
    _command(model, REVERSE)
    clock.run(0.01)
    assert (model.lo1, model.lo2) == (False, True)


def test_reverser_direction_change_needs_a_stop_unless_direct_transition():
    model, clock = _model()
    _command(model, FORWARD)
    clock.run(2)
    _command(model, REVERSE)  # 683 bit 9 = 0: stop required during transition
    clock.run(1)
    assert not model.lo1 and not model.lo2
    _command(model, 0)
    clock.run(0.01)
    _command(model, REVERSE)
    clock.run(0.01)
    assert model.lo2

    direct, clock2 = _model({ltmr.REG_CONTROL_SETTING: 1 << 9})
    _command(direct, FORWARD)
    clock2.run(2)
    _command(direct, REVERSE)
    clock2.run(0.01)
    assert (direct.lo1, direct.lo2) == (False, True)


def test_the_transition_timeout_holds_the_other_direction_after_a_stop():
    model, clock = _model({ltmr.REG_CONTROL_SETTING: 1 << 9, 541: 2})  # 541 = 2 s
    _command(model, FORWARD)
    clock.run(2)
    _command(model, REVERSE)
    clock.run(0.01)
    assert not model.lo1 and not model.lo2
    assert model.registers[ltmr.REG_STATUS_2] & Status2.TRANSITION_LOCKOUT  # 456 bit 9
    took = clock.run_until(lambda: model.lo2, 5)
    assert 1.9 <= took <= 2.01
    assert not model.registers[ltmr.REG_STATUS_2] & Status2.TRANSITION_LOCKOUT


@pytest.mark.parametrize("mode", [OperatingMode.OVERLOAD_2W, OperatingMode.INDEPENDENT_2W])
def test_overload_and_independent_modes_drive_lo1_and_lo2_from_bits_0_and_1(mode):
    model, clock = _model({ltmr.REG_OPERATING_MODE: mode})
    for bits, outputs in (
        (FORWARD, (True, False)),
        (REVERSE, (False, True)),
        (FORWARD | REVERSE, (True, True)),
        (0, (False, False)),
    ):
        _command(model, bits)
        clock.run(0.01)
        assert (model.lo1, model.lo2) == outputs


def test_two_speed_low_speed_on_flc1_high_speed_on_flc2():
    model, clock = _model(
        {
            ltmr.REG_OPERATING_MODE: OperatingMode.TWO_SPEED_2W,
            ltmr.REG_FLC1: 50,
            ltmr.REG_FLC2: 100,
            ltmr.REG_CONTROL_SETTING: 1 << 9,
        },
        load=80,
    )
    _command(model, FORWARD | LOW_SPEED)
    clock.run(2)
    assert (model.lo1, model.lo2) == (True, False)
    assert not model.registers[ltmr.REG_STATUS_2] & Status2.SPEED_FLC2
    assert _udint(model, ltmr.REG_AVERAGE_CURRENT) == 320  # 80 % of FLC1 4.0 A
    _command(model, FORWARD)
    clock.run(2)
    assert (model.lo1, model.lo2) == (False, True)
    assert model.registers[ltmr.REG_STATUS_2] & Status2.SPEED_FLC2  # 456 bit 6
    assert _udint(model, ltmr.REG_AVERAGE_CURRENT) == 640  # 80 % of FLC2 8.0 A


def test_two_step_moves_to_step_2_when_the_current_falls_or_after_the_timeout():
    model, clock = _model({ltmr.REG_OPERATING_MODE: OperatingMode.TWO_STEP_2W}, load=80)
    _command(model, FORWARD)
    clock.run(0.5)
    assert (model.lo1, model.lo2) == (True, False)  # step 1 during the start
    clock.run(0.6)
    assert (model.lo1, model.lo2) == (False, True)  # below 644 = 150 % FLC after the start
    assert _udint(model, ltmr.REG_MOTOR_STARTS_COUNT) == 1  # one start, two steps

    heavy, clock2 = _model({ltmr.REG_OPERATING_MODE: OperatingMode.TWO_STEP_2W}, load=200)
    _command(heavy, FORWARD)
    took = clock2.run_until(lambda: heavy.lo2, 10)
    assert abs(took - 5) < 0.02  # 643 = 5 s


def test_commands_count_only_with_the_network_as_remote_channel():
    model, clock = _model({ltmr.REG_CONTROL_SETTING: 1 << 5})  # 683 bits 5-6 = 1: terminal strip
    _command(model, FORWARD)
    clock.run(1)
    assert not model.lo1


# ---------------------------------------------------------------------------- communication loss


@pytest.mark.parametrize(
    "mode, command, strategy, outputs",
    [
        (OperatingMode.REVERSER_2W, FORWARD, FallbackStrategy.HOLD, (True, False)),
        (OperatingMode.REVERSER_2W, FORWARD, FallbackStrategy.OFF, (False, False)),
        (OperatingMode.REVERSER_2W, 0, FallbackStrategy.LO1_ON, (True, False)),
        (OperatingMode.REVERSER_2W, FORWARD, FallbackStrategy.LO2_ON, (False, True)),
        (OperatingMode.OVERLOAD_2W, 0, FallbackStrategy.BOTH_ON, (True, True)),
        (OperatingMode.TWO_STEP_2W, FORWARD, FallbackStrategy.RUN, (False, True)),
        # not allowed in the mode (DT_OutputFallbackStrategy "Motor Modes"): LO1, LO2 off
        (OperatingMode.REVERSER_2W, FORWARD, FallbackStrategy.BOTH_ON, (False, False)),
        (OperatingMode.TWO_STEP_2W, FORWARD, FallbackStrategy.LO1_ON, (False, False)),
    ],
)
def test_communication_loss_applies_the_fallback_of_682(mode, command, strategy, outputs):
    model, clock = _model({ltmr.REG_OPERATING_MODE: mode, ltmr.REG_NETWORK_FALLBACK: strategy})
    _command(model, command)
    clock.run(2)
    model.network_lost()
    _command(model, 0)  # what the PLC wrote no longer counts
    clock.run(3)
    assert (model.lo1, model.lo2) == outputs
    assert model.registers[ltmr.REG_STATUS_2] & Status2.NETWORK_COMM_LOSS


def test_communication_loss_alarm_and_trip_109_when_enabled():
    model, clock = _model(
        {ltmr.REG_TRIP_ENABLE_1: TripEnable1.NETWORK_PORT, ltmr.REG_ALARM_ENABLE_1: AlarmEnable1.NETWORK_PORT}
    )
    _command(model, FORWARD)
    clock.run(2)
    model.network_lost()
    clock.run(0.01)
    assert model.registers[ltmr.REG_ALARM_CODE] == ltmr_codes.ALARM_NETWORK_COMM  # 460 = 109
    assert model.registers[ltmr.REG_ALARM_REGISTER_1] & AlarmRegister1.NETWORK_PORT  # 461 bit 15
    assert model.registers[ltmr.REG_TRIP_CODE] == ltmr_codes.TRIP_NETWORK_COMM  # 451 = 109
    assert model.registers[ltmr.REG_TRIP_REGISTER_1] & TripRegister1.NETWORK_PORT  # 452 bit 15
    model.network_restored()
    clock.run(0.01)
    assert not model.registers[ltmr.REG_STATUS_2] & Status2.NETWORK_COMM_LOSS
    assert model.registers[ltmr.REG_ALARM_CODE] == 0
    assert model.tripped  # a trip stays until reset


def test_the_fallback_lasts_until_cleared():
    model, clock = _model({ltmr.REG_NETWORK_FALLBACK: FallbackStrategy.OFF})
    _command(model, FORWARD)
    clock.run(2)
    model.network_lost()
    clock.run(1)
    model.network_restored()
    clock.run(1)
    assert not model.lo1  # restored, but the fallback holds
    model.clear_fallback()
    clock.run(0.01)
    assert model.lo1
