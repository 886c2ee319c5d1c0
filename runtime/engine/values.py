"""ST values as a test writes and reads them, and back.

Reading (``to_python``): BOOL -> bool, integers and bit strings -> int,
REAL/LREAL -> float, TIME/LTIME -> datetime.timedelta, DATE/TOD/DT (and
their L- forms) -> their IEC literal text ("D#2024-01-02"), STRING -> str,
an enumeration -> an ``EnumValue`` (a str: the enumerator's name as
declared, equal to 'Run', 'E_State.Run' in any case, and to its integer
value), ARRAY -> list (nested per dimension), STRUCT and FB instance ->
dict of variable name -> value.

Writing (``from_python``) is checked: a wrong kind of value or one outside
the type's range raises ``ValueError`` naming the variable, its ST type and
what it takes. Nothing is wrapped, truncated or rounded silently. A string
must fit the declared length (a WSTRING's counts UTF-16 code units: U+1F600
counts 2) and hold no lone surrogate (U+D800..U+DFFF
alone is no character: no STRING or WSTRING holds one, UTF-8 and UTF-16
cannot encode it, and an OPC UA or JSON reader would fail on it). A REAL or
LREAL takes NaN and infinities only when the caller allows them
(``finite=False``, the test API): every surface of a server writes finite
numbers only (docs/guide/surfaces.md "Seeing and changing a running PLC"). The value echoed
in a message is cut (config/values.py ``got``, ``cut``).
"""

from __future__ import annotations

import math
import re
import struct
from datetime import timedelta
from typing import Any

from ..config.values import cut, got
from ..durations import parse_duration_ns
from ..st import types as T
from ..st.rtlib.rtlib import iec_literal, string_length
from ..st.syntax.literals import LiteralError, parse_based, parse_hash_literal
from ..st.valuejson import SKIPPED_SECTIONS


class EnumValue(str):
    """An enumerator read from the PLC: the name as declared (``str(v)``,
    ``v.name``), its type (``v.type_name``) and integer (``v.value``). It
    compares equal, case-insensitively as ST names do, to 'Running' and
    'E_State.Running', and to its integer value."""

    name: str
    type_name: str
    value: int

    def __new__(cls, name: str, type_name: str, value: int) -> EnumValue:
        obj = super().__new__(cls, name)
        obj.name = name
        obj.type_name = type_name
        obj.value = value
        return obj

    def __reduce__(self) -> tuple:
        """Pickled as its three parts (str's own reduction would lose them):
        a value a sweep's worker process or pytest-xdist sends back."""
        return (EnumValue, (self.name, self.type_name, self.value))

    def __eq__(self, other: object) -> bool:
        if isinstance(other, EnumValue):
            return self.type_name.upper() == other.type_name.upper() and self.value == other.value
        if isinstance(other, int) and not isinstance(other, bool):
            return self.value == other
        if isinstance(other, str):
            kind, dot, name = other.rpartition(".")
            if dot and kind.upper() != self.type_name.upper():
                return False
            return name.upper() == self.name.upper()
        return NotImplemented

    def __ne__(self, other: object) -> bool:
        eq = self.__eq__(other)
        return eq if eq is NotImplemented else not eq

    def __hash__(self) -> int:
        return hash(self.name.upper())

    def __repr__(self) -> str:
        return f"{self.type_name}.{self.name}"


def to_python(t: T.Type, v: Any) -> Any:
    """A value of ST type t as a test reads it (module docstring)."""
    t = T.resolve(t)
    if isinstance(t, T.ElementaryType):
        if t.is_bool:
            return bool(v)
        if t.is_intlike:
            return int(v)
        if t.is_real:
            return float(v)
        if t.category == T.DURATION:
            return timedelta(microseconds=int(v) * t.unit_ns / 1000)
        if t.is_time:
            return iec_literal(t, v)
        return v
    if isinstance(t, T.SubrangeType):
        return int(v)
    if isinstance(t, T.EnumType):
        name = t.name_of(v)
        return EnumValue(name, t.name, int(v)) if name is not None else int(v)
    if isinstance(t, T.StringType):
        return str(v)
    if isinstance(t, T.ArrayType):
        return _array_out(len(t.dims), t.elem, v)
    if isinstance(t, (T.StructType, T.FBType)):
        return instance_to_python(v)
    if isinstance(t, T.RefType):
        return None if v is None else "<ref>"
    return None if v is None else str(v)


def instance_to_python(obj: Any) -> dict:
    """A struct or FB/PROGRAM instance as a dict (VAR_IN_OUT, VAR_EXTERNAL and VAR_TEMP left out)."""
    return {
        name: to_python(ty, getattr(obj, attr))
        for name, attr, ty, section in type(obj)._VARS_
        if section not in SKIPPED_SECTIONS
    }


def _array_out(ndims: int, elem: T.Type, v: list) -> list:
    if ndims <= 1:
        return [to_python(elem, item) for item in v]
    return [_array_out(ndims - 1, elem, row) for row in v]


def type_text(t: T.Type) -> str:
    """The ST type as a message names it, with the range of an integer."""
    r = T.resolve(t)
    if isinstance(r, T.ElementaryType) and r.is_intlike:
        return f"{r.name} ({r.lo}..{r.hi})"
    if isinstance(r, T.SubrangeType):
        return f"{r.name}"
    if isinstance(r, T.EnumType):
        return f"{r.name} ({', '.join(r.spelled.values())})"
    return r.name


#: what a STRING's and a WSTRING's length counts (IEC 61131-3: a WSTRING's are UTF-16 code units)
_UNITS = {False: "characters", True: "UTF-16 units (a character beyond U+FFFF counts 2)"}

#: a code point of the surrogate range: alone it is no character
LONE_SURROGATE = re.compile("[\ud800-\udfff]")


def lone_surrogate(text: str) -> int | None:
    """The index of the first lone surrogate in text, or None."""
    if text.isascii():
        return None
    found = LONE_SURROGATE.search(text)
    return None if found is None else found.start()


def without_lone_surrogates(text: str) -> str:
    """text with each lone surrogate replaced by U+FFFD (as a UTF-16 decoder does)."""
    return text if lone_surrogate(text) is None else LONE_SURROGATE.sub("\ufffd", text)


def shown(value: Any) -> str:
    """A value as a message echoes it: a long string cut to its first characters and its length."""
    return got(value) if isinstance(value, str) else cut(repr(value))


def from_python(t: T.Type, value: Any, path: str, *, finite: bool = False) -> Any:
    """value, given by a test for the variable at path of ST type t, in the
    form the generated code stores (ints, floats, ms for TIME ...). Raises
    ValueError naming path, the type and what it takes. finite: a REAL
    takes no NaN or infinity (a server's write)."""
    r = T.resolve(t)

    def bad(takes: str) -> ValueError:
        return ValueError(cut(f"{path} is {type_text(t)}: write {takes}, not {shown(value)}"))

    if isinstance(r, T.ElementaryType):
        return _elementary_in(r, value, bad, finite)
    if isinstance(r, T.SubrangeType):
        n = _integer(value)
        if n is None or not r.lo <= n <= r.hi:
            raise bad(f"an integer from {r.lo} to {r.hi}")
        return n
    if isinstance(r, T.EnumType):
        return _enum_in(r, value, bad)
    if isinstance(r, T.StringType):
        if not isinstance(value, str):
            raise bad("a str")
        if string_length(value, r.wide) > r.length:
            raise bad(f"a str of at most {r.length} {_UNITS[r.wide]}")
        at = lone_surrogate(value)
        if at is not None:
            raise bad(f"text (U+{ord(value[at]):04X} at index {at} is a lone surrogate, no character)")
        return value
    raise bad("a value of an elementary type (write arrays and structs element by element or as a list / dict)")


def _integer(value: Any) -> int | None:
    """An int from an int or an ST integer literal ('16#FF', '2#1010', 'INT#5'); None
    otherwise (a time or date literal too: 'T#2s' is no integer)."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int):
        return value
    if isinstance(value, str):
        text = value.strip().replace("_", "")
        try:
            if text.lstrip("+-").isdigit():
                return int(text)
            if "#" in text:
                prefix = text.split("#", 1)[0]
                if prefix.isdigit():
                    return parse_based(text)
                lit = parse_hash_literal(text)
                if getattr(lit, "kind", None) != "int":  # T#2s is no integer (its ns were taken)
                    return None
                v = getattr(lit, "value", None)
                return v if isinstance(v, int) and not isinstance(v, bool) else None
        except (LiteralError, ValueError):
            return None
    return None


def _elementary_in(t: T.ElementaryType, value: Any, bad, finite: bool = False) -> Any:
    if t.is_bool:
        if isinstance(value, bool) or (isinstance(value, int) and value in (0, 1)):
            return bool(value)
        if isinstance(value, str) and value.strip().upper() in ("TRUE", "FALSE", "BOOL#TRUE", "BOOL#FALSE"):
            return value.strip().upper().endswith("TRUE")
        raise bad("True/False, 1/0 or 'TRUE'/'FALSE'")
    if t.is_intlike:
        n = _integer(value)
        if n is None:
            raise bad("an integer (or an ST literal such as '16#FF')")
        assert t.lo is not None and t.hi is not None
        if not t.lo <= n <= t.hi:
            raise bad(f"an integer from {t.lo} to {t.hi}")
        return n
    if t.is_real:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise bad("a number")
        within = f"a number within the {t.name} range (about ±{_REAL_MAX[t.bits]})"
        try:
            x = float(value)
        except OverflowError:  # an int of hundreds of digits
            raise bad(within) from None
        if finite and not math.isfinite(x):
            raise bad(f"a finite number (NaN and infinity are not taken from outside): {within}")
        if t.bits == 32 and math.isfinite(x):
            try:
                x = struct.unpack("<f", struct.pack("<f", x))[0]
            except OverflowError:
                raise bad(within) from None
        return x
    if t.category == T.DURATION:
        ns = duration_value_ns(value)
        if ns is None:
            raise bad("a duration: a timedelta or 'T#2s', '1m30s', '250ms'")
        raw, rest = divmod(ns, t.unit_ns)
        if rest:
            raise bad(f"a whole number of {'ms' if t.unit_ns == 1_000_000 else 'ns'}")
        assert t.lo is not None and t.hi is not None
        if not t.lo <= raw <= t.hi:
            raise bad(f"a duration within {t.name}'s range")
        return raw
    if t.is_time:
        if isinstance(value, str) and "#" in value:
            try:
                lit = parse_hash_literal(value.strip())
            except LiteralError:
                lit = None
            v = getattr(lit, "value", None)
            if isinstance(v, int):
                return v // t.unit_ns
        raise bad(f"an IEC literal such as {iec_literal(t, 0)!r}")
    raise bad("a value of this type")


_REAL_MAX = {32: "3.4e38", 64: "1.8e308"}


def duration_value_ns(value: Any) -> int | None:
    if isinstance(value, timedelta):
        return (value.days * 86_400 + value.seconds) * 1_000_000_000 + value.microseconds * 1_000
    if isinstance(value, str):
        text = value.strip()
        negative = text.upper().startswith(("T#-", "TIME#-", "LTIME#-"))
        if negative:
            text = text.replace("-", "", 1)
        if text.upper().startswith("LTIME#"):
            text = text[6:]
        ns = parse_duration_ns(text)
        return None if ns is None else (-ns if negative else ns)
    return None


def _enum_in(t: T.EnumType, value: Any, bad) -> int:
    names = ", ".join(t.spelled.values())
    if isinstance(value, EnumValue):
        if value.type_name.upper() != t.name.upper():
            raise bad(f"one of {names}")
        return value.value
    if isinstance(value, int) and not isinstance(value, bool):
        if value in t.values.values():
            return value
        raise bad(f"one of {names} (or their values {', '.join(str(v) for v in t.values.values())})")
    if isinstance(value, str):
        kind, dot, name = value.strip().rpartition(".")
        if not dot:
            kind, hash_, name = value.strip().rpartition("#")
            dot = hash_
        if (not dot or kind.upper() == t.name.upper()) and name.upper() in t.values:
            return int(t.values[name.upper()])
    raise bad(f"one of {names}")
