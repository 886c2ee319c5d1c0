"""The Danfoss FC profile (8-10 = [0], the factory setting): the control word
(object 2690h = parameter 16-80), the status word (2643h = 16-03) and the
reference and actual value in percent (2692h = 16-82, 2645h = 16-05).
Numbers from manual 003 §4.4 (Tabellen 4.7, 4.10, §4.4.4) and digest 003 §4.

    word = control_word(run=True)                  # 0x047C
    reference_raw(50.0)                            # 0x2000
    StatusWord(0x0F07) & StatusWord.RUNNING        # in operation

The manual prints no control word values; the derived ones (digest 003
§4.5) are the tests' vectors: run 047C, ramp stop 043C, quick stop while
running 046C, reverse 847C, 50 % 2000h, -100 % C000h.
"""

from __future__ import annotations

import enum

# The objects of the FC profile (manual 003 §4.4.1, §4.4.3; 2645h is 16-05 by
# the index rule of §5.1, the manual names no object for the actual value).
OBJ_CONTROL_WORD = 0x2690  # 16-80 Bus Steuerwort 1
OBJ_REFERENCE = 0x2692  # 16-82 Bus Sollwert 1
OBJ_STATUS_WORD = 0x2643  # 16-03 Zustandswort
OBJ_ACTUAL = 0x2645  # 16-05 Hauptistwert [%]


class ControlWord(enum.IntFlag):
    """Tabelle 4.7. Bits 2-5 are active low: 0 asks for the function
    (DC brake, coast, quick stop, hold output frequency)."""

    PRESET_LSB = 0x0001  # bits 00/01: preset reference of 3-10 (Tabelle 4.8)
    PRESET_MSB = 0x0002
    RAMP = 0x0004  # 0: DC brake (2-01, 2-02)
    NO_COAST = 0x0008  # 0: coast
    NO_QUICK_STOP = 0x0010  # 0: quick stop, ramp 3-81
    USE_RAMP = 0x0020  # 0: hold the output frequency
    START = 0x0040  # 0: ramp stop
    RESET = 0x0080  # rising edge: acknowledge a trip
    JOG = 0x0100  # speed 3-19
    RAMP_2 = 0x0200  # 0: ramp 1 (3-4x), 1: ramp 2 (3-5x)
    DATA_VALID = 0x0400  # 0: the drive ignores the word
    RELAY_01 = 0x0800  # relay 01, with 5-40 = control word bit 11
    RELAY_04 = 0x1000  # relay 04, with 5-40 = control word bit 12
    SETUP_LSB = 0x2000  # bits 13/14: set-up 1-4 (Tabelle 4.9), with 0-10 = [9]
    SETUP_MSB = 0x4000
    REVERSE = 0x8000  # with 8-54 = [1] Bus, [2] or [3]


class StatusWord(enum.IntFlag):
    """Tabelle 4.10."""

    CONTROL_READY = 0x0001
    DRIVE_READY = 0x0002
    ENABLED = 0x0004  # 0: coasting
    TRIP = 0x0008
    ERROR = 0x0010  # an error, no trip
    TRIP_LOCK = 0x0040
    WARNING = 0x0080
    AT_REFERENCE = 0x0100
    BUS_CONTROL = 0x0200  # 0: local operation
    IN_FREQUENCY_LIMIT = 0x0400  # 0: at 4-11 / 4-13 (Tabelle 4.10; the simulator has only 4-14)
    RUNNING = 0x0800  # a start signal, or output frequency > 0 Hz
    THERMAL_STOP = 0x1000  # stopped by over-temperature, restarts by itself
    VOLTAGE_LIMIT = 0x2000
    TORQUE_LIMIT = 0x4000  # current above 4-18
    THERMAL_TIMER = 0x8000


#: the word of a drive told to stand by: data valid, no stop function asked
#: for (ramp, no coast, no quick stop, use ramp), not started
STANDBY = (
    ControlWord.DATA_VALID
    | ControlWord.RAMP
    | ControlWord.NO_COAST
    | ControlWord.NO_QUICK_STOP
    | (ControlWord.USE_RAMP)
)

# §4.4.4: 100 % = 4000h, -100 % = C000h, as a signed 16-bit word
REFERENCE_100 = 0x4000


def control_word(
    *,
    run: bool = False,
    reverse: bool = False,
    coast: bool = False,
    quick_stop: bool = False,
    dc_brake: bool = False,
    freeze: bool = False,
    jog: bool = False,
    ramp_2: bool = False,
    reset: bool = False,
    relay_01: bool = False,
    relay_04: bool = False,
    preset: int = 0,
    setup: int = 1,
) -> int:
    """The control word for what is asked; DATA_VALID is always set (a word
    without it is ignored, so a stop must be a valid word). preset 0-3
    selects the 3-10 preset reference (bits 00/01), setup 1-4 the set-up."""
    if not 0 <= preset <= 3:
        raise ValueError(f"preset reference is 0..3 (bits 00/01), not {preset}")
    if not 1 <= setup <= 4:
        raise ValueError(f"set-up is 1..4 (bits 13/14), not {setup}")
    word = int(STANDBY) | preset | (setup - 1) << 13
    for asked, flag in (
        (coast, ControlWord.NO_COAST),
        (quick_stop, ControlWord.NO_QUICK_STOP),
        (dc_brake, ControlWord.RAMP),
        (freeze, ControlWord.USE_RAMP),
    ):
        if asked:
            word &= ~flag
    for asked, flag in (
        (run, ControlWord.START),
        (reverse, ControlWord.REVERSE),
        (jog, ControlWord.JOG),
        (ramp_2, ControlWord.RAMP_2),
        (reset, ControlWord.RESET),
        (relay_01, ControlWord.RELAY_01),
        (relay_04, ControlWord.RELAY_04),
    ):
        if asked:
            word |= flag
    return word


def preset_of(word: int) -> int:
    """The preset reference a control word selects, 0-3 (3-10[0..3])."""
    return word & 0x0003


def setup_of(word: int) -> int:
    """The set-up a control word selects, 1-4."""
    return ((word >> 13) & 0x0003) + 1


def reference_raw(percent: float) -> int:
    """A reference in percent as the 16-bit word (signed, two's complement):
    rounded half away from zero, clamped to -32768..32767 (about +-200 %)."""
    raw = abs(percent) * REFERENCE_100 / 100
    whole = int(raw + 0.5) * (1 if percent >= 0 else -1)
    return max(-0x8000, min(0x7FFF, whole)) & 0xFFFF


def reference_percent(word: int) -> float:
    """The percent of a reference or actual value word (HIW is scaled as the
    reference, §4.4.4)."""
    signed = word - 0x10000 if word & 0x8000 else word
    return signed * 100 / REFERENCE_100


#: 2690h while the PLC holds its outputs safe (a task fault, the stop): data
#: valid, coast (bit 3 = 0: the output transistors off, the motor runs down
#: freely) and no start (bit 6 = 0): 0434h. Coast rather than quick stop
#: (046C without start): it needs no ramp (3-81) and no working power section,
#: and is what DSP 402's 0000h does (transition 9) and what 0000h, ignored
#: for its bit 10 = 0, never does (§4.4.2, Tabelle 4.7; digest 003 §4.5)
SAFE_CONTROL_WORD = control_word(coast=True)
