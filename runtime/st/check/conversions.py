"""Implicit conversions: which value may go into which type, and how.

The one rule (IEC 61131-3 Fig. 11, softened by the profile), read by both
sides of the compiler:

* the checker asks ``check_implicit`` whether a value may go into a type
  without a conversion function: silently, with W121 or as error E021 (a
  narrowing, by the profile), or not at all (E020, E022);
* the code generator asks ``store_step`` what a store does to the value's
  representation (nothing, wrap, round to binary32, truncate, convert), and
  writes a folded constant as ``const_as`` converts it, as the checker does
  for initial values.

Operands of a binary operation meet in ``common_type``; a generic parameter
takes an argument as ``generic_fit`` says.
"""

from __future__ import annotations

from typing import Any

from .. import ast as A
from .. import types as T
from ..diagnostics import DiagnosticBag
from ..profile import Profile, names_where
from ..rtlib import rt_bytes, rtlib
from .oop import extends_fb, fb_hint, interface_accepts

# ---------------------------------------------------------------- widening
# IEC 61131-3 (3rd ed.) Figure 11: implicit conversions that lose nothing.
_WIDEN: dict[str, tuple] = {
    "SINT": ("INT", "DINT", "LINT", "REAL", "LREAL"),
    "INT": ("DINT", "LINT", "REAL", "LREAL"),
    "DINT": ("LINT", "LREAL"),
    "LINT": (),
    "USINT": ("UINT", "UDINT", "ULINT", "INT", "DINT", "LINT", "REAL", "LREAL"),
    "UINT": ("UDINT", "ULINT", "DINT", "LINT", "REAL", "LREAL"),
    "UDINT": ("ULINT", "LINT", "LREAL"),
    "ULINT": (),
    "BOOL": ("BYTE", "WORD", "DWORD", "LWORD"),
    "BYTE": ("WORD", "DWORD", "LWORD"),
    "WORD": ("DWORD", "LWORD"),
    "DWORD": ("LWORD",),
    "LWORD": (),
    "REAL": ("LREAL",),
    "LREAL": (),
    "TIME": ("LTIME",),
    "LTIME": (),
    "DATE": ("LDATE",),
    "TIME_OF_DAY": ("LTIME_OF_DAY",),
    "DATE_AND_TIME": ("LDATE_AND_TIME",),
    "LDATE": (),
    "LTIME_OF_DAY": (),
    "LDATE_AND_TIME": (),
}


def widens_to(src: T.ElementaryType, dst: T.ElementaryType) -> bool:
    """True when src converts implicitly and losslessly to dst (IEC Fig. 11)."""
    return src is dst or dst.name in _WIDEN.get(src.name, ())


def smallest_common(a: T.ElementaryType, b: T.ElementaryType) -> T.ElementaryType | None:
    """The smallest elementary type both widen to (for a binary operation),
    or None if there is none."""
    if widens_to(a, b):
        return b
    if widens_to(b, a):
        return a
    for cand in (T.INT, T.DINT, T.LINT, T.UINT, T.UDINT, T.ULINT, T.WORD, T.DWORD, T.LWORD, T.REAL, T.LREAL, T.LTIME):
        if widens_to(a, cand) and widens_to(b, cand):
            return cand
    return None


_BITS_AS_UNSIGNED = {T.BYTE: T.USINT, T.WORD: T.UINT, T.DWORD: T.UDINT, T.LWORD: T.ULINT}


def common_type(a: T.ElementaryType, b: T.ElementaryType, profile: Profile) -> T.ElementaryType | None:
    """The type a binary operation on a and b computes in (None: there is
    none). Where the profile mixes integers and bit strings (CODESYS), a bit
    string meets an integer as the unsigned integer of its size."""
    if profile.int_bits_mix:
        if a.is_bits and b.is_bits:
            return a if a.bits >= b.bits else b
        if a.is_bits and b.is_integer:
            a = _BITS_AS_UNSIGNED.get(a, a)
        if b.is_bits and a.is_integer:
            b = _BITS_AS_UNSIGNED.get(b, b)
    return smallest_common(a, b)


def generic_fit(t: T.Type, generic: str, profile: Profile) -> T.Type:
    """The type an argument of type t takes for a generic parameter:
    itself when it is a member; an integer widens into ANY_REAL (SQRT(i),
    as CODESYS accepts); a bit string counts as ANY_INT where the profile
    mixes them (SHL(w, BYTE#2))."""
    if T.is_generic_member(t, generic):
        return t
    te = T.base_elementary(t)
    g = generic.upper()
    if te is not None and te.is_intlike and g == "ANY_REAL":
        return T.REAL if widens_to(te, T.REAL) else T.LREAL
    if te is not None and te.is_bits and g in ("ANY_INT", "ANY_UNSIGNED") and profile.int_bits_mix:
        return {8: T.USINT, 16: T.UINT, 32: T.UDINT, 64: T.ULINT}[te.bits]
    if te is not None and te.is_intlike and not te.is_bits and g == "ANY_BIT" and profile.int_bits_mix:
        # SHR(size, 2) with size : UINT (OSCAT): CODESYS shifts the integer's bits
        return {8: T.BYTE, 16: T.WORD, 32: T.DWORD, 64: T.LWORD}[te.bits]
    return t


# ---------------------------------------------------------------- the checker's question


def same_type(a: T.Type, b: T.Type) -> bool:
    """The same type for assignment: aliases resolved, strings of one width
    at any length, arrays of the same element type and dimension sizes."""
    a, b = T.resolve(a), T.resolve(b)
    if a is b:
        return True
    if isinstance(a, T.StringType) and isinstance(b, T.StringType):
        return a.wide == b.wide
    if isinstance(a, T.ArrayType) and isinstance(b, T.ArrayType):
        if len(a.dims) != len(b.dims) or not same_type(a.elem, b.elem):
            return False
        return all(x is None or y is None or (x[1] - x[0]) == (y[1] - y[0]) for x, y in zip(a.dims, b.dims))
    if isinstance(a, T.RefType) and isinstance(b, T.RefType):
        return same_type(a.target, b.target)
    if isinstance(a, T.SubrangeType) and isinstance(b, T.SubrangeType):
        return a.base is b.base and a.lo == b.lo and a.hi == b.hi
    return False


def is_flexible(e: A.Expr) -> bool:
    """An untyped numeric literal (or a constant expression of them) that
    takes the type its context needs. A chain a + b + c ... is walked down
    its left side in a loop, not a call per operator (docs/reference/language.md "Limits")."""
    spine: list[A.Binary] = []
    while isinstance(e, A.Binary) and e.flexible is None:
        spine.append(e)
        e = e.left
    if isinstance(e, A.Binary):
        result = bool(e.flexible)
    elif isinstance(e, A.Literal):
        result = e.type_name is None and e.kind in ("int", "real", "bool")
    elif isinstance(e, A.Unary):
        result = e.op in ("-", "+") and is_flexible(e.operand)
    else:
        result = False
    for b in reversed(spine):
        result = result and is_flexible(b.right)
        b.flexible = result
    return result


def is_0_or_1(e: A.Expr) -> bool:
    """The literal 0 or 1, a lone digit (not 1-0, INT#1 or 16#1): what the
    profile may let stand for FALSE and TRUE."""
    return (
        isinstance(e, A.Literal)
        and e.kind == "int"
        and e.type_name is None
        and e.value in (0, 1)
        and (e.pos.line, e.pos.end_line, e.pos.end_col - e.pos.col) == (e.pos.line, e.pos.line, 1)
    )


def const_fits(value: Any, se: T.ElementaryType, de: T.ElementaryType, e: A.Expr) -> bool:
    """Whether the folded value of e, of type se, goes into de as it is: an
    untyped literal adapts to any type that holds it."""
    if not is_flexible(e):
        return False
    if isinstance(value, bool) or se.is_bool:
        return de.is_bool
    if isinstance(value, int) and se.is_intlike:
        # an integer that does not fit was reported (E022) by check_implicit
        return T.int_fits(de, value) if de.is_intlike else de.is_real
    if isinstance(value, float) and se.is_real:
        return de.is_real
    return False


def enum_example(t: T.Type) -> str:
    """An enumerator of t as written with its type (for a hint)."""
    t = T.resolve(t)
    if isinstance(t, T.EnumType) and t.values:
        k = next(iter(t.values))
        return f"{t.name}#{t.spelled[k]}"
    return ""


def _literal_out_of_range(value: int, de: T.ElementaryType, e: A.Expr, profile: Profile, diags: DiagnosticBag) -> bool:
    """An untyped integer constant that does not fit de: E022, or where the
    profile converts literals (CODESYS, TwinCAT: the literal is typed as the
    smallest type holding it and converted like a variable, warning C0195
    for UINT := -1) W122 and the value wrapped to de (const_as)."""
    msg = f"{value} does not fit {de.name} ({de.lo}..{de.hi})"
    fits_an_integer = T.int_fits(T.LINT, value) or T.int_fits(T.ULINT, value)
    if profile.literal_range == "warning" and fits_an_integer:
        wrapped = rtlib.wrap(de, value)
        diags.warning(
            "W122",
            f"{msg}: converted implicitly to {wrapped}",
            e.pos,
            f"write the value {de.name} holds ({wrapped}), or use a larger type",
        )
        return True
    hint = "use a larger type, or write the value the type holds"
    if fits_an_integer:
        hint += f" (the {names_where(lambda p: p.literal_range == 'warning')} profiles convert it with a warning)"
    diags.error("E022", msg, e.pos, hint)
    return False


def check_implicit(src: T.Type, dst: T.Type, e: A.Expr, what: str, profile: Profile, diags: DiagnosticBag) -> bool:
    """Report unless a value of type src (the expression e) may be stored
    into dst implicitly (IEC 61131-3 Fig. 11, softened by the profile).
    False when it is an error."""
    s, d = T.resolve(src), T.resolve(dst)
    de0 = T.base_elementary(d)
    if (
        isinstance(e.const, int)
        and not isinstance(e.const, bool)
        and de0 is not None
        and de0.is_intlike
        and is_flexible(e)
        and not T.int_fits(de0, e.const)
    ):
        if isinstance(d, T.ElementaryType):
            return _literal_out_of_range(e.const, de0, e, profile, diags)
        diags.error("E022", f"{e.const} does not fit {de0.name} ({de0.lo}..{de0.hi})", e.pos, "use a larger type")
        return False
    if same_type(s, d):
        return True
    if isinstance(d, T.InterfaceType):  # an instance implementing it, NULL or 0 (CODESYS)
        if isinstance(s, T.NullType) or e.const == 0 or interface_accepts(s, d):
            return True
        diags.error(
            "E020",
            f"cannot use {src} as {dst} in {what}",
            e.pos,
            f"only instances of function blocks that IMPLEMENT {d.name} (or interfaces that extend it) fit",
        )
        return False
    if isinstance(d, T.RefType):
        if isinstance(s, T.NullType) or (
            isinstance(s, T.RefType)
            and (same_type(s.target, d.target) or decays_to(s, d) or extends_fb(s.target, d.target))
        ):
            return True
        if isinstance(s, T.RefType) and d.pointer and not s.reference and rt_bytes.view_unit(d.target) is not None:
            if rt_bytes.layout_of(s.target) is not None:
                return True  # a byte view (st/rtlib/rt_bytes.py): CODESYS type punning
            diags.error(
                "E161",
                f"a {d} over {s.target} (its bytes) is not supported",
                e.pos,
                "byte views reach elementary values, strings, and arrays and structures of them; "
                "not function block instances, pointers or ARRAY[*]",
            )
            return False
        if e.const == 0 and isinstance(s, T.ElementaryType) and s.is_intlike:
            return True
        diags.error(
            "E020",
            f"cannot use {src} as {dst} in {what}",
            e.pos,
            (fb_hint(s.target, d.target) if isinstance(s, T.RefType) else None)
            or "take a reference with REF(variable) or ADR(variable)",
        )
        return False
    if isinstance(d, T.EnumType) or isinstance(s, T.EnumType):
        if (
            isinstance(d, T.ElementaryType)
            and isinstance(s, T.EnumType)
            and profile.int_bits_mix
            and d.is_intlike
            and widens_to(s.base, d)
        ):
            return True
        from_int = isinstance(s, T.ElementaryType) and s.is_intlike
        if isinstance(d, T.EnumType) and from_int and profile.loose_enums and not d.strict:
            # CODESYS, TwinCAT: an enumeration without {attribute 'strict'} takes an integer
            diags.warning(
                "W151",
                f"{src} into the enumeration {dst} in {what}: the value may be none of its enumerators",
                e.pos,
                f"use an enumerator, e.g. {enum_example(d)}; "
                "{attribute 'strict'} before the TYPE makes this an error",
            )
            return True
        hint = f"use an enumerator of {dst}, e.g. {enum_example(d)}"
        if from_int and profile.loose_enums:
            hint = f"{dst} is {{attribute 'strict'}}: " + hint
        diags.error(
            "E020",
            f"cannot use {src} as {dst} in {what}",
            e.pos,
            hint if isinstance(d, T.EnumType) else "enumerations convert only explicitly",
        )
        return False
    if isinstance(d, T.StringType):
        if isinstance(s, T.StringType) and s.wide == d.wide:
            return True
        diags.error(
            "E020",
            f"cannot use {src} as {dst} in {what}",
            e.pos,
            "convert explicitly, e.g. INT_TO_STRING(x)"
            if not isinstance(s, T.StringType)
            else "use WSTRING_TO_STRING / STRING_TO_WSTRING",
        )
        return False
    se, de = T.base_elementary(s), T.base_elementary(d)
    if se is None or de is None:
        diags.error("E020", f"cannot use {src} as {dst} in {what}", e.pos, "the types must be the same")
        return False
    if isinstance(d, T.SubrangeType):
        if isinstance(e.const, int) and not (d.lo <= e.const <= d.hi):
            diags.error("E022", f"{e.const} is outside {d} in {what}", e.pos)
            return False
        return check_implicit(src, d.base, e, what, profile, diags)
    if de.is_bool and is_0_or_1(e):
        if profile.bool_from_0_1:
            return True  # FALSE / TRUE (the code generator stores a bool: const_as)
        diags.error(
            "E020",
            f"cannot use {src} as {dst} in {what}",
            e.pos,
            f"write {'TRUE' if e.const else 'FALSE'} (the {names_where(lambda p: p.bool_from_0_1)} profiles "
            "take 1 and 0 for BOOL)",
        )
        return False
    # a constant that fits is always fine (untyped literals adapt)
    if e.const is not None and const_fits(e.const, se, de, e):
        return True
    if widens_to(se, de):
        return True
    if profile.int_bits_mix and se.is_intlike and de.is_intlike and se.bits <= de.bits:
        return True
    lossy = (
        (se.is_intlike or se.is_real)
        and (de.is_intlike or de.is_real)
        or (se.category == T.DURATION and de.category == T.DURATION)
    )
    if lossy:
        msg = f"implicit conversion from {src} to {dst} in {what} may lose data"
        hint = f"convert explicitly: {se.name}_TO_{de.name}(...)"
        if profile.narrowing == "error":
            diags.error("E021", msg, e.pos, hint)
            return False
        diags.warning("W121", msg, e.pos, hint)
        return True
    hint = f"convert explicitly: {se.name}_TO_{de.name}(...)"
    if de.is_bool and se.is_intlike:
        hint = "compare it instead, e.g. x <> 0"
    diags.error("E020", f"cannot use {src} as {dst} in {what}", e.pos, hint)
    return False


# ---------------------------------------------------------------- constants


def const_repr(value: Any, t: T.ElementaryType) -> Any:
    """A constant of elementary type t in the form t stores: REAL rounded to
    binary32 (an integer once, not through a double), LREAL a float, BOOL a
    bool; other values as they are."""
    if t.is_real:
        if t is T.LREAL:
            return float(value)
        if isinstance(value, int) and not isinstance(value, bool):
            return rtlib.int_to_f32(value)
        return rtlib.f32(float(value))
    if t.is_bool:
        return bool(value)
    return value


def const_as(value: Any, src: T.Type, dst: T.Type) -> Any:
    """A folded constant converted to the representation of dst."""
    d = T.resolve(dst)
    if isinstance(d, T.StringType):
        return rtlib.cut_string(value, d.length, d.wide) if isinstance(value, str) else value
    de = T.base_elementary(d)
    se = T.base_elementary(src)
    if de is None or se is None:
        return value
    if de.is_real or de.is_bool:
        return const_repr(value, de)
    if de.is_intlike or de.is_time:
        if se.is_real:
            value = rtlib.round_half_away(value)
        if se.is_time and de.is_time and se.unit_ns != de.unit_ns:
            value = value * se.unit_ns // de.unit_ns
        return rtlib.wrap(de, int(value)) if (de.is_intlike or de.category == T.DURATION) else int(value)
    return value


def stores_literal(dst: T.Type) -> bool:
    """Whether a folded constant stored into dst is written as a literal
    (converted by const_as): into elementary types and strings."""
    d = T.resolve(dst)
    return not isinstance(d, T.RefType) and (T.base_elementary(d) is not None or isinstance(d, T.StringType))


# ---------------------------------------------------------------- the code generator's question
# What storing a value that is not a folded constant does to it; the code
# generator writes the Python for each step.
KEEP = "keep"  # it already has the destination's representation
TRUNCATE = "truncate"  # a string maybe longer than the destination: cut to its length
CHECK_RANGE = "check_range"  # into a subrange: the step into its base type, then a bounds check
TO_BOOL = "to_bool"  # a number into BOOL: value <> 0
TO_INT = "to_int"  # BOOL into an integer: 0 or 1
TO_FLOAT = "to_float"  # a number into LREAL, or an integer exact in binary32 into REAL
TO_F32 = "to_f32"  # a number into REAL: rounded to binary32
WRAP = "wrap"  # an integer into an integer type: wrapped to it unless the value provably fits
CONVERT = "convert"  # the rest (REAL to integer, time units, time to number): the library converter
TO_FIRST_ELEMENT = "to_first_element"  # a POINTER TO an ARRAY into a POINTER TO its element
TO_NULL = "to_null"  # NULL (or the 0 CODESYS allows) into a reference: no reference
TO_BYTES = "to_bytes"  # a pointer into a POINTER TO BYTE (WORD, ...) over its bytes (st/rtlib/rt_bytes.py)


def decays_to(s: T.RefType, d: T.RefType) -> bool:
    """A POINTER TO an ARRAY stored as a POINTER TO its element type: a
    pointer to the first element (CODESYS: p := ADR(arr))."""
    arr = T.resolve(s.target)
    return (
        d.pointer
        and isinstance(arr, T.ArrayType)
        and not arr.variable_length
        and same_type(arr.elem, d.target)
        and not same_type(s.target, d.target)
    )


def reinterprets(s: T.RefType, d: T.RefType) -> bool:
    """A pointer stored as a POINTER TO BYTE, WORD, REAL ... (or an ARRAY
    of them) over another type: a byte view of its target (CODESYS type
    punning, st/rtlib/rt_bytes.py)."""
    return (
        d.pointer
        and not s.reference
        and not same_type(s.target, d.target)
        and rt_bytes.view_unit(d.target) is not None
        and rt_bytes.layout_of(s.target) is not None
    )


def store_step(src: T.Type | None, dst: T.Type, e: A.Expr | None) -> str:
    """What storing a value of type src (the expression e, if known) into
    dst does to it: one of the steps above."""
    d = T.resolve(dst)
    s = T.resolve(src) if src is not None else d
    if isinstance(d, T.RefType):
        if isinstance(s, T.RefType) and decays_to(s, d):
            return TO_FIRST_ELEMENT
        if isinstance(s, T.RefType) and reinterprets(s, d):
            return TO_BYTES
        return KEEP if isinstance(s, T.RefType) else TO_NULL
    if isinstance(d, T.InterfaceType):
        return KEEP if isinstance(s, (T.FBType, T.InterfaceType)) else TO_NULL
    if isinstance(d, T.StringType):
        # a WSTRING's length counts UTF-16 units, a STRING's characters (one may be 2 units)
        fits = isinstance(s, T.StringType) and s.length <= d.length and (s.wide or not d.wide)
        return KEEP if fits else TRUNCATE
    if isinstance(d, T.SubrangeType):
        return CHECK_RANGE
    de = T.base_elementary(d)
    se = T.base_elementary(s)
    if de is None or se is None:
        return KEEP
    if isinstance(d, T.EnumType) or isinstance(s, T.EnumType) and de is se:
        return KEEP
    if de.is_bool:
        return KEEP if se.is_bool else TO_BOOL
    if de.is_real:
        if se.is_real:
            # every REAL expression is already a binary32 value (the code generator
            # rounds after each operation), so only an LREAL rounds into a REAL
            return KEEP if de is T.LREAL or se is T.REAL else TO_F32
        if se.is_bool or se.is_intlike:
            # an integer that widens to REAL (16 bits at most) is exact in binary32
            return TO_FLOAT if de is T.LREAL or widens_to(se, T.REAL) else TO_F32
        return CONVERT
    if se.is_real or (se.is_time and se.unit_ns != de.unit_ns) or se.is_time != de.is_time:
        return CONVERT
    if se.is_bool:
        return TO_INT
    return WRAP


def ref_target(t: T.Type | None) -> T.Type | None:
    """What a REFERENCE TO / POINTER TO t designates (None for other types)."""
    r = T.resolve(t) if t is not None else None
    return r.target if isinstance(r, T.RefType) else None


#: the string functions whose result may be longer than any argument
_GROWING = frozenset(("CONCAT", "INSERT", "REPLACE", "WCONCAT", "WINSERT", "WREPLACE"))


def string_result(name: str, rty: T.Type, arg_types: list) -> T.Type:
    """The result type of a string function with its true length bound:
    CONCAT, INSERT and REPLACE give at most the sum of their strings'
    lengths, so a store cuts the result to the destination's length (IEC
    61131-3 ed.3 6.4.2) unless it surely fits."""
    r = T.resolve(rty)
    if name.upper() not in _GROWING or not isinstance(r, T.StringType):
        return rty
    n = sum(t.length for t in map(T.resolve, arg_types) if isinstance(t, T.StringType))
    return T.StringType(n, r.wide)


def conversion_exists(src: T.Type, dst: T.Type) -> bool:
    """Whether TO_<dst> converts a value of src: every pair of elementary
    types and strings but CHAR and WCHAR, which convert with integers, bit
    strings, strings and each other only (IEC 61131-3 ed.3 Table 23, 27)."""
    se, de = T.base_elementary(src), T.base_elementary(dst)
    if (se is not None and se.is_char) or (de is not None and de.is_char):
        return rtlib.converts_char(src, dst)
    return True
