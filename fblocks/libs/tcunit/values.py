"""Values as TcUnit prints them in its failure messages, and its comparisons
of ANY values (AssertEquals) and of arrays (AssertArrayEquals_*,
AssertArray2dEquals_*, AssertArray3dEquals_*).

The texts are those of TcUnit's messages as its verifier project expects
them ("EXP: 0xAB, ACT: 0xCD"): BOOL TRUE/FALSE; BYTE, WORD, DWORD, LWORD as
0x and 2, 4, 8, 16 upper-case hex digits; integers in decimal; REAL and
LREAL as TwinCAT's REAL_TO_STRING (1234.5, 24.0); TIME T#12h34m15s10ms,
LTIME LTIME#1000d15h23m12s34ms2us44ns, DATE D#1996-05-06, DATE_AND_TIME
DT#1996-05-06-15:36:30, TIME_OF_DAY TOD#15:36:30.123; STRING as it is. A
WSTRING is never printed (TcUnit: "Not possible to print EXP unicode
WSTRING value").

AssertEquals of two ANY values (tcunit.org, API "AssertEquals"): values of
different type classes fail with "(Type class = INT)" / "(Type class =
UINT)"; two strings of different lengths with "(Data size (LEN) = 16)"; two
values of different sizes with "(Data size = 4)"; two elementary values of
one type as the typed assert of that type; anything else (a STRUCT, an
ARRAY, an enumeration) byte by byte, shown as 0x and the hex of its first
39 bytes.
"""

from __future__ import annotations

from dataclasses import dataclass
from itertools import product

from softplc.runtime.st import sizes
from softplc.runtime.st import types as T
from softplc.runtime.st.rtlib.refs import CellRef
from softplc.runtime.st.rtlib.rt_bytes import layout_of
from softplc.runtime.st.rtlib.rt_numeric import f32
from softplc.runtime.st.rtlib.rt_text import iec_literal
from softplc.runtime.st.rtlib.rt_varray import VarArray

WSTRING_EXPECTED = "Not possible to print EXP unicode WSTRING value"
WSTRING_ACTUAL = "Not possible to print ACT unicode WSTRING value"
SIZES_DIFFER = ", size of arrays not matching."

_HEX_DIGITS = {"BYTE": 2, "WORD": 4, "DWORD": 8, "LWORD": 16}
# TcUnit's names of the type classes (F_AnyTypeClassToString) where they are not the type's
_CLASS_NAMES = {"DATE_AND_TIME": "DATEANDTIME", "TIME_OF_DAY": "TIMEOFDAY"}
# the types AssertEquals (ANY) hands to a typed assert
_TYPED = frozenset(
    "BOOL BYTE DATE DATE_AND_TIME DINT DWORD INT LINT LREAL LTIME LWORD REAL SINT STRING WSTRING TIME "
    "TIME_OF_DAY UDINT UINT ULINT USINT WORD".split()
)
_ANY_BYTES_SHOWN = 39


@dataclass(frozen=True)
class Outcome:
    """An assert's result: whether it holds, what it calls its type
    (TcUnit's assertion type: INT, Array_INT, ANY), the two texts, the
    message as TcUnit prints it, and the key TcUnit tells identical asserts
    by (service.py)."""

    holds: bool
    atype: str
    expected: str
    actual: str
    message: str
    key: tuple


def elementary_name(ty) -> str | None:
    """The elementary type's name of ty (DATE_AND_TIME, STRING, WSTRING), or None."""
    r = T.resolve(ty)
    if isinstance(r, T.StringType):
        return "WSTRING" if r.wide else "STRING"
    if isinstance(r, T.ElementaryType):
        return r.name
    return None


def text(ty, value) -> str:
    """value of type ty as TcUnit prints it."""
    name = elementary_name(ty)
    if name == "STRING":
        return str(value)
    if name in _HEX_DIGITS:
        return f"0x{int(value):0{_HEX_DIGITS[name]}X}"
    if name in ("TIME", "LTIME"):
        return _duration(name, int(value))
    return iec_literal(ty, value)


_DURATION_UNITS: tuple = (("d", 86_400_000_000_000), ("h", 3_600_000_000_000), ("m", 60_000_000_000))
_DURATION_UNITS += (("s", 1_000_000_000), ("ms", 1_000_000), ("us", 1_000), ("ns", 1))


def _duration(name: str, value: int) -> str:
    """TwinCAT's TIME_TO_STRING and LTIME_TO_STRING: T#12h34m15s10ms,
    LTIME#213503d23h34m33s709ms551us615ns; both types unsigned there."""
    e = T.ELEMENTARY[name]
    n = (value % (1 << e.bits)) * e.unit_ns
    parts = []
    for unit, size in _DURATION_UNITS:
        if size < e.unit_ns:
            break
        q, n = divmod(n, size)
        if q:
            parts.append(f"{q}{unit}")
    prefix = "T#" if name == "TIME" else "LTIME#"
    return prefix + ("".join(parts) or ("0ms" if name == "TIME" else "0ns"))


def typed(kind: str, ty, expected, actual, holds: bool, message: str) -> Outcome:
    """An AssertEquals_<T>, AssertTrue or AssertFalse: the ST compared, this
    writes the texts."""
    name = elementary_name(ty) or "ANY"
    atype = "BOOL" if kind in ("AssertTrue", "AssertFalse") else name
    if name == "WSTRING":
        exp, act = WSTRING_EXPECTED, WSTRING_ACTUAL
    else:
        exp, act = text(ty, expected), text(ty, actual)
    return Outcome(holds, atype, exp, act, message, (atype, _hashable(expected), _hashable(actual)))


def type_class(ty) -> str:
    """TcUnit's name of the type class of ty (what ANY carries)."""
    r = T.resolve(ty)
    if isinstance(r, T.EnumType):
        return "ENUM"
    if isinstance(r, T.SubrangeType):
        return "SUBRANGE"
    if isinstance(r, T.ArrayType):
        return "ARRAY"
    if isinstance(r, T.StructType):
        return "USERDEF"
    if isinstance(r, T.RefType):
        return "POINTER" if r.pointer else "REFERENCE"
    if isinstance(r, T.InterfaceType):
        return "INTERFACE"
    name = elementary_name(r)
    if name is None or name not in _TYPED:
        return "UNKNOWN"
    return _CLASS_NAMES.get(name, name)


def any_equals(te, expected, ta, actual, message: str) -> Outcome:
    """TcUnit's AssertEquals (ANY)."""
    ce, ca = type_class(te), type_class(ta)
    if ce != ca:
        return _any(False, f"(Type class = {ce})", f"(Type class = {ca})", message, (ce, ca, None, None))
    name = elementary_name(te)
    if name in ("STRING", "WSTRING"):
        if len(expected) != len(actual):
            what = "LEN" if name == "STRING" else "WLEN"
            exp, act = f"(Data size ({what}) = {len(expected)})", f"(Data size ({what}) = {len(actual)})"
            return _any(False, exp, act, message, (ce, expected, actual))
        return typed("AssertEquals_" + name, te, expected, actual, expected == actual, message)
    se, sa = sizes.sizeof(te), sizes.sizeof(ta)
    if se != sa:
        return _any(False, f"(Data size = {se})", f"(Data size = {sa})", message, (ce, se, sa))
    if name in _TYPED and ce not in ("ENUM", "SUBRANGE"):
        if name in ("REAL", "LREAL"):  # TcUnit: AssertEquals_REAL with Delta 0.0
            holds = not abs(_real(name, expected - actual)) > 0.0
        else:
            holds = expected == actual
        return typed("AssertEquals_" + name, te, expected, actual, holds, message)
    be, ba = _bytes(te, expected), _bytes(ta, actual)
    if be is None or ba is None:  # no byte layout (an FB inside): the values compared
        return _any(expected == actual, "(no byte view)", "(no byte view)", message, (ce, id(expected), id(actual)))
    exp = "0x" + be[:_ANY_BYTES_SHOWN].hex().upper()
    act = "0x" + ba[:_ANY_BYTES_SHOWN].hex().upper()
    return _any(be == ba, exp, act, message, (ce, be, ba))


def _any(holds: bool, exp: str, act: str, message: str, key: tuple) -> Outcome:
    return Outcome(holds, "ANY", exp, act, message, ("ANY", *key))


def _bytes(ty, value) -> bytes | None:
    lay = layout_of(ty)
    if lay is None:
        return None
    return lay.read(CellRef(value) if lay.leaf else value, 0, lay.size)


def _real(name: str, x: float) -> float:
    return f32(x) if name == "REAL" else x


def _hashable(value):
    if isinstance(value, list):
        return tuple(_hashable(v) for v in value)
    return value


# ---------------------------------------------------------------- arrays


def arrays(kind: str, te, expecteds, ta, actuals, delta: float, message: str) -> Outcome:
    """AssertArrayEquals_<T>, AssertArray2dEquals_<T>, AssertArray3dEquals_<T>:
    the sizes of every dimension, then the elements in order (those of a
    REAL or LREAL array equal within Delta); the first that differs is
    shown with its index in each array (ARRAY[2] = 5, ARRAY[-4,0] = 0.0)."""
    arr = T.resolve(te)
    assert isinstance(arr, T.ArrayType)
    elem = arr.elem
    name = elementary_name(elem) or "ANY"
    dims = kind[len("AssertArray")] if kind[len("AssertArray")] in "23" else ""
    atype = f"Array{dims}D_{name}" if dims else f"Array_{name}"
    be, ba = _bounds(te, expecteds), _bounds(ta, actuals)
    se, sa = [hi - lo + 1 for lo, hi in be], [hi - lo + 1 for lo, hi in ba]
    key = (atype, _count(se), _count(sa))  # TcUnit keys an array assert by its sizes, not its values
    if (not dims and _count(se) != _count(sa)) or (dims and se != sa):
        exp, act = (_size(be, se), _size(ba, sa)) if dims else (f"SIZE = {_count(se)}", f"SIZE = {_count(sa)}")
        return Outcome(False, atype, exp, act, message + SIZES_DIFFER, key)
    fe, fa = _flat(expecteds, len(be)), _flat(actuals, len(ba))
    shape = se if dims else [_count(se)]
    for at, (x, y) in zip(product(*(range(n) for n in shape)), zip(fe, fa)):
        if _differs(name, x, y, delta):
            ie = [lo + i for (lo, _hi), i in zip(be, at)] if dims else [be[0][0] + at[0]]
            ia = [lo + i for (lo, _hi), i in zip(ba, at)] if dims else [ba[0][0] + at[0]]
            exp = f"ARRAY[{','.join(map(str, ie))}] = {text(elem, x)}"
            act = f"ARRAY[{','.join(map(str, ia))}] = {text(elem, y)}"
            return Outcome(False, atype, exp, act, message, key)
    return Outcome(True, atype, "", "", message, key)


def _differs(name: str, x, y, delta: float) -> bool:
    if name in ("REAL", "LREAL"):
        return abs(_real(name, x - y)) > delta
    return x != y


def _bounds(ty, value) -> list:
    if isinstance(value, VarArray):
        return list(value.bounds)
    arr = T.resolve(ty)
    assert isinstance(arr, T.ArrayType)
    return list(arr.dims)


def _count(sizes_: list) -> int:
    n = 1
    for s in sizes_:
        n *= s
    return n


def _size(bounds: list, sizes_: list) -> str:
    ranges = ",".join(f"{lo}..{hi}" for lo, hi in bounds)
    return f"SIZE = [{ranges}] ({'x'.join(map(str, sizes_))})"


def _flat(value, dims: int) -> list:
    items = list(value.data if isinstance(value, VarArray) else value)
    for _ in range(dims - 1):
        items = [x for row in items for x in row]
    return items
