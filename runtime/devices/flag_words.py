"""A register or word of a device's manual in words: the names of the
bits set in it (an enum.IntFlag of the device's package), for `softplc
log` (Device.object_text)."""

from __future__ import annotations

import enum


def flag_words(flags: type[enum.IntFlag], value: int) -> str:
    """'READY ON RUNNING' for the members of flags set in value; 'none' when none is."""
    names = [m.name.lower().replace("_", " ") for m in flags if m.name and m.value and value & m.value == m.value]
    return ", ".join(names) if names else "none"


__all__ = ["flag_words"]
