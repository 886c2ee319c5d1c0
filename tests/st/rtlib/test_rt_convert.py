"""rt_convert.py: the <src>_TO_<dst> conversions (through rtlib: the
expectations also use f32 and iec_literal)."""

from __future__ import annotations

from softplc.runtime.st import types as T
from softplc.runtime.st.rtlib import rtlib as r

from .rt_helpers import INF, NAN, STRING, WSTRING, conv

# ---------------------------------------------------------------- conversions


def test_integer_conversions_wrap():
    assert conv(T.INT, T.SINT, 300) == 44
    assert conv(T.INT, T.SINT, 4223) == 127  # CODESYS example
    assert conv(T.DINT, T.UINT, -1) == 65535
    assert conv(T.UDINT, T.DINT, 2**32 - 1) == -1
    assert conv(T.INT, T.WORD, -1) == 0xFFFF
    assert conv(T.WORD, T.INT, 0x8000) == -32768
    assert conv(T.LINT, T.ULINT, -2) == 2**64 - 2
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
    assert conv(T.ULINT, T.REAL, 2**64 - 1) == 18446744073709551616.0
    assert conv(T.LINT, T.REAL, 2**53 + 2**29 + 1) == 9007200328482816.0  # rounded once
    assert conv(T.LREAL, T.REAL, 0.1) == 0.10000000149011612
    assert conv(T.LREAL, T.REAL, 1e300) == INF
    assert conv(T.REAL, T.LREAL, r.f32(0.1)) == 0.10000000149011612
    assert conv(T.ULINT, T.LREAL, 2**64 - 1) == 1.8446744073709552e19
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
    assert conv(T.TIME, T.UDINT, -1) == 2**32 - 1
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
    assert conv(T.DT, T.LDT, dt) == dt * 10**9
    assert conv(T.LDT, T.DT, dt * 10**9 + 999_999_999) == dt  # floor to the second
    assert conv(T.LDT, T.LTOD, dt * 10**9 + 7) == 45_015 * 10**9 + 7
    assert conv(T.LDT, T.LDATE, dt * 10**9) == 19724 * 86_400 * 10**9
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
    assert r.from_ns(T.DATE, 86_400 * 10**9) == 86_400
    assert r.to_ns(T.TIME, 2) == 2_000_000
    assert r.to_ns(T.DT, 1) == 10**9
