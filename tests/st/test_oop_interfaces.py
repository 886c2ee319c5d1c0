"""INTERFACEs (runtime/st/check/checker_oop.py, codegen_oop.py, rt_oop.py).
IEC 61131-3 ed.3 6.6.6: an interface declares methods (CODESYS and TwinCAT
also properties); a FUNCTION_BLOCK IMPLEMENTS one or several; a variable of
an interface type designates an instance of such a block (or none: it is 0
until assigned, and `itf = 0` tests it); calls through it go to the
instance's method; `itf2 ?= itf1` (6.6.6.7) gives the instance if it
implements the target interface, else NULL; CODESYS __QUERYINTERFACE does
the same and tells whether it did. A call through an unassigned interface
is a runtime fault at the call (CODESYS raises an exception there)."""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import diagnostics, run_st

SHAPES = """
INTERFACE I_Named
PROPERTY Name : STRING GET END_GET END_PROPERTY
END_INTERFACE
INTERFACE I_Shape EXTENDS I_Named
METHOD Area : REAL END_METHOD
METHOD Scale
VAR_INPUT k : REAL; END_VAR
END_METHOD
END_INTERFACE
INTERFACE I_Counted
METHOD Count : INT END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Square IMPLEMENTS I_Shape, I_Counted
VAR side : REAL := 2.0; calls : INT; END_VAR
METHOD Area : REAL
calls := calls + 1;
Area := side * side;
END_METHOD
METHOD Scale
VAR_INPUT k : REAL; END_VAR
side := side * k;
END_METHOD
METHOD Count : INT
Count := calls;
END_METHOD
PROPERTY Name : STRING
GET Name := 'square'; END_GET
END_PROPERTY
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Circle IMPLEMENTS I_Shape
VAR r : REAL := 1.0; END_VAR
METHOD Area : REAL
Area := 3.0 * r * r;
END_METHOD
METHOD Scale
VAR_INPUT k : REAL; END_VAR
r := r * k;
END_METHOD
PROPERTY Name : STRING
GET Name := 'circle'; END_GET
END_PROPERTY
END_FUNCTION_BLOCK
"""


def test_calls_dispatch_through_interface_variables():
    src = (
        SHAPES
        + """
PROGRAM main
VAR sq : FB_Square; ci : FB_Circle; shapes : ARRAY[1..2] OF I_Shape; i : INT;
    total : REAL; names : STRING; n : I_Named; END_VAR
shapes[1] := sq; shapes[2] := ci;
total := 0.0; names := '';
FOR i := 1 TO 2 DO
    shapes[i].Scale(k := 2.0);
    total := total + shapes[i].Area();
    names := CONCAT(names, shapes[i].Name);
END_FOR
n := shapes[2];                   (* I_Shape EXTENDS I_Named *)
names := CONCAT(names, n.Name);
END_PROGRAM
"""
    )
    r = run_st(src)
    assert r.get("total") == 16.0 + 12.0 and r.get("names") == "squarecirclecircle"
    assert r.instance.v_sq.v_side == 4.0  # the instance itself was scaled, not a copy


def test_unassigned_interface_is_zero_and_its_call_is_a_fault():
    src = (
        SHAPES
        + """
PROGRAM main
VAR s, t : I_Shape; sq : FB_Square; before, after, same : BOOL; a : REAL; END_VAR
before := s = 0;
s := sq; t := sq;
after := s <> NULL;
same := s = t;
s := 0;
a := s.Area();
END_PROGRAM
"""
    )
    with pytest.raises(STFault) as info:
        run_st(src)
    fault = info.value
    assert fault.kind == "reference" and (fault.pos.line, fault.pos.col) == (52, 1)  # a := s.Area();
    assert "designates no function block instance" in str(fault)


@pytest.mark.parametrize("use", ["n := s.Name;", "s.Scale(k := 2.0);"])
def test_a_property_or_method_through_a_null_interface_is_the_same_fault(use):
    # Python's own AttributeError on None, classified by st/faults.py
    src = (
        SHAPES
        + f"""
PROGRAM main
VAR s : I_Shape; n : STRING; END_VAR
{use}
END_PROGRAM
"""
    )
    with pytest.raises(STFault) as info:
        run_st(src)
    fault = info.value
    assert fault.kind == "reference" and fault.pos.line == SHAPES.count("\n") + 4
    assert "designates no function block instance" in str(fault)


def test_nulls_before_the_fault():
    src = (
        SHAPES
        + """
PROGRAM main
VAR s, t, u : I_Shape; sq : FB_Square; ci : FB_Circle; before, after, same, other : BOOL; END_VAR
before := s = 0;
s := sq; t := sq; u := ci;
after := s <> NULL;
same := s = t;                    (* the same instance *)
other := s = u;
END_PROGRAM
"""
    )
    r = run_st(src)
    assert (r.get("before"), r.get("after"), r.get("same"), r.get("other")) == (True, True, True, False)


def test_assignment_attempt_and_queryinterface():
    src = (
        SHAPES
        + """
PROGRAM main
VAR sq : FB_Square; ci : FB_Circle; s1, s2 : I_Shape; c1, c2 : I_Counted;
    q1, q2 : BOOL; n1, n2 : INT; END_VAR
s1 := sq; s2 := ci;
c1 ?= s1;                            (* a square is counted *)
c2 := c1;
c2 ?= s2;                            (* a circle is not: NULL *)
s1.Area();
n1 := c1.Count();
q1 := __QUERYINTERFACE(s1, c2);      (* TRUE, c2 designates the square *)
q2 := __QUERYINTERFACE(s2, c1);      (* FALSE, c1 unchanged *)
n2 := c2.Count() + c1.Count();
END_PROGRAM
"""
    )
    r = run_st(src)
    assert (r.get("n1"), r.get("q1"), r.get("q2"), r.get("n2")) == (1, True, False, 2)


def test_interface_as_input_of_a_function_and_of_a_block():
    src = (
        SHAPES
        + """
FUNCTION AreaOf : REAL
VAR_INPUT s : I_Shape; END_VAR
IF s <> 0 THEN AreaOf := s.Area(); END_IF
END_FUNCTION
FUNCTION_BLOCK FB_User
VAR_INPUT shape : I_Shape; END_VAR
VAR_OUTPUT a : REAL; END_VAR
a := AreaOf(shape) + AreaOf(0);
END_FUNCTION_BLOCK
PROGRAM main
VAR sq : FB_Square; u : FB_User; a : REAL; END_VAR
u(shape := sq); a := u.a;
END_PROGRAM
"""
    )
    assert run_st(src).get("a") == 4.0


def test_implementing_all_of_an_interface_is_checked():
    src = """
INTERFACE I_A
METHOD Go : BOOL
VAR_INPUT speed : INT; END_VAR
END_METHOD
PROPERTY Level : INT GET END_GET SET END_SET END_PROPERTY
END_INTERFACE
FUNCTION_BLOCK FB_Missing IMPLEMENTS I_A
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Other IMPLEMENTS I_A, I_Nothing
METHOD Go : BOOL
VAR_INPUT speed : REAL; END_VAR
END_METHOD
PROPERTY Level : INT GET Level := 0; END_GET END_PROPERTY
END_FUNCTION_BLOCK
"""
    got = sorted((d.code, d.pos.line) for d in diagnostics(src))
    assert got == [
        ("E140", 10),  # I_Nothing
        ("E145", 8),  # FB_Missing lacks Go
        ("E145", 8),  # ... and Level
        ("E145", 11),  # Go with another signature
        ("E145", 14),  # Level without SET
    ]


def test_storing_something_else_into_an_interface_is_e020():
    src = """
INTERFACE I_A
METHOD Go END_METHOD
END_INTERFACE
FUNCTION_BLOCK FB_Plain
END_FUNCTION_BLOCK
PROGRAM main
VAR i : I_A; p : FB_Plain; x : INT; END_VAR
i := p;
i := x;
END_PROGRAM
"""
    assert [(d.code, d.pos.line) for d in diagnostics(src)] == [("E020", 9), ("E020", 10)]
