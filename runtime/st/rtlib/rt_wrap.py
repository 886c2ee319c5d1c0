"""Runtime library, storing a value: the normalisation for its type (integers
and bit strings wrap, REAL rounds to binary32, time and date types by their
meaning, STRING[n] truncates), as closures built once per type."""

from __future__ import annotations

from collections.abc import Callable

from ..types import (
    BITS,
    BOOLCAT,
    DATECAT,
    DURATION,
    LREAL,
    REALCAT,
    SIGNED,
    TODCAT,
    UNSIGNED,
    ElementaryType,
    StringType,
    Type,
    base_elementary,
    resolve,
)
from .rt_numeric import f32
from .rt_strings import wcut
from .rt_timedate import DAY_NS

# ---------------------------------------------------------------- wrapping


def int_wrapper(t: ElementaryType) -> Callable[[int], int]:
    """Wrapping to the range of integer, bit string or duration type t."""
    if t.lo is None:
        raise TypeError(f"{t.name} has no integer range")
    mask = (1 << t.bits) - 1
    if t.lo < 0:  # signed integers and TIME/LTIME
        half = 1 << (t.bits - 1)

        def wrap_signed(v: int) -> int:
            return ((v + half) & mask) - half

        return wrap_signed

    def wrap_unsigned(v: int) -> int:
        return v & mask

    return wrap_unsigned


def time_wrapper(t: ElementaryType) -> Callable[[int], int]:
    """Store normalisation of time and date types.

    TIME/LTIME wrap like DINT/LINT. TOD/LTOD wrap at midnight (they are a
    time of day: TOD#23:59:59.999 + T#1ms = TOD#00:00). DATE/LDATE are kept at
    midnight (types.py: "DATE at midnight"). DT/LDT wrap as unsigned."""
    c = t.category
    if c == DURATION:
        return int_wrapper(t)
    day = DAY_NS // t.unit_ns
    if c == TODCAT:

        def wrap_tod(v: int) -> int:
            return v % day

        return wrap_tod
    mask = (1 << t.bits) - 1
    if c == DATECAT:

        def wrap_date(v: int) -> int:
            v &= mask
            return v - v % day

        return wrap_date

    def wrap_dt(v: int) -> int:
        return v & mask

    return wrap_dt


def identity(v):
    return v


def _truncate_string(n: int, wide: bool) -> Callable[[str], str]:
    if wide:  # UTF-16 units, never half a character
        return lambda v: wcut(v, n)

    def trunc_str(v: str) -> str:
        return v if len(v) <= n else v[:n]

    return trunc_str


_WRAPPERS: dict = {}


def wrapper(t: Type) -> Callable:
    """A closure normalising a value for storing into t: integers and bit
    strings wrap, BOOL -> bool, REAL -> f32, time/date types per wrap_time,
    STRING[n] truncates to n characters, enums and subranges use their base
    (the subrange check itself is the code generator's). Aggregates: identity.
    Cached per type object."""
    w = _WRAPPERS.get(t)
    if w is not None:
        return w
    r = resolve(t)
    if isinstance(r, StringType):
        w = _truncate_string(r.length, r.wide)
    else:
        e = base_elementary(r)
        if e is None:
            w = identity
        elif e.category == BOOLCAT:
            w = bool
        elif e.category in (SIGNED, UNSIGNED, BITS):
            w = int_wrapper(e)
        elif e.category == REALCAT:
            w = float if e is LREAL else f32
        else:
            w = time_wrapper(e)
    _WRAPPERS[t] = w
    return w


def wrap(t: Type, v):
    """General store normalisation (the code generator inlines the common
    integer cases; this is the fallback). See ``wrapper``."""
    w = _WRAPPERS.get(t)
    if w is None:
        w = wrapper(t)
    return w(v)


def wrap_time(t: ElementaryType, v: int) -> int:
    """Normalise v for storing into time/date type t: TIME/LTIME wrap like
    DINT/LINT, TOD/LTOD wrap at midnight, DATE/LDATE go to midnight, DT/LDT
    wrap as unsigned (see time_wrapper)."""
    return wrap(t, v)
