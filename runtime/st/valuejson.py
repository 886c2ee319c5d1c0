"""ST values as JSON-ready Python data (for ``softplc exec`` and tools).

The encoding, per type (see types.py for how values are held in Python):

  BOOL                         true / false
  integers, bit strings        JSON integers (exact; 64-bit values too)
  subranges                    integers
  REAL, LREAL                  numbers; REAL is written with the fewest digits
                               that still round-trip through binary32 (0.1, not
                               0.10000000149011612); non-finite values, which
                               JSON cannot hold, are the strings "inf", "-inf"
                               and "nan"
  TIME, LTIME, DATE, TOD, DT,  IEC literal strings ("T#1h2m3s4ms", "D#2024-01-02",
  and their L- variants        ...), as rtlib.iec_literal writes them
  STRING, WSTRING              strings
  enumerations                 the enumerator's name as declared; a value that
                               names no enumerator (possible after a cast) stays
                               an integer
  ARRAY                        lists, nested one level per dimension
  STRUCT, FUNCTION_BLOCK       objects: variable name as declared -> value
  REF_TO, POINTER TO           null when NULL, else the string "<ref>" (a
                               reference has no value of its own to show)
  an INTERFACE                 null when unassigned, else "<ref>" too: it
                               designates an instance, which has its own entry

An instance dump (``encode_instance``) lists a POU's own state: VAR,
VAR_INPUT, VAR_OUTPUT, VAR_GLOBAL and struct fields. VAR_IN_OUT and
VAR_EXTERNAL are left out because they are references to variables that live
elsewhere (they would show another object's data twice, or not at all once
the call is over); VAR_TEMP is left out because it holds nothing between
calls.
"""

from __future__ import annotations

import json
import math
import struct
from typing import Any

from . import types as T
from .rtlib.rtlib import iec_literal

# Sections whose variables are not part of an instance's own state.
SKIPPED_SECTIONS = frozenset({"VAR_IN_OUT", "VAR_EXTERNAL", "VAR_TEMP"})


def encode_value(t: T.Type, v: Any) -> Any:
    """One value of ST type ``t`` as JSON-ready data (see the module docstring)."""
    t = T.resolve(t)
    if isinstance(t, T.ElementaryType):
        return _encode_elementary(t, v)
    if isinstance(t, T.SubrangeType):
        return int(v)
    if isinstance(t, T.EnumType):
        name = t.name_of(v)
        return name if name is not None else int(v)
    if isinstance(t, T.StringType):
        return str(v)
    if isinstance(t, T.ArrayType):
        return _encode_array(len(t.dims), t.elem, v)
    if isinstance(t, (T.StructType, T.FBType)):
        return encode_instance(v)
    if isinstance(t, (T.RefType, T.InterfaceType)):
        return None if v is None else "<ref>"
    # Anything else (ADR# addresses, NULL) has no better form than its text.
    return None if v is None else str(v)


def encode_instance(obj: Any, skip: frozenset = frozenset()) -> dict:
    """A PROGRAM, FUNCTION_BLOCK instance or STRUCT value as a dict of its
    variables (name as declared -> encoded value), in declaration order;
    variables named in skip and those hidden by {attribute 'hide'}
    (``_HIDDEN_``) are left out."""
    out: dict[str, Any] = {}
    skip = skip | getattr(type(obj), "_HIDDEN_", frozenset())
    for st_name, pyname, vtype, section in type(obj)._VARS_:
        if section in SKIPPED_SECTIONS or st_name in skip:
            continue
        out[st_name] = encode_value(vtype, getattr(obj, pyname))
    return out


def _encode_elementary(t: T.ElementaryType, v: Any) -> Any:
    if t.is_bool:
        return bool(v)
    if t.is_intlike:
        return int(v)
    if t.is_real:
        return _encode_real(float(v), single=(t.bits == 32))
    if t.is_time:
        return iec_literal(t, v)
    return v


def _encode_real(x: float, single: bool) -> Any:
    if math.isnan(x):
        return "nan"
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    if single:
        return _shortest_binary32(x)
    return x


def _shortest_binary32(x: float) -> float:
    """The float with the fewest significant digits that rounds to the same
    binary32 value as x: REAL 0.1 is stored as 0.10000000149011612 in a Python
    float, but a PLC engineer expects to read 0.1."""
    try:
        want = struct.pack("<f", x)
    except OverflowError:  # not a binary32 value after all; keep it exact
        return x
    for digits in range(1, 10):  # 9 digits always round-trip a binary32
        y = float(f"{x:.{digits}g}")
        try:
            if struct.pack("<f", y) == want:
                return y
        except OverflowError:  # rounded up past the largest REAL (4e38)
            continue
    return x


def _encode_array(ndims: int, elem: T.Type, v: list) -> list:
    if ndims <= 1:
        return [encode_value(elem, item) for item in v]
    return [_encode_array(ndims - 1, elem, row) for row in v]


def json_text(data: Any, **options: Any) -> str:
    """json.dumps(data, ensure_ascii=False, **options) when that is UTF-8
    text, else (a string holding a lone surrogate, which no UTF-8 writer
    takes) the same JSON with \\uXXXX escapes: valid JSON all the same."""
    text = json.dumps(data, ensure_ascii=False, **options)
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return json.dumps(data, **options)
    return text
