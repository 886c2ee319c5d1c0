"""The FC profile (runtime/devices/fc280/profile.py): the control word for
what is asked and the reference in percent, with the vectors the issue and
digest 003 §4.5 derive from Tabelle 4.7 and §4.4.4 (the manual prints no
control word values)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.fc280.profile import (
    ControlWord,
    StatusWord,
    control_word,
    preset_of,
    reference_percent,
    reference_raw,
    setup_of,
)


@pytest.mark.parametrize(
    "asked, word",
    [
        ({"run": True}, 0x047C),  # start: bits 2, 3, 4, 5, 6, 10
        ({}, 0x043C),  # ramp stop
        ({"run": True, "quick_stop": True}, 0x046C),  # quick stop while running (3-81)
        ({"run": True, "reverse": True}, 0x847C),
        ({"run": True, "coast": True}, 0x0474),
        ({"run": True, "dc_brake": True}, 0x0478),
        ({"run": True, "freeze": True}, 0x045C),
        ({"run": True, "jog": True}, 0x057C),
        ({"run": True, "ramp_2": True}, 0x067C),
        ({"run": True, "preset": 3}, 0x047F),
        ({"run": True, "reset": True}, 0x04FC),
        ({"reset": True}, 0x04BC),
        ({"run": True, "relay_01": True, "relay_04": True}, 0x1C7C),
        ({"run": True, "setup": 4}, 0x647C),
    ],
)
def test_control_words(asked, word):
    assert control_word(**asked) == word


def test_every_word_is_valid_data():
    # a word without bit 10 is ignored by the drive: a stop must be valid too
    assert control_word() & ControlWord.DATA_VALID
    assert control_word(coast=True, quick_stop=True, dc_brake=True) & ControlWord.DATA_VALID


def test_preset_and_setup_read_back_and_range():
    for preset in range(4):
        for setup in range(1, 5):
            word = control_word(preset=preset, setup=setup)
            assert (preset_of(word), setup_of(word)) == (preset, setup)
    with pytest.raises(ValueError):
        control_word(preset=4)
    with pytest.raises(ValueError):
        control_word(setup=0)


@pytest.mark.parametrize(
    "percent, raw",
    [
        (0, 0x0000),
        (25, 0x1000),
        (50, 0x2000),
        (75, 0x3000),
        (100, 0x4000),
        (150, 0x6000),
        (-25, 0xF000),
        (-50, 0xE000),
        (-100, 0xC000),
        (250, 0x7FFF),
        (-250, 0x8000),
        (0.003, 0x0000),
        (0.0031, 0x0001),
    ],
)
def test_reference_words(percent, raw):
    # §4.4.4 (M8): 0 % = 0, 100 % = 4000h, -100 % = C000h; clamped to a signed word
    assert reference_raw(percent) == raw


def test_reference_and_actual_back_to_percent():
    assert reference_percent(0x4000) == 100.0 and reference_percent(0xC000) == -100.0
    assert reference_percent(0x2000) == 50.0 and reference_percent(0x0000) == 0.0


def test_status_word_bits_of_tabelle_4_10():
    word = StatusWord(0x0F07)
    assert StatusWord.CONTROL_READY in word and StatusWord.RUNNING in word and StatusWord.AT_REFERENCE in word
    assert StatusWord.TRIP not in word and StatusWord.BUS_CONTROL in word
    assert StatusWord(0x0248) & (StatusWord.TRIP | StatusWord.TRIP_LOCK) == StatusWord.TRIP | StatusWord.TRIP_LOCK
