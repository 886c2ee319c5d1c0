"""Implicit conversions (runtime/st/check/conversions.py): the one rule the checker
and the code generator read."""

from __future__ import annotations

import pytest

from softplc.runtime.st import ast as A
from softplc.runtime.st import types as T
from softplc.runtime.st.check import conversions as C
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.profile import CODESYS, IEC, get_profile
from softplc.runtime.st.rtlib import rtlib

from ..conftest import codes, diagnostics, prog, run_st

SUB = T.SubrangeType(T.INT, 1, 3)
COLOUR = T.EnumType("Colour", {"RED": 0, "GREEN": 1}, {"RED": "Red", "GREEN": "Green"})
# {attribute 'strict'} before its TYPE (CODESYS, TwinCAT)
STRICT = T.EnumType("Strict", {"RED": 0, "GREEN": 1}, {"RED": "Red", "GREEN": "Green"}, strict=True)


def variable(ty: T.Type) -> A.Expr:
    """A checked, non-constant expression of type ty."""
    return A.Name("v", ty=ty)


def literal(value, kind: str = "int") -> A.Expr:
    """An untyped literal as the checker leaves it (folded)."""
    return A.Literal(kind, value, const=value)


def verdict(src: T.Type, dst: T.Type, e: A.Expr, profile: str = "codesys") -> tuple:
    diags = DiagnosticBag()
    ok = C.check_implicit(src, dst, e, "the assignment", get_profile(profile), diags)
    return ok, [d.code for d in diags.items]


@pytest.mark.parametrize(
    "src,dst,widens",
    [
        (T.INT, T.DINT, True),
        (T.DINT, T.INT, False),
        (T.USINT, T.INT, True),
        (T.UDINT, T.REAL, False),
        (T.DINT, T.LREAL, True),
        (T.BOOL, T.BYTE, True),
        (T.INT, T.WORD, False),
        (T.TIME, T.LTIME, True),
        (T.DATE, T.LDATE, True),
        (T.REAL, T.REAL, True),
    ],
)
def test_widening_follows_iec_figure_11(src, dst, widens):
    assert C.widens_to(src, dst) is widens


@pytest.mark.parametrize(
    "a,b,profile,common",
    [
        (T.INT, T.UINT, IEC, T.DINT),
        (T.SINT, T.INT, IEC, T.INT),
        (T.REAL, T.DINT, IEC, T.LREAL),
        (T.WORD, T.INT, IEC, None),
        (T.WORD, T.INT, CODESYS, T.DINT),
        (T.BYTE, T.WORD, CODESYS, T.WORD),
        (T.BOOL, T.INT, IEC, None),
    ],
)
def test_common_type_of_two_operands(a, b, profile, common):
    assert C.common_type(a, b, profile) is common


@pytest.mark.parametrize(
    "t,generic,profile,fit",
    [
        (T.INT, "ANY_NUM", IEC, T.INT),
        (T.INT, "ANY_REAL", IEC, T.REAL),
        (T.DINT, "ANY_REAL", IEC, T.LREAL),
        (T.WORD, "ANY_INT", CODESYS, T.UINT),
        (T.WORD, "ANY_INT", IEC, T.WORD),
    ],
)
def test_generic_parameters_take_their_argument(t, generic, profile, fit):
    assert C.generic_fit(t, generic, profile) is fit


@pytest.mark.parametrize(
    "src,dst,profile,expected",
    [
        (T.INT, T.DINT, "iec", (True, [])),
        (T.DINT, T.INT, "iec", (False, ["E021"])),
        (T.DINT, T.INT, "codesys", (True, ["W121"])),
        (T.LREAL, T.REAL, "codesys", (True, ["W121"])),
        (T.LTIME, T.TIME, "iec", (False, ["E021"])),
        (T.INT, T.WORD, "codesys", (True, [])),
        (T.INT, T.BOOL, "codesys", (False, ["E020"])),
        (T.TIME, T.DINT, "codesys", (False, ["E020"])),
        (T.StringType(10), T.StringType(5), "iec", (True, [])),
        (T.StringType(10), T.StringType(5, wide=True), "iec", (False, ["E020"])),
        (COLOUR, T.INT, "codesys", (True, [])),
        (COLOUR, T.INT, "iec", (False, ["E020"])),
        # CODESYS: an integer goes into an enumeration unless it is strict
        (T.INT, COLOUR, "codesys", (True, ["W151"])),
        (T.INT, STRICT, "twincat", (False, ["E020"])),
        (T.INT, COLOUR, "iec", (False, ["E020"])),
        (T.INT, SUB, "iec", (True, [])),
    ],
)
def test_what_may_be_stored_where(src, dst, profile, expected):
    assert verdict(src, dst, variable(src), profile) == expected


def test_untyped_literals_adapt_where_they_fit():
    assert verdict(T.DINT, T.INT, literal(1000), "iec") == (True, [])
    assert verdict(T.DINT, T.INT, literal(70000), "iec") == (False, ["E022"])
    assert verdict(T.DINT, T.INT, literal(70000), "codesys") == (True, ["W122"])
    assert verdict(T.DINT, SUB, literal(70000), "codesys") == (False, ["E022"])
    assert verdict(T.LREAL, T.REAL, literal(0.1, "real"), "iec") == (True, [])
    assert verdict(T.INT, SUB, literal(5), "iec") == (False, ["E022"])
    assert verdict(T.INT, SUB, literal(2), "iec") == (True, [])
    # a typed literal does not adapt
    typed = A.Literal("int", 1000, "DINT", const=1000)
    assert verdict(T.DINT, T.INT, typed, "iec") == (False, ["E021"])


def test_the_hints_say_how_to_convert():
    diags = DiagnosticBag()
    C.check_implicit(T.INT, T.BOOL, variable(T.INT), "the assignment", IEC, diags)
    C.check_implicit(T.DINT, T.INT, variable(T.DINT), "input 'IN'", CODESYS, diags)
    C.check_implicit(T.INT, STRICT, variable(T.INT), "the assignment", CODESYS, diags)
    C.check_implicit(T.INT, COLOUR, variable(T.INT), "the assignment", IEC, diags)
    assert [(d.code, d.message, d.hint) for d in diags.items] == [
        ("E020", "cannot use INT as BOOL in the assignment", "compare it instead, e.g. x <> 0"),
        (
            "W121",
            "implicit conversion from DINT to INT in input 'IN' may lose data",
            "convert explicitly: DINT_TO_INT(...)",
        ),
        (
            "E020",
            "cannot use INT as Strict in the assignment",
            "Strict is {attribute 'strict'}: use an enumerator of Strict, e.g. Strict#Red",
        ),
        ("E020", "cannot use INT as Colour in the assignment", "use an enumerator of Colour, e.g. Colour#Red"),
    ]


def test_same_type_ignores_string_lengths_and_array_offsets():
    assert C.same_type(T.StringType(10), T.StringType(80))
    assert C.same_type(T.ArrayType([(1, 3)], T.INT), T.ArrayType([(0, 2)], T.INT))
    assert not C.same_type(T.ArrayType([(1, 3)], T.INT), T.ArrayType([(1, 4)], T.INT))
    assert C.same_type(T.AliasType("Speed", T.REAL), T.REAL)
    assert not C.same_type(T.SubrangeType(T.INT, 1, 3), T.INT)


@pytest.mark.parametrize(
    "value,src,dst,result",
    [
        (0.1, T.LREAL, T.REAL, rtlib.f32(0.1)),
        (70000, T.DINT, T.INT, 4464),
        (2.5, T.REAL, T.INT, 3),
        (-2.5, T.LREAL, T.DINT, -3),
        (1, T.INT, T.BOOL, True),
        ("abcdef", T.StringType(10), T.StringType(3), "abc"),
        (1000, T.TIME, T.LTIME, 1_000_000_000),
        (5, T.INT, T.LREAL, 5.0),
    ],
)
def test_a_folded_constant_converts_at_compile_time(value, src, dst, result):
    got = C.const_as(value, src, dst)
    assert got == result and type(got) is type(result)


@pytest.mark.parametrize(
    "src,dst,e,step",
    [
        (T.INT, T.DINT, None, C.WRAP),  # the code generator skips it when the range fits
        (T.DINT, T.INT, None, C.WRAP),
        (T.REAL, T.REAL, None, C.KEEP),  # every REAL expression is binary32 (rounded per operation)
        (T.REAL, T.REAL, variable(T.REAL), C.KEEP),
        (T.REAL, T.LREAL, None, C.KEEP),
        (T.LREAL, T.REAL, variable(T.LREAL), C.TO_F32),
        (T.INT, T.REAL, None, C.TO_FLOAT),  # 16 bits: exact in binary32
        (T.DINT, T.REAL, None, C.TO_F32),  # the CODESYS W121 narrowing rounds
        (T.INT, T.LREAL, None, C.TO_FLOAT),
        (T.REAL, T.INT, None, C.CONVERT),
        (T.TIME, T.LTIME, None, C.CONVERT),
        (T.BOOL, T.BYTE, None, C.TO_INT),
        (T.BYTE, T.BOOL, None, C.TO_BOOL),
        (T.StringType(10), T.StringType(80), None, C.KEEP),
        (T.StringType(80), T.StringType(10), None, C.TRUNCATE),
        (T.INT, SUB, None, C.CHECK_RANGE),
        (COLOUR, COLOUR, None, C.KEEP),
        (T.RefType(T.INT), T.RefType(T.INT), None, C.KEEP),
    ],
)
def test_what_a_store_does_to_the_value(src, dst, e, step):
    assert C.store_step(src, dst, e) == step


def test_constants_are_stored_as_literals_except_references():
    assert C.stores_literal(T.INT) and C.stores_literal(T.StringType(5)) and C.stores_literal(COLOUR)
    assert not C.stores_literal(T.RefType(T.INT)) and not C.stores_literal(T.ArrayType([(0, 1)], T.INT))


# ---------------------------------------------------------------- in programs


def test_narrowing_is_an_error_in_iec_and_a_warning_in_codesys():
    src = prog("d : DINT := 100000; i : INT; r : REAL; l : LREAL;", "i := d; r := l;")
    assert codes(src, "iec") == ["E021", "E021"]
    assert codes(src, "codesys") == ["W121", "W121"]


def test_widening_is_silent():
    src = prog(
        "s : SINT; i : INT; d : DINT; r : REAL; l : LREAL; u : USINT; w : WORD; b : BYTE;",
        "i := s; d := i; l := r; r := i; i := u; w := b; l := d;",
    )
    assert codes(src, "iec") == []


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_literal_out_of_range_for_its_type_is_an_error_in_the_strict_profiles(profile):
    assert codes(prog("x : SINT := 200;", ""), profile) == ["E022"]
    assert codes(prog("x : INT;", "x := 70000;"), profile) == ["E022"]
    assert codes(prog("x : USINT;", "x := -1;"), profile) == ["E022"]
    [d] = diagnostics(prog("w : UINT := -1;", ""), profile)
    assert (d.code, d.message) == ("E022", "-1 does not fit UINT (0..65535)")
    assert "codesys and twincat profiles convert it with a warning" in (d.hint or "")


LITERALS_CONVERTED = prog(
    "w : WORD := -1; i : INT := 40000; b : BYTE; u : UDINT; s : SINT;",
    "b := 300;\nu := -1;\ns := 255;",
)


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_a_literal_out_of_range_converts_with_a_warning_in_codesys_and_twincat(profile):
    # CODESYS/TwinCAT type an untyped literal as the smallest type that holds
    # it and convert it like a variable: `test2 : UINT := -1;` compiles with
    # warning C0195 (help page of the 'warning disable' pragma). The value
    # wraps as the conversion function does: -1 -> 16#FFFF, 40000 -> -25536.
    found = [(d.code, d.message) for d in diagnostics(LITERALS_CONVERTED, profile)]
    assert found == [
        ("W122", "-1 does not fit WORD (0..65535): converted implicitly to 65535"),
        ("W122", "40000 does not fit INT (-32768..32767): converted implicitly to -25536"),
        ("W122", "300 does not fit BYTE (0..255): converted implicitly to 44"),
        ("W122", "-1 does not fit UDINT (0..4294967295): converted implicitly to 4294967295"),
        ("W122", "255 does not fit SINT (-128..127): converted implicitly to -1"),
    ]
    runner = run_st(LITERALS_CONVERTED, profile=profile)
    assert [runner.get(v) for v in ("w", "i", "b", "u", "s")] == [65535, -25536, 44, 4294967295, -1]


def test_a_literal_too_large_for_any_integer_stays_an_error_in_every_profile():
    # CODESYS C0001: "Constant ... too large for type 'ANY_INT'"
    src = prog("x : LINT;", "x := 18446744073709551616;")
    assert codes(src, "codesys") == ["E022"]
    # a subrange is checked against its own bounds, never wrapped into them
    assert codes(prog("x : INT(1..3) := 40000;", ""), "codesys") == ["E022"]
    # a typed literal is checked against its own type (C0001 for INT#123456)
    assert codes(prog("x : DINT := INT#40000;", ""), "codesys") == ["E022"]


# ---------------------------------------------------------------- 0 and 1 for BOOL

BOOL_01 = """
TYPE Flags : STRUCT on : BOOL; off : BOOL; END_STRUCT END_TYPE
FUNCTION Pass : BOOL
VAR_INPUT b : BOOL; END_VAR
Pass := b;
END_FUNCTION
PROGRAM main
VAR
  a : BOOL := 1;
  f : Flags := (on := 1, off := 0);
  arr : ARRAY[1..2] OF BOOL := [0, 1];
  b : BOOL;
  c : BOOL := TRUE;
  p : BOOL;
  t : TON;
END_VAR
b := 1;
c := 0;
p := Pass(1);
t(IN := 1, PT := T#10ms);
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["matiec", "codesys", "twincat", "schneider"])
def test_0_and_1_go_into_bool_as_false_and_true(profile):
    # CODESYS, TwinCAT, Schneider and MatIEC take b := 1 (IEC 61131-3 ed.2
    # B.1.2: '0' and '1' spell BOOL literals); stored as real bools, so the
    # values compare and print as BOOLs do
    r = run_st(BOOL_01, cycles=2, profile=profile)
    values = [r.get(n) for n in ("a", "f.on", "f.off", "b", "c", "p", "t.IN", "t.Q")] + r.get("arr")
    assert values == [True, True, False, True, False, True, True, True, False, True]
    assert all(type(v) is bool for v in values)
    assert r.program.warnings == []


def test_0_and_1_for_bool_are_e020_in_iec_with_a_hint():
    ds = diagnostics(BOOL_01, "iec")
    assert [(d.code, d.pos.line, d.pos.col) for d in ds] == [
        ("E020", 9, 15),
        ("E020", 10, 23),
        ("E020", 10, 33),
        ("E020", 11, 33),
        ("E020", 11, 36),
        ("E020", 17, 6),
        ("E020", 18, 6),
        ("E020", 19, 11),
        ("E020", 20, 9),
    ]
    assert ds[0].hint == "write TRUE (the matiec, codesys, twincat and schneider profiles take 1 and 0 for BOOL)"
    assert ds[1].message == "cannot use INT as BOOL in the initial value of 'f.on'"
    assert ds[2].hint.startswith("write FALSE ")
    assert (
        codes(
            BOOL_01.replace(":= 1", ":= TRUE")
            .replace(":= 0", ":= FALSE")
            .replace("[0, 1]", "[FALSE, BOOL#1]")
            .replace("Pass(1)", "Pass(TRUE)"),
            "iec",
        )
        == []
    )


@pytest.mark.parametrize("value", ["2", "-1", "16#1", "INT#1", "1 - 0", "n"])
def test_only_the_digits_0_and_1_stand_for_bool(value):
    src = prog("b : BOOL; n : INT := 1;", f"b := {value};")
    for profile in ("codesys", "matiec"):
        [d] = diagnostics(src, profile)
        assert d.code == "E020" and d.hint == "compare it instead, e.g. x <> 0", (profile, value)


def test_a_shift_takes_an_integer_where_the_profile_mixes_integers_and_bits():
    """OSCAT's ARRAY_ functions shift a byte count: SHR(size, 2) with size :
    UINT. CODESYS accepts an integer in SHL/SHR/ROL/ROR and shifts its
    bits; IEC 61131-3 (Table 26) wants ANY_BIT."""
    src = prog("size : UINT := 20; n : INT; w : WORD;", "n := UINT_TO_INT(SHR(size, 2)) - 1; w := SHL(size, 1);")
    r = run_st(src)
    assert (r.get("n"), r.get("w")) == (4, 40)
    assert codes(src, "iec") == ["E020", "E020"]
