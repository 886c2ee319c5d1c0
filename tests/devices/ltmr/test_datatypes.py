"""LTMR data types (datatypes.py) with the manual's own numbers (manual 001
§5.4-5.5; digest 001 §6-7): DT_DateTime, DT_CommercialReference, two-register
and signed values."""

from __future__ import annotations

import datetime as dt

import pytest

from softplc.runtime.devices.ltmr import datatypes as ltmr_datatypes
from softplc.runtime.devices.ltmr import registers as ltmr

# ---------------------------------------------------------------------------
# DT_DateTime (L1866-1966)
# ---------------------------------------------------------------------------


def test_manual_datetime_example_encodes():
    # "If date is September 4, 2008 at 7 a.m., 50 minutes and 32 seconds": 655 = 3 2 0 0,
    # 656 = 0 7 5 0, 657 = 0 9 0 4, 658 = 2 0 0 8 (nibbles 15-12 .. 3-0)
    assert ltmr_datatypes.encode_datetime(dt.datetime(2008, 9, 4, 7, 50, 32)) == (0x3200, 0x0750, 0x0904, 0x2008)


def test_manual_datetime_example_decodes():
    assert ltmr_datatypes.decode_datetime((0x3200, 0x0750, 0x0904, 0x2008)) == dt.datetime(2008, 9, 4, 7, 50, 32)


@pytest.mark.parametrize(
    "when, words",
    [
        (dt.datetime(2006, 1, 1, 0, 0, 0), (0x0000, 0x0000, 0x0101, 0x2006)),  # minimum DT#2006-01-01:00:00:00
        (dt.datetime(2099, 12, 31, 23, 59, 59), (0x5900, 0x2359, 0x1231, 0x2099)),  # maximum DT#2099-12-31-23:59:59
        (dt.datetime(2008, 2, 29, 12, 0, 0), (0x0000, 0x1200, 0x0229, 0x2008)),  # a leap day
    ],
)
def test_datetime_limits_both_ways(when, words):
    assert ltmr_datatypes.encode_datetime(when) == words
    assert ltmr_datatypes.decode_datetime(words) == when


@pytest.mark.parametrize("when", [dt.datetime(2005, 12, 31, 23, 59, 59), dt.datetime(2100, 1, 1)])
def test_datetime_outside_the_limits_is_an_error(when):
    # "If you give values outside the limits, the system will return a detected error."
    with pytest.raises(ValueError, match="outside"):
        ltmr_datatypes.encode_datetime(when)


@pytest.mark.parametrize(
    "words, why",
    [
        ((0x0000, 0x0000, 0x0229, 0x2007), "2007-02-29: not a leap year"),
        ((0x0000, 0x0000, 0x0931, 0x2008), "September has 30 days"),
        ((0x0000, 0x0000, 0x1301, 0x2008), "month 13"),
        ((0x6000, 0x0000, 0x0101, 0x2008), "second 60"),
        ((0x0000, 0x2400, 0x0101, 0x2008), "hour 24"),
        ((0x0000, 0x0000, 0x1231, 0x2005), "before 2006"),
        ((0x0000, 0x0000, 0x0101, 0x2100), "after 2099"),
        ((0x3A00, 0x0750, 0x0904, 0x2008), "0xA is not a BCD digit"),
        ((0x3200, 0x0750, 0x0904, 0x20F8), "0xF in the year"),
    ],
)
def test_invalid_datetime_words_are_errors(words, why):
    with pytest.raises(ValueError):
        ltmr_datatypes.decode_datetime(words)


def test_datetime_drops_fractions_of_a_second():
    assert ltmr_datatypes.encode_datetime(dt.datetime(2008, 9, 4, 7, 50, 32, 999_000)) == (
        0x3200,
        0x0750,
        0x0904,
        0x2008,
    )


# ---------------------------------------------------------------------------
# DT_CommercialReference (L1817-1865), A16
# ---------------------------------------------------------------------------


def test_commercial_reference_example_with_spaces_or_nuls():
    # 64 = 'L','T'; 65 = 'M',(space); 66 = 'R',(blank); 67-69 blank. The caption says "LTMR".
    with_spaces = (0x4C54, 0x4D20, 0x5220, 0x2020, 0x2020, 0x2020)
    with_nuls = (0x4C54, 0x4D20, 0x5200, 0x0000, 0x0000, 0x0000)
    assert ltmr_datatypes.decode_commercial_reference(with_spaces) == "LTM R"
    assert ltmr_datatypes.decode_commercial_reference(with_nuls) == "LTM R"
    assert ltmr_datatypes.encode_commercial_reference("LTM R") == with_spaces


def test_commercial_reference_round_trip_and_limits():
    words = ltmr_datatypes.encode_commercial_reference("LTMR08CFM")
    assert len(words) == 6 and words[0] == 0x4C54
    assert ltmr_datatypes.decode_commercial_reference(words) == "LTMR08CFM"
    assert (
        ltmr_datatypes.decode_commercial_reference(ltmr_datatypes.encode_commercial_reference("ABCDEFGHIJKL"))
        == "ABCDEFGHIJKL"
    )
    with pytest.raises(ValueError):
        ltmr_datatypes.encode_commercial_reference("ABCDEFGHIJKLM")
    with pytest.raises(ValueError):
        ltmr_datatypes.encode_commercial_reference("LTMR Ω")


# ---------------------------------------------------------------------------
# Two-register values and signed registers (A5)
# ---------------------------------------------------------------------------


def test_udint_lower_register_is_msw_by_default():
    # digest 001 §7.2: 500/501 = 0x0000/0x04D2 -> 1234 -> 12.34 A (if the lower register is the MSW)
    value = ltmr_datatypes.udint_from_registers(0x0000, 0x04D2)
    assert value == 1234
    assert value * ltmr.REGISTERS[ltmr.REG_AVERAGE_CURRENT].scale == pytest.approx(12.34)
    assert ltmr_datatypes.udint_to_registers(1234) == (0x0000, 0x04D2)
    assert ltmr_datatypes.udint_from_registers(0x0001, 0x0002) == 0x00010002


def test_udint_other_word_order():
    assert ltmr_datatypes.udint_from_registers(0x04D2, 0x0000, msw_first=False) == 1234
    assert ltmr_datatypes.udint_to_registers(0x00010002, msw_first=False) == (0x0002, 0x0001)
    with pytest.raises(ValueError):
        ltmr_datatypes.udint_to_registers(-1)
    with pytest.raises(ValueError):
        ltmr_datatypes.udint_to_registers(1 << 32)


def test_signed_registers():
    assert ltmr_datatypes.int16(0xFFF6) == -10  # 472 controller internal temperature -10 °C
    assert (
        ltmr_datatypes.int16(0x7FFF) == 32767
        and ltmr_datatypes.int16(0x8000) == -32768
        and ltmr_datatypes.int16(25) == 25
    )
    assert ltmr_datatypes.dint_from_registers(0xFFFF, 0xFFFE) == -2
    assert ltmr.REGISTERS[472].type == "Int" and ltmr.REGISTERS[472].signed


def test_full_load_current():
    # 96 = 80 (8.0 A FLC max) and 652 = 50 % -> FLC1 = 4.0 A
    assert ltmr_datatypes.full_load_current_amps(80, 50) == pytest.approx(4.0)
