"""The LTMR's registers in the manual's words, for `softplc log`
(Device.object_text): the status and control registers bit by bit
(bits.py, manual 001 L3516-3571, L4917-4955), 455's current ratio
(bits 8-13, 32 = 100 % FLC, L3538), the trip and alarm codes (451, 460:
codes.py, DT_FaultCode / DT_WarningCode)."""

from __future__ import annotations

from ..flag_words import flag_words
from .bits import STATUS1_CURRENT_SHIFT, Control1, Control2, Status1, Status2, current_ratio_percent
from .codes import alarm_text, trip_text
from .registers import object_to_register

_FLAGS = {455: Status1, 456: Status2, 704: Control1, 705: Control2}


def object_text(index: int, subindex: int, value: int) -> str | None:
    try:
        register = object_to_register(index, subindex)
    except ValueError:  # not one of its register objects
        return None
    if register == 455:
        ratio = current_ratio_percent(value >> STATUS1_CURRENT_SHIFT)
        return f"{flag_words(Status1, value)}; current {ratio:g} % FLC"
    if register in _FLAGS:
        return flag_words(_FLAGS[register], value)
    if register == 451:
        return trip_text(value)
    if register == 460:
        return alarm_text(value)
    return None


__all__ = ["object_text"]
