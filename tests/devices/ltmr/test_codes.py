"""LTMR enumerations, trip and alarm codes (codes.py) with the manual's own
numbers (manual 001 §5.4 and the register tables; digest 001 §6-7)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.ltmr import codes as ltmr_codes
from softplc.runtime.devices.ltmr.codes import FallbackStrategy, OperatingMode, ResetMode

# ---------------------------------------------------------------------------
# Enumerations
# ---------------------------------------------------------------------------


def test_operating_modes():
    # 540: 2 = 2-wire overload ... 11 = 3-wire 2-speed, 256-511 custom logic
    assert [m.value for m in OperatingMode] == list(range(2, 12))
    assert OperatingMode.TWO_STEP_3W == 9 and OperatingMode.REVERSER_2W == 6
    assert ltmr_codes.is_custom_logic(256) and ltmr_codes.is_custom_logic(511)
    assert (
        not ltmr_codes.is_custom_logic(255)
        and not ltmr_codes.is_custom_logic(512)
        and not ltmr_codes.is_custom_logic(11)
    )


OVERLOAD, INDEPENDENT, REVERSER, TWO_STEP, TWO_SPEED, CUSTOM = 2, 5, 6, 9, 10, 300

# "Motor Modes" column of DT_OutputFallbackStrategy (L2171-2194)
FALLBACK_MATRIX = {
    FallbackStrategy.HOLD: {OVERLOAD, INDEPENDENT, REVERSER, TWO_STEP, TWO_SPEED, CUSTOM},  # all modes
    FallbackStrategy.RUN: {TWO_STEP},  # 2-step only
    FallbackStrategy.OFF: {OVERLOAD, INDEPENDENT, REVERSER, TWO_STEP, TWO_SPEED, CUSTOM},  # all modes
    FallbackStrategy.BOTH_ON: {OVERLOAD, INDEPENDENT, CUSTOM},  # overload, independent and custom only
    FallbackStrategy.LO1_ON: {OVERLOAD, INDEPENDENT, REVERSER, TWO_SPEED, CUSTOM},  # except 2-step
    FallbackStrategy.LO2_ON: {OVERLOAD, INDEPENDENT, REVERSER, TWO_SPEED, CUSTOM},  # except 2-step
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
    assert ltmr_codes.CANOPEN_BAUD_CODES == {
        0: 10_000,
        1: 20_000,
        2: 50_000,
        3: 125_000,
        4: 250_000,
        5: 500_000,
        6: 800_000,
        7: 1_000_000,
        8: None,
        9: 250_000,
    }


# ---------------------------------------------------------------------------
# Trip and alarm codes (L2043-2145, L2218-2278), copied
# ---------------------------------------------------------------------------

MANUAL_TRIP_CODES = {
    0: "No detected error",
    3: "Ground current",
    4: "Thermal overload",
    5: "Long start",
    6: "Jam",
    7: "Current phase imbalance",
    8: "Undercurrent",
    10: "Test",
    11: "HMI port detected error",
    12: "HMI port communication loss",
    13: "Network port internal detected error",
    16: "External trip",
    18: "ON-OFF diagnostic",
    19: "Wiring diagnostic",
    20: "Overcurrent",
    21: "Current phase loss",
    22: "Current phase reversal",
    23: "Motor temp sensor",
    24: "Voltage phase imbalance",
    25: "Voltage phase loss",
    26: "Voltage phase reversal",
    27: "Undervoltage",
    28: "Overvoltage",
    29: "Underpower",
    30: "Overpower",
    31: "Under power factor",
    32: "Over power factor",
    33: "LTME configuration",
    34: "Temperature sensor short-circuit",
    35: "Temperature sensor open-circuit",
    36: "CT reversal",
    37: "Out of boundary CT ratio",
    46: "Start check",
    47: "Run checkback",
    48: "Stop check",
    49: "Stop checkback",
    51: "Controller internal temperature detected error",
    55: "Controller internal detected error (Stack overflow)",
    56: "Controller internal detected error (RAM detected error)",
    57: "Controller internal detected error (RAM checksum detected error)",
    58: "Controller internal detected error (Hardware watchdog trip)",
    60: "L2 current detected in single-phase mode",
    64: "Non-volatile memory detected error",
    65: "Expansion module communication detected error",
    66: "Stuck reset button",
    67: "Logic function detected error",
    109: "Network port comm detected error",
    111: "Fast device replacement trip",
    555: "Network port configuration detected error",
}
MANUAL_ALARM_CODES = {
    0: "No alarm",
    3: "Ground current",
    4: "Thermal overload",
    5: "Long start",
    6: "Jam",
    7: "Current phase imbalance",
    8: "Undercurrent",
    10: "HMI port",
    11: "LTMR internal temperature",
    18: "Diagnostic",
    19: "Wiring",
    20: "Overcurrent",
    21: "Current phase loss",
    23: "Motor temp sensor",
    24: "Voltage phase imbalance",
    25: "Voltage phase loss",
    27: "Undervoltage",
    28: "Overvoltage",
    29: "Underpower",
    30: "Overpower",
    31: "Under power factor",
    32: "Over power factor",
    33: "LTME configuration",
    46: "Start check",
    47: "Run checkback",
    48: "Stop check",
    49: "Stop checkback",
    109: "Network port comm loss",
    555: "Network port configuration",
}


def test_trip_codes_as_printed_with_100_104_expanded():
    expected = dict(MANUAL_TRIP_CODES)
    expected.update(dict.fromkeys(range(100, 105), "Network port internal detected error"))  # "100-104"
    assert ltmr_codes.TRIP_CODES == expected


def test_alarm_codes_as_printed():
    assert ltmr_codes.ALARM_CODES == MANUAL_ALARM_CODES


def test_code_texts():
    assert ltmr_codes.trip_text(ltmr_codes.TRIP_THERMAL_OVERLOAD) == "Thermal overload"
    assert (
        ltmr_codes.trip_text(ltmr_codes.TRIP_TEST) == "Test" and ltmr_codes.alarm_text(10) == "HMI port"
    )  # same number, two meanings
    assert ltmr_codes.trip_text(ltmr_codes.TRIP_NETWORK_COMM) == "Network port comm detected error"
    assert ltmr_codes.alarm_text(ltmr_codes.ALARM_NETWORK_COMM) == "Network port comm loss"
    assert ltmr_codes.alarm_text(ltmr_codes.ALARM_THERMAL_OVERLOAD) == "Thermal overload"
    assert ltmr_codes.trip_text(1) == "unknown trip code 1" and ltmr_codes.alarm_text(999) == "unknown alarm code 999"
