"""Runtime library, values as ST literal text, both ways: reading the
literal forms (STRING_TO_* and the value parsers) and writing them
(*_TO_STRING, JSON output, messages)."""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from datetime import date as _date

from ...durations import UNITS_NS
from ..types import (
    BITS,
    BOOLCAT,
    DATECAT,
    DTCAT,
    DURATION,
    LREAL,
    REALCAT,
    SIGNED,
    TODCAT,
    UNSIGNED,
    ElementaryType,
    EnumType,
    StringType,
    Type,
    base_elementary,
    resolve,
)
from .rt_numeric import f32
from .rt_timedate import DAY_NS, EPOCH_ORD
from .rt_wrap import time_wrapper

_INF = math.inf
_NAN = math.nan

# ---------------------------------------------------------------- text -> value

_INT_RE = re.compile(
    r"(?:(?:U?S?INT|U?[DL]?INT|L?D?WORD|BYTE|BOOL)#)?([+-]?)"
    r"(?:(2|8|16)#([0-9A-F](?:_?[0-9A-F])*)|([0-9](?:_?[0-9])*))\Z",
    re.I,
)
_REAL_RE = re.compile(
    r"(?:L?REAL#)?"
    r"([+-]?(?:[0-9](?:_?[0-9])*(?:\.(?:[0-9](?:_?[0-9])*)?)?|\.[0-9](?:_?[0-9])*)"
    r"(?:E[+-]?[0-9]+)?)\Z",
    re.I,
)
_REAL_WORDS = {"INF": _INF, "+INF": _INF, "-INF": -_INF, "NAN": _NAN}


def parse_int(text: str) -> int | None:
    """An IEC integer literal ('42', '-7', '16#FF', '2#1010_0001', 'INT#5'),
    surrounding blanks allowed; None if the text is anything else."""
    m = _INT_RE.match(text.strip())
    if m is None:
        return None
    sign, base, digits, dec = m.groups()
    try:
        v = int(digits, int(base)) if base else int(dec)
    except ValueError:  # e.g. 2#102
        return None
    return -v if sign == "-" else v


def parse_real(text: str) -> float | None:
    """A real or integer literal ('1.5', '-2.5E-3', 'REAL#1', '16#FF'),
    or INF / -INF / NAN (what real_to_string writes); None if invalid."""
    s = text.strip()
    m = _REAL_RE.match(s)
    if m is not None:
        return float(m.group(1))
    w = _REAL_WORDS.get(s.upper())
    if w is not None:
        return w
    v = parse_int(s)
    return None if v is None else float(v)


def parse_bool(text: str) -> bool | None:
    """'TRUE' / 'FALSE' (any case, optional BOOL# prefix) or an integer
    literal (non-zero is TRUE); None if invalid."""
    s = text.strip().upper()
    if s.startswith("BOOL#"):
        s = s[5:]
    if s == "TRUE":
        return True
    if s == "FALSE":
        return False
    v = parse_int(s)
    return None if v is None else v != 0


_PREFIXES = {
    DURATION: ("T", "TIME", "LT", "LTIME"),
    DATECAT: ("D", "DATE", "LD", "LDATE"),
    TODCAT: ("TOD", "TIME_OF_DAY", "LTOD", "LTIME_OF_DAY"),
    DTCAT: ("DT", "DATE_AND_TIME", "LDT", "LDATE_AND_TIME"),
}
_UNIT_NS = UNITS_NS  # IEC duration units in nanoseconds (runtime/durations.py)
_DUR_RE = re.compile(r"(?:[0-9]+(?:\.[0-9]+)?(?:ms|us|ns|d|h|m|s))+\Z", re.I)
_DUR_PART = re.compile(r"([0-9]+)(?:\.([0-9]+))?(ms|us|ns|d|h|m|s)", re.I)
_DATE_RE = re.compile(r"([0-9]{4})-([0-9]{1,2})-([0-9]{1,2})")
_TOD_RE = re.compile(r"([0-9]{1,2}):([0-9]{1,2})(?::([0-9]{1,2})(?:\.([0-9]+))?)?")


def _date_ns(m) -> int | None:
    try:
        d = _date(int(m.group(1)), int(m.group(2)), int(m.group(3)))
    except ValueError:
        return None
    return (d.toordinal() - EPOCH_ORD) * DAY_NS


def _tod_ns(m) -> int | None:
    h, mi, s, frac = m.groups()
    h, mi, s = int(h), int(mi), int(s or 0)
    if h > 23 or mi > 59 or s > 59:
        return None
    ns = ((h * 60 + mi) * 60 + s) * 1_000_000_000
    if frac:
        ns += int(frac[:9].ljust(9, "0"))
    return ns


def parse_temporal(text: str, category: str) -> int | None:
    """Parse a time or date literal of the given category (types.DURATION,
    DATECAT, TODCAT, DTCAT) to nanoseconds (since 1970 for dates, since
    midnight for TOD), like the ST parser. The prefix ('T#', 'TIME#', 'LT#',
    'D#', 'TOD#', 'DT#' ...) is optional but must belong to the category;
    underscores are ignored. None if invalid."""
    s = text.strip()
    prefix, sep, body = s.partition("#")
    if sep:
        if prefix.upper() not in _PREFIXES[category]:
            return None
    else:
        body = s
    body = body.replace("_", "")
    if category == DURATION:
        neg = body.startswith("-")
        if neg or body.startswith("+"):
            body = body[1:]
        if not _DUR_RE.match(body):
            return None
        ns = 0
        for whole, frac, unit in _DUR_PART.findall(body):
            u = _UNIT_NS[unit.lower()]
            ns += int(whole) * u
            if frac:
                ns += int(frac) * u // 10 ** len(frac)
        return -ns if neg else ns
    if category == DATECAT:
        m = _DATE_RE.fullmatch(body)
        return None if m is None else _date_ns(m)
    if category == TODCAT:
        m = _TOD_RE.fullmatch(body)
        return None if m is None else _tod_ns(m)
    # DT: date '-' time of day
    m = _DATE_RE.match(body)
    if m is None or body[m.end() : m.end() + 1] != "-":
        return None
    d = _date_ns(m)
    t = _TOD_RE.fullmatch(body, m.end() + 1)
    if d is None or t is None:
        return None
    tod = _tod_ns(t)
    return None if tod is None else d + tod


# ---------------------------------------------------------------- value -> text


def _digits_exp(s: str) -> tuple:
    """'-1.25e+02' / '0.001' -> (neg, significant digits, decimal exponent of
    the first digit)."""
    neg = s[:1] == "-"
    if neg:
        s = s[1:]
    mant, _, ex = s.partition("e")
    ip, _, fp = mant.partition(".")
    digits = ip + fp
    e = len(ip) - 1 + (int(ex) if ex else 0)
    stripped = digits.lstrip("0")
    e -= len(digits) - len(stripped)
    return neg, stripped.rstrip("0") or "0", e


def _shortest_f32(x: float) -> str:
    for p in range(9):  # 9 significant digits always round-trip binary32
        s = f"{x:.{p}e}"
        if f32(float(s)) == x:
            return s
    return f"{x:.8e}"


def real_to_string(x: float, lreal: bool = False) -> str:
    """REAL_TO_STRING / LREAL_TO_STRING.

    Rule: the shortest decimal that reads back to the same REAL (binary32) or
    LREAL (binary64); fixed notation with at least one fractional digit when
    1E-5 <= |x| < 1E7 (REAL) or < 1E15 (LREAL), else d.dddE+XX; both are
    valid ST real literals. Examples: 1.5 -> '1.5', 100.0 -> '100.0',
    0.1 -> '0.1', 1.0E20 -> '1.0E+20'. Zero is '0.0' (also -0.0); the
    non-finite values are 'INF', '-INF' and 'NAN'."""
    if x != x:
        return "NAN"
    if x == _INF:
        return "INF"
    if x == -_INF:
        return "-INF"
    if x == 0:
        return "0.0"
    if lreal:
        s = repr(float(x))
        hi = 15
    else:
        s = _shortest_f32(f32(x))
        hi = 7
    neg, digits, e = _digits_exp(s)
    if -5 <= e < hi:
        if e >= 0:
            if len(digits) <= e + 1:
                out = digits + "0" * (e + 1 - len(digits)) + ".0"
            else:
                out = digits[: e + 1] + "." + digits[e + 1 :]
        else:
            out = "0." + "0" * (-e - 1) + digits
    else:
        out = f"{digits[0]}.{digits[1:] or '0'}E{'-' if e < 0 else '+'}{abs(e):02d}"
    return "-" + out if neg else out


def real32_to_string(x: float) -> str:
    return real_to_string(x, False)


def real64_to_string(x: float) -> str:
    return real_to_string(x, True)


def bool_to_string(v) -> str:
    return "TRUE" if v else "FALSE"


_LIT_PREFIX = {
    "TIME": "T#",
    "LTIME": "LT#",
    "DATE": "D#",
    "LDATE": "LD#",
    "TIME_OF_DAY": "TOD#",
    "LTIME_OF_DAY": "LTOD#",
    "DATE_AND_TIME": "DT#",
    "LDATE_AND_TIME": "LDT#",
}
_DUR_UNITS = (
    ("d", 86_400_000_000_000),
    ("h", 3_600_000_000_000),
    ("m", 60_000_000_000),
    ("s", 1_000_000_000),
    ("ms", 1_000_000),
    ("us", 1_000),
    ("ns", 1),
)


def _fmt_duration(ns: int, unit_ns: int) -> str:
    sign = "-" if ns < 0 else ""
    n = -ns if ns < 0 else ns
    parts = []
    smallest = "ns"
    for name, size in _DUR_UNITS:
        if size < unit_ns:
            break
        smallest = name
        q, n = divmod(n, size)
        if q:
            parts.append(f"{q}{name}")
    return sign + ("".join(parts) or "0" + smallest)


def _fmt_tod(ns: int) -> str:
    sec, frac = divmod(ns % DAY_NS, 1_000_000_000)
    mi, s = divmod(sec, 60)
    h, mi = divmod(mi, 60)
    # %d, not {:d}: it also takes a float (truncated), as this always has
    out = "%02d:%02d:%02d" % (h, mi, s)  # noqa: UP031
    if frac:
        out += "." + ("%09d" % frac).rstrip("0")  # noqa: UP031
    return out


def _fmt_date(ns: int) -> str:
    return _date.fromordinal(EPOCH_ORD + ns // DAY_NS).isoformat()


def temporal_formatter(e: ElementaryType) -> Callable[[int], str]:
    """A closure formatting a raw value of time/date type e as its literal."""
    prefix = _LIT_PREFIX[e.name]
    unit = e.unit_ns
    norm = time_wrapper(e)
    c = e.category
    if c == DURATION:

        def fmt_duration(v: int) -> str:
            return prefix + _fmt_duration(norm(v) * unit, unit)

        return fmt_duration
    if c == DATECAT:

        def fmt_date(v: int) -> str:
            return prefix + _fmt_date(norm(v) * unit)

        return fmt_date
    if c == TODCAT:

        def fmt_tod(v: int) -> str:
            return prefix + _fmt_tod(norm(v) * unit)

        return fmt_tod

    def fmt_dt(v: int) -> str:
        ns = norm(v) * unit
        return prefix + _fmt_date(ns) + "-" + _fmt_tod(ns)

    return fmt_dt


_TEMPORAL_FORMATTERS: dict = {}


def _quote(s: str, wide: bool) -> str:
    q = '"' if wide else "'"
    out = []
    for ch in s:
        if ch == "$":
            out.append("$$")
        elif ch == q:
            out.append("$" + q)
        elif ch == "\n":
            out.append("$N")
        elif ch == "\r":
            out.append("$R")
        elif ch == "\t":
            out.append("$T")
        elif ch == "\f":
            out.append("$P")
        elif ord(ch) < 32 or ord(ch) == 127:
            out.append(("$%04X" if wide else "$%02X") % ord(ch))
        else:
            out.append(ch)
    return q + "".join(out) + q


def iec_literal(t: Type, value) -> str:
    """Format a value of type t as an ST literal (for JSON output, messages
    and *_TO_STRING). Time and date types:

      TIME  T#1h2m3s4ms (T#0ms, T#-5s, T#1d2h)   LTIME LT#1s500us7ns (LT#0ns)
      DATE  D#2024-01-02                          LDATE LD#2024-01-02
      TOD   TOD#12:30:15.5 (fraction omitted when zero)   LTOD LTOD#...
      DT    DT#2024-01-02-12:30:15                LDT   LDT#2024-01-02-12:30:15.5

    These read back through the ST parser and parse_temporal to the same
    value. Other types: BOOL TRUE/FALSE, integers in decimal, reals per
    real_to_string, strings quoted with $ escapes, enumerations
    Type#Name when the value names an enumerator."""
    r = resolve(t)
    if isinstance(r, StringType):
        return _quote(value, r.wide)
    if isinstance(r, EnumType):
        name = r.name_of(value)
        if name is not None:
            return f"{r.name}#{name}"
    e = base_elementary(r)
    if e is None:
        return str(value)
    c = e.category
    if c == BOOLCAT:
        return "TRUE" if value else "FALSE"
    if c in (SIGNED, UNSIGNED, BITS):
        return str(int(value))
    if c == REALCAT:
        return real_to_string(value, e is LREAL)
    fmt = _TEMPORAL_FORMATTERS.get(e)
    if fmt is None:
        fmt = _TEMPORAL_FORMATTERS[e] = temporal_formatter(e)
    return fmt(value)
