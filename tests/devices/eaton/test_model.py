"""The Eaton PowerXL drive model alone (no Modbus): registers, ramps, control
word, status word, faults, hardware enable and communication loss, driven
through the model's API with explicit times. Expected values come from
manual 002 ("L<n>") and its digest, worked out here by hand."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import faults as eaton_faults
from softplc.runtime.devices.eaton import parameters as eaton_parameters
from softplc.runtime.devices.eaton import registers as eaton
from softplc.runtime.devices.eaton import settings as eaton_settings
from softplc.runtime.devices.eaton.model import EatonDriveModel, ModbusRefusal
from softplc.runtime.devices.eaton.registers import ControlWord as CW
from softplc.runtime.devices.eaton.registers import Family
from softplc.runtime.devices.eaton.registers import StatusWord as SW

S = 1_000_000_000
POLL = 100_000_000  # the master's telegram period while "polling"
ALL = list(Family)
RUN, REV, RESET, COAST, QUICK = CW.RUN, CW.REVERSE, CW.FAULT_RESET, CW.COAST, CW.QUICK_STOP
IDLE = SW.READY | SW.ZERO_SPEED | SW.HARDWARE_ENABLE  # 0x00A1


class Master:
    """A PLC talking to one drive: every request is a telegram; time in seconds."""

    def __init__(self, family: Family, *, de11: bool = False, registers: dict | None = None) -> None:
        self.family = family
        self.drive = EatonDriveModel(family, de11=de11, registers=registers)
        self.t = 0

    def write(self, register: int, *values: int) -> None:
        self.drive.telegram(self.t)
        self.drive.write(register, [int(v) for v in values], self.t)

    def read(self, register: int, count: int = 1) -> list:
        self.drive.telegram(self.t)
        return self.drive.read(register, count, self.t)

    def param(self, number: str, value: int) -> None:
        self.write(eaton_parameters.parameter_register(self.family, number), value)

    def run(self, hz: float, bits: int = RUN) -> None:
        self.write(eaton.REG_SPEED_SETPOINT, eaton.speed_setpoint_raw(hz))
        self.write(eaton.REG_CONTROL_WORD, bits)

    def wait(self, seconds: float, *, poll: bool = True) -> None:
        """Let time pass; with poll, a telegram every 100 ms (and one at the
        end) feeds the watchdog."""
        end = self.t + round(seconds * S)
        while poll and self.t + POLL < end:
            self.t += POLL
            self.drive.telegram(self.t)
        self.t = end
        self.drive.advance(end)
        if poll:
            self.drive.telegram(end)

    @property
    def flags(self) -> SW:
        return eaton.status_flags(self.drive.status())

    @property
    def speed_raw(self) -> int:
        return self.drive.register(eaton.REG_ACTUAL_SPEED)


def at_50hz(family: Family, **kwargs) -> Master:
    master = Master(family, **kwargs)
    master.run(50.0)
    master.wait(5.0)
    assert master.drive.actual_hz == 50.0
    return master


# ---------------------------------------------------------------- registers and status


@pytest.mark.parametrize(
    "family, de11, id17",
    [
        (Family.DA1, False, 5632),
        (Family.DB1, False, 8198),
        (Family.DC1, False, 10),
        (Family.DE1, False, 8),
        (Family.DE1, True, 9),
    ],
)  # L1086-1096
def test_device_identification(family, de11, id17):
    master = Master(family, de11=de11)
    assert master.read(eaton.REG_DEVICE_ID) == [id17]
    assert eaton.model_from_id17(id17) == ("DE11" if de11 else family.name)


@pytest.mark.parametrize("family", ALL)
def test_a_stopped_enabled_drive_is_ready_at_zero_speed(family):
    status, speed, current = Master(family).read(eaton.REG_STATUS_WORD, 3)
    assert status == 0x00A1 == IDLE  # READY, zero speed, hardware enable; no fault number
    assert (speed, current) == (0, 0)
    assert Master(family).read(eaton.REG_DI_STATUS) == [1]  # bit 0 = DI1 (L954)


def test_manual_example_m1_reads_status_word_0_from_a_da1_with_sto_open():
    # digest §2.5: 01 03 00 05 00 01 94 0B -> 01 03 02 00 00 B8 44. A stopped DA1 answers 0
    # when STO (its enable, L316) is open: not ready, no STO status, and no zero-speed bit either.
    master = Master(Family.DA1)
    master.drive.di1 = False
    assert master.read(eaton.register_number(0x0005)) == [0x0000]


@pytest.mark.parametrize("family", ALL)
def test_run_to_50hz_on_a_5s_ramp(family):
    master = Master(family)
    master.run(50.0)
    master.wait(2.5)
    assert master.read(eaton.REG_ACTUAL_SPEED) == [250]
    assert master.flags == SW.READY | SW.RUNNING | SW.SPEED_CONTROL_ACTIVE | SW.HARDWARE_ENABLE
    master.wait(2.5)
    assert master.speed_raw == 500
    assert SW.AT_SETPOINT in master.flags and SW.ZERO_SPEED not in master.flags
    # simulator's motor: 8.2 A rated at 50 Hz, 4 kW
    assert master.drive.register(eaton.REG_MOTOR_CURRENT) == 82
    if family is not Family.DE1:
        assert master.read(eaton.REG_TORQUE, 2) == [1000, 40]  # 100.0 %, 4.0 kW


def test_setpoint_is_limited_to_f_max_and_f_min():
    master = Master(Family.DB1)
    master.param("P-02", eaton.PARAMETER_FREQUENCY.to_raw(10.0))
    master.run(80.0)
    assert master.drive.setpoint_hz == 50.0
    master.write(eaton.REG_SPEED_SETPOINT, 30)  # 3.0 Hz
    assert master.drive.setpoint_hz == 10.0
    master.write(eaton.REG_CONTROL_WORD, RUN | CW.ZERO_SETPOINT)
    assert master.drive.setpoint_hz == 0.0


def test_ramp_position_does_not_depend_on_the_step_size():
    timeout_off = {eaton_parameters.parameter_register(Family.DA1, eaton_settings.DA1_COMM_TIMEOUT): 0}
    fine, coarse = (EatonDriveModel(Family.DA1, registers=timeout_off) for _ in range(2))
    for drive in (fine, coarse):
        drive.write(eaton.REG_SPEED_SETPOINT, [437], 0)
        drive.write(eaton.REG_CONTROL_WORD, [RUN], 0)
    samples, last_ms = {}, 0
    for t_ms, command in ((3_000, RUN | REV), (7_300, 0), (10_000, None)):
        for t in range(last_ms + 1, t_ms + 1):
            fine.advance(t * 1_000_000)
        last_ms = t_ms
        coarse.advance(t_ms * 1_000_000)
        samples[t_ms] = [(d.actual_hz, d.read(6, 5, t_ms * 1_000_000)) for d in (fine, coarse)]
        if command is not None:
            for drive in (fine, coarse):
                drive.write(eaton.REG_CONTROL_WORD, [command], t_ms * 1_000_000)
    for t_ms, (a, b) in samples.items():
        assert a == b, t_ms
    assert samples[3_000][0][0] == 30.0  # 3 s x 50 Hz / 5 s
    assert samples[7_300][0][0] == -13.0  # 30 -> 0 in 3 s, then 1.3 s x 10 Hz/s towards -43.7
    assert samples[10_000][0] == (0.0, [IDLE, 0, 0, 0, 0])  # -13 -> 0 in 1.3 s: stopped at 8.6 s


# ---------------------------------------------------------------- control word


def test_reverse_ramps_down_through_zero_and_up_the_other_way():
    master = at_50hz(Family.DA1)
    master.write(eaton.REG_CONTROL_WORD, RUN | REV)
    master.wait(2.5)
    assert master.drive.actual_hz == 25.0 and SW.REVERSE not in master.flags
    master.wait(2.5)
    assert master.drive.actual_hz == 0.0 and master.drive.running
    master.wait(2.5)
    assert master.drive.actual_hz == -25.0
    assert master.speed_raw == 250  # ID 7 carries no sign; status bit 2 the direction (A24)
    assert SW.REVERSE in master.flags and SW.AT_SETPOINT not in master.flags
    master.wait(2.5)
    assert master.drive.actual_hz == -50.0 and SW.AT_SETPOINT in master.flags


@pytest.mark.parametrize("family", ALL)
def test_clearing_run_ramps_down_and_stops(family):
    master = at_50hz(family)
    master.write(eaton.REG_CONTROL_WORD, 0)
    master.wait(2.5)
    assert master.speed_raw == 250 and SW.RUNNING in master.flags
    master.wait(2.5)
    assert not master.drive.running
    assert master.flags == IDLE


def test_coast_stops_the_output_at_once_and_needs_a_new_run_edge():
    master = at_50hz(Family.DC1)
    master.write(eaton.REG_CONTROL_WORD, RUN | COAST)
    assert master.drive.actual_hz == 0.0 and not master.drive.running
    master.write(eaton.REG_CONTROL_WORD, RUN)
    master.wait(1.0)
    assert not master.drive.running
    master.write(eaton.REG_CONTROL_WORD, 0)
    master.write(eaton.REG_CONTROL_WORD, RUN)
    master.wait(1.0)
    assert master.drive.actual_hz == 10.0


@pytest.mark.parametrize("family, number", [(Family.DA1, "P2-25"), (Family.DB1, "P-24"), (Family.DC1, "P-24")])
def test_quick_stop_uses_ramp_2(family, number):
    master = at_50hz(family)
    # 200 counts = 2.00 s: DA1 FS2 counts 0.01 s (L1332), DB1/DC1 "300 ≙ 3.00 s" (L1659)
    master.param(number, 200)
    master.write(eaton.REG_CONTROL_WORD, RUN | QUICK)
    master.wait(1.0)
    assert master.drive.actual_hz == 25.0
    master.wait(1.0)
    assert not master.drive.running


# ---------------------------------------------------------------- faults and enable


@pytest.mark.parametrize("family", ALL)
def test_fault_coasts_and_a_reset_edge_clears_it(family):
    master = at_50hz(family)
    master.drive.trip(4)  # I.t-trP, motor overload
    word = master.read(eaton.REG_STATUS_WORD)[0]
    assert word == 4 << 8 | SW.FAULT | SW.ZERO_SPEED | SW.HARDWARE_ENABLE
    assert master.drive.actual_hz == 0.0 and not master.drive.running
    master.write(eaton.REG_CONTROL_WORD, RUN | RESET)  # rising edge of bit 2
    assert master.drive.fault == 0 and master.flags == IDLE
    master.wait(1.0)
    assert not master.drive.running  # RUN was never released: no new edge
    master.drive.trip(11)
    master.write(eaton.REG_CONTROL_WORD, RUN | RESET)  # bit 2 held: no edge, no reset
    assert eaton.fault_number(master.drive.status()) == 11
    master.write(eaton.REG_CONTROL_WORD, 0)
    master.write(eaton.REG_CONTROL_WORD, RESET)
    master.write(eaton.REG_CONTROL_WORD, RUN)
    master.wait(1.0)
    assert master.drive.actual_hz == 10.0


@pytest.mark.parametrize("family", ALL)
def test_losing_the_hardware_enable_coasts(family):
    master = at_50hz(family)
    master.drive.di1 = False
    assert not master.drive.running and master.drive.actual_hz == 0.0
    assert master.read(eaton.REG_STATUS_WORD) == [0]
    assert master.read(eaton.REG_DI_STATUS) == [0]
    master.drive.di1 = True
    master.wait(1.0)
    assert not master.drive.running and master.flags == IDLE
    master.write(eaton.REG_CONTROL_WORD, 0)
    master.write(eaton.REG_CONTROL_WORD, RUN)
    master.wait(1.0)
    assert master.drive.running


# ---------------------------------------------------------------- communication loss


def test_da1_trips_after_p5_05_without_telegrams():
    master = at_50hz(Family.DA1)  # P5-05 factory 20 = 2.0 s (L387), P5-06 factory 0 = trip
    master.wait(1.9, poll=False)
    assert master.drive.running
    master.wait(0.2, poll=False)
    assert master.drive.fault == eaton_faults.COMM_LOSS_FAULT and not master.drive.running
    assert master.drive.status() >> 8 == 50
    assert master.drive.status() & 0xFF == SW.FAULT | SW.ZERO_SPEED | SW.HARDWARE_ENABLE
    master.write(eaton.REG_CONTROL_WORD, RESET)  # telegrams are back: the reset works
    assert master.drive.fault == 0


@pytest.mark.parametrize(
    "action, at_4_5s, at_7_1s, fault",
    [
        (eaton_settings.Da1CommLossAction.TRIP, 0.0, 0.0, 50),
        (eaton_settings.Da1CommLossAction.RAMP_STOP_THEN_TRIP, 25.0, 0.0, 50),
        (eaton_settings.Da1CommLossAction.RAMP_STOP_NO_FAULT, 25.0, 0.0, 0),
        (eaton_settings.Da1CommLossAction.FIXED_FREQUENCY_8, 25.0, 10.0, 0),
    ],
)
def test_da1_comm_loss_actions(action, at_4_5s, at_7_1s, fault):
    master = at_50hz(Family.DA1)
    master.param(eaton_settings.DA1_COMM_LOSS_ACTION, action)
    master.param("P2-08", eaton.PARAMETER_FREQUENCY.to_raw(10.0))
    master.wait(4.5, poll=False)  # loss at 2.0 s, then 2.5 s of a 5 s ramp from 50 Hz
    assert master.drive.actual_hz == at_4_5s
    master.wait(2.6, poll=False)
    assert master.drive.actual_hz == at_7_1s
    assert master.drive.fault == fault
    assert master.drive.running == (action is eaton_settings.Da1CommLossAction.FIXED_FREQUENCY_8)


def test_da1_after_a_no_fault_ramp_stop_run_needs_a_new_edge():
    master = at_50hz(Family.DA1)
    master.param(eaton_settings.DA1_COMM_LOSS_ACTION, eaton_settings.Da1CommLossAction.RAMP_STOP_NO_FAULT)
    master.wait(10.0, poll=False)
    assert not master.drive.running and master.flags == IDLE
    master.write(eaton.REG_CONTROL_WORD, RUN)  # the PLC is back, RUN still set
    master.wait(1.0)
    assert not master.drive.running
    master.write(eaton.REG_CONTROL_WORD, 0)
    master.write(eaton.REG_CONTROL_WORD, RUN)
    master.wait(1.0)
    assert master.drive.actual_hz == 10.0


def test_da1_fixed_frequency_8_ends_when_telegrams_return():
    master = at_50hz(Family.DA1)
    master.param(eaton_settings.DA1_COMM_LOSS_ACTION, eaton_settings.Da1CommLossAction.FIXED_FREQUENCY_8)
    master.wait(8.0, poll=False)
    assert master.drive.actual_hz == 10.0  # default P2-08 of the simulator
    master.wait(5.0)
    assert master.drive.actual_hz == 50.0


def test_da1_p5_05_zero_switches_the_watchdog_off():
    master = at_50hz(Family.DA1)
    master.param(eaton_settings.DA1_COMM_TIMEOUT, 0)
    master.wait(60.0, poll=False)
    assert master.drive.running and master.drive.fault == 0


def _set_timeout_code(master: Master, code: int) -> None:
    row = next(r for r in eaton_parameters.parameter_rows(master.family, "P-36") if "Timeout" in r.name)
    master.write(row.register, row.insert(master.drive.register(row.register), code))


@pytest.mark.parametrize("family", [Family.DB1, Family.DC1, Family.DE1])
@pytest.mark.parametrize(
    "code, at_40ms, at_2_54s, fault",
    [
        (1, 0.0, 0.0, 50),  # t 30 ms: trips
        (5, 49.9, 24.9, 0),  # r 30 ms: ramps down at 10 Hz/s from 30 ms on, no fault
        (0, 50.0, 50.0, 0),  # off
    ],
)
def test_compact_comm_timeout_codes(family, code, at_40ms, at_2_54s, fault):
    master = at_50hz(family)
    _set_timeout_code(master, code)  # the write is the last telegram
    master.wait(0.030, poll=False)
    assert master.drive.running  # a telegram now would still be in time
    master.wait(0.010, poll=False)
    assert master.drive.actual_hz == at_40ms
    master.wait(2.5, poll=False)
    assert master.drive.actual_hz == at_2_54s
    master.wait(60.0, poll=False)
    assert master.drive.fault == fault
    assert master.drive.running == (code == 0)


@pytest.mark.parametrize("family, factory_trips_after", [(Family.DB1, 3.0), (Family.DC1, 3.0), (Family.DE1, None)])
def test_compact_factory_timeouts(family, factory_trips_after):
    master = at_50hz(family)  # DB1/DC1 code 4 "t 3000 ms" (L400, L423, A8), DE1 0 (L445)
    master.wait(2.99, poll=False)
    assert master.drive.running
    master.wait(0.02, poll=False)
    assert master.drive.fault == (0 if factory_trips_after is None else eaton_faults.COMM_LOSS_FAULT)


@pytest.mark.parametrize("family", [Family.DA1, Family.DB1])
def test_no_watchdog_before_the_first_telegram(family):
    drive = EatonDriveModel(family)
    drive.write(eaton.REG_SPEED_SETPOINT, [500], 0)  # writes without telegram(): no connection yet
    drive.write(eaton.REG_CONTROL_WORD, [RUN], 0)
    drive.advance(60 * S)
    assert drive.running and drive.fault == 0
    drive.telegram(60 * S)
    drive.advance(64 * S)
    assert drive.fault == eaton_faults.COMM_LOSS_FAULT


# ---------------------------------------------------------------- ramps and control source


@pytest.mark.parametrize(
    "family, switch, on, off",
    [
        (Family.DA1, eaton_parameters.DA1_FIELDBUS_RAMP_CONTROL, 1, 0),  # P5-07 (L389)
        (Family.DB1, "P-12", eaton_parameters.DB1_DC1_MODBUS_RAMPS_SOURCE, 3),  # L397
        (Family.DC1, "P-12", eaton_parameters.DB1_DC1_MODBUS_RAMPS_SOURCE, 3),  # L413
    ],
)
def test_id4_ramp_time_only_with_the_bus_ramp_switch(family, switch, on, off):
    for value, expected in ((off, 250), (on, 125)):
        master = Master(family)
        master.param(switch, value)
        master.write(eaton.REG_RAMP_TIME, 1000)  # 10.00 s (0.01 s, L807)
        master.run(50.0)
        master.wait(2.5)
        assert master.speed_raw == expected, value
        master.write(eaton.REG_CONTROL_WORD, 0)  # the bus ramp decelerates too
        master.wait(1.0)
        assert master.speed_raw == expected - (100 if value == off else 50)


@pytest.mark.parametrize("family", ALL)
def test_run_is_ignored_when_the_control_source_is_not_modbus(family):
    master = Master(family)
    master.param(eaton_parameters.CONTROL_SOURCE_PARAMETER[family], 0)  # terminal control
    master.run(50.0)
    master.wait(2.0)
    assert not master.drive.running
    assert master.drive.register(eaton.REG_CONTROL_WORD) == RUN  # stored all the same
    assert SW.READY not in master.flags


# ---------------------------------------------------------------- refusals


@pytest.mark.parametrize("family", ALL)
def test_refused_reads(family):
    master = Master(family)
    with pytest.raises(ModbusRefusal) as refusal:
        master.read(5)  # in no register group (digest §3.1)
    assert refusal.value.code == 2
    assert len(master.read(6, 11)) == 11
    with pytest.raises(ModbusRefusal) as refusal:
        master.read(6, 12)  # at most 11 registers per FC03 (L667)
    assert refusal.value.code == 3
    with pytest.raises(ModbusRefusal) as refusal:
        master.read(1000)
    assert refusal.value.code == 2


@pytest.mark.parametrize(
    "family, stop_only, reserved",
    [
        (Family.DA1, "P1-07", "P3-14"),
        (Family.DB1, "P-07", None),
        (Family.DC1, "P-09", None),
        (Family.DE1, "P-01", None),
    ],
)
def test_refused_writes(family, stop_only, reserved):
    master = Master(family)
    for register in (eaton.REG_STATUS_WORD, eaton.REG_DEVICE_ID, 5):
        with pytest.raises(ModbusRefusal) as refusal:
            master.write(register, 0)
        assert refusal.value.code == 2
    if reserved:
        with pytest.raises(ModbusRefusal) as refusal:
            master.param(reserved, 1)
        assert refusal.value.code == 2
    register = eaton_parameters.parameter_register(family, stop_only)
    value = master.drive.register(register)
    master.write(register, value)  # stopped: accepted
    master.run(50.0)
    master.wait(0.1)
    with pytest.raises(ModbusRefusal) as refusal:
        master.write(register, value)
    assert refusal.value.code == 3
    accel = eaton_parameters.parameter_register(family, "P1-03" if family is Family.DA1 else "P-03")
    master.write(accel, master.drive.register(accel))  # a RUN parameter while running: accepted


@pytest.mark.parametrize("family", [Family.DB1, Family.DC1])
def test_block_write_over_the_missing_register_3_changes_nothing(family):
    master = Master(family)
    with pytest.raises(ModbusRefusal) as refusal:
        master.write(eaton.REG_CONTROL_WORD, RUN, 500, 0, 300)  # IDs 1-4; DB1/DC1 have no ID 3 (A11)
    assert refusal.value.code == 2
    assert master.drive.register(eaton.REG_CONTROL_WORD) == 0 and not master.drive.running


def test_out_of_range_values_are_refused():
    master = Master(Family.DA1)
    for register, value in (
        (eaton.REG_RAMP_TIME, 60001),
        (eaton.REG_TORQUE_SETPOINT, 2001),
        (eaton_parameters.parameter_register(Family.DA1, eaton_settings.DA1_COMM_LOSS_ACTION), 4),
        (eaton_parameters.parameter_register(Family.DA1, eaton_settings.DA1_COMM_TIMEOUT), 51),
    ):
        with pytest.raises(ModbusRefusal) as refusal:
            master.write(register, value)
        assert refusal.value.code == 3
    master.write(eaton.REG_RAMP_TIME, 60000)
    dc1 = Master(Family.DC1)
    with pytest.raises(ModbusRefusal):
        _set_timeout_code(dc1, 9)  # P-36 timeout codes 0..8 (L423)
