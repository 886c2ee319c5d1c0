"""The simulated LTMR's settings at power-up and the manual's constants the
model (model.py) works with: every register of the map, the factory settings
of manual 001 (DOCA0132EN, shared/manuals/001_*.txt, "L<n>") and, where the
manual gives no value, the simulator's choices ("simulator choice, not in the
manual").

    registers = default_registers()     # {register: value}, 0..0xFFFF
"""

from __future__ import annotations

from .bits import (
    FACTORY_SETTINGS,
    GENERAL_CONFIG2_RESET_MODE_MASK,
    AlarmEnable1,
    GeneralConfig1,
    TripEnable1,
)
from .codes import FallbackStrategy, OperatingMode, ResetMode
from .datatypes import encode_commercial_reference
from .registers import (
    REG_ALARM_ENABLE_1,
    REG_FLC1,
    REG_FLC2,
    REG_FLC_MAX,
    REG_GENERAL_CONFIG_1,
    REG_GENERAL_CONFIG_2,
    REG_NETWORK_FALLBACK,
    REG_OPERATING_MODE,
    REG_THERMAL_ALARM_THRESHOLD,
    REG_THERMAL_RESET_THRESHOLD,
    REG_TRIP_CLASS,
    REG_TRIP_ENABLE_1,
    REGISTERS,
)

S = 1_000_000_000

# ---------------------------------------------------------------- simulator choices (not in the manual)

DEFAULT_FLC_MAX = 80  # 96, x 0.1 A: 8.0 A, the digest's example (digest 001 §6.4)
DEFAULT_FLC1 = 50  # 652, % FLCmax: 4.0 A
DEFAULT_FLC2 = 100  # 653, % FLCmax: 8.0 A at high speed
DEFAULT_TRIP_CLASS = 10  # 606, s
DEFAULT_THERMAL_RESET_THRESHOLD = 75  # 608, % trip level
DEFAULT_THERMAL_ALARM_THRESHOLD = 85  # 609, % trip level
DEFAULT_RESET_MODE = ResetMode.REMOTE
DEFAULT_OPERATING_MODE = OperatingMode.REVERSER_2W
DEFAULT_NETWORK_FALLBACK = FallbackStrategy.OFF  # 682: a lost PLC stops the motor
DEFAULT_TRANSITION_TIMEOUT_S = 0  # 541, s: no anti-backspin wait unless configured
DEFAULT_STEP_TIMEOUT_S = 5  # 643, unit not printed (manual 001 L4708): taken as s like 541
DEFAULT_STEP_THRESHOLD = 150  # 644, % FLC, unit not printed (L4713)
DEFAULT_LOAD_PERCENT = 80.0  # % FLC while running
DEFAULT_COMMERCIAL_REFERENCE = "LTMR08CBD"  # 64-69: an LTMR with an 8 A current range
DEFAULT_CURRENT_RANGE_MAX = 80  # 81, x 0.1 A
# Enabled protections: thermal overload trip (631 bit 3), self test (bit 9, the
# factory setting, L4519); thermal overload and network port alarms (632 bits 3, 15).
# The network port trip (631 bit 15) is off: a lost PLC raises an alarm and
# applies the fallback, and the motor runs again without a trip reset.
DEFAULT_TRIP_ENABLE_1 = TripEnable1.THERMAL_OVERLOAD | TripEnable1.SELF_TEST
DEFAULT_ALARM_ENABLE_1 = AlarmEnable1.THERMAL_OVERLOAD | AlarmEnable1.NETWORK_PORT
# 601: config via network port (factory, L230), 3 phases (bits 13-14 = 2, DT_PhaseNumber)
DEFAULT_GENERAL_CONFIG_1 = GeneralConfig1.CONFIG_VIA_NETWORK | (2 << 13)


# ---------------------------------------------------------------- from the manual

RUNNING_THRESHOLD_PERCENT = 10  # 455 bit 7: "current greater than 10% FLC" (L3533)
DIRECT_TRANSITION = 1 << 9  # 683 bit 9: 1 = stop not required during transition (L4870)
LOCAL_DEFAULT_MODE = 1 << 2  # 683 bit 2: 0 = remote, 1 = local (with LTMCU)
REMOTE_CHANNEL_SHIFT = 5  # 683 bits 5-6: 0 = network, 1 = terminal strip, 2 = HMI
REG_TRANSITION_TIMEOUT = 541  # s
REG_STEP_TIMEOUT = 643
REG_STEP_THRESHOLD = 644
REG_CURRENT_RANGE_MAX = 81
REG_COMMERCIAL_REFERENCE = 64
REG_THERMAL_TRIPS_COUNT = 103
REG_NETWORK_PORT_TRIPS_COUNT = 114
REG_THERMAL_ALARMS_COUNT = 116
REG_TRIPS_COUNT = 122
REG_ALARMS_COUNT = 123
REG_LO1_CLOSINGS = 124  # UDInt 124-125
REG_LO2_CLOSINGS = 126  # UDInt 126-127
STATISTICS = range(100, 450)  # cleared by 705 bit 1


START_DURATION_NS = 1 * S  # inrush of a direct-on-line start
START_CURRENT_PERCENT = 600.0  # % FLC during the inrush (or the load, if higher: a locked rotor)
MAX_STEP_NS = 10_000_000  # events (trip, alarm, reset threshold) are seen within 10 ms


def default_registers() -> dict:
    """Every register of the map at 0, then the manual's factory settings,
    then the simulator's choices above."""
    registers = dict.fromkeys(REGISTERS, 0)
    registers.update(FACTORY_SETTINGS)
    for i, word in enumerate(encode_commercial_reference(DEFAULT_COMMERCIAL_REFERENCE)):
        registers[REG_COMMERCIAL_REFERENCE + i] = word
    registers.update(
        {
            REG_CURRENT_RANGE_MAX: DEFAULT_CURRENT_RANGE_MAX,
            REG_FLC_MAX: DEFAULT_FLC_MAX,
            REG_OPERATING_MODE: DEFAULT_OPERATING_MODE,
            REG_TRANSITION_TIMEOUT: DEFAULT_TRANSITION_TIMEOUT_S,
            REG_GENERAL_CONFIG_1: DEFAULT_GENERAL_CONFIG_1,
            REG_GENERAL_CONFIG_2: (FACTORY_SETTINGS.get(REG_GENERAL_CONFIG_2, 0) & ~GENERAL_CONFIG2_RESET_MODE_MASK)
            | DEFAULT_RESET_MODE,
            REG_TRIP_CLASS: DEFAULT_TRIP_CLASS,
            REG_THERMAL_RESET_THRESHOLD: DEFAULT_THERMAL_RESET_THRESHOLD,
            REG_THERMAL_ALARM_THRESHOLD: DEFAULT_THERMAL_ALARM_THRESHOLD,
            REG_TRIP_ENABLE_1: DEFAULT_TRIP_ENABLE_1,
            REG_ALARM_ENABLE_1: DEFAULT_ALARM_ENABLE_1,
            REG_STEP_TIMEOUT: DEFAULT_STEP_TIMEOUT_S,
            REG_STEP_THRESHOLD: DEFAULT_STEP_THRESHOLD,
            REG_FLC1: DEFAULT_FLC1,
            REG_FLC2: DEFAULT_FLC2,
            REG_NETWORK_FALLBACK: DEFAULT_NETWORK_FALLBACK,
        }
    )
    return {reg: int(value) & 0xFFFF for reg, value in registers.items()}
