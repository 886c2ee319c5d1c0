"""Runtime library, time and date arithmetic: the IEC functions ADD_TIME ...
DAY_OF_WEEK on raw values (see types.py), and the calendar constants."""

from __future__ import annotations

from datetime import date as _date

from ..faults import RangeFault
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


def CONCAT_DATE_LTOD(d: int, tod: int) -> int:
    """DATE (seconds) + LTOD -> LDT (IEC 61131-3 ed.3 Table 37)."""
    return ((d - d % _DAY_S) * 1_000_000_000 + tod % DAY_NS) & _M64


# CONCAT_DATE, CONCAT_TOD, CONCAT_DT (IEC 61131-3 ed.3 Table 37): a field
# outside the calendar (month 13, Feb 30, hour 24, second 60) or a date the
# type cannot hold (DATE and DT: 1970-01-01 .. 2106-02-07, 32-bit seconds;
# LDT: 64-bit nanoseconds, to 2554) is a runtime fault at the call, like an
# array index out of bounds: IEC leaves it open, and CODESYS's DTUtil
# returns a zero date with an error code that is easily missed.

_LAST_DAY_32 = _M32 // _DAY_S  # 2106-02-07, the last day DATE holds


def _days(fn: str, year: int, month: int, day: int, last: int) -> int:
    """Days from 1970-01-01 to the date; a RangeFault if it is none or
    beyond day ``last``."""
    try:
        n = _date(year, month, day).toordinal() - EPOCH_ORD
    except (ValueError, OverflowError):
        raise RangeFault("range", f"{fn}: {year}-{month:02}-{day:02} is not a date") from None
    if not 0 <= n <= last:
        end = _date.fromordinal(EPOCH_ORD + last).isoformat()
        raise RangeFault("range", f"{fn}: {year}-{month:02}-{day:02} is outside 1970-01-01 .. {end}")
    return n


def _tod_ms(fn: str, hour: int, minute: int, second: int, ms: int) -> int:
    if not (0 <= hour < 24 and 0 <= minute < 60 and 0 <= second < 60 and 0 <= ms < 1000):
        raise RangeFault("range", f"{fn}: {hour:02}:{minute:02}:{second:02}.{ms:03} is not a time of day")
    return ((hour * 60 + minute) * 60 + second) * 1000 + ms


def _stamp(year: int, month: int, day: int, hour: int, minute: int, second: int) -> str:
    return f"{year}-{month:02}-{day:02}-{hour:02}:{minute:02}:{second:02}"


def CONCAT_DATE(year: int, month: int, day: int) -> int:
    """-> DATE."""
    return _days("CONCAT_DATE", year, month, day, _LAST_DAY_32) * _DAY_S


def CONCAT_LDATE(year: int, month: int, day: int) -> int:
    """-> LDATE (nanoseconds since 1970-01-01, to 2554)."""
    return _days("CONCAT_LDATE", year, month, day, _M64 // DAY_NS) * DAY_NS


def CONCAT_TOD(hour: int, minute: int, second: int, millisecond: int) -> int:
    return _tod_ms("CONCAT_TOD", hour, minute, second, millisecond)


def CONCAT_LTOD(hour: int, minute: int, second: int, millisecond: int) -> int:
    return _tod_ms("CONCAT_LTOD", hour, minute, second, millisecond) * 1_000_000


def CONCAT_DT(year: int, month: int, day: int, hour: int, minute: int, second: int, millisecond: int) -> int:
    """-> DT (the milliseconds are dropped: DT counts seconds)."""
    secs = _tod_ms("CONCAT_DT", hour, minute, second, millisecond) // 1000
    n = _days("CONCAT_DT", year, month, day, _LAST_DAY_32)
    if n * _DAY_S + secs > _M32:
        raise RangeFault("range", f"CONCAT_DT: {_stamp(year, month, day, hour, minute, second)} is beyond DT")
    return n * _DAY_S + secs


def CONCAT_LDT(year: int, month: int, day: int, hour: int, minute: int, second: int, millisecond: int) -> int:
    ns = _tod_ms("CONCAT_LDT", hour, minute, second, millisecond) * 1_000_000
    n = _days("CONCAT_LDT", year, month, day, _M64 // DAY_NS)
    if n * DAY_NS + ns > _M64:
        raise RangeFault("range", f"CONCAT_LDT: {_stamp(year, month, day, hour, minute, second)} is beyond LDT")
    return n * DAY_NS + ns


def DAY_OF_WEEK(d: int) -> int:
    """IEC 3rd ed.: 0 = Sunday .. 6 = Saturday (1970-01-01 was a Thursday)."""
    return (d // _DAY_S + 4) % 7
