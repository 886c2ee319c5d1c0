"""rt_numeric.py: REAL rounding and real functions, integer division and
rounding, bit strings and BCD, with the examples of the CODESYS documentation."""

from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from softplc.runtime.st.rtlib import rt_numeric as r

from .rt_helpers import INF, NAN

# ---------------------------------------------------------------- REAL


def test_f32_rounds_to_binary32():
    assert r.f32(0.1) == 0.10000000149011612
    assert r.f32(1.0) == 1.0
    assert r.f32(16777217.0) == 16777216.0  # ties to even


def test_f32_overflow_and_specials():
    assert r.f32(3.5e38) == INF
    assert r.f32(-3.5e38) == -INF
    assert r.f32(3.4028235e38) == 3.4028234663852886e38  # FLT_MAX stays
    assert r.f32(INF) == INF
    assert math.isnan(r.f32(NAN))
    assert r.f32(10**400) == INF  # an int beyond any float
    assert r.f32(1e-46) == 0.0  # underflow


def test_rdiv_is_ieee():
    assert r.rdiv(1.0, 0.0) == INF
    assert r.rdiv(-1.0, 0.0) == -INF
    assert r.rdiv(1.0, -0.0) == -INF
    assert math.isnan(r.rdiv(0.0, 0.0))
    assert r.rdiv(7.0, 2.0) == 3.5


def test_expt():
    assert r.expt(2, 7) == 128.0  # CODESYS example
    assert r.expt(7, 2) == 49.0
    assert math.isnan(r.expt(-8.0, 1 / 3))
    assert r.expt(0.0, -1) == INF
    assert r.expt(-0.0, -1) == -INF
    assert r.expt(10.0, 400) == INF
    assert r.expt(-10.0, 401) == -INF
    assert r.expt(-2.0, 3) == -8.0


def test_real_functions_never_raise():
    assert math.isnan(r.sqrt(-1.0))
    assert r.sqrt(16) == 4.0
    assert r.ln(0.0) == -INF
    assert math.isnan(r.ln(-1.0))
    assert r.log(1000.0) == pytest.approx(3.0)
    assert r.log(0) == -INF
    assert r.exp(1000.0) == INF
    assert math.isnan(r.sin(INF))
    assert math.isnan(r.tan(INF))
    assert math.isnan(r.asin(2.0))
    assert math.isnan(r.acos(-2.0))
    assert r.atan2(1.0, 0.0) == pytest.approx(math.pi / 2)


# ---------------------------------------------------------------- integers


def test_idiv_truncates_toward_zero():
    assert r.idiv(-7, 2) == -3
    assert r.idiv(7, -2) == -3
    assert r.idiv(-7, -2) == 3
    assert r.idiv(7, 2) == 3
    assert r.idiv(-6, 2) == -3
    assert r.idiv(0, -5) == 0


def test_imod_takes_sign_of_dividend():
    assert r.imod(-7, 2) == -1
    assert r.imod(7, -2) == 1
    assert r.imod(-7, -2) == -1
    assert r.imod(7, 2) == 1
    assert r.imod(-6, 3) == 0


def test_division_by_zero_raises():
    with pytest.raises(ZeroDivisionError):
        r.idiv(1, 0)
    with pytest.raises(ZeroDivisionError):
        r.imod(1, 0)


@settings(max_examples=300, deadline=None)
@given(st.integers(-(2**64), 2**64), st.integers(-(2**64), 2**64).filter(bool))
def test_idiv_imod_identity(a, b):
    q, m = r.idiv(a, b), r.imod(a, b)
    assert q * b + m == a
    assert abs(m) < abs(b)
    assert m == 0 or (m < 0) == (a < 0)
    assert q == int(a / b) or abs(a) > 2**52  # trunc of the exact quotient


def test_round_half_away_from_zero():
    # CODESYS: REAL_TO_INT(1.5) = 2, (1.4) = 1, (-1.5) = -2
    assert r.round_half_away(1.5) == 2
    assert r.round_half_away(1.4) == 1
    assert r.round_half_away(-1.5) == -2
    assert r.round_half_away(-1.4) == -1
    assert r.round_half_away(2.5) == 3  # not banker's rounding
    assert r.round_half_away(0.49999999999999994) == 0  # no x + 0.5 trap
    assert r.round_half_away(NAN) == 0
    assert r.round_half_away(INF) == 0
    assert r.round_half_away(1e20) == 10**20


def test_trunc():
    assert r.trunc(-2.7) == -2
    assert r.trunc(2.7) == 2
    assert r.trunc(NAN) == 0


# ---------------------------------------------------------------- bit strings


def test_shifts_and_rotations():
    assert r.shl(8, 0x81, 1) == 0x02
    assert r.shr(8, 0x81, 1) == 0x40
    assert r.rol(8, 0x81, 1) == 0x03
    assert r.ror(8, 0x81, 1) == 0xC0
    assert r.shl(8, 0x45, 2) == 0x14  # CODESYS SHL example, BYTE
    assert r.shl(16, 0x45, 2) == 0x0114  # ... and WORD
    assert r.shr(8, 0x45, 2) == 0x11


def test_shift_by_width_or_more():
    assert r.shl(8, 0xFF, 8) == 0
    assert r.shr(16, 0xFFFF, 40) == 0
    assert r.rol(8, 0x81, 9) == 0x03  # modulo width
    assert r.ror(8, 0x81, 17) == 0xC0
    assert r.shl(8, 0x81, -1) == 0x40  # negative: the other way
    assert r.rol(8, 0x81, -1) == 0xC0


def test_shift_signed_pattern():
    assert r.shr(16, -1, 4) == 0x0FFF  # logical, zeros shifted in
    assert r.shl(16, -1, 4) == 0xFFF0


# ---------------------------------------------------------------- BCD


def test_bcd():
    assert r.bcd_to_int(0x27, 8) == 27  # CODESYS BCD_TO_INT(2#00100111)
    assert r.int_to_bcd(81, 8) == 0x81  # CODESYS INT_TO_BCD(81) = 2#10000001
    assert r.bcd_to_int(0x1234, 16) == 1234
    assert r.int_to_bcd(9999, 16) == 0x9999
    assert r.bcd_to_int(0x1A, 8) == -1  # invalid nibble
    assert r.int_to_bcd(100, 8) == 0xFF  # does not fit
    assert r.int_to_bcd(-1, 16) == 0xFFFF
    assert r.int_to_bcd(0, 8) == 0
