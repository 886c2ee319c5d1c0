"""Fault texts, relay-manager words and DI digit words of the MPU2-S
(codewords.py, and through parameters.encode_words/decode_words): E5, E6,
E7, E12 and V19 of digest 004, and the decisions A25/A26."""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.devices.mpu2s import codewords
from softplc.runtime.devices.mpu2s.codewords import Event, RelayEvent
from softplc.runtime.devices.mpu2s.parameters import decode_words, encode_words, parameter


def ascii_word(pair: str) -> int:
    return ord(pair[0]) << 8 | ord(pair[1])


def test_fault_text_e5():
    # E5, terminal 62: ID 732 'OP', 733 'MN', 734 'KL', 735 'IJ', 736 'GH', 737 'EF', 738 'CD', 739 'AB'
    expected = {732: "OP", 733: "MN", 734: "KL", 735: "IJ", 736: "GH", 737: "EF", 738: "CD", 739: "AB"}
    # A25: the printed example ",ABCDEFGHJKLMNOP'" lacks the I its own mapping shows
    words = encode_words(parameter("fault_text_62"), "ABCDEFGHIJKLMNOP")
    assert words == {i: ascii_word(pair) for i, pair in expected.items()}
    assert decode_words(parameter("fault_text_62"), words) == "ABCDEFGHIJKLMNOP"


def test_fault_text_ids_per_terminal():
    # §3.5: 62 -> 732-739, 63 -> 740-747 ... 73 -> 820-827
    assert codewords.text_ids(62) == range(732, 740)
    assert codewords.text_ids(63) == range(740, 748)
    assert codewords.text_ids(73) == range(820, 828)
    for n, terminal in enumerate(range(62, 74)):
        assert parameter(f"4.2.{140 + n}").ids == tuple(codewords.text_ids(terminal))
    with pytest.raises(ValueError):
        codewords.text_ids(74)


def test_short_texts_are_padded_with_spaces_a25():
    words = codewords.text_words("GEN FAULT")
    assert words[0] == ascii_word("  ") and words[-1] == ascii_word("GE")
    assert words[3] == ascii_word("T ")  # characters 9-10: 'T' and the first pad
    assert codewords.text_of(words) == "GEN FAULT"
    assert codewords.text_of(codewords.text_words("")) == ""


def test_bad_texts():
    with pytest.raises(ValueError, match="16 characters"):
        codewords.text_words("ABCDEFGHIJKLMNOPQ")
    with pytest.raises(ValueError, match="ASCII"):
        codewords.text_words("Öldruck")
    with pytest.raises(ValueError):
        codewords.text_of([0] * 7)
    # characters 15-16 are NUL and 'A' (the first ID), the rest spaces: NUL shows as '?'
    assert codewords.text_of([0x0041] + [0x2020] * 7) == " " * 14 + "?A"


@given(st.text(st.characters(min_codepoint=0x20, max_codepoint=0x7E), max_size=16))
def test_texts_round_trip(text):
    assert codewords.text_of(codewords.text_words(text)) == text.rstrip(" ")


def test_relay_word_e12_and_v19():
    # V19: event 68 "GLS EIN" alone, end of chain -> 4404h
    assert RelayEvent(68, end=True).word == 0x4404
    assert Event.GCB_CLOSED == 68
    # E12: low byte bit 2 end, bit 1 invert, bit 0 AND(1)/OR(0)
    assert RelayEvent(1, invert=True).word == 0x0102
    assert RelayEvent(1, and_next=True).word == 0x0101
    assert RelayEvent(98, end=True, invert=True, and_next=True).word == 0x6207
    assert RelayEvent.from_word(0x4404) == RelayEvent(68, end=True)
    with pytest.raises(ValueError, match="bits 7-3"):
        RelayEvent.from_word(0x4408)
    for bad in (0, 99, True):
        with pytest.raises(ValueError):
            RelayEvent(bad)


def test_relay_chains():
    p = parameter("relay_1")
    assert p.ids == (436, 437, 438) and parameter("relay_7").ids == (454, 455, 456)
    assert codewords.relay_ids(2) == range(439, 442)
    # F2/F3 common alarm AND NOT GCB closed, OR mains fault (AND before OR)
    chain = (RelayEvent(5, and_next=True), RelayEvent(68, invert=True), RelayEvent(71, end=True))
    words = encode_words(p, chain)
    assert words == {436: 0x0501, 437: 0x4402, 438: 0x4704}
    assert decode_words(p, words) == chain
    # a chain that ends at the first ID: the other IDs need not be read
    assert decode_words(p, {436: 0x4404}) == (RelayEvent(68, end=True),)
    with pytest.raises(ValueError, match="not read"):
        decode_words(p, {436: 0x4400})
    # A30: the third ID ends the chain, whatever its bit 2
    assert codewords.relay_events([0x0100, 0x0200, 0x0300]) == (RelayEvent(1), RelayEvent(2), RelayEvent(3))
    with pytest.raises(ValueError):
        encode_words(p, (RelayEvent(68),))  # the last must end the chain
    with pytest.raises(ValueError):
        encode_words(p, (RelayEvent(68, end=True), RelayEvent(1, end=True)))
    with pytest.raises(ValueError):
        encode_words(p, [])
    with pytest.raises(ValueError):
        encode_words(p, "text")


def test_sync_events_of_section_3_8():
    assert {e.name: e.value for e in Event} == {
        "GCB_CONNECT_TIME": 29,  # Zuschaltzeitfehler GLS
        "GCB_CLOSED": 68,  # GLS EIN
        "GCB_CLOSE_FAULT": 89,  # Störung GLS EIN
        "GCB_OPEN_FAULT": 91,  # Störung GLS AUF
        "BLACK_START_TIME": 94,  # Zuschaltzeit außerhalb Grenzen Schwarzstart
    }


@pytest.mark.parametrize(
    "digit, seconds",
    [(0, 0.1), (1, 0.2), (2, 0.5), (3, 1), (4, 2), (5, 5), (6, 10), (7, 20), (8, 50), (9, 100)],
)
def test_di_delay_codes_e6(digit, seconds):
    assert codewords.di_delay_word((seconds, 0.1, 0.1, 0.1)) == digit * 1000  # A26: DI 1 is the thousands
    assert codewords.di_delays(digit) == (0.1, 0.1, 0.1, seconds)


def test_fault_class_digits_e7():
    assert codewords.fault_class_word((3, 3, 3, 3)) == 3333  # the range end "3333", decimal (A26)
    assert codewords.fault_class_word((0, 0, 0, 0)) == 0
    assert codewords.fault_classes(1023) == (1, 0, 2, 3)
    for bad in ((4, 0, 0, 0), (0, 0, 0), (0, 0, 0, -1), (1.0, 0, 0, 0)):
        with pytest.raises(ValueError):
            codewords.fault_class_word(bad)
    with pytest.raises(ValueError):
        codewords.fault_classes(10000)
