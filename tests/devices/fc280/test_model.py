"""The FC 280 drive model alone (no bus), in virtual nanoseconds: the
parameter memory with save and restore, the FC profile (manual 003 §4.4),
the DSP 402 state machine (§4.3, Tabelle 4.3), ramps, the control word
timeout 8-03/8-04, the lost master, alarms and warnings. Expected values
are worked out here from the manual and the factory settings: 3-03 = 50 Hz,
1-23 = 50 Hz, 1-25 = 1500 RPM, 3-41 = 3-42 = 3 s, 3-51 = 3-52 = 10 s,
3-81 = 1 s, 4-14 = 65 Hz, 3-19 = 300 RPM, 8-90 = 100 RPM."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.fc280.control import DspState
from softplc.runtime.devices.fc280.model import (
    CONTROL_WORD_TIMEOUT,
    DRIVE_INITIALISED,
    FIELDBUS_FAULT,
    OVER_CURRENT,
    Fc280Model,
)
from softplc.runtime.devices.fc280.profile import control_word, reference_raw
from softplc.runtime.devices.fc280.store import Refusal, Refused

S = 1_000_000_000
MS = 1_000_000
RUN, STOP, COAST, QUICK, DC, FREEZE = 0x047C, 0x043C, 0x0474, 0x046C, 0x0478, 0x045C  # digest 003 §4.5


class Drive:
    """A model and its time, in ms."""

    def __init__(self, **parameters) -> None:
        self.m = Fc280Model({k.replace("_", "-"): v for k, v in parameters.items()})
        self.t = 0

    def after(self, ms: float) -> Drive:
        self.t += round(ms * MS)
        self.m.advance(self.t)
        return self

    def write(self, number: str, raw: int, sub: int = 0) -> Drive:
        self.m.write(number, raw, self.t, sub)
        return self

    def ctw(self, word: int, reference: float | None = None) -> Drive:
        if reference is not None:
            raw = reference_raw(reference)
            self.write("16-82", raw - 0x10000 if raw & 0x8000 else raw)  # Int16
        return self.write("16-80", word)

    def sending(self, word: int, ms: int, every_ms: int = 100) -> Drive:
        """A master repeating the control word for ms."""
        for _ in range(ms // every_ms):
            self.ctw(word).after(every_ms)
        return self.ctw(word)

    def cw(self, word: int) -> Drive:
        self.m.dsp_control(word, self.t)
        return self

    @property
    def hz(self) -> float:
        return self.m.output_hz

    @property
    def stw(self) -> int:
        return self.m.read("16-03")

    @property
    def sw(self) -> int:
        return self.m.dsp_status_word()


def running_at(percent: float = 50.0, **parameters) -> Drive:
    drive = Drive(**parameters).ctw(RUN, percent)
    return drive.after(5000)


# ---------------------------------------------------------------------------- parameters


def test_factory_settings_and_presets():
    m = Fc280Model({"8-03": 50, "3-10": [100, 200]})
    assert m.read("8-03") == 50 and m.read("8-04") == 0 and m.read("8-10") == 0  # Tabelle 6.1
    assert [m.read("3-10", i) for i in range(3)] == [100, 200, 0]
    assert m.read("15-40") == "FC 280"
    with pytest.raises(ValueError):
        Fc280Model({"16-03": 1})  # a readout takes no preset
    with pytest.raises(ValueError):
        Fc280Model({"8-10": 5})  # [5] is not an option of 8-10 (A16)


@pytest.mark.parametrize(
    "number, raw, sub, reason",
    [
        ("8-04", 6, 0, Refusal.HIGH),
        ("8-03", 0, 0, Refusal.LOW),  # 0.1 s the least
        ("10-02", 0, 0, Refusal.LOW),
        ("10-02", 128, 0, Refusal.HIGH),
        ("8-10", 5, 0, Refusal.RANGE),  # only [0] and [7]
        ("10-01", 19, 0, Refusal.RANGE),  # no [19] (A33)
        ("10-31", 1, 0, Refusal.RANGE),
        ("16-90", 0, 0, Refusal.READ_ONLY),
        ("16-03", 0, 0, Refusal.READ_ONLY),
        ("3-10", 0, 8, Refusal.NO_ELEMENT),
        ("3-10", 10001, 1, Refusal.HIGH),
    ],
)
def test_writes_outside_the_range_are_refused(number, raw, sub, reason):
    m = Fc280Model()
    with pytest.raises(Refused) as refused:
        m.write(number, raw, 0, sub)
    assert refused.value.reason is reason


def test_8_02_cannot_change_while_the_motor_runs():
    drive = running_at()
    with pytest.raises(Refused) as refused:
        drive.write("8-02", 1)
    assert refused.value.reason is Refusal.STATE  # chapter 6: "bei laufendem Motor nicht"
    drive.ctw(STOP).after(5000).write("8-02", 1)


def test_written_values_are_volatile_until_saved():
    m = Fc280Model()
    m.write("8-03", 50, 0)
    m.power_cycle(S)
    assert m.read("8-03") == 10  # §3.1.5: RAM only
    m.write("8-03", 50, S)
    m.save(2)  # communication parameters only
    m.power_cycle(2 * S)
    assert m.read("8-03") == 10
    m.write("8-03", 50, 2 * S)
    m.save(4)  # drive parameters
    m.write("8-04", 2, 2 * S)
    m.power_cycle(3 * S)
    assert (m.read("8-03"), m.read("8-04")) == (50, 0)
    with pytest.raises(Refused):
        m.save(3)  # reserved


def test_10_31_saves_and_returns_to_off_10_33_saves_every_write():
    m = Fc280Model()
    m.write("8-03", 50, 0)
    m.write("10-31", 2, 0)  # [2] Store all setups
    assert m.read("10-31") == 0  # "kehrt zu [0] Aus zurück"
    m.write("10-33", 1, 0)  # [1] Ein
    m.write("8-04", 3, 0)
    m.power_cycle(S)
    assert (m.read("8-03"), m.read("8-04"), m.read("10-33")) == (50, 3, 1)


def test_restore_applies_at_the_next_power_cycle_with_alarm_80():
    m = Fc280Model({"8-03": 50}, kept={"10-02": 5})
    m.write("8-04", 5, 0)
    m.save(1)
    m.restore(1)
    assert m.read("8-04") == 5  # not before the power cycle (§7.1.10)
    m.reset_node(S)
    assert m.read("8-04") == 5 and not m.tripped  # NMT reset node is no power cycle
    m.power_cycle(2 * S)
    assert (m.read("8-03"), m.read("8-04"), m.read("10-02")) == (10, 0, 5)  # the node id stays the configuration's
    assert m.read("16-90") == DRIVE_INITIALISED  # Alarm 80 (§3.1.5 HINWEIS)
    assert m.read("16-03") & 0x0008
    m.write("16-80", STOP, 2 * S)
    m.write("16-80", STOP | 0x80, 2 * S)
    assert m.read("16-90") == 0 and not m.tripped
    m.power_cycle(3 * S)
    assert not m.tripped  # once


# ---------------------------------------------------------------------------- FC profile


def test_power_up_status_and_a_run_with_its_ramp():
    drive = Drive()
    assert drive.stw == 0x0603  # control and drive ready, bus control, frequency limit ok; coasting
    drive.ctw(RUN, 50.0)  # 047C, 2000h
    assert drive.stw == 0x0E07  # start given: running, not yet at the reference
    drive.after(1000)
    assert drive.hz == pytest.approx(50 / 3)  # 3-41: 3 s for 50 Hz (3-03)
    drive.after(500)
    assert drive.hz == 25.0 and drive.stw == 0x0F07  # digest 003 §4.6
    assert drive.m.read("16-05") == 0x2000  # HIW scaled as the reference (§4.4.4)
    drive.ctw(STOP).after(750)
    assert drive.hz == 12.5  # 3-42: 3 s for 50 Hz
    drive.after(750)
    assert drive.hz == 0 and drive.stw == 0x0607


def test_a_word_without_data_valid_is_ignored():
    drive = running_at()
    drive.ctw(STOP & ~0x0400).after(5000)  # bit 10 = 0
    assert drive.hz == 25.0 and drive.m.read("16-80") == STOP & ~0x0400
    drive.ctw(0x0000).after(5000)
    assert drive.hz == 25.0  # 0000 does not stop the drive (digest 003 §4.5)


def test_coast_quick_stop_and_dc_brake():
    drive = running_at(100.0)
    drive.ctw(QUICK).after(500)
    assert drive.hz == 25.0  # 3-81: 1 s for 50 Hz
    drive.after(500)
    assert drive.hz == 0
    drive = running_at(100.0)
    drive.ctw(COAST)
    assert drive.hz == 0 and drive.stw == 0x0603  # bit 2 = 0: coasting
    drive = running_at(100.0)
    drive.ctw(DC)
    assert drive.hz == 0 and drive.m.dc_braking and drive.stw & 0x0004
    drive.after(9990)
    assert drive.m.dc_braking
    drive.after(10)
    assert not drive.m.dc_braking  # 2-02: 10.0 s


def test_hold_output_frequency_stops_only_by_coast_or_dc_brake():
    drive = Drive().ctw(RUN, 100.0).after(1500)
    assert drive.hz == 25.0
    drive.ctw(FREEZE, 20.0).after(3000)
    assert drive.hz == 25.0
    drive.ctw(FREEZE & ~0x0040).after(3000)  # ramp stop with bit 5 = 0: still held
    assert drive.hz == 25.0
    drive.ctw(FREEZE & ~0x0010).after(3000)  # quick stop too
    assert drive.hz == 25.0
    drive.ctw(FREEZE & ~0x0008)
    assert drive.hz == 0


def test_jog_ramp_2_and_preset_references():
    drive = Drive().ctw(0x057C).after(1000)
    assert drive.hz == 10.0  # 3-19: 300 RPM = 10 Hz
    drive = Drive().ctw(0x053C).after(1000)
    assert drive.hz == 10.0  # bit 8 starts by itself (A23: simulator choice)
    drive = Drive().ctw(0x067C, 100.0).after(1000)
    assert drive.hz == 5.0  # 3-51: 10 s for 50 Hz
    drive = Drive(**{"3-10": [0, 2500, 5000]}).ctw(0x047D, 12.5).after(5000)
    assert drive.hz == 18.75  # bus 12.5 % + preset 3-10[1] 25 %: "werden addiert" (§4.4.4)
    drive.ctw(0x047E).after(5000)
    assert drive.hz == 31.25  # + 3-10[2] 50 %


def test_parameters_written_while_the_motor_runs_act_at_once():
    drive = Drive().ctw(RUN, 50.0).after(600)
    assert drive.hz == 10.0  # 3-41: 3 s for 50 Hz
    drive.write("3-41", 600).after(1200)  # 6 s for 50 Hz from here on
    assert drive.hz == 20.0
    drive.after(600)
    assert drive.hz == 25.0 and drive.stw == 0x0F07
    drive.write("4-14", 200)  # 20.0 Hz: the output is above the limit, the target is the limit
    assert drive.stw == 0x0A07  # neither at the reference nor inside the frequency limit
    drive.after(150)
    assert drive.hz == 22.5  # down with 3-42, 3 s for 50 Hz
    drive.after(150)
    assert drive.hz == 20.0 and drive.stw == 0x0B07 and drive.m.read("16-05") == 6554  # 40 % of 4000h
    drive.write("3-03", 100_000)  # 100 Hz: 16-05 is 20 % at once, the 20 Hz limit stays the target
    assert drive.m.read("16-05") == 3277 and drive.stw == 0x0B07
    drive.write("4-14", 650).after(600)  # back to 65 Hz: up to 50 % of 100 Hz, 6 s for 100 Hz
    assert drive.hz == 30.0


def test_a_restore_brings_the_factory_ramps_back_at_the_next_power_cycle():
    drive = Drive(**{"3-41": 600}).ctw(RUN, 50.0).after(1200)
    assert drive.hz == 10.0  # the preset's 6 s for 50 Hz
    drive.m.restore(4)
    drive.m.power_cycle(drive.t)
    assert drive.hz == 0 and drive.m.read("16-90") == DRIVE_INITIALISED
    drive.ctw(STOP).ctw(STOP | 0x80).ctw(RUN, 50.0).after(600)  # reset Alarm 80, start again
    assert drive.hz == 10.0  # the factory 3 s for 50 Hz


def test_reversing_and_the_8_54_selection():
    drive = Drive().ctw(control_word(run=True, reverse=True), 50.0).after(5000)
    assert control_word(run=True, reverse=True) == 0x847C
    assert drive.hz == -25.0 and drive.m.read("16-05") == 0xE000 - 0x10000  # -50 %
    drive = Drive(**{"8-54": 0}).ctw(0x847C, 50.0).after(5000)
    assert drive.hz == 25.0  # [0] Klemme: the bus bit does nothing


def test_negative_reference_with_reverse_runs_forward():
    # M16, §4.4.4: "-x- ergibt +"
    assert Drive().ctw(0x847C, -50.0).after(5000).hz == 25.0
    assert Drive().ctw(RUN, -50.0).after(5000).hz == -25.0


def test_reference_range_and_the_4_14_limit():
    drive = Drive(**{"3-00": 0, "3-02": 10_000}).ctw(RUN, 50.0).after(5000)
    assert drive.hz == 30.0  # min-max: 10 Hz + 50 % of 40 Hz
    assert drive.m.read("16-05") == 0x2000
    drive = Drive().ctw(RUN, 150.0).after(5000)
    assert drive.hz == 65.0  # 75 Hz asked, 4-14 = 65.0 Hz
    assert drive.stw == 0x0B07  # bit 10 = 0: at the limit; bit 8 = 0 ... not the reference


def test_relays_and_set_up_selection():
    drive = Drive(**{"5-40": [36, 37], "0-10": 9}).ctw(STOP | 0x0800 | 0x4000)
    assert drive.m.relay_01 and not drive.m.relay_04 and drive.m.active_setup == 3
    drive.ctw(STOP | 0x1000 | 0x2000)
    assert not drive.m.relay_01 and drive.m.relay_04 and drive.m.active_setup == 2
    assert Drive().ctw(STOP | 0x6000).m.active_setup == 1  # only with 0-10 = [9]
    assert not Drive().ctw(STOP | 0x0800).m.relay_01  # only with 5-40 = control word bit 11


def test_gating_by_8_01_and_8_5x():
    assert Drive(**{"8-50": 0}).ctw(COAST, 50.0).after(5000).hz == 25.0  # coast from the terminal only
    assert Drive(**{"8-53": 2}).ctw(RUN, 50.0).after(5000).hz == 0  # start: bus AND (idle) terminal
    assert Drive(**{"8-53": 0, "8-01": 2}).ctw(RUN, 50.0).after(5000).hz == 25.0  # control word only
    assert Drive(**{"8-01": 1}).ctw(RUN, 50.0).after(5000).hz == 0  # terminals only
    drive = Drive(**{"8-02": 1}).ctw(RUN, 50.0).after(5000)
    assert drive.hz == 0 and not drive.stw & 0x0200  # not the bus's control word


# ---------------------------------------------------------------------------- alarms and warnings


def test_a_trip_coasts_and_needs_a_rising_reset_edge():
    drive = running_at()
    drive.m.over_current()
    assert drive.hz == 0 and drive.m.read("16-90") == OVER_CURRENT
    assert drive.stw == 0x0608  # trip, bus control, frequency limit ok
    drive.ctw(0x04FC)  # 047C -> 04FC: the edge
    assert not drive.m.tripped and drive.stw & 0x0800  # the start is still there: it runs again
    drive.m.over_current()
    drive.ctw(0x04FC)
    assert drive.m.tripped  # no edge
    drive.ctw(RUN).ctw(0x04FC)
    assert not drive.m.tripped


def test_trip_lock_needs_a_power_cycle():
    drive = Drive()
    drive.m.trip(0x00001000, lock=True)  # short circuit
    assert drive.stw & 0x0048 == 0x0048
    drive.m.press_reset()
    assert drive.m.tripped
    drive.m.power_cycle(S)
    assert not drive.m.tripped


def test_warnings_show_in_the_status_words():
    drive = Drive()
    drive.m.warn(0x00000040)  # torque limit
    assert drive.stw == 0x0603 | 0x0080 | 0x4000 and drive.m.read("16-92") == 0x40
    drive.m.warn(0x00000001, "16-93")
    drive.m.clear_warning(0x00000040)
    assert drive.stw == 0x0683 and drive.m.read("16-93") == 1
    with pytest.raises(ValueError):
        drive.m.warn(1, "16-90")
    with pytest.raises(ValueError):
        drive.m.trip(1, word="16-92")


# ---------------------------------------------------------------------------- 8-03 / 8-04


def _timed_out(reaction: int, percent: float = 50.0) -> Drive:
    """Running at the reference, 8-03 = 1 s (the factory setting), then no
    control word: just past the timeout, which came 1 ms ago."""
    drive = Drive(**{"8-04": reaction}).ctw(RUN, percent).sending(RUN, 5000)
    drive.after(1001)
    assert drive.m.word_timed_out
    return drive


def test_timeout_off_keeps_the_last_word():
    drive = _timed_out(0).after(5000)
    assert drive.hz == 25.0 and drive.m.read("16-92") == 0


def test_timeout_starts_with_the_first_valid_word_and_only_valid_words_retrigger():
    drive = Drive(**{"8-04": 2}).after(10_000)
    assert not drive.m.word_timed_out
    drive.ctw(RUN, 50.0).after(900).ctw(RUN).after(900)
    assert not drive.m.word_timed_out
    drive.ctw(RUN & ~0x0400).after(101)  # A28: a word without bit 10 does not count
    assert drive.m.word_timed_out and drive.m.read("16-92") == CONTROL_WORD_TIMEOUT


def test_timeout_freeze():
    drive = Drive(**{"8-04": 1}).ctw(RUN, 100.0).after(1000)
    assert drive.hz == pytest.approx(50 / 3)
    drive.after(1)
    frozen = drive.hz
    drive.after(5000)
    assert drive.hz == frozen and drive.stw & 0x0080
    drive.ctw(RUN).after(900)  # communication back: the word counts again
    assert drive.hz == pytest.approx(frozen + 15) and drive.m.read("16-92") == 0


def test_timeout_stop_restarts_with_communication():
    drive = _timed_out(2).after(1499)
    assert drive.hz == 0 and drive.m.read("16-92") == CONTROL_WORD_TIMEOUT
    assert drive.stw == 0x0687  # stopped, warning
    drive.ctw(RUN).after(900)
    assert drive.hz == 15.0 and not drive.m.tripped


def test_timeout_jog_and_max_speed():
    assert _timed_out(3).after(900).hz == 10.0  # 3-19
    assert _timed_out(4).after(2400).hz == 65.0  # 4-14
    assert _timed_out(3, -50.0).after(900).hz == -10.0  # the direction it turns


def test_timeout_stop_and_alarm():
    drive = _timed_out(5).after(999)
    assert drive.hz == pytest.approx(25 / 3) and not drive.m.tripped  # ramping down
    drive.after(500)
    assert drive.hz == 0 and drive.m.read("16-90") == CONTROL_WORD_TIMEOUT  # then the alarm
    drive.ctw(RUN).after(900)
    assert drive.m.tripped and drive.hz == 0  # needs a reset
    drive.ctw(RUN | 0x0080).after(900)
    assert not drive.m.tripped and drive.hz == 15.0


def test_stop_and_alarm_is_latched_when_communication_returns_while_ramping_down():
    # 8-04 [5] (chapter 6): stops, then needs a reset; the restart on return is [2]'s
    drive = _timed_out(5).after(500)
    ramping = drive.hz
    drive.ctw(RUN).after(100)  # a valid word again, the motor still turning
    assert drive.hz < ramping and drive.m.read("16-92") == CONTROL_WORD_TIMEOUT  # the warning meanwhile
    drive.sending(RUN, 1000)
    assert drive.hz == 0 and drive.m.read("16-90") == CONTROL_WORD_TIMEOUT and drive.stw & 0x0008
    drive.m.press_reset()  # [Reset]: communication is back, so the drive runs
    drive.sending(RUN, 1500)
    assert drive.hz == 25.0 and not drive.m.tripped
    drive = Drive(**{"8-04": 5})
    drive.m.comm_lost(0)
    drive.m.press_reset()  # the master still gone: the alarm again
    assert drive.m.read("16-90") == FIELDBUS_FAULT


def test_a_lost_master_gets_the_8_04_function_and_warning_34():
    # A6: §3.1.4 (8-04) and §7.1.8 (warning 34): both
    drive = running_at(**{"8-04": 2, "8-03": 600})
    drive.m.comm_lost(drive.t)
    assert drive.m.read("16-92") == FIELDBUS_FAULT
    drive.after(1500)
    assert drive.hz == 0
    drive.m.comm_restored(drive.t)
    drive.after(1500)
    assert drive.hz == 25.0 and drive.m.read("16-92") == 0
    drive = Drive(**{"8-04": 5})
    drive.m.comm_lost(0)
    assert drive.m.read("16-90") == FIELDBUS_FAULT  # at standstill at once
    drive = Drive()
    drive.m.comm_lost(0)
    assert drive.m.read("16-92") == FIELDBUS_FAULT and not drive.m.tripped  # 8-04 [0]: the warning only


# ---------------------------------------------------------------------------- DSP 402


TABELLE_4_3 = [
    # (transition, control word, status word), in an order that walks every one
    (1, 0x0000, 0x0240),
    (2, 0x0006, 0x0231),
    (3, 0x0007, 0x0233),
    (4, 0x000F, 0x0237),
    (5, 0x0007, 0x0233),
    (6, 0x0006, 0x0231),
    (7, 0x0001, 0x0240),
    (2, 0x0006, 0x0231),
    (7, 0x0000, 0x0240),
    (2, 0x0006, 0x0231),
    (3, 0x0007, 0x0233),
    (10, 0x0001, 0x0240),
    (2, 0x0006, 0x0231),
    (3, 0x0007, 0x0233),
    (10, 0x0000, 0x0240),
    (2, 0x0006, 0x0231),
    (3, 0x0007, 0x0233),
    (4, 0x000F, 0x0237),
    (8, 0x0006, 0x0231),
    (3, 0x0007, 0x0233),
    (4, 0x000F, 0x0237),
    (9, 0x0001, 0x0240),
    (2, 0x0006, 0x0231),
    (3, 0x0007, 0x0233),
    (4, 0x000F, 0x0237),
    (9, 0x0000, 0x0240),
    (2, 0x0006, 0x0231),
    (3, 0x0007, 0x0233),
    (4, 0x000F, 0x0237),
    (11, 0x0002, 0x0207),
    (16, 0x000F, 0x0207),  # not supported: stays in quick stop active
    (12, 0x0001, 0x0240),
    (2, 0x0006, 0x0231),
    (3, 0x0007, 0x0233),
    (4, 0x000F, 0x0237),
    (11, 0x0002, 0x0207),
    (12, 0x0000, 0x0240),
]


def test_every_transition_of_tabelle_4_3():
    drive = Drive()
    assert drive.sw == 0x0000  # Startzustand: the FC profile
    drive.write("8-10", 7)
    assert drive.sw == 0x0200  # transition 0: not ready to switch on
    for transition, word, status in TABELLE_4_3:
        drive.cw(word)
        assert (transition, drive.sw) == (transition, status)
    drive.cw(0x0006).cw(0x000F)
    drive.m.over_current()
    assert drive.sw == 0x023F and drive.m.dsp_state == DspState.FAULT  # 13, 14 (A20: as printed)
    drive.cw(0x0000)
    assert drive.sw == 0x023F  # 15 needs the reset edge (A21)
    drive.cw(0x0080)
    assert drive.sw == 0x0240  # 15


def test_dsp_402_runs_in_rpm_with_the_velocity_mode_bits():
    drive = Drive(**{"8-10": 7}).cw(0x0006).cw(0x000F)
    drive.m.dsp_target(1500, drive.t)
    drive.after(5000)
    assert drive.hz == 0 and drive.sw == 0x0237  # A22: 000F enables, the motor does not follow
    drive.cw(0x007F).after(1500)
    assert drive.hz == 25.0 and drive.sw == 0x4237  # running, not yet at the reference
    drive.after(1500)
    assert drive.hz == 50.0 and drive.m.velocity_rpm == 1500 and drive.sw == 0x4737
    drive.cw(0x0007).after(1500)
    assert drive.hz == 25.0 and drive.sw == 0x4233  # transition 5: ramps down (3-42)
    drive.after(1500)
    assert drive.sw == 0x0233
    drive.cw(0x000F).cw(0x007F).after(3000).cw(0x0002).after(500)
    assert drive.hz == 25.0 and drive.sw == 0x4207  # transition 11: the quick stop ramp 3-81
    drive.after(500)
    assert drive.hz == 0 and drive.sw == 0x0207
    drive.cw(0x0000).cw(0x0006).cw(0x007F).after(3000).cw(0x0000)
    assert drive.hz == 0 and drive.sw == 0x0240  # transition 9: the power section off


def test_dsp_402_jog_reverse_and_speed_limit():
    drive = Drive(**{"8-10": 7}).cw(0x0006).cw(0x080F).after(1000)
    assert drive.hz == pytest.approx(10 / 3)  # 8-90: 100 RPM
    drive.cw(0x807F)
    drive.m.dsp_target(-750, drive.t)
    drive.after(3000)
    assert drive.hz == 25.0  # negative target with reverse: forward
    drive.m.dsp_target(3000, drive.t)
    drive.after(6000)
    assert drive.hz == -65.0 and drive.sw & 0x0800  # bit 11: at the 4-14 limit (A19)


def test_the_other_profiles_objects_are_refused():
    drive = Drive()
    with pytest.raises(Refused):
        drive.cw(0x0006)
    drive.write("8-10", 7)
    with pytest.raises(Refused) as refused:
        drive.ctw(RUN)
    assert refused.value.reason is Refusal.STATE
