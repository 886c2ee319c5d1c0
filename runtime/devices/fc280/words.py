"""The FC 280's FC profile objects in the manual's words, for `softplc
log` (Device.object_text): the control word 16-80 (2690h, Tabelle 4.7:
bits 2-5 ask for their function at 0), the status word 16-03 (2643h,
Tabelle 4.10), the reference 16-82 and the actual value 16-05 in percent
(§4.4.4: 4000h = 100 %). Manual 003 §4.4; the FC profile is 8-10 = [0],
the factory setting: a drive set to DSP 402 has other words there."""

from __future__ import annotations

from ..flag_words import flag_words
from .profile import (
    OBJ_ACTUAL,
    OBJ_CONTROL_WORD,
    OBJ_REFERENCE,
    OBJ_STATUS_WORD,
    ControlWord,
    StatusWord,
    reference_percent,
)

#: control word bits that ask for their function at 0 (Tabelle 4.7)
_LOW_ACTIVE = (
    (ControlWord.RAMP, "DC brake"),
    (ControlWord.NO_COAST, "coast"),
    (ControlWord.NO_QUICK_STOP, "quick stop"),
    (ControlWord.USE_RAMP, "hold output frequency"),
)
_HIGH_ACTIVE = (
    (ControlWord.START, "start"),
    (ControlWord.RESET, "reset"),
    (ControlWord.JOG, "jog"),
    (ControlWord.RAMP_2, "ramp 2"),
    (ControlWord.RELAY_01, "relay 01"),
    (ControlWord.RELAY_04, "relay 04"),
    (ControlWord.REVERSE, "reverse"),
)


def control_word_text(word: int) -> str:
    if not word & ControlWord.DATA_VALID:
        return "not valid (bit 10 = 0): ignored"
    asked = [name for bit, name in _LOW_ACTIVE if not word & bit]
    asked += [name for bit, name in _HIGH_ACTIVE if word & bit]
    if not word & ControlWord.START:
        asked.append("ramp stop")
    preset, setup = word & 0x0003, (word >> 13) & 0x0003
    return ", ".join(asked) + f"; preset {preset + 1}" + (f", set-up {setup + 1}" if setup else "")


def object_text(index: int, subindex: int, value: int) -> str | None:
    if subindex != 0:
        return None
    if index == OBJ_CONTROL_WORD:
        return control_word_text(value)
    if index == OBJ_STATUS_WORD:
        return flag_words(StatusWord, value)
    if index in (OBJ_REFERENCE, OBJ_ACTUAL):
        return f"{reference_percent(value & 0xFFFF):.2f} %"
    return None


__all__ = ["control_word_text", "object_text"]
