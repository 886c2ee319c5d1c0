"""Generic inputs of user-written functions (runtime/st/check/checker_generics.py).

IEC 61131-3 ed.3 leaves generic types in user-declared POUs to the
implementation; CODESYS and TwinCAT accept ``x : ANY_NUM`` as an input of
a FUNCTION. Here the input takes an argument of any type of the family and
holds it in the family's widest type (ANY_NUM/ANY_REAL: LREAL,
ANY_INT/ANY_SIGNED: LINT, ANY_UNSIGNED: ULINT, ANY_BIT: LWORD), so the
body computes with the value itself.
"""

from __future__ import annotations

from .conftest import diagnostics, prog, run_st

FUNCS = """
FUNCTION Half : LREAL
VAR_INPUT x : ANY_NUM; END_VAR
Half := x / 2;
END_FUNCTION

FUNCTION Bigger : LINT
VAR_INPUT a : ANY_INT; b : ANY_INT; END_VAR
Bigger := MAX(a, b);
END_FUNCTION

FUNCTION Low : LWORD
VAR_INPUT w : ANY_BIT; END_VAR
Low := w AND 16#FF;
END_FUNCTION
"""


def test_a_generic_input_takes_every_member_of_its_family():
    src = FUNCS + prog(
        "i : INT := 7; r : REAL := 3.0; d : LREAL; h1 : LREAL; h2 : LREAL; h3 : LREAL;"
        "s : SINT := -5; u : UDINT := 4000000000; m : LINT; w : WORD := 16#1234; lo : LWORD;",
        "h1 := Half(i);\nh2 := Half(r);\nh3 := Half(x := 1.5);\nm := Bigger(s, u);\nlo := Low(w);",
    )
    r = run_st(src)
    assert (r.get("h1"), r.get("h2"), r.get("h3")) == (3.5, 1.5, 0.75)
    assert (r.get("m"), r.get("lo")) == (4000000000, 0x34)


def test_a_type_outside_the_family_or_an_unsupported_generic_is_coded():
    src = (
        FUNCS
        + """
FUNCTION Any1 : INT
VAR_INPUT v : ANY; END_VAR
Any1 := 1;
END_FUNCTION
FUNCTION_BLOCK Fb
VAR_INPUT n : ANY_NUM; END_VAR
END_FUNCTION_BLOCK
"""
        + prog("r : REAL; t : TIME; h : LREAL; m : LINT;", "m := Bigger(r, 1);\nh := Half(t);")
    )
    found = [(d.code, d.pos.line, d.message) for d in diagnostics(src)]
    assert found == [
        ("E012", 18, "generic type 'ANY' cannot be used here"),
        ("E012", 22, "generic type 'ANY_NUM' cannot be used here"),
        ("E020", 28, "input 'a' is ANY_INT; got REAL"),
        ("E020", 29, "input 'x' is ANY_NUM; got TIME"),
    ]
