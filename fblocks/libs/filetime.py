"""The Windows FILETIME clock TwinCAT reads (100 ns intervals since
1601-01-01 UTC), the engine's date in it, and the calendar of a FILETIME
(Tc2_System F_GetSystemTime, Tc2_Utilities SYSTEMTIME_TO_FILETIME ...).

The date is the engine's (runtime/program/context.py ExecContext.date_ns):
the host's clock in real time, the virtual clock from 2000-01-01 in
virtual time, so a test that runs 10 virtual minutes sees F_GetSystemTime
advance by 10 minutes.
"""

from __future__ import annotations

import datetime as _dt

#: 100 ns intervals from 1601-01-01 to 1970-01-01 (369 years, 89 leap days)
UNIX_EPOCH_AS_FILETIME = 116_444_736_000_000_000
#: the largest FILETIME Windows converts (FileTimeToSystemTime: below 2^63)
MAX_FILETIME = (1 << 63) - 1
_1601 = _dt.datetime(1601, 1, 1)


def from_unix_ns(ns: int) -> int:
    """UTC nanoseconds since 1970 -> FILETIME."""
    return ns // 100 + UNIX_EPOCH_AS_FILETIME


def to_unix_ns(ft: int) -> int:
    """FILETIME -> UTC nanoseconds since 1970."""
    return (ft - UNIX_EPOCH_AS_FILETIME) * 100


def now(ctx) -> int:
    """The engine's date as a FILETIME (ctx: the ExecContext)."""
    return from_unix_ns(ctx.date_ns())


def local(ctx, ft: int) -> int:
    """A UTC FILETIME in the engine's local time (virtual time: UTC)."""
    utc_s = to_unix_ns(ft) // 1_000_000_000
    return ft + ctx.utc_offset_s(utc_s) * 10_000_000


def calendar(ft: int) -> tuple | None:
    """(year, month, day of week 0 = Sunday, day, hour, minute, second,
    millisecond) of a FILETIME, or None outside 1601..30827 (Windows'
    SYSTEMTIME range)."""
    if not 0 <= ft <= MAX_FILETIME:
        return None
    try:
        t = _1601 + _dt.timedelta(microseconds=ft // 10)
    except OverflowError:
        return None
    return (t.year, t.month, (t.weekday() + 1) % 7, t.day, t.hour, t.minute, t.second, t.microsecond // 1000)


def from_calendar(year: int, month: int, day: int, hour: int, minute: int, second: int, ms: int) -> int | None:
    """The FILETIME of a calendar date, or None for an invalid one."""
    try:
        t = _dt.datetime(year, month, day, hour, minute, second, ms * 1000)
    except (ValueError, OverflowError):
        return None
    delta = t - _1601
    return (delta.days * 86_400 + delta.seconds) * 10_000_000 + delta.microseconds * 10
