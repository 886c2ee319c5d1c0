"""Values of ST literals, from the token text to the Python value the AST
carries (see ``ast.Literal``): integers and reals, strings with their ``$``
escapes resolved, and every time and date kind as an int of nanoseconds.

Each function raises ``LiteralError`` with a message and a hint when the text
is not a valid literal; the parser turns that into an E003 diagnostic.
"""

from __future__ import annotations

import datetime
import re
from fractions import Fraction

from .. import ast


class LiteralError(ValueError):
    def __init__(self, message: str, hint: str | None = None) -> None:
        super().__init__(message)
        self.message = message
        self.hint = hint


NS_PER = {"D": 86_400 * 10**9, "H": 3_600 * 10**9, "M": 60 * 10**9, "S": 10**9, "MS": 10**6, "US": 10**3, "NS": 1}
_UNIT_ORDER = ("D", "H", "M", "S", "MS", "US", "NS")
_EPOCH_ORDINAL = datetime.date(1970, 1, 1).toordinal()
_NS_PER_DAY = NS_PER["D"]

# Prefix of a time or date literal -> Literal.kind
_TIME_PREFIXES = {
    "T": "time",
    "TIME": "time",
    "LT": "ltime",
    "LTIME": "ltime",
    "D": "date",
    "DATE": "date",
    "LD": "ldate",
    "LDATE": "ldate",
    "TOD": "tod",
    "TIME_OF_DAY": "tod",
    "LTOD": "ltod",
    "LTIME_OF_DAY": "ltod",
    "DT": "dt",
    "DATE_AND_TIME": "dt",
    "LDT": "ldt",
    "LDATE_AND_TIME": "ldt",
}
_NUMERIC_TYPES = frozenset(
    (
        "SINT",
        "INT",
        "DINT",
        "LINT",
        "USINT",
        "UINT",
        "UDINT",
        "ULINT",
        "BYTE",
        "WORD",
        "DWORD",
        "LWORD",
        "REAL",
        "LREAL",
    )
)
_STRING_TYPES = {"STRING": "string", "CHAR": "string", "WSTRING": "wstring", "WCHAR": "wstring"}
ELEMENTARY_NAMES = _NUMERIC_TYPES | {"BOOL"} | set(_STRING_TYPES) | set(_TIME_PREFIXES)

_DIGITS = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ"
_DURATION_PART = re.compile(r"(\d[\d_]*)(?:\.(\d[\d_]*))?_?(MS|US|NS|D|H|M|S)_?", re.I | re.A)
_DATE = re.compile(r"(\d{1,4})-(\d{1,2})-(\d{1,2})", re.A)
_TOD = re.compile(r"(\d{1,2}):(\d{1,2})(?::(\d{1,2})(?:\.(\d*))?)?", re.A)
_REAL = re.compile(r"\d[\d_]*(?:\.\d[\d_]*)?(?:e[-+]?\d+)?", re.I | re.A)


# ---------------------------------------------------------------- numbers

MAX_DIGITS = 128  # LWORD in base 2 is 64; more is a typo (and Python's int() has limits)


def _check_underscores(digits: str, text: str) -> str:
    """The digits without their underscores. Doubled underscores pass here
    (TwinCAT takes 16#7f_ff__ff); the checker refuses them where the profile
    does (``doubled_underscore``): IEC 61131-3 wants one between two digits."""
    if not digits or digits.startswith("_") or digits.endswith("_"):
        raise LiteralError(f"invalid number '{text}'", "an underscore may only stand between two digits")
    digits = digits.replace("_", "")
    if len(digits) > MAX_DIGITS:
        raise LiteralError(f"number too long ({len(digits)} digits)")
    return digits


def parse_int(text: str) -> int:
    """``1_000`` -> 1000."""
    return int(_check_underscores(text, text))


def parse_based(text: str) -> int:
    """``16#FF``, ``2#1010_1010``, ``8#17``."""
    base_s, _, digits = text.partition("#")
    if base_s not in ("2", "8", "16"):
        raise LiteralError(f"invalid base '{base_s}' in '{text}'", "the base is 2, 8 or 16: 2#1010, 8#17, 16#FF")
    base = int(base_s)
    digits = _check_underscores(digits, text)
    for ch in digits.upper():
        if _DIGITS.find(ch) not in range(base):
            raise LiteralError(f"digit '{ch}' is not valid in base {base} ('{text}')")
    return int(digits, base)


def parse_c_hex(text: str) -> int:
    """``0x00032007`` (Schneider manuals)."""
    return int(_check_underscores(text[2:], text), 16)


def parse_real(text: str) -> float:
    """``1.5``, ``1.0E-3``, ``1_000.5``, ``1e5``."""
    if not _REAL.fullmatch(text):
        raise LiteralError(f"invalid real number '{text}'")
    mant, sep, exp = text.upper().partition("E")
    whole, _, frac = mant.partition(".")
    _check_underscores(whole, text)
    if frac:
        _check_underscores(frac, text)
    value = float(mant.replace("_", "") + ("E" + exp if sep else ""))
    if value == float("inf"):
        raise LiteralError(f"real number '{text}' is too large")
    return value


def _number(body: str) -> tuple:
    """A (possibly signed, possibly based) number after a type prefix."""
    sign = -1 if body.startswith("-") else 1
    unsigned = body.lstrip("+-")
    if "#" in unsigned:
        return "int", sign * parse_based(unsigned)
    if "." in unsigned or "E" in unsigned.upper():
        return "real", sign * parse_real(unsigned)
    if not unsigned.replace("_", "").isdigit():
        raise LiteralError(f"invalid number '{body}'")
    return "int", sign * parse_int(unsigned)


# ---------------------------------------------------------------- strings

_ESCAPES = {"$": "$", "'": "'", '"': '"', "L": "\n", "N": "\n", "P": "\f", "R": "\r", "T": "\t"}


def parse_string(text: str) -> str:
    """Decode a quoted literal: '...' (STRING, $hh escapes) or "..."
    (WSTRING, $hhhh escapes)."""
    quote = text[0]
    body = text[1:-1]
    width = 2 if quote == "'" else 4
    out = []
    i, n = 0, len(body)
    while i < n:
        ch = body[i]
        if ch != "$":
            out.append(ch)
            i += 1
            continue
        nxt = body[i + 1 : i + 2]
        if nxt.upper() in _ESCAPES:
            out.append(_ESCAPES[nxt.upper()])
            i += 2
            continue
        code = body[i + 1 : i + 1 + width]
        if len(code) == width and all(c in "0123456789abcdefABCDEF" for c in code):
            unit = int(code, 16)
            if 0xD800 <= unit <= 0xDFFF:
                out.append(_surrogate_pair(unit, body[i + 5 : i + 10]))
                i += 10
                continue
            out.append(chr(unit))
            i += 1 + width
            continue
        raise LiteralError(
            f"invalid escape '${nxt}' in string",
            f"use $$ for '$', $' or $\", $L $N $P $R $T, or ${'h' * width} ({width} hex digits) for a character code",
        )
    return "".join(out)


def _surrogate_pair(high: int, rest: str) -> str:
    """The character of a UTF-16 surrogate pair written $D83D$DE00 (high,
    then rest: the next escape); a lone surrogate is no character, and no
    WSTRING may hold one (it could not be encoded for OPC UA, JSON, a
    retain file)."""
    low = int(rest[1:], 16) if len(rest) == 5 and rest[0] == "$" and _is_hex(rest[1:]) else -1
    if 0xD800 <= high <= 0xDBFF and 0xDC00 <= low <= 0xDFFF:
        return chr(0x10000 + ((high - 0xD800) << 10) + (low - 0xDC00))
    raise LiteralError(
        f"'${high:04X}' is a lone UTF-16 surrogate, not a character",
        "write the character itself, or a high and a low surrogate together ($D83D$DE00)",
    )


def _is_hex(text: str) -> bool:
    return all(c in "0123456789abcdefABCDEF" for c in text)


# ---------------------------------------------------------------- time and date


def parse_duration(body: str) -> int:
    """``1h2m3s4ms``, ``-5s``, ``1.5s``, ``100us`` -> nanoseconds."""
    sign = 1
    if body[:1] in "+-":
        sign = -1 if body[0] == "-" else 1
        body = body[1:]
    pos, total, last_rank = 0, Fraction(0), -1
    parts = list(_DURATION_PART.finditer(body))
    for k, m in enumerate(parts):
        if m.start() != pos:
            break
        pos = m.end()
        whole, frac, unit = m.group(1), m.group(2), m.group(3).upper()
        rank = _UNIT_ORDER.index(unit)
        if rank <= last_rank:
            raise LiteralError(
                f"invalid time literal: unit '{m.group(3)}' out of order",
                "write the units largest first: d, h, m, s, ms, us, ns (T#1h30m)",
            )
        last_rank = rank
        if frac is not None and k != len(parts) - 1:
            raise LiteralError(
                "invalid time literal: only the last unit may have a fraction", "T#1h30m or T#1.5h, not T#1.5h30m"
            )
        value = Fraction(parse_int(whole))
        if frac is not None:
            value += Fraction(parse_int(frac), 10 ** len(frac.replace("_", "")))
        total += value * NS_PER[unit]
    if pos != len(body) or not parts:
        raise LiteralError(
            f"invalid time literal '{body}'",
            "a duration is numbers with units d, h, m, s, ms, us, ns: T#1h2m3s, T#1.5s, T#200ms",
        )
    return sign * round(total)


def _date_days(text: str) -> int:
    m = _DATE.fullmatch(text)
    if not m:
        raise LiteralError(f"invalid date '{text}'", "write dates as year-month-day: D#2024-01-31")
    try:
        d = datetime.date(int(m.group(1)), int(m.group(2)), int(m.group(3)))
    except ValueError as e:
        raise LiteralError(f"invalid date '{text}': {e}") from None
    return d.toordinal() - _EPOCH_ORDINAL


def _tod_ns(text: str) -> int:
    m = _TOD.fullmatch(text)
    if not m:
        raise LiteralError(f"invalid time of day '{text}'", "write it as hours:minutes:seconds: TOD#12:30:15.5")
    h, mi, s, frac = int(m.group(1)), int(m.group(2)), int(m.group(3) or 0), m.group(4) or ""
    if h > 23 or mi > 59 or s > 59:
        raise LiteralError(f"invalid time of day '{text}'", "hours 0-23, minutes and seconds 0-59")
    ns = ((h * 60 + mi) * 60 + s) * 10**9
    if frac:
        ns += round(Fraction(int(frac), 10 ** len(frac)) * 10**9)
    return ns


def parse_date(body: str) -> int:
    return _date_days(body) * _NS_PER_DAY


def parse_tod(body: str) -> int:
    return _tod_ns(body)


def parse_dt(body: str) -> int:
    m = re.fullmatch(r"(\d+-\d+-\d+)-(.*)", body, re.A)
    if not m:
        raise LiteralError(
            f"invalid date and time '{body}'",
            "write it as year-month-day-hours:minutes:seconds: DT#2024-01-31-12:30:00",
        )
    return _date_days(m.group(1)) * _NS_PER_DAY + _tod_ns(m.group(2))


_TIME_PARSERS = {
    "time": parse_duration,
    "ltime": parse_duration,
    "date": parse_date,
    "ldate": parse_date,
    "tod": parse_tod,
    "ltod": parse_tod,
    "dt": parse_dt,
    "ldt": parse_dt,
}


# ---------------------------------------------------------------- prefix#body

HashValue = ast.Literal | ast.EnumLiteral | ast.SchneiderAddress


def parse_hash_literal(text: str) -> HashValue:
    """Everything written ``prefix#body``: time and date literals, typed
    literals (INT#5, INT#16#FF, REAL#1.5, BOOL#TRUE, STRING#'x'), enumeration
    values (Color#Red) and Schneider addresses (ADR#0.1.SYS). Positions are
    left to the caller."""
    prefix, _, body = text.partition("#")
    upper = prefix.upper()
    kind = _TIME_PREFIXES.get(upper)
    if kind is not None:
        if not body[:1].isdigit() and body[:1] not in "+-":
            raise LiteralError(f"invalid {upper}# literal '{text}'")
        return ast.Literal(kind, _TIME_PARSERS[kind](body))
    if upper == "ADR":
        parts = tuple(body.split("."))
        if not all(parts):
            raise LiteralError(f"invalid Schneider address '{text}'", "e.g. ADR#0.1.SYS")
        return ast.SchneiderAddress(parts)
    first = body[:1]
    if first in ("'", '"'):
        want = _STRING_TYPES.get(upper)
        if want is not None and (want == "wstring") != (first == '"'):
            quoted = 'double-quoted "..."' if want == "wstring" else "single-quoted '...'"
            raise LiteralError(f"invalid {upper} literal '{text}'", f"{upper}# takes a {quoted} string")
        return ast.Literal("wstring" if first == '"' else "string", parse_string(body), type_name=upper)
    if first.isalpha() or first == "_":
        if upper == "BOOL":
            if body.upper() in ("TRUE", "FALSE"):
                return ast.Literal("bool", body.upper() == "TRUE", type_name="BOOL")
            raise LiteralError(f"invalid BOOL literal '{text}'", "BOOL#TRUE, BOOL#FALSE, BOOL#1 or BOOL#0")
        if upper in ELEMENTARY_NAMES:
            raise LiteralError(f"invalid {upper} literal '{text}'")
        return ast.EnumLiteral(prefix, body)
    num_kind, value = _number(body)
    if upper == "BOOL":
        if num_kind == "int" and value in (0, 1):
            return ast.Literal("bool", bool(value), type_name="BOOL")
        raise LiteralError(f"invalid BOOL literal '{text}'", "BOOL#TRUE, BOOL#FALSE, BOOL#1 or BOOL#0")
    if upper in _STRING_TYPES:
        raise LiteralError(f"invalid {upper} literal '{text}'", f"{upper}#'text'")
    return ast.Literal(num_kind, value, type_name=upper)


# ---------------------------------------------------------------- direct addresses

_LOCATED = re.compile(r"%([IQM])([XBWDL]?)(?:([\d.]+)(?::(X?)(\d+))?|\*)", re.I | re.A)


def parse_located(text: str) -> ast.LocatedAddress:
    """``%IX0.3`` / ``%MW3250:X0`` / ``%MW3250:4`` / ``%I*`` (a LOCATED token).
    Raises LiteralError for absurdly long numbers."""
    m = _LOCATED.fullmatch(text)
    if m is None:
        raise LiteralError(f"'{text}' is not a direct address")
    area, size, idx, bit_x, num = m.groups()
    if any(len(n) > 18 for n in (idx or "").split(".") + [num or ""]):
        raise LiteralError(f"invalid direct address '{text}': number too long")
    indices = tuple(int(i) for i in idx.split(".")) if idx else ()
    bit = table = None
    if num is not None:
        if bit_x:
            bit = int(num)
        else:
            table = int(num)
    return ast.LocatedAddress(area.upper(), size.upper(), indices, bit, table, text)
