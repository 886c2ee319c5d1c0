"""FC 280 parameters over CANopen (runtime/devices/fc280/parameters.py):
the index rule (manual 003 §5.1, Tabelle 5.1, M7), the conversion index
(Tabelle 6.2, M15) and the configured writes by parameter number."""

from __future__ import annotations

import re
from fractions import Fraction

import pytest

from softplc.runtime.devices.fc280.parameters import (
    CONVERSION_FACTORS,
    PARAMETERS,
    encode,
    from_raw,
    index_of,
    number_of,
    parameter,
    sdo_object,
    to_raw,
)


@pytest.mark.parametrize(
    "number, index",
    [
        ("0-01", 0x2001),
        ("0-10", 0x200A),
        ("0-11", 0x200B),
        ("1-00", 0x2064),
        ("1-01", 0x2065),
        ("10-01", 0x23E9),
        ("3-41", 0x2155),
        ("8-03", 0x2323),
        ("16-80", 0x2690),
        ("16-82", 0x2692),
        ("16-03", 0x2643),
        ("10-02", 0x23EA),
        ("99-99", 0x470F),
    ],
)
def test_the_index_rule(number, index):
    assert index_of(number) == index and number_of(index) == number


def test_the_conversion_indices_of_tabelle_6_2():
    assert CONVERSION_FACTORS[100] == 1 and CONVERSION_FACTORS[67] == Fraction(1, 60)
    assert [CONVERSION_FACTORS[i] for i in (6, 5, 4, 3, 2, 1, 0)] == [10**6, 10**5, 10**4, 1000, 100, 10, 1]
    assert [CONVERSION_FACTORS[-i] for i in range(1, 7)] == [Fraction(1, 10**i) for i in range(1, 7)]  # -6: A34


def test_8_03_one_second_is_raw_10_on_the_wire():
    # digest 003 D7: 605: 2B 23 23 00 0A 00 00 00
    p = parameter("8-03")
    assert (p.index, p.size, to_raw(p, 1.0), encode(p, to_raw(p, 1.0))) == (0x2323, 2, 10, b"\x0a\x00")
    assert from_raw(p, 10) == 1.0 and to_raw(p, 0.1) == 1


def test_rpm_parameters_with_index_67_as_printed():
    # 8-90 Bus Jog 1: 100 RPM, conversion index 67 = 1/60 -> raw 6000 (A34)
    assert to_raw(parameter("8-90"), 100) == 6000 and from_raw(parameter("8-90"), 6000) == 100


def test_halves_round_away_from_zero():
    assert to_raw(parameter("8-03"), 0.25) == 3


def test_values_beyond_the_type_are_refused():
    # 8-03 ranges to 18000 s in the manual but is a UInt16 of 0.1 s (A27)
    with pytest.raises(ValueError, match=r"8-03 Steuerwort Timeout-Zeit: 7000.0 s is raw 70000, outside 0..65535"):
        to_raw(parameter("8-03"), 7000.0)
    # found by the fuzz harness (tests/fuzz): inf crashed with OverflowError, nan with an odd ValueError
    for value in (float("inf"), float("-inf"), float("nan")):
        with pytest.raises(ValueError, match=rf"8-07 Diagnose Trigger: {value} is no value a parameter holds"):
            to_raw(parameter("8-07"), value)


def test_the_manuals_parameter_list_with_its_defaults():
    assert (parameter("8-03").default, parameter("8-04").default, parameter("8-10").default) == (10, 0, 0)
    assert (parameter("10-01").default, parameter("10-02").default) == (20, 127)  # 125 kbit/s, node 127
    assert {p.source for p in PARAMETERS.values()} == {"Tabelle 6.1", "simulator choice"}


def test_configured_writes():
    assert sdo_object("8-03", 0.5) == (0x2323, 0, 2, 5)
    assert sdo_object(" 8-4 ", 5) == (0x2324, 0, 1, 5)
    assert sdo_object("3-10[0]", 10.0) == (0x2136, 1, 2, 1000)  # element [0] at sub-index 1 (A35)
    for bad, message in (
        ("8", "g-nn"),
        ("3-10", "is an array"),
        ("8-03[0]", "not an array"),
        ("3-10[8]", "elements [0] to [7]"),
        ("15-40", "is text"),
        ("99-98", "not one"),
    ):
        with pytest.raises(ValueError, match=re.escape(message)):
            sdo_object(bad, 1)
