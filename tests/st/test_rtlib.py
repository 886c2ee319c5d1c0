"""The runtime library: IEC/CODESYS semantics of arithmetic, conversion,
strings, bit strings, BCD and time/date values, with the examples the
CODESYS documentation gives."""
import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from softplc.runtime.st import rtlib as r
from softplc.runtime.st import types as T

STRING = T.StringType(80)
WSTRING = T.StringType(80, wide=True)
NAN = float("nan")
INF = float("inf")


def conv(src, dst, v):
    return r.make_converter(src, dst)(v)


def ns(text, cat):
    return r.parse_temporal(text, cat)


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
    assert r.f32(10 ** 400) == INF  # an int beyond any float
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
@given(st.integers(-2 ** 64, 2 ** 64), st.integers(-2 ** 64, 2 ** 64).filter(bool))
def test_idiv_imod_identity(a, b):
    q, m = r.idiv(a, b), r.imod(a, b)
    assert q * b + m == a
    assert abs(m) < abs(b)
    assert m == 0 or (m < 0) == (a < 0)
    assert q == int(a / b) or abs(a) > 2 ** 52  # trunc of the exact quotient


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
    assert r.round_half_away(1e20) == 10 ** 20


def test_trunc():
    assert r.trunc(-2.7) == -2
    assert r.trunc(2.7) == 2
    assert r.trunc(NAN) == 0


def test_wrap():
    assert r.wrap(T.INT, 32768) == -32768
    assert r.wrap(T.SINT, 300) == 44
    assert r.wrap(T.UINT, -1) == 65535
    assert r.wrap(T.BYTE, 256 + 7) == 7
    assert r.wrap(T.ULINT, -1) == 2 ** 64 - 1
    assert r.wrap(T.REAL, 0.1) == 0.10000000149011612
    assert r.wrap(T.BOOL, 2) is True
    assert r.wrap(T.StringType(3), "abcdef") == "abc"
    assert r.wrapper(T.INT) is r.wrapper(T.INT)  # cached


def test_wrap_time():
    assert r.wrap_time(T.TIME, 2 ** 31) == -(2 ** 31)
    assert r.wrap_time(T.TIME, -5000) == -5000
    assert r.wrap_time(T.TOD, 86_400_000 + 5) == 5  # wraps at midnight
    assert r.wrap_time(T.TOD, -1) == 86_399_999
    assert r.wrap_time(T.DATE, 86_400 * 3 + 100) == 86_400 * 3  # kept at midnight
    assert r.wrap_time(T.DT, -1) == 2 ** 32 - 1


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


# ---------------------------------------------------------------- strings

def test_string_functions_codesys_examples():
    assert r.LEN("SUSI") == 4
    assert r.LEFT("SUSI", 3) == "SUS"
    assert r.RIGHT("SUSI", 3) == "USI"
    assert r.MID("SUSI", 2, 2) == "US"
    assert r.CONCAT("SUSI", "WILLI") == "SUSIWILLI"
    assert r.CONCAT("a", "b", "c") == "abc"
    assert r.INSERT("SUSI", "XY", 2) == "SUXYSI"
    assert r.DELETE("SUXYSI", 2, 3) == "SUSI"
    assert r.REPLACE("SUXYSI", "K", 2, 2) == "SKYSI"
    assert r.FIND("abcdef", "de") == 4
    assert r.FIND("abcdef", "x") == 0


def test_string_edge_cases_never_raise():
    assert r.LEFT("SUSI", 0) == ""
    assert r.LEFT("SUSI", -1) == ""
    assert r.LEFT("SUSI", 10) == "SUSI"
    assert r.RIGHT("SUSI", 0) == ""
    assert r.RIGHT("SUSI", 10) == "SUSI"
    assert r.MID("SUSI", 2, 0) == ""
    assert r.MID("SUSI", 2, 5) == ""
    assert r.MID("SUSI", 10, 3) == "SI"
    assert r.MID("SUSI", 2, -1) == ""
    assert r.INSERT("SUSI", "XY", 0) == "XYSUSI"
    assert r.INSERT("SUSI", "XY", -3) == "XYSUSI"
    assert r.INSERT("SUSI", "XY", 9) == "SUSIXY"
    assert r.DELETE("SUSI", 2, 0) == "SUSI"
    assert r.DELETE("SUSI", 2, 5) == "SUSI"
    assert r.DELETE("SUSI", 10, 2) == "S"
    assert r.DELETE("SUSI", -1, 2) == "SUSI"
    assert r.REPLACE("SUSI", "XY", 1, 9) == "SUSIXY"
    assert r.REPLACE("SUSI", "XY", 1, 0) == "XYUSI"
    assert r.REPLACE("SUSI", "XY", -2, 2) == "SXYUSI"
    assert r.FIND("abc", "") == 0
    assert r.FIND("", "a") == 0


# ---------------------------------------------------------------- parsing text

def test_parse_int():
    assert r.parse_int("  42 ") == 42
    assert r.parse_int("-7") == -7
    assert r.parse_int("16#FF") == 255
    assert r.parse_int("16#ff") == 255
    assert r.parse_int("2#1010_0001") == 0xA1
    assert r.parse_int("8#17") == 15
    assert r.parse_int("INT#-5") == -5
    assert r.parse_int("1_000") == 1000
    assert r.parse_int("abc34") is None
    assert r.parse_int("34abc") is None
    assert r.parse_int("3.5") is None
    assert r.parse_int("2#102") is None
    assert r.parse_int("") is None
    assert r.parse_int("1__0") is None
    assert r.parse_int("0x1F") is None


def test_parse_real_and_bool():
    assert r.parse_real("1.5") == 1.5
    assert r.parse_real(" -2.5E-3 ") == -0.0025
    assert r.parse_real("1e3") == 1000.0
    assert r.parse_real("REAL#2") == 2.0
    assert r.parse_real("16#10") == 16.0
    assert r.parse_real("INF") == INF
    assert r.parse_real("1.5x") is None
    assert r.parse_real("nan?") is None
    assert r.parse_bool("TRUE") is True
    assert r.parse_bool(" false ") is False
    assert r.parse_bool("BOOL#TRUE") is True
    assert r.parse_bool("1") is True
    assert r.parse_bool("0") is False
    assert r.parse_bool("yes") is None


def test_parse_temporal():
    assert ns("T#1s500ms", T.DURATION) == 1_500_000_000
    assert ns("TIME#1h2m3s4ms", T.DURATION) == 3_723_004_000_000
    assert ns("t#-1d_2h", T.DURATION) == -26 * 3_600_000_000_000
    assert ns("T#1.5s", T.DURATION) == 1_500_000_000
    assert ns("LT#1us7ns", T.DURATION) == 1007
    assert ns("1m30s", T.DURATION) == 90_000_000_000  # prefix optional
    assert ns("D#2024-01-02", T.DATECAT) == 19724 * 86_400 * 10 ** 9
    assert ns("TOD#12:30:15.5", T.TODCAT) == 45_015_500_000_000
    assert ns("TIME_OF_DAY#12:30", T.TODCAT) == 45_000_000_000_000
    assert ns("DT#2024-01-02-12:30:15", T.DTCAT) == (19724 * 86_400 + 45_015) * 10 ** 9
    assert ns("D#2024-02-30", T.DATECAT) is None
    assert ns("TOD#25:00:00", T.TODCAT) is None
    assert ns("D#2024-01-02", T.DURATION) is None  # wrong prefix
    assert ns("T#5", T.DURATION) is None  # no unit
    assert ns("T#", T.DURATION) is None


# ---------------------------------------------------------------- literals

def test_iec_literal_time():
    assert r.iec_literal(T.TIME, 3_723_004) == "T#1h2m3s4ms"
    assert r.iec_literal(T.TIME, 0) == "T#0ms"
    assert r.iec_literal(T.TIME, -5000) == "T#-5s"
    assert r.iec_literal(T.TIME, 26 * 3_600_000) == "T#1d2h"
    assert r.iec_literal(T.LTIME, 1_000_500_007) == "LT#1s500us7ns"
    assert r.iec_literal(T.LTIME, 0) == "LT#0ns"


def test_iec_literal_dates():
    day = 19724 * 86_400  # 2024-01-02
    assert r.iec_literal(T.DATE, day) == "D#2024-01-02"
    assert r.iec_literal(T.TOD, 45_015_500) == "TOD#12:30:15.5"
    assert r.iec_literal(T.TOD, 45_015_000) == "TOD#12:30:15"
    assert r.iec_literal(T.DT, day + 45_015) == "DT#2024-01-02-12:30:15"
    assert r.iec_literal(T.LDATE, day * 10 ** 9) == "LD#2024-01-02"
    assert r.iec_literal(T.LTOD, 45_015_000_000_001) == "LTOD#12:30:15.000000001"
    assert r.iec_literal(T.LDT, (day + 45_015) * 10 ** 9 + 500_000_000) == \
        "LDT#2024-01-02-12:30:15.5"
    assert r.iec_literal(T.DATE, 0) == "D#1970-01-01"
    assert r.iec_literal(T.DT, 2 ** 32 - 1) == "DT#2106-02-07-06:28:15"


def test_iec_literal_other_types():
    assert r.iec_literal(T.BOOL, True) == "TRUE"
    assert r.iec_literal(T.INT, -5) == "-5"
    assert r.iec_literal(T.REAL, 1.5) == "1.5"
    assert r.iec_literal(STRING, "it's $5\n") == "'it$'s $$5$N'"
    assert r.iec_literal(WSTRING, 'say "hi"') == '"say $"hi$""'
    color = T.EnumType("Color", {"RED": 0, "GREEN": 1}, {"RED": "Red", "GREEN": "Green"})
    assert r.iec_literal(color, 1) == "Color#Green"
    assert r.iec_literal(color, 7) == "7"


_TEMPORAL = [(T.TIME, T.DURATION, st.integers(-2 ** 31, 2 ** 31 - 1)),
             (T.LTIME, T.DURATION, st.integers(-2 ** 63, 2 ** 63 - 1)),
             (T.DATE, T.DATECAT, st.integers(0, 2 ** 32 // 86_400 - 1).map(lambda d: d * 86_400)),
             (T.TOD, T.TODCAT, st.integers(0, 86_400_000 - 1)),
             (T.DT, T.DTCAT, st.integers(0, 2 ** 32 - 1)),
             (T.LTOD, T.TODCAT, st.integers(0, 86_400 * 10 ** 9 - 1)),
             (T.LDT, T.DTCAT, st.integers(0, 2 ** 64 - 1))]


@pytest.mark.parametrize("t,cat,values", _TEMPORAL, ids=[x[0].name for x in _TEMPORAL])
def test_iec_literal_round_trips(t, cat, values):
    @settings(max_examples=60, deadline=None)
    @given(values)
    def check(v):
        text = r.iec_literal(t, v)
        assert r.from_ns(t, r.parse_temporal(text, cat)) == v
        assert conv(STRING, t, text) == v  # STRING_TO_<t>
    check()


# ---------------------------------------------------------------- REAL <-> STRING

def test_real_to_string():
    assert r.real_to_string(1.5) == "1.5"
    assert r.real_to_string(100.0) == "100.0"
    assert r.real_to_string(r.f32(0.1)) == "0.1"  # shortest, not 0.100000001
    assert r.real_to_string(-2.5) == "-2.5"
    assert r.real_to_string(1e20) == "1.0E+20"
    assert r.real_to_string(r.f32(1e-6)) == "1.0E-06"
    assert r.real_to_string(r.f32(0.00001)) == "0.00001"
    assert r.real_to_string(12345678.0) == "1.2345678E+07"
    assert r.real_to_string(12345678.0, lreal=True) == "12345678.0"
    assert r.real_to_string(0.1, lreal=True) == "0.1"
    assert r.real_to_string(0.0) == "0.0"
    assert r.real_to_string(-0.0) == "0.0"
    assert r.real_to_string(INF) == "INF"
    assert r.real_to_string(-INF) == "-INF"
    assert r.real_to_string(NAN) == "NAN"


@settings(max_examples=300, deadline=None)
@given(st.floats(width=32, allow_nan=False))
def test_real_to_string_round_trips(x):
    assert conv(STRING, T.REAL, conv(T.REAL, STRING, x)) == x


@settings(max_examples=300, deadline=None)
@given(st.floats(allow_nan=False))
def test_lreal_to_string_round_trips(x):
    assert conv(STRING, T.LREAL, conv(T.LREAL, STRING, x)) == x


# ---------------------------------------------------------------- conversions

def test_integer_conversions_wrap():
    assert conv(T.INT, T.SINT, 300) == 44
    assert conv(T.INT, T.SINT, 4223) == 127  # CODESYS example
    assert conv(T.DINT, T.UINT, -1) == 65535
    assert conv(T.UDINT, T.DINT, 2 ** 32 - 1) == -1
    assert conv(T.INT, T.WORD, -1) == 0xFFFF
    assert conv(T.WORD, T.INT, 0x8000) == -32768
    assert conv(T.LINT, T.ULINT, -2) == 2 ** 64 - 2
    assert conv(T.SINT, T.LINT, -5) == -5


def test_real_to_integer_rounds_then_wraps():
    assert conv(T.REAL, T.INT, 1.5) == 2
    assert conv(T.REAL, T.INT, 1.4) == 1
    assert conv(T.REAL, T.INT, -1.5) == -2
    assert conv(T.LREAL, T.SINT, 300.4) == 44
    assert conv(T.REAL, T.UINT, -1.0) == 65535
    assert conv(T.REAL, T.DINT, NAN) == 0
    assert conv(T.LREAL, T.DINT, INF) == 0
    assert conv(T.REAL, T.BYTE, 255.5) == 0  # 256 wraps


def test_to_real():
    assert conv(T.DINT, T.REAL, 16777217) == 16777216.0
    assert conv(T.ULINT, T.REAL, 2 ** 64 - 1) == 18446744073709551616.0
    assert conv(T.LINT, T.REAL, 2 ** 53 + 2 ** 29 + 1) == 9007200328482816.0  # rounded once
    assert conv(T.LREAL, T.REAL, 0.1) == 0.10000000149011612
    assert conv(T.LREAL, T.REAL, 1e300) == INF
    assert conv(T.REAL, T.LREAL, r.f32(0.1)) == 0.10000000149011612
    assert conv(T.ULINT, T.LREAL, 2 ** 64 - 1) == 1.8446744073709552e19
    assert conv(T.BOOL, T.REAL, True) == 1.0


def test_bool_conversions():
    assert conv(T.INT, T.BOOL, 0) is False
    assert conv(T.INT, T.BOOL, -3) is True
    assert conv(T.REAL, T.BOOL, 0.5) is True
    assert conv(T.REAL, T.BOOL, 0.0) is False
    assert conv(T.TIME, T.BOOL, 59) is True  # CODESYS TIME_TO_BOOL(T#59ms)
    assert conv(T.TIME, T.BOOL, 0) is False
    assert conv(T.BOOL, T.INT, True) == 1
    assert conv(T.BOOL, T.BYTE, False) == 0
    assert conv(T.BOOL, T.TIME, True) == 1  # T#1ms
    assert conv(T.BOOL, T.DATE, True) == 0  # 1 s after midnight -> the day


def test_time_number_conversions_are_raw():
    assert conv(T.TIME, T.DINT, 1000) == 1000  # TIME_TO_DINT(T#1s)
    assert conv(T.TIME, T.DWORD, 300_000) == 300_000  # TIME_TO_DWORD(T#5m)
    assert conv(T.TIME, T.UDINT, -1) == 2 ** 32 - 1
    assert conv(T.LTIME, T.INT, 2001) == 2001
    assert conv(T.DINT, T.TIME, 1500) == 1500
    assert conv(T.REAL, T.TIME, 1.5) == 2  # ms, rounded
    assert conv(T.TIME, T.REAL, 1500) == 1500.0
    d15 = 14 * 86_400  # D#1970-01-15
    assert conv(T.DATE, T.INT, d15) == 29952  # CODESYS DATE_TO_INT example
    assert conv(T.DATE, T.BYTE, d15) == 0
    assert conv(T.DT, T.BYTE, d15 + 5 * 3600 + 5 * 60 + 5) == 129  # CODESYS DT_TO_BYTE
    assert conv(T.UDINT, T.DATE, d15 + 100) == d15  # kept at midnight
    assert conv(T.DINT, T.TOD, -1) == 86_399_999  # wraps at midnight


def test_time_date_conversions():
    dt = 19724 * 86_400 + 45_015  # DT#2024-01-02-12:30:15
    assert conv(T.DT, T.TOD, dt) == 45_015_000
    assert conv(T.DT, T.DATE, dt) == 19724 * 86_400
    assert conv(T.DATE, T.DT, 19724 * 86_400) == 19724 * 86_400
    assert conv(T.DT, T.LDT, dt) == dt * 10 ** 9
    assert conv(T.LDT, T.DT, dt * 10 ** 9 + 999_999_999) == dt  # floor to the second
    assert conv(T.LDT, T.LTOD, dt * 10 ** 9 + 7) == 45_015 * 10 ** 9 + 7
    assert conv(T.LDT, T.LDATE, dt * 10 ** 9) == 19724 * 86_400 * 10 ** 9
    assert conv(T.TIME, T.LTIME, 1500) == 1_500_000_000
    assert conv(T.LTIME, T.TIME, 1_999_999) == 1  # truncated
    assert conv(T.LTIME, T.TIME, -1_500_999) == -1  # toward zero
    assert conv(T.TOD, T.LTOD, 45_015_500) == 45_015_500_000_000
    assert conv(T.TOD, T.TIME, 45_015_500) == 45_015_500
    assert conv(T.TIME, T.TOD, 25 * 3_600_000) == 3_600_000  # 25 h -> 01:00
    t = 5 * 86_400_000 + 4 * 3_600_000 + 3 * 60_000 + 2_001  # T#5d4h3m2s1ms
    assert r.iec_literal(T.DT, conv(T.TIME, T.DT, t)) == "DT#1970-01-06-04:03:02"  # CODESYS
    assert conv(T.LTIME, T.DATE, 2001) == 0  # LTIME_TO_DATE(LTIME#2us1ns) = D#1970-1-1
    assert conv(T.TOD, T.DT, 3_600_000) == 3600  # 1970-01-01-01:00


def test_to_string():
    assert conv(T.INT, STRING, 42) == "42"
    assert conv(T.BYTE, STRING, 255) == "255"
    assert conv(T.BOOL, STRING, True) == "TRUE"
    assert conv(T.BOOL, WSTRING, False) == "FALSE"
    assert conv(T.REAL, STRING, 1.5) == "1.5"
    assert conv(T.LREAL, STRING, 1 / 3) == "0.3333333333333333"
    assert conv(T.TIME, STRING, 12) == "T#12ms"  # CODESYS TIME_TO_STRING(T#12ms)
    assert conv(T.TIME, STRING, 1500) == "T#1s500ms"
    assert conv(T.DATE, STRING, 10_270 * 86_400) == "D#1998-02-13"  # CODESYS example
    assert conv(T.DT, STRING, 10_270 * 86_400 + 14 * 3600 + 20 * 60) == "DT#1998-02-13-14:20:00"
    assert conv(T.TOD, STRING, 43_200_000) == "TOD#12:00:00"


def test_from_string():
    assert conv(STRING, T.INT, "  42 ") == 42
    assert conv(STRING, T.INT, "16#FF") == 255
    assert conv(STRING, T.INT, "abc") == 0
    assert conv(STRING, T.WORD, "abc34") == 0  # CODESYS example
    assert conv(STRING, T.SINT, "300") == 44  # wraps like INT_TO_SINT
    assert conv(STRING, T.BOOL, "TRUE") is True  # CODESYS example
    assert conv(STRING, T.BOOL, "maybe") is False
    assert conv(STRING, T.TIME, "T#127ms") == 127  # CODESYS example
    assert conv(STRING, T.TIME, "T#1.5ms") == 1  # truncated to ms
    assert conv(STRING, T.TIME, "garbage") == 0
    assert conv(STRING, T.REAL, "0.1") == 0.10000000149011612
    assert conv(STRING, T.LREAL, "x") == 0.0
    assert conv(STRING, T.DATE, "D#2024-01-02") == 19724 * 86_400
    assert conv(STRING, T.TOD, "TOD#12:30:15.5") == 45_015_500
    assert conv(STRING, T.DT, "DT#2024-01-02-12:30:15") == 19724 * 86_400 + 45_015
    assert conv(STRING, T.LTIME, "LTIME#1ms7ns") == 1_000_007


def test_string_kinds():
    assert conv(WSTRING, STRING, "Grüße €") == "Grüße ?"  # STRING is 8-bit
    assert conv(STRING, WSTRING, "abc") == "abc"


def test_enum_and_subrange_convert_through_base():
    color = T.EnumType("Color", {"RED": 0, "GREEN": 1}, {"RED": "Red", "GREEN": "Green"})
    assert conv(color, T.DINT, 1) == 1
    assert conv(color, STRING, 1) == "1"
    assert conv(T.INT, color, 1) == 1
    sub = T.SubrangeType(T.INT, 0, 100)
    assert conv(sub, T.SINT, 100) == 100
    assert conv(T.DINT, sub, 70000) == 70000 - 65536


def test_convert_caches_and_matches_make_converter():
    assert r.convert(300, T.INT, T.SINT) == 44
    assert r.convert(300, T.INT, T.SINT) == 44
    assert r.convert(1.5, T.REAL, STRING) == "1.5"


def test_from_ns_and_to_ns():
    assert r.from_ns(T.TIME, 1_500_000) == 1  # T#1.5ms as TIME
    assert r.from_ns(T.TIME, -1_500_000) == -1
    assert r.from_ns(T.LTIME, 7) == 7
    assert r.from_ns(T.DATE, 86_400 * 10 ** 9) == 86_400
    assert r.to_ns(T.TIME, 2) == 2_000_000
    assert r.to_ns(T.DT, 1) == 10 ** 9


# ---------------------------------------------------------------- time and date arithmetic

DAY = 19724 * 86_400  # D#2024-01-02


def test_time_arithmetic():
    assert r.ADD_TIME(1000, 500) == 1500
    assert r.SUB_TIME(1000, 1500) == -500
    assert r.ADD_TIME(2 ** 31 - 1, 1) == -(2 ** 31)  # wraps like DINT
    assert r.MUL_TIME(1500, 3) == 4500
    assert r.MUL_TIME(1000, 1.5) == 1500
    assert r.MUL_TIME(3, 0.5) == 2  # 1.5 ms rounds away from zero
    assert r.DIV_TIME(10, 4) == 2  # integer divisor truncates
    assert r.DIV_TIME(-10, 4) == -2
    assert r.DIV_TIME(10, 4.0) == 3  # real divisor rounds
    with pytest.raises(ZeroDivisionError):
        r.DIV_TIME(10, 0)
    with pytest.raises(ZeroDivisionError):
        r.DIV_TIME(10, 0.0)
    assert r.ADD_LTIME(1, 2) == 3
    assert r.MUL_LTIME(10 ** 9, 2) == 2 * 10 ** 9
    assert r.DIV_LTIME(10 ** 9, 3) == 333_333_333


def test_tod_arithmetic_wraps_at_midnight():
    assert r.ADD_TOD_TIME(86_399_999, 1) == 0  # TOD#23:59:59.999 + T#1ms
    assert r.ADD_TOD_TIME(3_600_000, 1_800_000) == 5_400_000
    assert r.SUB_TOD_TIME(1_000, 2_000) == 86_399_000
    assert r.SUB_TOD_TOD(3_600_000, 7_200_000) == -3_600_000
    assert r.ADD_LTOD_LTIME(86_400 * 10 ** 9 - 1, 2) == 1
    assert r.SUB_LTOD_LTIME(0, 1) == 86_400 * 10 ** 9 - 1
    assert r.SUB_LTOD_LTOD(5, 7) == -2


def test_dt_arithmetic():
    assert r.ADD_DT_TIME(DAY, 1500) == DAY + 1  # DT has whole seconds
    assert r.ADD_DT_TIME(DAY, -1500) == DAY - 2  # floor
    assert r.SUB_DT_TIME(DAY, 1000) == DAY - 1
    assert r.SUB_DT_DT(DAY + 60, DAY) == 60_000
    assert r.SUB_DATE_DATE(DAY + 86_400, DAY) == 86_400_000
    assert r.SUB_DATE_DATE(DAY + 25 * 86_400, DAY) == 25 * 86_400_000 - 2 ** 32  # TIME wraps
    assert r.ADD_LDT_LTIME(5, 7) == 12
    assert r.SUB_LDT_LTIME(5, 7) == 2 ** 64 - 2
    assert r.SUB_LDT_LDT(5, 7) == -2
    assert r.SUB_LDATE_LDATE(86_400 * 10 ** 9, 0) == 86_400 * 10 ** 9


def test_concat_and_day_of_week():
    assert r.CONCAT_DATE_TOD(DAY, 45_015_500) == DAY + 45_015
    assert r.CONCAT_LDATE_LTOD(DAY * 10 ** 9, 5) == DAY * 10 ** 9 + 5
    assert r.CONCAT_DATE(2024, 1, 2) == DAY
    assert r.CONCAT_DATE(2024, 13, 1) == 0  # impossible date
    assert r.CONCAT_TOD(12, 30, 15, 500) == 45_015_500
    assert r.CONCAT_TOD(24, 0, 0, 1) == 1
    assert r.CONCAT_LTOD(0, 0, 1, 1) == 1_001_000_000
    assert r.CONCAT_DT(2024, 1, 2, 12, 30, 15, 999) == DAY + 45_015
    assert r.CONCAT_DT(2023, 2, 29, 0, 0, 0, 0) == 0
    assert r.CONCAT_LDT(2024, 1, 2, 0, 0, 1, 5) == (DAY + 1) * 10 ** 9 + 5_000_000
    assert r.DAY_OF_WEEK(0) == 4  # 1970-01-01 was a Thursday
    assert r.DAY_OF_WEEK(DAY) == 2  # 2024-01-02 was a Tuesday
    assert r.DAY_OF_WEEK(DAY + 5 * 86_400) == 0  # Sunday
