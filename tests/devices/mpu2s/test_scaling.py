"""MPU2-S scaling families: every documented endpoint pair of digest 004
§5.1 (real -> raw, printed in the manual), the rounding of §3.1, and
raw -> value -> raw identity for every family over every 16-bit word."""

from __future__ import annotations

from decimal import Decimal
from fractions import Fraction

import pytest
from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.devices.mpu2s import scaling
from softplc.runtime.devices.mpu2s.scaling import family

# digest §5.1 "Documented range endpoints as conversion vectors": (family, real, raw)
ENDPOINTS = [
    # f·256
    *(
        ("frequency", real, raw)
        for real, raw in [
            (40, 10240),
            (70, 17920),  # E1
            (50, 12800),
            (60, 15360),
            (85, 21760),
            (15, 3840),
            (0, 0),
            (0.02, 5),
            (0.49, 125),
            (0.00, 0),
            (1.00, 256),
            (0.05, 13),
            (5.00, 1280),
        ]
    ),
    # t[s]·50
    *(
        ("time", real, raw)
        for real, raw in [
            (0, 0),
            (999, 49950),
            (600, 30000),
            (99, 4950),
            (99.9, 4995),
            (0.02, 1),
            (99.98, 4999),
            (9.98, 499),
            (0.26, 13),
            (1.98, 99),
        ]
    ),
    # t[s]·1
    *(("seconds", real, raw) for real, raw in [(10, 10), (999, 999), (1, 1), (99, 99)]),
    # t[ms]·1
    *(("milliseconds", real, raw) for real, raw in [(40, 40), (300, 300)]),
    # t[ms]·0.5
    *(("pulse", real, raw) for real, raw in [(10, 5), (20, 10), (250, 125)]),
    # %·40
    *(("percent_40", real, raw) for real, raw in [(0.1, 4), (15.0, 600), (20.0, 800)]),
    # %·10
    *(
        ("percent_10", real, raw)
        for real, raw in [
            (0.5, 5),
            (25.0, 250),
            (0.1, 1),
            (10, 100),
            (120, 1200),
            (0, 0),
            (50, 500),
            (5, 50),
            (110, 1100),
            (80, 800),
            (150, 1500),
            (-99, -990),
            (99, 990),
            (100, 1000),
            (300, 3000),
        ]
    ),
    # ·10
    *(("gain", real, raw) for real, raw in [(0.1, 1), (99.9, 999), (1.0, 10), (9.9, 99)]),
    # ·1000
    *(("multiple", real, raw) for real, raw in [(0.1, 100), (3.0, 3000), (1.00, 1000), (3.00, 3000)]),
    # U·10
    *(("battery", real, raw) for real, raw in [(9.5, 95), (30.0, 300)]),
    # cosφ·100
    *(("cos_phi", real, raw) for real, raw in [(-0.7, -70), (-0.99, -99), (1.00, 100), (0.7, 70), (0.99, 99)]),
    # ramp: the printed range "1 Hz/s -> 102, 50 Hz/s -> 5120", with 102.4 (A13)
    *(("ramp", real, raw) for real, raw in [(1, 102), (50, 5120)]),
    # %·1 (4.2.34 0..100 %/s, 4.2.83 10..90 %) and plain ·1 (4.2.5 5..65000 V, 4.2.116 3..30°)
    *(("percent_1", real, raw) for real, raw in [(0, 0), (100, 100), (10, 10), (90, 90)]),
    *(("plain", real, raw) for real, raw in [(5, 5), (65000, 65000), (-9999, -9999), (3, 3), (30, 30)]),
]


@pytest.mark.parametrize("name, real, raw", ENDPOINTS, ids=lambda x: str(x))
def test_documented_endpoints(name, real, raw):
    assert family(name).to_raw(real) == raw


def test_rounding_to_nearest_as_documented():
    # §3.1: 0.05 Hz -> 13 (12.8), 0.49 Hz -> 125 (125.44), 0.02 Hz -> 5 (5.12)
    f = scaling.FREQUENCY
    assert (f.to_raw(0.05), f.to_raw(0.49), f.to_raw(0.02)) == (13, 125, 5)
    # V8, V9: 0.20 Hz -> 51 (51.2), 0.10 Hz -> 26 (25.6)
    assert (f.to_raw(0.20), f.to_raw(0.10)) == (51, 26)


def test_halves_round_away_from_zero():
    # 13 ms at 2 ms steps is 6.5 -> 7 (Python's round() would give 6); 15 ms: 7.5 -> 8
    assert scaling.PULSE.to_raw(13) == 7 and scaling.PULSE.to_raw(15) == 8
    assert scaling.COS_PHI.to_raw(-0.705) == -71 and scaling.COS_PHI.to_raw(0.705) == 71
    assert scaling.round_half_away(Fraction(-5, 2)) == -3 and scaling.round_half_away(Fraction(5, 2)) == 3


def test_values_are_taken_by_their_decimal_form():
    # 2.675 is 2.67499999... in binary; the user wrote 2.675: ·100 = 267.5 -> 268
    assert scaling.family("cos_phi").to_raw(2.675) == 268
    assert scaling.TIME.to_raw(Decimal("0.01")) == 1  # 0.5 -> 1
    assert scaling.TIME.to_raw(Fraction(1, 50)) == 1


def test_from_raw_of_exact_endpoints():
    assert scaling.FREQUENCY.from_raw(17920) == 70.0  # E1
    assert scaling.FREQUENCY.from_raw(12800) == 50.0
    assert scaling.TIME.from_raw(4999) == 99.98
    assert scaling.PULSE.from_raw(125) == 250.0
    assert scaling.COS_PHI.from_raw(-98) == -0.98
    assert scaling.RAMP.from_raw(5120) == 50.0


def test_voltage_families_need_their_factor():
    # 4.2.10: raw = U·KWUGNSEK/400, KWUGNSEK from ID 507; KWUNTSEK from ID 508 (4.2.110)
    assert scaling.FACTOR_IDS == {"voltage_gen": 507, "voltage_mains": 508}
    with pytest.raises(ValueError, match="KWUGNSEK.*ID 507"):
        family("voltage_gen")
    with pytest.raises(ValueError, match="KWUNTSEK.*ID 508"):
        family("voltage_mains")
    assert family("voltage_gen", 400).to_raw(400) == 400
    assert family("voltage_gen", 800).to_raw(25) == 50  # 25·800/400
    assert family("voltage_mains", 1000).to_raw(125) == 313  # 312.5 -> 313
    assert family("voltage_gen", 800).from_raw(50) == 25.0
    for bad in (0, -1, 0x10000, 1.5, True):
        with pytest.raises(ValueError):
            family("voltage_gen", bad)
    with pytest.raises(ValueError):
        family("frequency", 400)
    with pytest.raises(ValueError):
        family("furlongs")


def test_non_numbers_are_refused():
    for bad in (float("nan"), float("inf"), Decimal("NaN")):
        with pytest.raises(ValueError):
            scaling.FREQUENCY.to_raw(bad)
    with pytest.raises(TypeError):
        scaling.FREQUENCY.to_raw(True)
    with pytest.raises(TypeError):
        scaling.FREQUENCY.to_raw("50")  # type: ignore[arg-type]


WORDS = st.integers(-0x8000, 0xFFFF)  # every 16-bit word, read signed or unsigned


@pytest.mark.parametrize("name", sorted(scaling.FAMILIES))
@given(raw=WORDS)
def test_raw_value_raw_is_identity(name, raw):
    scale = family(name)
    assert scale.to_raw(scale.from_raw(raw)) == raw


@pytest.mark.parametrize("name", sorted(scaling.FACTOR_IDS))
@given(raw=WORDS, factor=st.integers(1, 0xFFFF))
def test_voltage_raw_value_raw_is_identity(name, raw, factor):
    scale = family(name, factor)
    assert scale.to_raw(scale.from_raw(raw)) == raw


def test_every_family_of_section_3_1_is_there():
    assert set(scaling.FAMILIES) | set(scaling.FACTOR_IDS) == {
        "frequency",
        "ramp",
        "time",
        "seconds",
        "milliseconds",
        "pulse",
        "percent_40",
        "percent_10",
        "percent_1",
        "gain",
        "multiple",
        "plain",
        "voltage_gen",
        "voltage_mains",
        "battery",
        "cos_phi",
    }
