"""LTMR bit registers (bits.py) with the manual's own numbers (the register
tables of manual 001; digest 001 §6-7)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.ltmr import bits as ltmr_bits
from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr.bits import (
    AlarmRegister1,
    Control1,
    Control2,
    GeneralConfig1,
    Status1,
    Status2,
    TripRegister1,
)

# ---------------------------------------------------------------------------
# Bits (register tables)
# ---------------------------------------------------------------------------


def test_status1_bits_as_printed():
    # 455, L3516-3543
    assert [
        Status1.READY,
        Status1.ON,
        Status1.TRIP,
        Status1.ALARM,
        Status1.TRIPPED,
        Status1.RESET_AUTHORIZED,
        Status1.CONTROLLER_POWER,
        Status1.RUNNING,
    ] == [1 << bit for bit in range(8)]
    assert (Status1.IN_REMOTE, Status1.STARTING) == (1 << 14, 1 << 15)
    assert (ltmr_bits.STATUS1_CURRENT_SHIFT, ltmr_bits.STATUS1_CURRENT_MASK) == (8, 0x3F)


def test_status1_sample_word():
    # digest 001 §6.3 DERIVED: ready + on + running + ratio 32 + in remote = 0x6083
    word = Status1.READY | Status1.ON | Status1.RUNNING | Status1.IN_REMOTE
    word = int(word) | ltmr_bits.current_ratio_field(100) << ltmr_bits.STATUS1_CURRENT_SHIFT
    assert word == 0x6083
    decoded = Status1(0x6083 & ~(ltmr_bits.STATUS1_CURRENT_MASK << ltmr_bits.STATUS1_CURRENT_SHIFT))
    assert Status1.RUNNING in decoded and Status1.IN_REMOTE in decoded and Status1.READY in decoded
    assert Status1.TRIPPED not in decoded and Status1.STARTING not in decoded
    field = (0x6083 >> ltmr_bits.STATUS1_CURRENT_SHIFT) & ltmr_bits.STATUS1_CURRENT_MASK
    assert field == 32 and ltmr_bits.current_ratio_percent(field) == 100.0


def test_current_ratio_field_scale():
    # "32 = 100% FLC - 63 = 200% FLC": linear 32 per 100 %, 63 is the saturated top (A14)
    assert ltmr_bits.current_ratio_field(100) == 32
    assert ltmr_bits.current_ratio_field(0) == 0
    assert ltmr_bits.current_ratio_field(50) == 16
    assert ltmr_bits.current_ratio_field(196.875) == 63
    assert ltmr_bits.current_ratio_field(200) == 63 and ltmr_bits.current_ratio_field(600) == 63
    assert ltmr_bits.current_ratio_field(10) == 3  # 3.2 rounds to 3
    assert ltmr_bits.current_ratio_percent(63) == pytest.approx(196.875)
    assert ltmr_bits.current_ratio_percent(1) == pytest.approx(3.125)


def test_status2_bits_as_printed():
    # 456, L3544-3571
    assert (
        Status2.AUTO_RESET_ACTIVE,
        Status2.POWER_CYCLE_REQUESTED,
        Status2.RESTART_TIME_UNDEFINED,
        Status2.RAPID_CYCLE_LOCKOUT,
        Status2.LOAD_SHEDDING,
        Status2.SPEED_FLC2,
        Status2.HMI_COMM_LOSS,
        Status2.NETWORK_COMM_LOSS,
        Status2.TRANSITION_LOCKOUT,
    ) == (1, 4, 8, 16, 32, 64, 128, 256, 512)
    assert Status2.NETWORK_COMM_LOSS == 0x0100  # TPDO1 byte 3 = 01 (digest 001 §7.2)


def test_control_words_of_the_rpdo1_vectors():
    # digest 001 §7.2 RPDO1 frames: run forward 01, run reverse 02, trip reset 08, forward + low speed 41
    assert Control1.RUN_FORWARD == 0x01 and Control1.RUN_REVERSE == 0x02 and Control1.TRIP_RESET == 0x08
    assert Control1.RUN_FORWARD | Control1.LOW_SPEED == 0x41
    assert Control1.SELF_TEST == 1 << 5
    assert [
        Control2.CLEAR_ALL,
        Control2.CLEAR_STATISTICS,
        Control2.CLEAR_THERMAL_CAPACITY,
        Control2.CLEAR_CONTROLLER_SETTINGS,
        Control2.CLEAR_NETWORK_SETTINGS,
    ] == [1, 2, 4, 8, 16]


def test_trip_and_alarm_register_bits():
    # 452 and 461 (L3423-3458, L3688-3717)
    assert (
        TripRegister1.GROUND_CURRENT,
        TripRegister1.THERMAL_OVERLOAD,
        TripRegister1.LONG_START,
        TripRegister1.JAM,
        TripRegister1.CURRENT_PHASE_IMBALANCE,
        TripRegister1.UNDERCURRENT,
    ) == (1 << 2, 1 << 3, 1 << 4, 1 << 5, 1 << 6, 1 << 7)
    assert (
        TripRegister1.TEST,
        TripRegister1.HMI_PORT,
        TripRegister1.CONTROLLER_INTERNAL,
        TripRegister1.INTERNAL_PORT,
        TripRegister1.NETWORK_PORT_CONFIG,
        TripRegister1.NETWORK_PORT,
    ) == (1 << 9, 1 << 10, 1 << 11, 1 << 12, 1 << 14, 1 << 15)
    assert (AlarmRegister1.THERMAL_OVERLOAD, AlarmRegister1.CONTROLLER_TEMPERATURE, AlarmRegister1.NETWORK_PORT) == (
        1 << 3,
        1 << 11,
        1 << 15,
    )
    assert 1 << 4 not in {int(m) for m in AlarmRegister1}  # bit 4 "(Not significant)"


def test_configuration_bits():
    assert GeneralConfig1.CONFIG_MODE == 1 and GeneralConfig1.CONFIG_VIA_NETWORK == 1 << 10
    assert (GeneralConfig1.CONFIG_VIA_HMI_KEYPAD, GeneralConfig1.CONFIG_VIA_HMI_TOOL) == (1 << 8, 1 << 9)
    # the network port trip / alarm enables: bit 15 of 631 and 632
    assert ltmr_bits.NETWORK_PORT_TRIP_ENABLE == 0x8000 and ltmr_bits.NETWORK_PORT_ALARM_ENABLE == 0x8000
    assert ltmr_bits.FACTORY_SETTINGS[ltmr.REG_GENERAL_CONFIG_1] & GeneralConfig1.CONFIG_VIA_NETWORK
    assert ltmr.BIT_NOTES[601][0] == "A" and ltmr.BIT_NOTES[602][0] == "C"
