"""The IEC 61131-3 standard functions: the table the checker and the code
generator use.

Each entry names its parameters with a *typespec*:

  'INT', 'TIME_OF_DAY', 'STRING' ...  a concrete type ('STRING'/'WSTRING' match
                                      any length)
  'ANY_NUM', 'ANY_BIT' ...            any member of the generic family
                                      (types.GENERICS), independently per
                                      parameter
  'T:ANY_NUM'                         a type variable: every parameter written
                                      with the same variable T gets one common
                                      type; a result 'T' is that type

  'POINTER TO BYTE'                   any pointer (ADR(x) of a variable, array,
                                      structure or string): the impl gets a byte
                                      view of its target (st/rtlib/rt_bytes.py), as
                                      Tc2_System's MEMCPY reads memory

``extensible`` means the last parameter repeats (ADD(a, b, c), MUX(k, a, b,
c)). A ``typed`` impl is called as impl(rtypes, *args) with rtypes = (result
type, type of argument 1, ...); the others as impl(*args). A ``context``
impl gets the ExecContext first (impl(ctx, ...)): the engine's clock and
date, the task that runs it (a vendor library's F_GetSystemTime).

Integer results of the arithmetic functions are NOT wrapped here: the code
generator wraps on store, and CODESYS also computes intermediate results
wider than the operands (ABS(INT#-32768) returns 32768, stored as -32768).
Where the width is part of the meaning the impl wraps: conversions, TRUNC,
shifts and rotations, NOT on bit strings, BCD.

Choices where IEC and CODESYS are silent are documented at the functions in
runtime/st/rtlib/rtlib.py; the ones made here:
  MUX   K beyond the last input selects the last input (CODESYS: "If K is
        greater than the number of other inputs (n), then CODESYS passes on
        the last value (INn)"); a negative K selects IN0.
  GT GE EQ LE LT  extensible: GT(a, b, c) = a > b AND b > c (IEC Table 28).
  LIMIT = MIN(MAX(IN, MN), MX), so MN > MX gives MX (IEC definition).
  EXPT, SQRT, LN ... return IEEE results (NaN, +-inf), never a fault.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from softplc.runtime.st import types as T
from softplc.runtime.st.rtlib import rtlib


@dataclass(frozen=True)
class StdFunc:
    name: str  # upper case
    params: tuple  # ((param_name, typespec), ...)
    ret: str  # typespec of the result
    impl: Callable  # the Python implementation
    extensible: bool = False  # last param repeats (ADD, MUX inputs, MAX, CONCAT, AND...)
    typed: bool = False  # impl(rtypes, *args), rtypes = (result_type, arg1_type, ...)
    context: bool = False  # impl(ctx, ...): the ExecContext (runtime/program/context.py) first


STANDARD_FUNCTIONS: dict[str, StdFunc] = {}


def parse_typespec(spec: str) -> tuple:
    """'T:ANY_NUM' -> ('T', 'ANY_NUM'); 'INT' -> (None, 'INT')."""
    var, sep, rest = spec.partition(":")
    return (var, rest) if sep else (None, spec)


def _def(name: str, params, ret: str, impl: Callable, extensible: bool = False, typed: bool = False) -> None:
    STANDARD_FUNCTIONS[name] = StdFunc(name, tuple(params), ret, impl, extensible, typed)


def _elem(t: T.Type) -> T.ElementaryType | None:
    return T.base_elementary(t) if t is not None else None


# ---------------------------------------------------------------- type conversion
# IEC 61131-3 3rd ed. Table 22-27: <T>_TO_<U> for every pair of elementary
# types, and the overloaded TO_<U>.

_STRING = T.StringType(80)
_WSTRING = T.StringType(80, wide=True)

# (spelling, type, typespec); TOD/DT/LTOD/LDT have a short and a long name
_CONV_TYPES = [(n, t, t.name) for n, t in T.ELEMENTARY.items()] + [
    ("STRING", _STRING, "STRING"),
    ("WSTRING", _WSTRING, "WSTRING"),
]


_CHARS = ("CHAR", "WCHAR")


def _build_conversions() -> None:
    converters: dict = {}
    for sn, st, sspec in _CONV_TYPES:
        for dn, dt, dspec in _CONV_TYPES:
            if st is dt:
                continue
            if (st.name in _CHARS or dt.name in _CHARS) and not rtlib.converts_char(st, dt):
                continue  # CHAR converts with integers, bit strings and strings only
            f = converters.get((st, dt))
            if f is None:
                f = converters[(st, dt)] = rtlib.make_converter(st, dt)
            _def(f"{sn}_TO_{dn}", (("IN", sspec),), dspec, f)
    for dn, dt, dspec in _CONV_TYPES:
        if dn not in _CHARS:  # TO_CHAR: from few types only; CHAR_TO_ / _TO_CHAR name them
            _def(f"TO_{dn}", (("IN", "ANY_ELEMENTARY"),), dspec, _generic_to(dt), typed=True)


def _generic_to(dst: T.Type) -> Callable:
    convert = rtlib.convert

    def to(rtypes, v):
        return convert(v, rtypes[1], dst)

    return to


_build_conversions()


# TRUNC: CODESYS/IEC 2nd ed. TRUNC -> DINT; TRUNC_<INT> and 3rd ed. <REAL>_TRUNC_<INT>.
def _trunc_to(t: T.ElementaryType) -> Callable:
    w = rtlib.wrapper(t)
    trunc = rtlib.trunc

    def trunc_to(x):
        return w(trunc(x))

    return trunc_to


_def("TRUNC", (("IN", "ANY_REAL"),), "DINT", _trunc_to(T.DINT))
for _i in T.INTEGERS:
    _def(f"TRUNC_{_i.name}", (("IN", "ANY_REAL"),), _i.name, _trunc_to(_i))
    for _r in T.REALS:
        _def(f"{_r.name}_TRUNC_{_i.name}", (("IN", _r.name),), _i.name, _trunc_to(_i))


# BCD (IEC 3rd ed. Table 22: WORD_BCD_TO_UINT, UINT_TO_BCD_WORD ...;
# CODESYS Util: BCD_TO_INT(BYTE) -> INT, INT_TO_BCD(INT) -> BYTE).
# Invalid BCD decodes to -1, an unencodable value encodes to all ones.
_BCD_BITS = (T.BYTE, T.WORD, T.DWORD, T.LWORD)


def _bcd_decoder(width: int, dst: T.ElementaryType) -> Callable:
    w = rtlib.wrapper(dst)
    dec = rtlib.bcd_to_int

    def bcd_to(x):
        return w(dec(x, width))

    return bcd_to


def _bcd_encoder(width: int) -> Callable:
    enc = rtlib.int_to_bcd

    def to_bcd(v):
        return enc(v, width)

    return to_bcd


def _bcd_decoder_typed(dst: T.ElementaryType) -> Callable:
    w = rtlib.wrapper(dst)
    dec = rtlib.bcd_to_int

    def bcd_to(rtypes, x):
        return w(dec(x, _elem(rtypes[1]).bits))

    return bcd_to


for _b in _BCD_BITS:
    for _i in T.INTEGERS:
        _def(f"{_b.name}_BCD_TO_{_i.name}", (("IN", _b.name),), _i.name, _bcd_decoder(_b.bits, _i))
        _def(f"{_i.name}_TO_BCD_{_b.name}", (("IN", _i.name),), _b.name, _bcd_encoder(_b.bits))
    _def(f"TO_BCD_{_b.name}", (("IN", "ANY_INT"),), _b.name, _bcd_encoder(_b.bits))
for _i in T.INTEGERS:
    _def(f"BCD_TO_{_i.name}", (("IN", "ANY_BIT"),), _i.name, _bcd_decoder_typed(_i), typed=True)
_def("INT_TO_BCD", (("IN", "INT"),), "BYTE", _bcd_encoder(8))  # CODESYS Util


def _is_valid_bcd(rtypes, x):
    """IS_VALID_BCD (IEC 3rd ed., beside the BCD conversions): every 4-bit
    digit of IN, within its type's width, is 0..9 (16#1234 yes, 16#12A4 no);
    what the BCD_TO_ conversions decode without the -1 of invalid BCD."""
    return rtlib.bcd_to_int(x, _elem(rtypes[1]).bits) >= 0


_def("IS_VALID_BCD", (("IN", "ANY_BIT"),), "BOOL", _is_valid_bcd, typed=True)


# ---------------------------------------------------------------- numeric (Table 23)

for _name, _fn in (
    ("SQRT", rtlib.sqrt),
    ("LN", rtlib.ln),
    ("LOG", rtlib.log),
    ("EXP", rtlib.exp),
    ("SIN", rtlib.sin),
    ("COS", rtlib.cos),
    ("TAN", rtlib.tan),
    ("ASIN", rtlib.asin),
    ("ACOS", rtlib.acos),
    ("ATAN", rtlib.atan),
):
    _def(_name, (("IN", "T:ANY_REAL"),), "T", _fn)
_def("ABS", (("IN", "T:ANY_NUM"),), "T", abs)  # ABS(INT#-32768) = 32768, wrapped on store
_def("EXPT", (("IN1", "T:ANY_REAL"), ("IN2", "ANY_NUM")), "T", rtlib.expt)
_def("ATAN2", (("Y", "T:ANY_REAL"), ("X", "T:ANY_REAL")), "T", rtlib.atan2)


# ---------------------------------------------------------------- arithmetic (Table 24)


def _is_real(t: T.Type, a, b) -> bool:
    e = _elem(t)
    if e is None:  # no type information: decide by the values
        return isinstance(a, float) or isinstance(b, float)
    return e.category == T.REALCAT


def _add(rtypes, a, b, *more):
    r = a + b
    for x in more:  # left to right, as a + b + c
        r += x
    return r


def _mul(rtypes, a, b, *more):
    r = a * b
    for x in more:
        r *= x
    return r


def _sub(rtypes, a, b):
    return a - b


def _div(rtypes, a, b):
    """Integer types truncate toward zero (ZeroDivisionError on 0), reals
    divide per IEEE."""
    if _is_real(rtypes[0], a, b):
        return rtlib.rdiv(a, b)
    return rtlib.idiv(a, b)


def _mod(rtypes, a, b):
    return rtlib.imod(a, b)


def _move(rtypes, x):
    return x


_def("ADD", (("IN1", "T:ANY_MAGNITUDE"), ("IN2", "T:ANY_MAGNITUDE")), "T", _add, extensible=True, typed=True)
_def("MUL", (("IN1", "T:ANY_NUM"), ("IN2", "T:ANY_NUM")), "T", _mul, extensible=True, typed=True)
_def("SUB", (("IN1", "T:ANY_MAGNITUDE"), ("IN2", "T:ANY_MAGNITUDE")), "T", _sub, typed=True)
_def("DIV", (("IN1", "T:ANY_NUM"), ("IN2", "T:ANY_NUM")), "T", _div, typed=True)
_def("MOD", (("IN1", "T:ANY_INT"), ("IN2", "T:ANY_INT")), "T", _mod, typed=True)
_def("MOVE", (("IN", "T:ANY"),), "T", _move, typed=True)


# ---------------------------------------------------------------- bit strings (Table 25, 26)


def _shift_fn(op: Callable) -> Callable:
    """Shift/rotate within the width of IN's type; the result has IN's type
    (a signed operand is shifted as its bit pattern and re-signed)."""

    def shift(rtypes, x, n):
        t = _elem(rtypes[1])
        r = op(t.bits, x, n)
        if t.category == T.BOOLCAT:
            return bool(r)
        if t.lo < 0:
            half = 1 << (t.bits - 1)
            return ((r + half) & ((1 << t.bits) - 1)) - half
        return r

    return shift


for _name, _op in (("SHL", rtlib.shl), ("SHR", rtlib.shr), ("ROL", rtlib.rol), ("ROR", rtlib.ror)):
    _def(_name, (("IN", "T:ANY_BIT"), ("N", "ANY_INT")), "T", _shift_fn(_op), typed=True)


def _and(a, b, *more):
    r = a & b
    for x in more:
        r &= x
    return r


def _or(a, b, *more):
    r = a | b
    for x in more:
        r |= x
    return r


def _xor(a, b, *more):
    r = a ^ b
    for x in more:
        r ^= x
    return r


def _not(rtypes, x):
    """Complement within IN's width: NOT BYTE#16#0F = 16#F0."""
    t = _elem(rtypes[1])
    if t.category == T.BOOLCAT:
        return not x
    if t.lo < 0:
        return ~x
    return x ^ t.hi


for _name, _fn in (("AND", _and), ("OR", _or), ("XOR", _xor)):
    _def(_name, (("IN1", "T:ANY_BIT"), ("IN2", "T:ANY_BIT")), "T", _fn, extensible=True)
_def("NOT", (("IN", "T:ANY_BIT"),), "T", _not, typed=True)


# ---------------------------------------------------------------- selection (Table 27)


def _sel(g, in0, in1):
    return in1 if g else in0


def _limit(mn, x, mx):
    if x < mn:
        x = mn
    if x > mx:
        x = mx
    return x


def _mux(k, *inputs):
    if k < 0:
        return inputs[0]
    if k >= len(inputs):
        return inputs[-1]
    return inputs[k]


_def("SEL", (("G", "BOOL"), ("IN0", "T:ANY"), ("IN1", "T:ANY")), "T", _sel)
_def("MAX", (("IN1", "T:ANY_ELEMENTARY"), ("IN2", "T:ANY_ELEMENTARY")), "T", max, extensible=True)
_def("MIN", (("IN1", "T:ANY_ELEMENTARY"), ("IN2", "T:ANY_ELEMENTARY")), "T", min, extensible=True)
_def("LIMIT", (("MN", "T:ANY_ELEMENTARY"), ("IN", "T:ANY_ELEMENTARY"), ("MX", "T:ANY_ELEMENTARY")), "T", _limit)
_def("MUX", (("K", "ANY_INT"), ("IN0", "T:ANY"), ("IN1", "T:ANY")), "T", _mux, extensible=True)


# ---------------------------------------------------------------- comparison (Table 28)


def _chain(op: Callable) -> Callable:
    def compare(a, b, *more):
        if not op(a, b):
            return False
        for x in more:
            if not op(b, x):
                return False
            b = x
        return True

    return compare


def _ne(a, b):
    return a != b


_CMP = (
    ("GT", lambda a, b: a > b),
    ("GE", lambda a, b: a >= b),
    ("EQ", lambda a, b: a == b),
    ("LE", lambda a, b: a <= b),
    ("LT", lambda a, b: a < b),
)
for _name, _cmp in _CMP:
    _def(_name, (("IN1", "T:ANY_ELEMENTARY"), ("IN2", "T:ANY_ELEMENTARY")), "BOOL", _chain(_cmp), extensible=True)
_def("NE", (("IN1", "T:ANY_ELEMENTARY"), ("IN2", "T:ANY_ELEMENTARY")), "BOOL", _ne)


# ---------------------------------------------------------------- strings (Table 29)
# IEC parameter names; CODESYS's W-prefixed WSTRING variants as well.


def _string_functions(prefix: str, s: str, r: str) -> None:
    """s: the typespec of the string parameters, r: of a string result."""
    _def(prefix + "LEN", (("IN", s),), "INT", rtlib.LEN)
    _def(prefix + "LEFT", (("IN", s), ("L", "ANY_INT")), r, rtlib.LEFT)
    _def(prefix + "RIGHT", (("IN", s), ("L", "ANY_INT")), r, rtlib.RIGHT)
    _def(prefix + "MID", (("IN", s), ("L", "ANY_INT"), ("P", "ANY_INT")), r, rtlib.MID)
    _def(prefix + "CONCAT", (("IN1", s), ("IN2", s)), r, rtlib.CONCAT, extensible=True)
    _def(prefix + "INSERT", (("IN1", s), ("IN2", s), ("P", "ANY_INT")), r, rtlib.INSERT)
    _def(prefix + "DELETE", (("IN", s), ("L", "ANY_INT"), ("P", "ANY_INT")), r, rtlib.DELETE)
    _def(prefix + "REPLACE", (("IN1", s), ("IN2", s), ("L", "ANY_INT"), ("P", "ANY_INT")), r, rtlib.REPLACE)
    _def(prefix + "FIND", (("IN1", s), ("IN2", s)), "INT", rtlib.FIND)


_string_functions("", "T:ANY_STRING", "T")
_string_functions("W", "WSTRING", "WSTRING")


# ---------------------------------------------------------------- time and date (Table 30, 35-37)

_TIME_FUNCS = (
    ("ADD_TIME", ("TIME", "TIME"), "TIME"),
    ("SUB_TIME", ("TIME", "TIME"), "TIME"),
    ("ADD_LTIME", ("LTIME", "LTIME"), "LTIME"),
    ("SUB_LTIME", ("LTIME", "LTIME"), "LTIME"),
    ("MUL_TIME", ("TIME", "ANY_NUM"), "TIME"),
    ("DIV_TIME", ("TIME", "ANY_NUM"), "TIME"),
    ("MUL_LTIME", ("LTIME", "ANY_NUM"), "LTIME"),
    ("DIV_LTIME", ("LTIME", "ANY_NUM"), "LTIME"),
    ("ADD_TOD_TIME", ("TIME_OF_DAY", "TIME"), "TIME_OF_DAY"),
    ("SUB_TOD_TIME", ("TIME_OF_DAY", "TIME"), "TIME_OF_DAY"),
    ("ADD_LTOD_LTIME", ("LTIME_OF_DAY", "LTIME"), "LTIME_OF_DAY"),
    ("SUB_LTOD_LTIME", ("LTIME_OF_DAY", "LTIME"), "LTIME_OF_DAY"),
    ("ADD_DT_TIME", ("DATE_AND_TIME", "TIME"), "DATE_AND_TIME"),
    ("SUB_DT_TIME", ("DATE_AND_TIME", "TIME"), "DATE_AND_TIME"),
    ("ADD_LDT_LTIME", ("LDATE_AND_TIME", "LTIME"), "LDATE_AND_TIME"),
    ("SUB_LDT_LTIME", ("LDATE_AND_TIME", "LTIME"), "LDATE_AND_TIME"),
    ("SUB_DATE_DATE", ("DATE", "DATE"), "TIME"),
    ("SUB_LDATE_LDATE", ("LDATE", "LDATE"), "LTIME"),
    ("SUB_TOD_TOD", ("TIME_OF_DAY", "TIME_OF_DAY"), "TIME"),
    ("SUB_LTOD_LTOD", ("LTIME_OF_DAY", "LTIME_OF_DAY"), "LTIME"),
    ("SUB_DT_DT", ("DATE_AND_TIME", "DATE_AND_TIME"), "TIME"),
    ("SUB_LDT_LDT", ("LDATE_AND_TIME", "LDATE_AND_TIME"), "LTIME"),
    ("CONCAT_DATE_TOD", ("DATE", "TIME_OF_DAY"), "DATE_AND_TIME"),
    ("CONCAT_LDATE_LTOD", ("LDATE", "LTIME_OF_DAY"), "LDATE_AND_TIME"),
    ("CONCAT_DATE_LTOD", ("DATE", "LTIME_OF_DAY"), "LDATE_AND_TIME"),  # ed.3 Table 37
)
for _name, (_in1, _in2), _ret in _TIME_FUNCS:
    _def(_name, (("IN1", _in1), ("IN2", _in2)), _ret, getattr(rtlib, _name))
# IEC 61131-3 ed.2 Table 30 spelled these MULTIME and DIVTIME (ed.3 renamed
# them); MatIEC keeps both names and OSCAT's port calls MULTIME.
_def("MULTIME", (("IN1", "TIME"), ("IN2", "ANY_NUM")), "TIME", rtlib.MUL_TIME)
_def("DIVTIME", (("IN1", "TIME"), ("IN2", "ANY_NUM")), "TIME", rtlib.DIV_TIME)

_YMD = (("YEAR", "ANY_INT"), ("MONTH", "ANY_INT"), ("DAY", "ANY_INT"))
_HMSM = (("HOUR", "ANY_INT"), ("MINUTE", "ANY_INT"), ("SECOND", "ANY_INT"), ("MILLISECOND", "ANY_INT"))
_def("CONCAT_DATE", _YMD, "DATE", rtlib.CONCAT_DATE)
_def("CONCAT_TOD", _HMSM, "TIME_OF_DAY", rtlib.CONCAT_TOD)
_def("CONCAT_LDATE", _YMD, "LDATE", rtlib.CONCAT_LDATE)
_def("CONCAT_LTOD", _HMSM, "LTIME_OF_DAY", rtlib.CONCAT_LTOD)
_def("CONCAT_DT", _YMD + _HMSM, "DATE_AND_TIME", rtlib.CONCAT_DT)
_def("CONCAT_LDT", _YMD + _HMSM, "LDATE_AND_TIME", rtlib.CONCAT_LDT)
_def("DAY_OF_WEEK", (("IN", "DATE"),), "INT", rtlib.DAY_OF_WEEK)
