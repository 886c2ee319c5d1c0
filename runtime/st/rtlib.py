"""Runtime library: the primitives generated code calls.

Every value follows the representation contract in ``types.py`` (TIME = int
ms, LTIME = int ns, DATE/DT = int s since 1970, TOD = int ms since midnight,
LDATE/LDT/LTOD = int ns, REAL = float rounded to binary32, strings = str).

The functions here are plain module-level functions: the code generator binds
them once (``f32 = rtlib.f32``) and calls them on hot paths, so they avoid
per-call allocation and dispatch. Where semantics need a type, a factory
(``make_converter``, ``wrapper``) builds a specialised closure once, at load
time, and the generated code calls the closure.

Error policy: nothing here raises for a value an ST program can produce,
except integer division and MOD by zero (ZeroDivisionError; the engine turns
it into an ST fault with the source location). Real arithmetic follows IEEE
754 (x/0.0 = +-inf, SQRT(-1) = NaN). Invalid text in STRING_TO_* conversions
gives 0 (CODESYS: "the operand must contain a valid value of the target type,
otherwise the result is 0").

Names of IEC functions are kept in upper case (LEFT, ADD_TOD_TIME, ...), so
that ST and Python read the same; lower-case names are primitives.
"""
from __future__ import annotations

import math
import re
import struct
from collections.abc import Callable
from datetime import date as _date

from .types import (
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

__all__ = [
    "f32", "idiv", "imod", "rdiv", "expt", "round_half_away", "trunc",
    "wrap", "wrap_time", "wrapper",
    "convert", "make_converter", "real_to_string", "parse_int", "parse_real",
    "parse_bool", "parse_temporal", "iec_literal", "to_ns", "from_ns",
    "shl", "shr", "rol", "ror", "bcd_to_int", "int_to_bcd",
    "sqrt", "ln", "log", "exp", "sin", "cos", "tan", "asin", "acos", "atan", "atan2",
    "LEN", "LEFT", "RIGHT", "MID", "CONCAT", "INSERT", "DELETE", "REPLACE", "FIND",
    "ADD_TIME", "SUB_TIME", "MUL_TIME", "DIV_TIME", "ADD_LTIME", "SUB_LTIME", "MUL_LTIME",
    "DIV_LTIME", "ADD_TOD_TIME", "ADD_LTOD_LTIME", "ADD_DT_TIME", "ADD_LDT_LTIME",
    "SUB_DATE_DATE", "SUB_LDATE_LDATE", "SUB_TOD_TOD", "SUB_LTOD_LTOD", "SUB_DT_DT",
    "SUB_LDT_LDT", "SUB_TOD_TIME", "SUB_LTOD_LTIME", "SUB_DT_TIME", "SUB_LDT_LTIME",
    "CONCAT_DATE_TOD", "CONCAT_LDATE_LTOD", "CONCAT_DATE", "CONCAT_TOD", "CONCAT_LTOD",
    "CONCAT_DT", "CONCAT_LDT", "DAY_OF_WEEK",
]

_INF = math.inf
_NAN = math.nan

# ---------------------------------------------------------------- REAL

_F32 = struct.Struct("<f")
_f32_pack = _F32.pack
_f32_unpack = _F32.unpack


def f32(x: float) -> float:
    """Round to IEEE binary32 (round to nearest even), like a C float cast:
    NaN and inf pass through, a finite value beyond FLT_MAX becomes +-inf."""
    try:
        return _f32_unpack(_f32_pack(x))[0]
    except (OverflowError, struct.error):
        # beyond FLT_MAX after rounding (or an int beyond any float): the C
        # cast gives inf; struct refuses instead
        return _INF if x > 0 else -_INF


_EXACT53 = 1 << 53


def _int_to_f32(v: int) -> float:
    """int -> REAL rounded once (int -> double -> float would round twice
    for values beyond 2**53)."""
    if -_EXACT53 <= v <= _EXACT53:
        return f32(float(v))
    a = -v if v < 0 else v
    shift = a.bit_length() - 24
    q = a >> shift
    r = a & ((1 << shift) - 1)
    half = 1 << (shift - 1)
    if r > half or (r == half and q & 1):  # ties to even
        q += 1
    x = float(q << shift)  # <= 25 significant bits: exact
    return f32(-x if v < 0 else x)


def rdiv(a: float, b: float) -> float:
    """Real division, IEEE 754: x/0 = +-inf (sign of x times sign of the
    zero), 0/0 = NaN. Never raises."""
    try:
        return a / b
    except ZeroDivisionError:
        if a != a or a == 0:
            return _NAN
        return math.copysign(_INF, a) * math.copysign(1.0, b)
    except OverflowError:  # huge int / int
        return math.copysign(_INF, a) * math.copysign(1.0, b)


def _is_odd_integer(y: float) -> bool:
    return math.isfinite(y) and y == math.floor(y) and math.fmod(y, 2.0) != 0.0


def expt(a, b) -> float:
    """a ** b as float with C pow() results: negative base with a non-integer
    exponent -> NaN, 0 ** negative -> inf, overflow -> +-inf. Never raises."""
    try:
        return math.pow(a, b)
    except ValueError:  # pole or domain error
        if a == 0:
            return math.copysign(_INF, a) if _is_odd_integer(b) else _INF
        return _NAN
    except OverflowError:
        if a < 0 and _is_odd_integer(b):
            return -_INF
        return _INF


# Real functions: the IEEE result instead of Python's ValueError.

def sqrt(x) -> float:
    try:
        return math.sqrt(x)
    except ValueError:
        return _NAN


def ln(x) -> float:
    try:
        return math.log(x)
    except ValueError:
        return -_INF if x == 0 else _NAN


def log(x) -> float:
    """LOG is base 10 (IEC)."""
    try:
        return math.log10(x)
    except ValueError:
        return -_INF if x == 0 else _NAN


def exp(x) -> float:
    try:
        return math.exp(x)
    except OverflowError:
        return _INF


def _nan_on_domain(fn: Callable) -> Callable:
    def f(x):
        try:
            return fn(x)
        except ValueError:  # sin(inf), asin(2) ...
            return _NAN
    f.__name__ = fn.__name__
    f.__doc__ = f"{fn.__name__}(x); NaN outside the domain."
    return f


sin = _nan_on_domain(math.sin)
cos = _nan_on_domain(math.cos)
tan = _nan_on_domain(math.tan)
asin = _nan_on_domain(math.asin)
acos = _nan_on_domain(math.acos)
atan = math.atan
atan2 = math.atan2  # (y, x); defined for every pair incl. (0, 0)


# ---------------------------------------------------------------- integers

def idiv(a: int, b: int) -> int:
    """Integer division truncating toward zero (IEC / CODESYS: -7 / 2 = -3;
    Python's // floors). b == 0 raises ZeroDivisionError."""
    q = a // b
    if q < 0 and q * b != a:
        q += 1
    return q


def imod(a: int, b: int) -> int:
    """Remainder with the sign of the dividend (a - idiv(a, b) * b):
    -7 MOD 2 = -1, 7 MOD -2 = 1. b == 0 raises ZeroDivisionError (a fault
    in CODESYS too)."""
    r = a % b
    if r and (a ^ b) < 0:  # signs differ: Python's % took the divisor's sign
        r -= b
    return r


def round_half_away(x: float) -> int:
    """REAL -> integer rounding: to nearest, halves away from zero
    (CODESYS: REAL_TO_INT(1.5) = 2, (1.4) = 1, (-1.5) = -2). NaN and inf
    give 0 (C leaves them undefined; we choose a value that does not crash)."""
    try:
        r = int(x)  # truncates
    except (OverflowError, ValueError):
        return 0
    d = x - r  # exact: the fraction of a double is representable
    if d >= 0.5:
        return r + 1
    if d <= -0.5:
        return r - 1
    return r


def trunc(x: float) -> int:
    """TRUNC: toward zero; NaN and inf give 0."""
    try:
        return int(x)
    except (OverflowError, ValueError):
        return 0


# ---------------------------------------------------------------- wrapping

_DAY_NS = 86_400_000_000_000


def _int_wrapper(t: ElementaryType) -> Callable[[int], int]:
    mask = (1 << t.bits) - 1
    if t.lo is not None and t.lo < 0:  # signed integers and TIME/LTIME
        half = 1 << (t.bits - 1)

        def wrap_signed(v: int) -> int:
            return ((v + half) & mask) - half
        return wrap_signed

    def wrap_unsigned(v: int) -> int:
        return v & mask
    return wrap_unsigned


def _time_wrapper(t: ElementaryType) -> Callable[[int], int]:
    """Store normalisation of time and date types.

    TIME/LTIME wrap like DINT/LINT. TOD/LTOD wrap at midnight (they are a
    time of day: TOD#23:59:59.999 + T#1ms = TOD#00:00). DATE/LDATE are kept at
    midnight (types.py: "DATE at midnight"). DT/LDT wrap as unsigned."""
    c = t.category
    if c == DURATION:
        return _int_wrapper(t)
    day = _DAY_NS // t.unit_ns
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


def _identity(v):
    return v


def _truncate_string(n: int) -> Callable[[str], str]:
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
        w = _truncate_string(r.length)
    else:
        e = base_elementary(r)
        if e is None:
            w = _identity
        elif e.category == BOOLCAT:
            w = bool
        elif e.category in (SIGNED, UNSIGNED, BITS):
            w = _int_wrapper(e)
        elif e.category == REALCAT:
            w = float if e is LREAL else f32
        else:
            w = _time_wrapper(e)
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
    wrap as unsigned (see _time_wrapper)."""
    return wrap(t, v)


# ---------------------------------------------------------------- bit strings
# IEC: SHL/SHR fill with zeros; ROL/ROR rotate within the width of IN.
# CODESYS leaves n >= width target dependent; we give 0 for shifts (what its
# static analysis SA0053 says: "a constant 0 is generated") and take n MOD
# width for rotations. A negative n shifts/rotates the other way.

def shl(width: int, x: int, n: int) -> int:
    if n < 0:
        return shr(width, x, -n)
    if n >= width:
        return 0
    return (x << n) & ((1 << width) - 1)


def shr(width: int, x: int, n: int) -> int:
    """Logical shift right of the width-bit pattern of x (zeros shifted in,
    also for signed operands)."""
    if n < 0:
        return shl(width, x, -n)
    if n >= width:
        return 0
    return (x & ((1 << width) - 1)) >> n


def rol(width: int, x: int, n: int) -> int:
    mask = (1 << width) - 1
    n %= width
    x &= mask
    return ((x << n) | (x >> (width - n))) & mask


def ror(width: int, x: int, n: int) -> int:
    return rol(width, x, -n)


# ---------------------------------------------------------------- BCD

def bcd_to_int(x: int, width: int) -> int:
    """Decode the width-bit BCD pattern x. A nibble above 9 gives -1
    (CODESYS Util BCD_TO_INT: "if the byte is not in BCD format the output
    is -1"; stored into an unsigned type that wraps to its maximum)."""
    x &= (1 << width) - 1
    r = 0
    mul = 1
    while x:
        d = x & 15
        if d > 9:
            return -1
        r += d * mul
        mul *= 10
        x >>= 4
    return r


def int_to_bcd(v: int, width: int) -> int:
    """Encode v as BCD in width bits. Negative or too many digits gives all
    ones (CODESYS Util INT_TO_BCD: 255 when the value does not fit a BCD
    byte)."""
    mask = (1 << width) - 1
    if v < 0:
        return mask
    r = 0
    shift = 0
    while v:
        v, d = divmod(v, 10)
        r |= d << shift
        shift += 4
    if shift > width:
        return mask
    return r


# ---------------------------------------------------------------- strings
# IEC 61131-3 Table 29 / CODESYS Standard library, positions 1-based.
# Out-of-range arguments never raise; the rule for each is in its docstring.

def LEN(s: str) -> int:
    return len(s)


def LEFT(s: str, n: int) -> str:
    """The first n characters; n <= 0 -> '', n > LEN -> s."""
    return s[:n] if n > 0 else ""


def RIGHT(s: str, n: int) -> str:
    """The last n characters; n <= 0 -> '', n > LEN -> s."""
    return s[-n:] if n > 0 else ""


def MID(s: str, n: int, p: int) -> str:
    """n characters from position p: MID('SUSI', 2, 2) = 'US'. p < 1 or
    p > LEN, or n <= 0 -> ''; n past the end -> up to the end."""
    if p < 1 or n <= 0:
        return ""
    return s[p - 1:p - 1 + n]


def CONCAT(*parts: str) -> str:
    return "".join(parts)


def INSERT(s1: str, s2: str, p: int) -> str:
    """s2 inserted after position p of s1: INSERT('SUSI', 'XY', 2) =
    'SUXYSI'. p <= 0 -> in front; p > LEN(s1) -> appended."""
    if p < 0:
        p = 0
    return s1[:p] + s2 + s1[p:]


def DELETE(s: str, n: int, p: int) -> str:
    """Delete n characters from position p: DELETE('SUXYSI', 2, 3) = 'SUSI'.
    p < 1 or p > LEN, or n <= 0 -> s unchanged; n past the end deletes to the
    end."""
    if p < 1 or n <= 0 or p > len(s):
        return s
    return s[:p - 1] + s[p - 1 + n:]


def REPLACE(s1: str, s2: str, n: int, p: int) -> str:
    """Replace n characters of s1 from position p by s2:
    REPLACE('SUXYSI', 'K', 2, 2) = 'SKYSI'. p is clamped to 1..LEN(s1)+1
    (so p past the end appends s2), n < 0 counts as 0."""
    if p < 1:
        p = 1
    elif p > len(s1) + 1:
        p = len(s1) + 1
    if n < 0:
        n = 0
    return s1[:p - 1] + s2 + s1[p - 1 + n:]


def FIND(s1: str, s2: str) -> int:
    """Position of the first s2 in s1, 0 if absent (also for an empty s2:
    there is nothing to find)."""
    if not s2:
        return 0
    return s1.find(s2) + 1


# ---------------------------------------------------------------- text -> value

_INT_RE = re.compile(
    r"(?:(?:U?S?INT|U?[DL]?INT|L?D?WORD|BYTE|BOOL)#)?([+-]?)"
    r"(?:(2|8|16)#([0-9A-F](?:_?[0-9A-F])*)|([0-9](?:_?[0-9])*))\Z", re.I)
_REAL_RE = re.compile(
    r"(?:L?REAL#)?"
    r"([+-]?(?:[0-9](?:_?[0-9])*(?:\.(?:[0-9](?:_?[0-9])*)?)?|\.[0-9](?:_?[0-9])*)"
    r"(?:E[+-]?[0-9]+)?)\Z", re.I)
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
_UNIT_NS = {"d": 86_400_000_000_000, "h": 3_600_000_000_000, "m": 60_000_000_000,
            "s": 1_000_000_000, "ms": 1_000_000, "us": 1_000, "ns": 1}
_DUR_RE = re.compile(r"(?:[0-9]+(?:\.[0-9]+)?(?:ms|us|ns|d|h|m|s))+\Z", re.I)
_DUR_PART = re.compile(r"([0-9]+)(?:\.([0-9]+))?(ms|us|ns|d|h|m|s)", re.I)
_DATE_RE = re.compile(r"([0-9]{4})-([0-9]{1,2})-([0-9]{1,2})")
_TOD_RE = re.compile(r"([0-9]{1,2}):([0-9]{1,2})(?::([0-9]{1,2})(?:\.([0-9]+))?)?")
_EPOCH_ORD = _date(1970, 1, 1).toordinal()


def _date_ns(m) -> int | None:
    try:
        d = _date(int(m.group(1)), int(m.group(2)), int(m.group(3)))
    except ValueError:
        return None
    return (d.toordinal() - _EPOCH_ORD) * _DAY_NS


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
    if m is None or body[m.end():m.end() + 1] != "-":
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
                out = digits[:e + 1] + "." + digits[e + 1:]
        else:
            out = "0." + "0" * (-e - 1) + digits
    else:
        out = f"{digits[0]}.{digits[1:] or '0'}E{'-' if e < 0 else '+'}{abs(e):02d}"
    return "-" + out if neg else out


def _real32_to_string(x: float) -> str:
    return real_to_string(x, False)


def _real64_to_string(x: float) -> str:
    return real_to_string(x, True)


def _bool_to_string(v) -> str:
    return "TRUE" if v else "FALSE"


_LIT_PREFIX = {"TIME": "T#", "LTIME": "LT#", "DATE": "D#", "LDATE": "LD#",
               "TIME_OF_DAY": "TOD#", "LTIME_OF_DAY": "LTOD#",
               "DATE_AND_TIME": "DT#", "LDATE_AND_TIME": "LDT#"}
_DUR_UNITS = (("d", 86_400_000_000_000), ("h", 3_600_000_000_000), ("m", 60_000_000_000),
              ("s", 1_000_000_000), ("ms", 1_000_000), ("us", 1_000), ("ns", 1))


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
    sec, frac = divmod(ns % _DAY_NS, 1_000_000_000)
    mi, s = divmod(sec, 60)
    h, mi = divmod(mi, 60)
    out = f"{h:02d}:{mi:02d}:{s:02d}"
    if frac:
        out += "." + f"{frac:09d}".rstrip("0")
    return out


def _fmt_date(ns: int) -> str:
    return _date.fromordinal(_EPOCH_ORD + ns // _DAY_NS).isoformat()


def _temporal_formatter(e: ElementaryType) -> Callable[[int], str]:
    """A closure formatting a raw value of time/date type e as its literal."""
    prefix = _LIT_PREFIX[e.name]
    unit = e.unit_ns
    norm = _time_wrapper(e)
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
        fmt = _TEMPORAL_FORMATTERS[e] = _temporal_formatter(e)
    return fmt(value)


# ---------------------------------------------------------------- conversion

def _time_from_ns_unit(src_unit: int, d: ElementaryType) -> Callable[[int], int]:
    """Convert a time/date raw value in units of src_unit ns to type d by
    its physical meaning: durations keep their length (truncated toward zero
    to d's resolution: LTIME_TO_TIME drops sub-ms), DATE takes the day
    (floor, DT_TO_DATE), TOD the time of day (DT_TO_TOD), DT the instant
    (floor to d's resolution). A duration meets a date as time since
    1970-01-01 (CODESYS: TIME_TO_DT(T#5d4h3m2s1ms) = DT#1970-01-06-04:03:02)
    or since midnight; TOD_TO_DT gives that time on 1970-01-01."""
    du = d.unit_ns
    w = _time_wrapper(d)
    c = d.category
    if c == DURATION:
        if src_unit == du:
            return w
        if src_unit > du:
            f = src_unit // du

            def scale_up(v: int) -> int:
                return w(v * f)
            return scale_up
        f = du // src_unit

        def scale_down(v: int) -> int:
            return w(idiv(v, f))  # toward zero
        return scale_down
    if c == DATECAT:
        per_day = _DAY_NS // du

        def to_date(v: int) -> int:
            return w((v * src_unit // _DAY_NS) * per_day)
        return to_date
    if c == TODCAT:
        def to_tod(v: int) -> int:
            return (v * src_unit % _DAY_NS) // du
        return to_tod

    def to_dt(v: int) -> int:
        return w(v * src_unit // du)
    return to_dt


def _narrow_string(v: str) -> str:
    """WSTRING -> STRING: STRING holds 8-bit characters (Latin-1 here);
    others become '?'."""
    try:
        v.encode("latin-1")
        return v
    except UnicodeEncodeError:
        return v.encode("latin-1", "replace").decode("latin-1")


def _classify(t: Type) -> tuple:
    r = resolve(t)
    if isinstance(r, StringType):
        return "str", r
    e = base_elementary(r)
    if e is None:
        raise TypeError(f"no conversion for type {t.name}")
    c = e.category
    if c == BOOLCAT:
        return "bool", e
    if c in (SIGNED, UNSIGNED, BITS):
        return "int", e
    if c == REALCAT:
        return "real", e
    return "time", e


def make_converter(src: Type, dst: Type) -> Callable:
    """A closure converting a value of type src to type dst, with IEC /
    CODESYS semantics (the <src>_TO_<dst> function). Bind it once, call it
    often. Enumerations and subranges convert through their base type.

      integer -> integer/bit string   wraps (INT_TO_SINT(300) = 44,
                                      DINT_TO_UINT(-1) = 65535)
      REAL -> integer/time            rounds half away from zero, then wraps;
                                      NaN and inf give 0
      integer -> REAL                 rounds to binary32
      any -> BOOL                     value <> 0; BOOL -> number 0/1
      time/date <-> number            the raw value: TIME ms, LTIME ns, DATE
                                      and DT s, TOD ms, L-dates ns
                                      (TIME_TO_DINT(T#1s) = 1000)
      time/date -> time/date          by meaning (see _time_from_ns_unit):
                                      TIME_TO_LTIME * 1e6, DT_TO_DATE,
                                      DT_TO_TOD, DATE_TO_DT
      number -> STRING                decimal ('42'); reals per
                                      real_to_string; BOOL 'TRUE'/'FALSE';
                                      time/date as literal ('T#1s500ms')
      STRING -> x                     parses the literal forms of x (blanks
                                      around allowed, 'INT#5', '16#FF',
                                      'T#1s'); invalid text gives 0 / FALSE
      WSTRING -> STRING               characters beyond Latin-1 -> '?'
    """
    sk, s = _classify(src)
    dk, d = _classify(dst)
    if s is d and sk != "str":
        return _identity

    if dk == "str":
        if sk == "str":
            return _narrow_string if (s.wide and not d.wide) else _identity
        if sk == "bool":
            return _bool_to_string
        if sk == "int":
            return str
        if sk == "real":
            return _real64_to_string if s is LREAL else _real32_to_string
        return _temporal_formatter(s)

    if dk == "bool":
        if sk == "str":
            def str_to_bool(v: str) -> bool:
                return parse_bool(v) or False
            return str_to_bool
        return bool  # <> 0; NaN is <> 0 as well

    if dk == "real":
        if sk == "str":
            if d is LREAL:
                def str_to_lreal(v: str) -> float:
                    x = parse_real(v)
                    return 0.0 if x is None else x
                return str_to_lreal

            def str_to_real(v: str) -> float:
                x = parse_real(v)
                return 0.0 if x is None else f32(x)
            return str_to_real
        if d is LREAL:
            return float
        return f32 if sk == "real" else _int_to_f32

    # integer, bit string or time/date destination
    w = _int_wrapper(d) if dk == "int" else _time_wrapper(d)
    if sk in ("int", "bool"):  # the wrappers turn a bool into 0/1
        return w
    if sk == "real":
        def real_to_int(v: float) -> int:
            return w(round_half_away(v))
        return real_to_int
    if sk == "time":
        if dk == "int":
            return w
        return _time_from_ns_unit(s.unit_ns, d)
    # from text
    if dk == "int":
        def str_to_int(v: str) -> int:
            x = parse_int(v)
            return 0 if x is None else w(x)
        return str_to_int
    from_ns_ = _time_from_ns_unit(1, d)
    cat = d.category

    def str_to_time(v: str) -> int:
        ns = parse_temporal(v, cat)
        return 0 if ns is None else from_ns_(ns)
    return str_to_time


_CONVERTERS: dict = {}


def convert(value, src: Type, dst: Type):
    """Convert one value from src to dst (see make_converter); converters
    are cached per (src, dst) pair."""
    key = (src, dst)
    f = _CONVERTERS.get(key)
    if f is None:
        f = _CONVERTERS[key] = make_converter(src, dst)
    return f(value)


def from_ns(t: ElementaryType, ns: int) -> int:
    """The raw value of time/date type t for a parser literal in ns
    (T#1.5ms -> TIME 1: truncated toward zero to t's resolution)."""
    return _time_from_ns_unit(1, t)(ns)


def to_ns(t: ElementaryType, raw: int) -> int:
    """Nanoseconds of a raw time/date value of type t."""
    return raw * t.unit_ns


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
    return (tod + t) % _DAY_NS


def SUB_LTOD_LTIME(tod: int, t: int) -> int:
    return (tod - t) % _DAY_NS


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
    return (d - d % _DAY_NS + tod % _DAY_NS) & _M64


def _days(year: int, month: int, day: int) -> int | None:
    try:
        return _date(year, month, day).toordinal() - _EPOCH_ORD
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
    return _tod_ms(hour, minute, second, millisecond) * 1_000_000 % _DAY_NS


def CONCAT_DT(year: int, month: int, day: int, hour: int, minute: int, second: int,
              millisecond: int) -> int:
    """-> DT (ms dropped); an impossible date gives DT#1970-01-01-00:00:00."""
    n = _days(year, month, day)
    if n is None:
        return 0
    return (n * _DAY_S + _tod_ms(hour, minute, second, millisecond) // 1000) & _M32


def CONCAT_LDT(year: int, month: int, day: int, hour: int, minute: int, second: int,
               millisecond: int) -> int:
    n = _days(year, month, day)
    if n is None:
        return 0
    return (n * _DAY_NS + _tod_ms(hour, minute, second, millisecond) * 1_000_000) & _M64


def DAY_OF_WEEK(d: int) -> int:
    """IEC 3rd ed.: 0 = Sunday .. 6 = Saturday (1970-01-01 was a Thursday)."""
    return (d // _DAY_S + 4) % 7
