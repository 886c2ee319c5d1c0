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

This module is the library's one import path (``rtlib.f32``, ...); the
functions live in modules by concern:

  rt_numeric.py   REAL rounding, real functions, integer division and
                  rounding, shifts and rotations, BCD
  rt_wrap.py      store normalisation per type (wrap, wrapper)
  rt_strings.py   the IEC string functions
  rt_text.py      values as literal text: parse_*, real_to_string,
                  iec_literal
  rt_convert.py   <src>_TO_<dst> conversions, time/date units
  rt_timedate.py  time and date arithmetic
"""

from __future__ import annotations

from .rt_convert import convert, converts_char, from_ns, make_converter, to_ns
from .rt_numeric import (
    acos,
    asin,
    atan,
    atan2,
    bcd_to_int,
    cos,
    exp,
    expt,
    f32,
    idiv,
    imod,
    int_to_bcd,
    int_to_f32,
    ln,
    log,
    rdiv,
    rol,
    ror,
    round_half_away,
    shl,
    shr,
    sin,
    sqrt,
    tan,
    trunc,
)
from .rt_strings import CONCAT, DELETE, FIND, INSERT, LEFT, LEN, MID, REPLACE, RIGHT, cut_string, string_length, wcut
from .rt_text import iec_literal, parse_bool, parse_int, parse_real, parse_temporal, real_to_string
from .rt_timedate import (
    ADD_DT_TIME,
    ADD_LDT_LTIME,
    ADD_LTIME,
    ADD_LTOD_LTIME,
    ADD_TIME,
    ADD_TOD_TIME,
    CONCAT_DATE,
    CONCAT_DATE_LTOD,
    CONCAT_DATE_TOD,
    CONCAT_DT,
    CONCAT_LDATE,
    CONCAT_LDATE_LTOD,
    CONCAT_LDT,
    CONCAT_LTOD,
    CONCAT_TOD,
    DAY_OF_WEEK,
    DIV_LTIME,
    DIV_TIME,
    MUL_LTIME,
    MUL_TIME,
    SUB_DATE_DATE,
    SUB_DT_DT,
    SUB_DT_TIME,
    SUB_LDATE_LDATE,
    SUB_LDT_LDT,
    SUB_LDT_LTIME,
    SUB_LTIME,
    SUB_LTOD_LTIME,
    SUB_LTOD_LTOD,
    SUB_TIME,
    SUB_TOD_TIME,
    SUB_TOD_TOD,
)
from .rt_wrap import wrap, wrap_time, wrapper

__all__ = [
    "wcut",
    "cut_string",
    "string_length",
    "f32",
    "int_to_f32",
    "idiv",
    "imod",
    "rdiv",
    "expt",
    "round_half_away",
    "trunc",
    "wrap",
    "wrap_time",
    "wrapper",
    "convert",
    "converts_char",
    "make_converter",
    "real_to_string",
    "parse_int",
    "parse_real",
    "parse_bool",
    "parse_temporal",
    "iec_literal",
    "to_ns",
    "from_ns",
    "shl",
    "shr",
    "rol",
    "ror",
    "bcd_to_int",
    "int_to_bcd",
    "sqrt",
    "ln",
    "log",
    "exp",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "LEN",
    "LEFT",
    "RIGHT",
    "MID",
    "CONCAT",
    "INSERT",
    "DELETE",
    "REPLACE",
    "FIND",
    "ADD_TIME",
    "SUB_TIME",
    "MUL_TIME",
    "DIV_TIME",
    "ADD_LTIME",
    "SUB_LTIME",
    "MUL_LTIME",
    "DIV_LTIME",
    "ADD_TOD_TIME",
    "ADD_LTOD_LTIME",
    "ADD_DT_TIME",
    "ADD_LDT_LTIME",
    "SUB_DATE_DATE",
    "SUB_LDATE_LDATE",
    "SUB_TOD_TOD",
    "SUB_LTOD_LTOD",
    "SUB_DT_DT",
    "SUB_LDT_LDT",
    "SUB_TOD_TIME",
    "SUB_LTOD_LTIME",
    "SUB_DT_TIME",
    "SUB_LDT_LTIME",
    "CONCAT_DATE_TOD",
    "CONCAT_LDATE_LTOD",
    "CONCAT_DATE_LTOD",
    "CONCAT_DATE",
    "CONCAT_LDATE",
    "CONCAT_TOD",
    "CONCAT_LTOD",
    "CONCAT_DT",
    "CONCAT_LDT",
    "DAY_OF_WEEK",
]
