"""The FC 280's FC profile words as `softplc log` prints them
(devices/fc280/words.py): the control word vectors of digest 003 §4.5
(derived from manual 003 Tabelle 4.7, which prints no values), the
status word of Tabelle 4.10, references of §4.4.4 (4000h = 100 %)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.fc280.profile import OBJ_ACTUAL, OBJ_CONTROL_WORD, OBJ_REFERENCE, OBJ_STATUS_WORD
from softplc.runtime.devices.fc280.words import object_text


@pytest.mark.parametrize(
    ("word", "text"),
    [
        (0x047C, "start; preset 1"),  # run
        (0x043C, "ramp stop; preset 1"),  # ramp stop
        (0x046C, "quick stop, start; preset 1"),  # quick stop while running
        (0x847C, "start, reverse; preset 1"),  # reverse
        (0x0434, "coast, ramp stop; preset 1"),  # softplc's safe word: coast, no start
        (0x04FC, "start, reset; preset 1"),
        (0x007C, "not valid (bit 10 = 0): ignored"),
    ],
)
def test_control_word_16_80(word, text):
    assert object_text(OBJ_CONTROL_WORD, 0, word) == text


def test_status_word_16_03_bit_by_bit():
    assert object_text(OBJ_STATUS_WORD, 0, 0x0F07) == (
        "control ready, drive ready, enabled, at reference, bus control, in frequency limit, running"
    )
    assert object_text(OBJ_STATUS_WORD, 0, 0x0008) == "trip"


@pytest.mark.parametrize(("raw", "text"), [(0x2000, "50.00 %"), (0xC000, "-100.00 %"), (0x4000, "100.00 %")])
def test_reference_and_actual_value_in_percent(raw, text):
    assert object_text(OBJ_REFERENCE, 0, raw) == text
    assert object_text(OBJ_ACTUAL, 0, raw) == text


def test_other_objects_have_no_words():
    assert object_text(0x1017, 0, 100) is None
