"""LTMR data types, bits, enumerations and codes with the manual's own numbers
(manual 001 §5.4-5.5 and the register tables; digest 001 §6-7)."""
from __future__ import annotations

import datetime as dt

import pytest

from softplc.runtime.devices.ltmr import bits as ltmr_bits
from softplc.runtime.devices.ltmr import codes as ltmr_codes
from softplc.runtime.devices.ltmr import datatypes as ltmr_datatypes
from softplc.runtime.devices.ltmr import profile as ltmr_profile
from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr.bits import AlarmRegister1, Control1, Control2, GeneralConfig1, Status1, Status2, TripRegister1
from softplc.runtime.devices.ltmr.codes import FallbackStrategy, OperatingMode, ResetMode

# ---------------------------------------------------------------------------
# DT_DateTime (L1866-1966)
# ---------------------------------------------------------------------------


def test_manual_datetime_example_encodes():
    # "If date is September 4, 2008 at 7 a.m., 50 minutes and 32 seconds": 655 = 3 2 0 0,
    # 656 = 0 7 5 0, 657 = 0 9 0 4, 658 = 2 0 0 8 (nibbles 15-12 .. 3-0)
    assert ltmr_datatypes.encode_datetime(dt.datetime(2008, 9, 4, 7, 50, 32)) == (0x3200, 0x0750, 0x0904, 0x2008)


def test_manual_datetime_example_decodes():
    assert ltmr_datatypes.decode_datetime((0x3200, 0x0750, 0x0904, 0x2008)) == dt.datetime(2008, 9, 4, 7, 50, 32)


@pytest.mark.parametrize("when, words", [
    (dt.datetime(2006, 1, 1, 0, 0, 0), (0x0000, 0x0000, 0x0101, 0x2006)),    # minimum DT#2006-01-01:00:00:00
    (dt.datetime(2099, 12, 31, 23, 59, 59), (0x5900, 0x2359, 0x1231, 0x2099)),   # maximum DT#2099-12-31-23:59:59
    (dt.datetime(2008, 2, 29, 12, 0, 0), (0x0000, 0x1200, 0x0229, 0x2008)),   # a leap day
])
def test_datetime_limits_both_ways(when, words):
    assert ltmr_datatypes.encode_datetime(when) == words
    assert ltmr_datatypes.decode_datetime(words) == when


@pytest.mark.parametrize("when", [dt.datetime(2005, 12, 31, 23, 59, 59), dt.datetime(2100, 1, 1)])
def test_datetime_outside_the_limits_is_an_error(when):
    # "If you give values outside the limits, the system will return a detected error."
    with pytest.raises(ValueError, match="outside"):
        ltmr_datatypes.encode_datetime(when)


@pytest.mark.parametrize("words, why", [
    ((0x0000, 0x0000, 0x0229, 0x2007), "2007-02-29: not a leap year"),
    ((0x0000, 0x0000, 0x0931, 0x2008), "September has 30 days"),
    ((0x0000, 0x0000, 0x1301, 0x2008), "month 13"),
    ((0x6000, 0x0000, 0x0101, 0x2008), "second 60"),
    ((0x0000, 0x2400, 0x0101, 0x2008), "hour 24"),
    ((0x0000, 0x0000, 0x1231, 0x2005), "before 2006"),
    ((0x0000, 0x0000, 0x0101, 0x2100), "after 2099"),
    ((0x3A00, 0x0750, 0x0904, 0x2008), "0xA is not a BCD digit"),
    ((0x3200, 0x0750, 0x0904, 0x20F8), "0xF in the year"),
])
def test_invalid_datetime_words_are_errors(words, why):
    with pytest.raises(ValueError):
        ltmr_datatypes.decode_datetime(words)


def test_datetime_drops_fractions_of_a_second():
    assert ltmr_datatypes.encode_datetime(dt.datetime(2008, 9, 4, 7, 50, 32, 999_000)) == (0x3200, 0x0750, 0x0904, 0x2008)


# ---------------------------------------------------------------------------
# DT_CommercialReference (L1817-1865), A16
# ---------------------------------------------------------------------------


def test_commercial_reference_example_with_spaces_or_nuls():
    # 64 = 'L','T'; 65 = 'M',(space); 66 = 'R',(blank); 67-69 blank. The caption says "LTMR".
    with_spaces = (0x4C54, 0x4D20, 0x5220, 0x2020, 0x2020, 0x2020)
    with_nuls = (0x4C54, 0x4D20, 0x5200, 0x0000, 0x0000, 0x0000)
    assert ltmr_datatypes.decode_commercial_reference(with_spaces) == "LTM R"
    assert ltmr_datatypes.decode_commercial_reference(with_nuls) == "LTM R"
    assert ltmr_datatypes.encode_commercial_reference("LTM R") == with_spaces


def test_commercial_reference_round_trip_and_limits():
    words = ltmr_datatypes.encode_commercial_reference("LTMR08CFM")
    assert len(words) == 6 and words[0] == 0x4C54
    assert ltmr_datatypes.decode_commercial_reference(words) == "LTMR08CFM"
    assert ltmr_datatypes.decode_commercial_reference(ltmr_datatypes.encode_commercial_reference("ABCDEFGHIJKL")) == "ABCDEFGHIJKL"
    with pytest.raises(ValueError):
        ltmr_datatypes.encode_commercial_reference("ABCDEFGHIJKLM")
    with pytest.raises(ValueError):
        ltmr_datatypes.encode_commercial_reference("LTMR Ω")


# ---------------------------------------------------------------------------
# Two-register values and signed registers (A5)
# ---------------------------------------------------------------------------


def test_udint_lower_register_is_msw_by_default():
    # digest 001 §7.2: 500/501 = 0x0000/0x04D2 -> 1234 -> 12.34 A (if the lower register is the MSW)
    value = ltmr_datatypes.udint_from_registers(0x0000, 0x04D2)
    assert value == 1234
    assert value * ltmr.REGISTERS[ltmr.REG_AVERAGE_CURRENT].scale == pytest.approx(12.34)
    assert ltmr_datatypes.udint_to_registers(1234) == (0x0000, 0x04D2)
    assert ltmr_datatypes.udint_from_registers(0x0001, 0x0002) == 0x00010002


def test_udint_other_word_order():
    assert ltmr_datatypes.udint_from_registers(0x04D2, 0x0000, msw_first=False) == 1234
    assert ltmr_datatypes.udint_to_registers(0x00010002, msw_first=False) == (0x0002, 0x0001)
    with pytest.raises(ValueError):
        ltmr_datatypes.udint_to_registers(-1)
    with pytest.raises(ValueError):
        ltmr_datatypes.udint_to_registers(1 << 32)


def test_signed_registers():
    assert ltmr_datatypes.int16(0xFFF6) == -10         # 472 controller internal temperature -10 °C
    assert ltmr_datatypes.int16(0x7FFF) == 32767 and ltmr_datatypes.int16(0x8000) == -32768 and ltmr_datatypes.int16(25) == 25
    assert ltmr_datatypes.dint_from_registers(0xFFFF, 0xFFFE) == -2
    assert ltmr.REGISTERS[472].type == "Int" and ltmr.REGISTERS[472].signed


def test_full_load_current():
    # 96 = 80 (8.0 A FLC max) and 652 = 50 % -> FLC1 = 4.0 A
    assert ltmr_datatypes.full_load_current_amps(80, 50) == pytest.approx(4.0)


# ---------------------------------------------------------------------------
# Bits (register tables)
# ---------------------------------------------------------------------------


def test_status1_bits_as_printed():
    # 455, L3516-3543
    assert [Status1.READY, Status1.ON, Status1.TRIP, Status1.ALARM, Status1.TRIPPED, Status1.RESET_AUTHORIZED,
            Status1.CONTROLLER_POWER, Status1.RUNNING] == [1 << bit for bit in range(8)]
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
    assert ltmr_bits.current_ratio_field(10) == 3          # 3.2 rounds to 3
    assert ltmr_bits.current_ratio_percent(63) == pytest.approx(196.875)
    assert ltmr_bits.current_ratio_percent(1) == pytest.approx(3.125)


def test_status2_bits_as_printed():
    # 456, L3544-3571
    assert (Status2.AUTO_RESET_ACTIVE, Status2.POWER_CYCLE_REQUESTED, Status2.RESTART_TIME_UNDEFINED,
            Status2.RAPID_CYCLE_LOCKOUT, Status2.LOAD_SHEDDING, Status2.SPEED_FLC2, Status2.HMI_COMM_LOSS,
            Status2.NETWORK_COMM_LOSS, Status2.TRANSITION_LOCKOUT) == (1, 4, 8, 16, 32, 64, 128, 256, 512)
    assert Status2.NETWORK_COMM_LOSS == 0x0100     # TPDO1 byte 3 = 01 (digest 001 §7.2)


def test_control_words_of_the_rpdo1_vectors():
    # digest 001 §7.2 RPDO1 frames: run forward 01, run reverse 02, trip reset 08, forward + low speed 41
    assert Control1.RUN_FORWARD == 0x01 and Control1.RUN_REVERSE == 0x02 and Control1.TRIP_RESET == 0x08
    assert Control1.RUN_FORWARD | Control1.LOW_SPEED == 0x41
    assert Control1.SELF_TEST == 1 << 5
    assert [Control2.CLEAR_ALL, Control2.CLEAR_STATISTICS, Control2.CLEAR_THERMAL_CAPACITY,
            Control2.CLEAR_CONTROLLER_SETTINGS, Control2.CLEAR_NETWORK_SETTINGS] == [1, 2, 4, 8, 16]


def test_trip_and_alarm_register_bits():
    # 452 and 461 (L3423-3458, L3688-3717)
    assert (TripRegister1.GROUND_CURRENT, TripRegister1.THERMAL_OVERLOAD, TripRegister1.LONG_START,
            TripRegister1.JAM, TripRegister1.CURRENT_PHASE_IMBALANCE, TripRegister1.UNDERCURRENT) == (
        1 << 2, 1 << 3, 1 << 4, 1 << 5, 1 << 6, 1 << 7)
    assert (TripRegister1.TEST, TripRegister1.HMI_PORT, TripRegister1.CONTROLLER_INTERNAL,
            TripRegister1.INTERNAL_PORT, TripRegister1.NETWORK_PORT_CONFIG, TripRegister1.NETWORK_PORT) == (
        1 << 9, 1 << 10, 1 << 11, 1 << 12, 1 << 14, 1 << 15)
    assert (AlarmRegister1.THERMAL_OVERLOAD, AlarmRegister1.CONTROLLER_TEMPERATURE,
            AlarmRegister1.NETWORK_PORT) == (1 << 3, 1 << 11, 1 << 15)
    assert 1 << 4 not in {int(m) for m in AlarmRegister1}      # bit 4 "(Not significant)"


def test_configuration_bits():
    assert GeneralConfig1.CONFIG_MODE == 1 and GeneralConfig1.CONFIG_VIA_NETWORK == 1 << 10
    assert (GeneralConfig1.CONFIG_VIA_HMI_KEYPAD, GeneralConfig1.CONFIG_VIA_HMI_TOOL) == (1 << 8, 1 << 9)
    # the network port trip / alarm enables: bit 15 of 631 and 632
    assert ltmr_bits.NETWORK_PORT_TRIP_ENABLE == 0x8000 and ltmr_bits.NETWORK_PORT_ALARM_ENABLE == 0x8000
    assert ltmr_bits.FACTORY_SETTINGS[ltmr.REG_GENERAL_CONFIG_1] & GeneralConfig1.CONFIG_VIA_NETWORK
    assert ltmr.BIT_NOTES[601][0] == "A" and ltmr.BIT_NOTES[602][0] == "C"


# ---------------------------------------------------------------------------
# Enumerations
# ---------------------------------------------------------------------------


def test_operating_modes():
    # 540: 2 = 2-wire overload ... 11 = 3-wire 2-speed, 256-511 custom logic
    assert [m.value for m in OperatingMode] == list(range(2, 12))
    assert OperatingMode.TWO_STEP_3W == 9 and OperatingMode.REVERSER_2W == 6
    assert ltmr_codes.is_custom_logic(256) and ltmr_codes.is_custom_logic(511)
    assert not ltmr_codes.is_custom_logic(255) and not ltmr_codes.is_custom_logic(512) and not ltmr_codes.is_custom_logic(11)


OVERLOAD, INDEPENDENT, REVERSER, TWO_STEP, TWO_SPEED, CUSTOM = 2, 5, 6, 9, 10, 300

# "Motor Modes" column of DT_OutputFallbackStrategy (L2171-2194)
FALLBACK_MATRIX = {
    FallbackStrategy.HOLD: {OVERLOAD, INDEPENDENT, REVERSER, TWO_STEP, TWO_SPEED, CUSTOM},    # all modes
    FallbackStrategy.RUN: {TWO_STEP},                                                         # 2-step only
    FallbackStrategy.OFF: {OVERLOAD, INDEPENDENT, REVERSER, TWO_STEP, TWO_SPEED, CUSTOM},     # all modes
    FallbackStrategy.BOTH_ON: {OVERLOAD, INDEPENDENT, CUSTOM},      # overload, independent and custom only
    FallbackStrategy.LO1_ON: {OVERLOAD, INDEPENDENT, REVERSER, TWO_SPEED, CUSTOM},            # except 2-step
    FallbackStrategy.LO2_ON: {OVERLOAD, INDEPENDENT, REVERSER, TWO_SPEED, CUSTOM},            # except 2-step
}


@pytest.mark.parametrize("strategy", list(FallbackStrategy))
def test_fallback_allowed_per_motor_mode(strategy):
    for mode in (OVERLOAD, INDEPENDENT, REVERSER, TWO_STEP, TWO_SPEED, CUSTOM):
        assert ltmr_codes.fallback_allowed(strategy, mode) == (mode in FALLBACK_MATRIX[strategy]), (strategy, mode)


def test_fallback_values_and_bad_arguments():
    assert [s.value for s in FallbackStrategy] == [0, 1, 2, 3, 4, 5]
    assert ltmr_codes.fallback_allowed(FallbackStrategy.RUN, OperatingMode.TWO_STEP_2W)
    with pytest.raises(ValueError):
        ltmr_codes.fallback_allowed(6, OVERLOAD)
    with pytest.raises(ValueError):
        ltmr_codes.fallback_allowed(FallbackStrategy.HOLD, 12)


def test_reset_modes_and_baud_codes():
    assert (ResetMode.MANUAL, ResetMode.REMOTE, ResetMode.AUTOMATIC) == (1, 2, 4)
    # "Network Port Baud Rate Setting" table (L183-206)
    assert ltmr_codes.CANOPEN_BAUD_CODES == {0: 10_000, 1: 20_000, 2: 50_000, 3: 125_000, 4: 250_000, 5: 500_000,
                                       6: 800_000, 7: 1_000_000, 8: None, 9: 250_000}


# ---------------------------------------------------------------------------
# Trip and alarm codes (L2043-2145, L2218-2278), copied
# ---------------------------------------------------------------------------

MANUAL_TRIP_CODES = {
    0: "No detected error", 3: "Ground current", 4: "Thermal overload", 5: "Long start", 6: "Jam",
    7: "Current phase imbalance", 8: "Undercurrent", 10: "Test", 11: "HMI port detected error",
    12: "HMI port communication loss", 13: "Network port internal detected error", 16: "External trip",
    18: "ON-OFF diagnostic", 19: "Wiring diagnostic", 20: "Overcurrent", 21: "Current phase loss",
    22: "Current phase reversal", 23: "Motor temp sensor", 24: "Voltage phase imbalance", 25: "Voltage phase loss",
    26: "Voltage phase reversal", 27: "Undervoltage", 28: "Overvoltage", 29: "Underpower", 30: "Overpower",
    31: "Under power factor", 32: "Over power factor", 33: "LTME configuration",
    34: "Temperature sensor short-circuit", 35: "Temperature sensor open-circuit", 36: "CT reversal",
    37: "Out of boundary CT ratio", 46: "Start check", 47: "Run checkback", 48: "Stop check", 49: "Stop checkback",
    51: "Controller internal temperature detected error",
    55: "Controller internal detected error (Stack overflow)",
    56: "Controller internal detected error (RAM detected error)",
    57: "Controller internal detected error (RAM checksum detected error)",
    58: "Controller internal detected error (Hardware watchdog trip)",
    60: "L2 current detected in single-phase mode", 64: "Non-volatile memory detected error",
    65: "Expansion module communication detected error", 66: "Stuck reset button",
    67: "Logic function detected error", 109: "Network port comm detected error",
    111: "Fast device replacement trip", 555: "Network port configuration detected error",
}
MANUAL_ALARM_CODES = {
    0: "No alarm", 3: "Ground current", 4: "Thermal overload", 5: "Long start", 6: "Jam",
    7: "Current phase imbalance", 8: "Undercurrent", 10: "HMI port", 11: "LTMR internal temperature",
    18: "Diagnostic", 19: "Wiring", 20: "Overcurrent", 21: "Current phase loss", 23: "Motor temp sensor",
    24: "Voltage phase imbalance", 25: "Voltage phase loss", 27: "Undervoltage", 28: "Overvoltage",
    29: "Underpower", 30: "Overpower", 31: "Under power factor", 32: "Over power factor",
    33: "LTME configuration", 46: "Start check", 47: "Run checkback", 48: "Stop check", 49: "Stop checkback",
    109: "Network port comm loss", 555: "Network port configuration",
}


def test_trip_codes_as_printed_with_100_104_expanded():
    expected = dict(MANUAL_TRIP_CODES)
    expected.update({code: "Network port internal detected error" for code in range(100, 105)})   # "100-104"
    assert ltmr_codes.TRIP_CODES == expected


def test_alarm_codes_as_printed():
    assert ltmr_codes.ALARM_CODES == MANUAL_ALARM_CODES


def test_code_texts():
    assert ltmr_codes.trip_text(ltmr_codes.TRIP_THERMAL_OVERLOAD) == "Thermal overload"
    assert ltmr_codes.trip_text(ltmr_codes.TRIP_TEST) == "Test" and ltmr_codes.alarm_text(10) == "HMI port"   # same number, two meanings
    assert ltmr_codes.trip_text(ltmr_codes.TRIP_NETWORK_COMM) == "Network port comm detected error"
    assert ltmr_codes.alarm_text(ltmr_codes.ALARM_NETWORK_COMM) == "Network port comm loss"
    assert ltmr_codes.alarm_text(ltmr_codes.ALARM_THERMAL_OVERLOAD) == "Thermal overload"
    assert ltmr_codes.trip_text(1) == "unknown trip code 1" and ltmr_codes.alarm_text(999) == "unknown alarm code 999"


# ---------------------------------------------------------------------------
# PDO defaults and identity (manual §4)
# ---------------------------------------------------------------------------


def test_pdo_defaults_as_printed_in_the_object_dictionary():
    assert ltmr_profile.RPDO1_DEFAULT == (0x20080510, 0x20080410, 0x20080110)
    assert ltmr_profile.TPDO1_DEFAULT == (0x20040610, 0x20040710, 0x20040810, 0x20040A10)
    assert ltmr_profile.RPDO4_DEFAULT == (0x30000120, 0x30000220)
    assert ltmr_profile.TPDO4_DEFAULT == (0x30000320, 0x30000420)


def test_identity_and_product_codes():
    assert ltmr_profile.VENDOR_ID == 0x0300005A and ltmr_profile.PRODUCT_REVISION == 0x00010001
    assert set(ltmr_profile.PRODUCT_CODES) == {0x30, 0x31, 0x130, 0x131}
    # "For TeSys T MMC L and TeSys T MMC L EV40, PKW use is restricted to read access." (L343)
    assert [ltmr_profile.pkw_read_only(code) for code in (0x30, 0x31, 0x130, 0x131)] == [False, False, True, True]
    assert [ltmr_profile.has_expansion_module(code) for code in (0x30, 0x31, 0x130, 0x131)] == [False, True, False, True]
    with pytest.raises(ValueError):
        ltmr_profile.pkw_read_only(0x32)
