"""LTMR enumerations and codes: operating modes, fallback and reset modes, baud codes, trip and alarm codes.

The manual's DT_* enumerations and the registers that hold one. Source:
manual 001 (DOCA0132EN, shared/manuals/001_5287ad2b8a6c20a4.txt; "L<n>" below
is a line of that file) and its digest (shared/digests/001_ltmr_canopen_en.md,
"§" and the ambiguities "A<n>" of its §10).

    trip_text(TRIP_THERMAL_OVERLOAD)  -> 'Thermal overload'
"""

from __future__ import annotations

import enum

# ---------------------------------------------------------------------------
# Enumerations
# ---------------------------------------------------------------------------


class OperatingMode(enum.IntEnum):
    """540 Motor operating mode (L4030); 256-511 = custom logic program 0-255."""

    OVERLOAD_2W = 2
    OVERLOAD_3W = 3
    INDEPENDENT_2W = 4
    INDEPENDENT_3W = 5
    REVERSER_2W = 6
    REVERSER_3W = 7
    TWO_STEP_2W = 8
    TWO_STEP_3W = 9
    TWO_SPEED_2W = 10
    TWO_SPEED_3W = 11


CUSTOM_LOGIC_FIRST = 256
CUSTOM_LOGIC_LAST = 511


def is_custom_logic(mode: int) -> bool:
    return CUSTOM_LOGIC_FIRST <= mode <= CUSTOM_LOGIC_LAST


def is_valid_operating_mode(mode: int) -> bool:
    return mode in OperatingMode._value2member_map_ or is_custom_logic(mode)


class FallbackStrategy(enum.IntEnum):
    """DT_OutputFallbackStrategy, registers 682 (network) and 645 (HMI), L2171-2194."""

    HOLD = 0  # hold LO1 LO2
    RUN = 1  # 2-step mode only
    OFF = 2  # LO1, LO2 off
    BOTH_ON = 3  # overload, independent and custom modes only
    LO1_ON = 4  # all modes except 2-step
    LO2_ON = 5  # all modes except 2-step


_OVERLOAD = {OperatingMode.OVERLOAD_2W, OperatingMode.OVERLOAD_3W}
_INDEPENDENT = {OperatingMode.INDEPENDENT_2W, OperatingMode.INDEPENDENT_3W}
_TWO_STEP = {OperatingMode.TWO_STEP_2W, OperatingMode.TWO_STEP_3W}


def fallback_allowed(strategy: int, mode: int) -> bool:
    """Whether a fallback strategy may be used with an operating mode, per the
    "Motor Modes" column of DT_OutputFallbackStrategy (L2171-2194)."""
    strategy = FallbackStrategy(strategy)
    if not is_valid_operating_mode(mode):
        raise ValueError(f"{mode} is not an LTMR operating mode (2-11 or 256-511)")
    if strategy in (FallbackStrategy.HOLD, FallbackStrategy.OFF):
        return True
    if strategy == FallbackStrategy.RUN:
        return mode in _TWO_STEP
    if strategy == FallbackStrategy.BOTH_ON:
        return mode in _OVERLOAD or mode in _INDEPENDENT or is_custom_logic(mode)
    return mode not in _TWO_STEP  # LO1_ON, LO2_ON


class ResetMode(enum.IntEnum):
    """DT_ResetMode, register 602 bits 0-2 (L2204-2214)."""

    MANUAL = 1  # manual or HMI
    REMOTE = 2  # remote by network
    AUTOMATIC = 4


class PhaseNumber(enum.IntEnum):
    """DT_PhaseNumber, register 601 bits 13-14 (L2195-2203)."""

    ONE_PHASE = 1
    THREE_PHASES = 2


# DT_CANopenExtBaudRate, register 695 (L183-206, L2003): code -> bit/s; 8 = autobaud.
# 9 "Factory setting" is 250 kbit/s (L206), the same rate as code 4 (A20).
CANOPEN_BAUD_CODES = {
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
# Trip and alarm codes (DT_FaultCode L2043-2145, DT_WarningCode L2218-2278)
# ---------------------------------------------------------------------------

TRIP_CODES = {
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
    **dict.fromkeys(range(100, 105), "Network port internal detected error"),  # printed "100-104"
    109: "Network port comm detected error",
    111: "Fast device replacement trip",
    555: "Network port configuration detected error",
}

ALARM_CODES = {
    0: "No alarm",
    3: "Ground current",
    4: "Thermal overload",
    5: "Long start",
    6: "Jam",
    7: "Current phase imbalance",
    8: "Undercurrent",
    10: "HMI port",  # 10 is "Test" as a trip code
    11: "LTMR internal temperature",  # 11 is "HMI port detected error" as a trip code
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

TRIP_NONE = 0
TRIP_THERMAL_OVERLOAD = 4
TRIP_TEST = 10
TRIP_NETWORK_COMM = 109
ALARM_NONE = 0
ALARM_THERMAL_OVERLOAD = 4
ALARM_NETWORK_COMM = 109


def trip_text(code: int) -> str:
    return TRIP_CODES.get(code, f"unknown trip code {code}")


def alarm_text(code: int) -> str:
    return ALARM_CODES.get(code, f"unknown alarm code {code}")
