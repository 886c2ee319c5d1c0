"""Runtime library, time and date arithmetic: the IEC functions ADD_TIME ...
DAY_OF_WEEK on raw values (see types.py), and the calendar constants."""

from __future__ import annotations

from datetime import date as _date

from .rt_numeric import idiv, round_half_away

DAY_NS = 86_400_000_000_000
EPOCH_ORD = _date(1970, 1, 1).toordinal()  # the ordinal of 1970-01-01, day 0 of DATE

# ---------------------------------------------------------------- time and date
# IEC 61131-3 Table 30 (2nd ed.) / Table 35-36 (3rd ed.). Results are
# normalised like a store would (durations wrap to 32/64 bit, TOD wraps at
# midnight). DT has 1 s resolution: adding T#1500ms to a DT gives the whole
# second at or before the exact result (floor).

_M32 = (1 << 32) - 1
_M64 = (1 << 64) - 1
_H32 = 1 << 31
_H64 = 1 << 63
_DAY_MS = 86_400_000
_DAY_S = 86_400


def _w32(v: int) -> int:
    return ((v + _H32) & _M32) - _H32


def _w64(v: int) -> int:
    return ((v + _H64) & _M64) - _H64


def ADD_TIME(a: int, b: int) -> int:
    return _w32(a + b)


def SUB_TIME(a: int, b: int) -> int:
    return _w32(a - b)


def ADD_LTIME(a: int, b: int) -> int:
    return _w64(a + b)


def SUB_LTIME(a: int, b: int) -> int:
    return _w64(a - b)


def _mul_dur(t: int, k) -> int:
    if isinstance(k, float):
        return round_half_away(t * k)
    return t * k


def _div_dur(t: int, k) -> int:
    if isinstance(k, float):
        if k == 0:
            raise ZeroDivisionError("time divided by zero")
        return round_half_away(t / k)
    return idiv(t, k)


def MUL_TIME(t: int, k) -> int:
    """TIME * ANY_NUM; a real factor rounds half away from zero."""
    return _w32(_mul_dur(t, k))


def DIV_TIME(t: int, k) -> int:
    """TIME / ANY_NUM: an integer divisor truncates toward zero like DINT
    division, a real one rounds half away from zero; a zero divisor raises
    ZeroDivisionError (an ST fault, as for integer division)."""
    return _w32(_div_dur(t, k))


def MUL_LTIME(t: int, k) -> int:
    return _w64(_mul_dur(t, k))


def DIV_LTIME(t: int, k) -> int:
    return _w64(_div_dur(t, k))


def ADD_TOD_TIME(tod: int, t: int) -> int:
    return (tod + t) % _DAY_MS


def SUB_TOD_TIME(tod: int, t: int) -> int:
    return (tod - t) % _DAY_MS


def ADD_LTOD_LTIME(tod: int, t: int) -> int:
    return (tod + t) % DAY_NS


def SUB_LTOD_LTIME(tod: int, t: int) -> int:
    return (tod - t) % DAY_NS


def ADD_DT_TIME(dt: int, t: int) -> int:
    return ((dt * 1000 + t) // 1000) & _M32


def SUB_DT_TIME(dt: int, t: int) -> int:
    return ((dt * 1000 - t) // 1000) & _M32


def ADD_LDT_LTIME(dt: int, t: int) -> int:
    return (dt + t) & _M64


def SUB_LDT_LTIME(dt: int, t: int) -> int:
    return (dt - t) & _M64


def SUB_DATE_DATE(a: int, b: int) -> int:
    """-> TIME (ms); wraps beyond 24 days like any TIME."""
    return _w32((a - b) * 1000)


def SUB_LDATE_LDATE(a: int, b: int) -> int:
    return _w64(a - b)


def SUB_TOD_TOD(a: int, b: int) -> int:
    return _w32(a - b)


def SUB_LTOD_LTOD(a: int, b: int) -> int:
    return _w64(a - b)


def SUB_DT_DT(a: int, b: int) -> int:
    return _w32((a - b) * 1000)


def SUB_LDT_LDT(a: int, b: int) -> int:
    return _w64(a - b)


def CONCAT_DATE_TOD(d: int, tod: int) -> int:
    """DATE + TOD -> DT (the TOD's milliseconds are dropped: DT has 1 s)."""
    return (d - d % _DAY_S + (tod % _DAY_MS) // 1000) & _M32


def CONCAT_LDATE_LTOD(d: int, tod: int) -> int:
    return (d - d % DAY_NS + tod % DAY_NS) & _M64


def _days(year: int, month: int, day: int) -> int | None:
    try:
        return _date(year, month, day).toordinal() - EPOCH_ORD
    except (ValueError, OverflowError):
        return None


def CONCAT_DATE(year: int, month: int, day: int) -> int:
    """-> DATE; an impossible date (month 13, Feb 30) gives D#1970-01-01."""
    n = _days(year, month, day)
    return 0 if n is None else (n * _DAY_S) & _M32


def _tod_ms(hour: int, minute: int, second: int, ms: int) -> int:
    # Computed arithmetically, then wrapped at midnight (out-of-range fields
    # carry over, like the time arithmetic does).
    return ((hour * 60 + minute) * 60 + second) * 1000 + ms


def CONCAT_TOD(hour: int, minute: int, second: int, millisecond: int) -> int:
    return _tod_ms(hour, minute, second, millisecond) % _DAY_MS


def CONCAT_LTOD(hour: int, minute: int, second: int, millisecond: int) -> int:
    return _tod_ms(hour, minute, second, millisecond) * 1_000_000 % DAY_NS


def CONCAT_DT(year: int, month: int, day: int, hour: int, minute: int, second: int, millisecond: int) -> int:
    """-> DT (ms dropped); an impossible date gives DT#1970-01-01-00:00:00."""
    n = _days(year, month, day)
    if n is None:
        return 0
    return (n * _DAY_S + _tod_ms(hour, minute, second, millisecond) // 1000) & _M32


def CONCAT_LDT(year: int, month: int, day: int, hour: int, minute: int, second: int, millisecond: int) -> int:
    n = _days(year, month, day)
    if n is None:
        return 0
    return (n * DAY_NS + _tod_ms(hour, minute, second, millisecond) * 1_000_000) & _M64


def DAY_OF_WEEK(d: int) -> int:
    """IEC 3rd ed.: 0 = Sunday .. 6 = Saturday (1970-01-01 was a Thursday)."""
    return (d // _DAY_S + 4) % 7
