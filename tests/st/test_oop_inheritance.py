"""EXTENDS, SUPER^, ABSTRACT, FINAL and access specifiers
(runtime/st/check/checker_oop.py, codegen_oop.py). IEC 61131-3 ed.3 6.6.5.2-6.6.5.7;
CODESYS help "Extending a function block" and "Object: Method": the derived
block inherits the base's variables and methods, overrides a method by
declaring it again with the same signature, calls the base's with SUPER^.M();
its own body runs when the instance is called, the base's body only through
SUPER^()."""

from __future__ import annotations

from .conftest import diagnostics, run_st

SHAPES = """
FUNCTION_BLOCK FB_Base
VAR_INPUT gain : INT := 1; END_VAR
VAR_OUTPUT out : INT; runs : INT; END_VAR
VAR hidden : INT; END_VAR
METHOD Value : INT
Value := 10 * gain;
END_METHOD
METHOD Describe : INT
Describe := Value() + 1;          (* dispatches: an override of Value is called *)
END_METHOD
METHOD FINAL Fixed : INT
Fixed := 7;
END_METHOD
runs := runs + 1;
hidden := hidden + 1;
out := Value();
END_FUNCTION_BLOCK

FUNCTION_BLOCK FB_Derived EXTENDS FB_Base
VAR_OUTPUT own : INT; END_VAR
METHOD Value : INT
Value := SUPER^.Value() + 5;      (* the base's, then more *)
END_METHOD
own := own + 1;
SUPER^();                         (* the base's body, on this instance *)
hidden := hidden + 100;           (* an inherited VAR *)
END_FUNCTION_BLOCK
"""


def test_override_super_and_body_inheritance():
    src = (
        SHAPES
        + """
PROGRAM main
VAR b : FB_Base; d : FB_Derived; bo, dout, dd, bd, f : INT; END_VAR
b(); d(gain := 2);
bo := b.out; dout := d.out; dd := d.Describe(); bd := b.Describe(); f := d.Fixed();
END_PROGRAM
"""
    )
    r = run_st(src, cycles=3)
    assert (r.get("bo"), r.get("bd")) == (10, 11)
    # d: Value = 10 * 2 + 5; the base body (SUPER^()) calls the override
    assert (r.get("dout"), r.get("dd"), r.get("f")) == (25, 26, 7)
    assert (r.get("d.runs"), r.get("d.own"), r.get("b.runs")) == (3, 3, 3)
    assert r.instance.v_d.v_hidden == 303


def test_a_derived_body_without_super_does_not_run_the_base_body():
    # CODESYS: the derived block's own body replaces the base's
    src = (
        SHAPES
        + """
FUNCTION_BLOCK FB_Quiet EXTENDS FB_Base
END_FUNCTION_BLOCK
PROGRAM main
VAR q : FB_Quiet; r : INT; END_VAR
q(); r := q.Value();
END_PROGRAM
"""
    )
    r = run_st(src, cycles=2)
    assert r.get("q.runs") == 0 and r.get("r") == 10


def test_three_levels_and_super_reaching_the_grandparent():
    src = (
        SHAPES
        + """
FUNCTION_BLOCK FB_Third EXTENDS FB_Derived
METHOD Value : INT
Value := SUPER^.Value() * 2;      (* FB_Derived's, which calls FB_Base's *)
END_METHOD
END_FUNCTION_BLOCK
PROGRAM main
VAR t : FB_Third; v, d : INT; END_VAR
v := t.Value(); d := t.Describe();
END_PROGRAM
"""
    )
    r = run_st(src)
    assert (r.get("v"), r.get("d")) == (30, 31)


def test_abstract_blocks_and_methods():
    src = """
FUNCTION_BLOCK ABSTRACT FB_Shape
METHOD ABSTRACT Area : REAL
END_METHOD
METHOD Twice : REAL
Twice := 2.0 * Area();
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Square EXTENDS FB_Shape
VAR_INPUT side : REAL := 3.0; END_VAR
METHOD Area : REAL
Area := side * side;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM main
VAR s : FB_Square; a : REAL; END_VAR
a := s.Twice();
END_PROGRAM
"""
    assert run_st(src).get("a") == 18.0


def test_abstract_and_final_rules_are_coded_errors():
    src = """
FUNCTION_BLOCK ABSTRACT FB_Shape
METHOD ABSTRACT Area : REAL
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Lazy EXTENDS FB_Shape
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Open
METHOD ABSTRACT Go
END_METHOD
METHOD FINAL Stay
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FINAL FB_Leaf EXTENDS FB_Open
METHOD Stay
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Beyond EXTENDS FB_Leaf
END_FUNCTION_BLOCK
PROGRAM main
VAR s : FB_Shape; END_VAR
END_PROGRAM
"""
    got = sorted((d.code, d.pos.line) for d in diagnostics(src))
    assert got == [
        ("E142", 6),  # FB_Lazy does not define Area
        ("E142", 9),  # an ABSTRACT METHOD in a block that is not ABSTRACT
        ("E142", 14),  # ... which FB_Leaf does not define
        ("E142", 21),  # an instance of an ABSTRACT block
        ("E143", 15),  # Stay is FINAL
        ("E143", 18),  # FB_Leaf is FINAL
    ]


def test_override_with_another_signature_and_redeclared_variable():
    src = """
FUNCTION_BLOCK FB_A
VAR x : INT; END_VAR
METHOD M : INT
VAR_INPUT a : INT; END_VAR
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_B EXTENDS FB_A
VAR x : INT; END_VAR
METHOD M : INT
VAR_INPUT a : REAL; END_VAR
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_C EXTENDS FB_Nothing
END_FUNCTION_BLOCK
"""
    got = sorted((d.code, d.pos.line) for d in diagnostics(src))
    assert got == [("E140", 14), ("E141", 9), ("E141", 10)]


def test_extends_cycle_is_reported_once():
    src = """
FUNCTION_BLOCK FB_A EXTENDS FB_B
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_B EXTENDS FB_A
END_FUNCTION_BLOCK
"""
    assert [d.code for d in diagnostics(src)] == ["E140"]


ACCESS = """
FUNCTION_BLOCK FB_A
METHOD PRIVATE Secret : INT
Secret := 1;
END_METHOD
METHOD PROTECTED Family : INT
Family := Secret() + 1;          (* the block itself: PRIVATE is visible *)
END_METHOD
METHOD INTERNAL Local : INT
Local := 3;
END_METHOD
METHOD PUBLIC Open : INT
Open := Family() + 10;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_B EXTENDS FB_A
METHOD Use : INT
Use := Family() + Local();       (* PROTECTED: visible in a derived block *)
END_METHOD
END_FUNCTION_BLOCK
"""


def test_access_specifiers_allow():
    src = (
        ACCESS
        + """
PROGRAM main
VAR b : FB_B; o, u, l : INT; END_VAR
o := b.Open(); u := b.Use(); l := b.Local();   (* INTERNAL: the same namespace *)
END_PROGRAM
"""
    )
    r = run_st(src)
    assert (r.get("o"), r.get("u"), r.get("l")) == (12, 5, 3)


def test_access_specifiers_refuse_with_e144():
    src = (
        ACCESS
        + """
FUNCTION_BLOCK FB_C EXTENDS FB_A
METHOD Peek : INT
Peek := Secret();                (* PRIVATE: not even in a derived block *)
END_METHOD
END_FUNCTION_BLOCK
PROGRAM main
VAR b : FB_B; x : INT; END_VAR
x := b.Secret();
x := b.Family();
END_PROGRAM
"""
    )
    got = [(d.code, d.pos.line, d.pos.col) for d in diagnostics(src)]
    assert got == [("E144", 24, 9), ("E144", 29, 6), ("E144", 30, 6)]


def test_super_without_a_base_and_this_body_call():
    src = """
FUNCTION_BLOCK FB
SUPER^();
THIS^();
END_FUNCTION_BLOCK
"""
    got = [(d.code, d.pos.line) for d in diagnostics(src)]
    assert got == [("E146", 3), ("E146", 4)]
