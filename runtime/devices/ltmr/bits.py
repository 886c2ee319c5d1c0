"""The LTMR's bit registers: status, control, trip, alarm, configuration and enable words, bit by bit.

One IntFlag per Word register, the fields of a register that are not single
bits, and the factory settings the manual states. Source: manual 001
(DOCA0132EN, shared/manuals/001_5287ad2b8a6c20a4.txt; "L<n>" below is a line
of that file) and its digest (shared/digests/001_ltmr_canopen_en.md, "§" and
the ambiguities "A<n>" of its §10).

    Status1(0x6083)                  -> READY|ON|RUNNING|IN_REMOTE (+ current ratio 32 = 100 %)
"""

from __future__ import annotations

import enum

# ---------------------------------------------------------------------------
# Bits
# ---------------------------------------------------------------------------


class Status1(enum.IntFlag):
    """455 System status register 1 (L3516-3543)."""

    READY = 1 << 0
    ON = 1 << 1
    TRIP = 1 << 2
    ALARM = 1 << 3
    TRIPPED = 1 << 4
    RESET_AUTHORIZED = 1 << 5
    CONTROLLER_POWER = 1 << 6  # "(Not significant)" in the Data Formats example; decoded (A13)
    RUNNING = 1 << 7  # current above 10 % FLC
    IN_REMOTE = 1 << 14
    STARTING = 1 << 15


# 455 bits 8-13: motor average current ratio, "32 = 100% FLC - 63 = 200% FLC" (L3538)
STATUS1_CURRENT_SHIFT = 8
STATUS1_CURRENT_MASK = 0x3F


def current_ratio_field(percent: float) -> int:
    """The 6-bit current ratio field of 455 for a current in % FLC:
    percent * 32 / 100, rounded, saturating at 63 (A14: 63 means about 200 %)."""
    return max(0, min(STATUS1_CURRENT_MASK, round(percent * 32 / 100)))


def current_ratio_percent(field: int) -> float:
    """% FLC of the 455 current ratio field (A14: linear, 32 = 100 %)."""
    return (field & STATUS1_CURRENT_MASK) * 100 / 32


class Status2(enum.IntFlag):
    """456 System status register 2 (L3544-3571)."""

    AUTO_RESET_ACTIVE = 1 << 0
    POWER_CYCLE_REQUESTED = 1 << 2
    RESTART_TIME_UNDEFINED = 1 << 3
    RAPID_CYCLE_LOCKOUT = 1 << 4
    LOAD_SHEDDING = 1 << 5  # note 1
    SPEED_FLC2 = 1 << 6  # 0 = FLC1 setting used, 1 = FLC2
    HMI_COMM_LOSS = 1 << 7
    NETWORK_COMM_LOSS = 1 << 8
    TRANSITION_LOCKOUT = 1 << 9


class Control1(enum.IntFlag):
    """704 Control register 1 (L4917-4937). Bits 0 and 1 also drive LO1/LO2 in
    overload mode (German edition L2576, A12)."""

    RUN_FORWARD = 1 << 0
    RUN_REVERSE = 1 << 1
    TRIP_RESET = 1 << 3
    SELF_TEST = 1 << 5
    LOW_SPEED = 1 << 6


#: 704 while the PLC holds its outputs safe: no run command (bits 0 and 1 off),
#: so LO1 and LO2 open and the motor stops (L4917-4937)
SAFE_CONTROL_1 = Control1(0)


class Control2(enum.IntFlag):
    """705 Control register 2 (L4938-4955)."""

    CLEAR_ALL = 1 << 0
    CLEAR_STATISTICS = 1 << 1
    CLEAR_THERMAL_CAPACITY = 1 << 2
    CLEAR_CONTROLLER_SETTINGS = 1 << 3
    CLEAR_NETWORK_SETTINGS = 1 << 4


class TripRegister1(enum.IntFlag):
    """452 Trip register 1 (L3423-3458)."""

    GROUND_CURRENT = 1 << 2
    THERMAL_OVERLOAD = 1 << 3
    LONG_START = 1 << 4
    JAM = 1 << 5
    CURRENT_PHASE_IMBALANCE = 1 << 6
    UNDERCURRENT = 1 << 7
    TEST = 1 << 9
    HMI_PORT = 1 << 10
    CONTROLLER_INTERNAL = 1 << 11
    INTERNAL_PORT = 1 << 12
    NETWORK_PORT_CONFIG = 1 << 14
    NETWORK_PORT = 1 << 15


class TripRegister2(enum.IntFlag):
    """453 Trip register 2 (L3459-3506); bits 6-15 need the LTMEV40."""

    EXTERNAL_SYSTEM = 1 << 0
    DIAGNOSTIC = 1 << 1
    WIRING = 1 << 2
    OVERCURRENT = 1 << 3
    CURRENT_PHASE_LOSS = 1 << 4
    CURRENT_PHASE_REVERSAL = 1 << 5
    MOTOR_TEMPERATURE_SENSOR = 1 << 6
    VOLTAGE_PHASE_IMBALANCE = 1 << 7
    VOLTAGE_PHASE_LOSS = 1 << 8
    VOLTAGE_PHASE_REVERSAL = 1 << 9
    UNDERVOLTAGE = 1 << 10
    OVERVOLTAGE = 1 << 11
    UNDERPOWER = 1 << 12
    OVERPOWER = 1 << 13
    UNDER_POWER_FACTOR = 1 << 14
    OVER_POWER_FACTOR = 1 << 15


class AlarmRegister1(enum.IntFlag):
    """461 Alarm register 1 (L3688-3717)."""

    GROUND_CURRENT = 1 << 2
    THERMAL_OVERLOAD = 1 << 3
    JAM = 1 << 5
    CURRENT_PHASE_IMBALANCE = 1 << 6
    UNDERCURRENT = 1 << 7
    HMI_PORT = 1 << 10
    CONTROLLER_TEMPERATURE = 1 << 11
    NETWORK_PORT = 1 << 15


class AlarmRegister2(enum.IntFlag):
    """462 Alarm register 2 (L3718-3763); bits 7-15 need the LTMEV40."""

    DIAGNOSTIC = 1 << 1
    OVERCURRENT = 1 << 3
    CURRENT_PHASE_LOSS = 1 << 4
    CURRENT_PHASE_REVERSAL = 1 << 5
    MOTOR_TEMPERATURE_SENSOR = 1 << 6
    VOLTAGE_PHASE_IMBALANCE = 1 << 7
    VOLTAGE_PHASE_LOSS = 1 << 8
    UNDERVOLTAGE = 1 << 10
    OVERVOLTAGE = 1 << 11
    UNDERPOWER = 1 << 12
    OVERPOWER = 1 << 13
    UNDER_POWER_FACTOR = 1 << 14
    OVER_POWER_FACTOR = 1 << 15


class NetworkPortStatus(enum.IntFlag):
    """490 Network port status (L3893-3909)."""

    COMMUNICATING = 1 << 0
    CONNECTED = 1 << 1
    SELF_TESTING = 1 << 2
    SELF_DETECTING = 1 << 3
    BAD_CONFIG = 1 << 4


class GeneralConfig1(enum.IntFlag):
    """601 General configuration register 1 (L4330-4357). Bits 8-10 are the
    configuration channels, "one bit is set to 1"."""

    CONFIG_MODE = 1 << 0  # 1 = go to the configuration menu (note A)
    CONFIG_VIA_HMI_KEYPAD = 1 << 8
    CONFIG_VIA_HMI_TOOL = 1 << 9
    CONFIG_VIA_NETWORK = 1 << 10  # factory setting: enabled (L230)
    MOTOR_STAR_DELTA = 1 << 11  # note B
    PHASE_SEQUENCE_ACB = 1 << 12
    AUXILIARY_FAN = 1 << 15


# 601 bits 13-14 motor phases, DT_PhaseNumber (L2195): 1 = 1 phase, 2 = 3 phases
GENERAL_CONFIG1_PHASES_SHIFT = 13
GENERAL_CONFIG1_PHASES_MASK = 0x3
# 602 bits 0-2 trip reset mode, DT_ResetMode (L4358, note C)
GENERAL_CONFIG2_RESET_MODE_MASK = 0x7


class TripEnable1(enum.IntFlag):
    """631 Trip enable register 1 (L4519-4547)."""

    GROUND_CURRENT = 1 << 2
    THERMAL_OVERLOAD = 1 << 3
    LONG_START = 1 << 4
    JAM = 1 << 5
    CURRENT_PHASE_IMBALANCE = 1 << 6
    UNDERCURRENT = 1 << 7
    SELF_TEST = 1 << 9  # factory setting: enabled
    HMI_PORT = 1 << 10
    NETWORK_PORT = 1 << 15


class AlarmEnable1(enum.IntFlag):
    """632 Alarm enable register 1 (L4548-4578)."""

    GROUND_CURRENT = 1 << 2
    THERMAL_OVERLOAD = 1 << 3
    JAM = 1 << 5
    CURRENT_PHASE_IMBALANCE = 1 << 6
    UNDERCURRENT = 1 << 7
    HMI_PORT = 1 << 10
    CONTROLLER_TEMPERATURE = 1 << 11
    NETWORK_PORT = 1 << 15


# The communication-loss trip and alarm enables for the network port: bit 15 of 631 and 632
NETWORK_PORT_TRIP_ENABLE = TripEnable1.NETWORK_PORT
NETWORK_PORT_ALARM_ENABLE = AlarmEnable1.NETWORK_PORT

# Register values the manual states as factory settings; every other register
# starts at 0 here. 601 bit 10 (L230), 602 bit 3 HMI parity even (L4358),
# 631 bit 9 self test (L4519), 650 English (DT_Language5, L2155).
FACTORY_SETTINGS = {
    601: int(GeneralConfig1.CONFIG_VIA_NETWORK),
    602: 1 << 3,
    631: int(TripEnable1.SELF_TEST),
    650: 1,
}
