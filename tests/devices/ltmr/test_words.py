"""The LTMR's registers as `softplc log` prints them (devices/ltmr/words.py):
455 bit by bit with its current ratio (manual 001 L3516-3543: 32 = 100 %
FLC), 704, the trip and alarm codes (DT_FaultCode, DT_WarningCode)."""

from __future__ import annotations

from softplc.runtime.devices.ltmr.registers import register_to_object
from softplc.runtime.devices.ltmr.words import object_text


def words(register: int, value: int) -> str | None:
    return object_text(*register_to_object(register), value)


def test_system_status_register_1_with_its_current_ratio():
    # bits.py's example: ready, on, running, in remote, current ratio 32 = 100 % FLC
    assert words(455, 0x6083) == "ready, on, running, in remote; current 100 % FLC"


def test_control_register_1():
    assert words(704, 0x0001) == "run forward"
    assert words(704, 0x0008) == "trip reset"
    assert words(704, 0) == "none"


def test_trip_and_alarm_codes():
    assert words(451, 4) == "Thermal overload"
    assert words(460, 4) == "Thermal overload"


def test_a_register_without_words_and_another_object():
    assert words(457, 3) is None
    assert object_text(0x1017, 0, 100) is None
