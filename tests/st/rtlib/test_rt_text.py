"""rt_text.py: values read from and written as ST literal text (through
rtlib: the round trips also convert)."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from softplc.runtime.st import types as T
from softplc.runtime.st.rtlib import rtlib as r

from .rt_helpers import INF, NAN, STRING, WSTRING, conv, ns

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
    assert ns("D#2024-01-02", T.DATECAT) == 19724 * 86_400 * 10**9
    assert ns("TOD#12:30:15.5", T.TODCAT) == 45_015_500_000_000
    assert ns("TIME_OF_DAY#12:30", T.TODCAT) == 45_000_000_000_000
    assert ns("DT#2024-01-02-12:30:15", T.DTCAT) == (19724 * 86_400 + 45_015) * 10**9
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
    assert r.iec_literal(T.LDATE, day * 10**9) == "LD#2024-01-02"
    assert r.iec_literal(T.LTOD, 45_015_000_000_001) == "LTOD#12:30:15.000000001"
    assert r.iec_literal(T.LDT, (day + 45_015) * 10**9 + 500_000_000) == "LDT#2024-01-02-12:30:15.5"
    assert r.iec_literal(T.DATE, 0) == "D#1970-01-01"
    assert r.iec_literal(T.DT, 2**32 - 1) == "DT#2106-02-07-06:28:15"


def test_iec_literal_other_types():
    assert r.iec_literal(T.BOOL, True) == "TRUE"
    assert r.iec_literal(T.INT, -5) == "-5"
    assert r.iec_literal(T.REAL, 1.5) == "1.5"
    assert r.iec_literal(STRING, "it's $5\n") == "'it$'s $$5$N'"
    assert r.iec_literal(WSTRING, 'say "hi"') == '"say $"hi$""'
    color = T.EnumType("Color", {"RED": 0, "GREEN": 1}, {"RED": "Red", "GREEN": "Green"})
    assert r.iec_literal(color, 1) == "Color#Green"
    assert r.iec_literal(color, 7) == "7"


_TEMPORAL = [
    (T.TIME, T.DURATION, st.integers(-(2**31), 2**31 - 1)),
    (T.LTIME, T.DURATION, st.integers(-(2**63), 2**63 - 1)),
    (T.DATE, T.DATECAT, st.integers(0, 2**32 // 86_400 - 1).map(lambda d: d * 86_400)),
    (T.TOD, T.TODCAT, st.integers(0, 86_400_000 - 1)),
    (T.DT, T.DTCAT, st.integers(0, 2**32 - 1)),
    (T.LTOD, T.TODCAT, st.integers(0, 86_400 * 10**9 - 1)),
    (T.LDT, T.DTCAT, st.integers(0, 2**64 - 1)),
]


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
