"""PROPERTY with GET and SET (runtime/st/check/checker_oop.py, codegen_oop.py).
CODESYS help "Object: Property" (TwinCAT the same): reading inst.P calls
the GET accessor, inst.P := v calls SET; inside both the property's name is
the value (the result of GET, the input of SET); inside the block it is
read and written as P or THIS^.P."""

from __future__ import annotations

from .conftest import diagnostics, run_st

VALVE = """
FUNCTION_BLOCK FB_Valve
VAR pos : REAL; nsets : INT; END_VAR
PROPERTY Position : REAL
GET
    Position := pos;
END_GET
SET
    VAR clipped : REAL; END_VAR
    clipped := LIMIT(0.0, Position, 100.0);
    pos := clipped;
    nsets := nsets + 1;
END_SET
END_PROPERTY
PROPERTY Sets : INT
GET Sets := nsets; END_GET
END_PROPERTY
METHOD Open
Position := 100.0;               (* inside: the SET accessor *)
END_METHOD
METHOD Half : REAL
Half := THIS^.Position / 2.0;    (* inside: the GET accessor *)
END_METHOD
END_FUNCTION_BLOCK
"""


def test_get_and_set_from_outside_and_inside():
    src = (
        VALVE
        + """
PROGRAM main
VAR v : FB_Valve; a, b, h : REAL; n : INT; END_VAR
v.Position := 150.0;             (* clipped by SET *)
a := v.Position;
v.Position := v.Position - 30.0;
b := v.Position;
v.Open();
h := v.Half();
n := v.Sets;
END_PROGRAM
"""
    )
    r = run_st(src)
    assert (r.get("a"), r.get("b"), r.get("h"), r.get("n")) == (100.0, 70.0, 50.0, 3)


def test_property_without_set_cannot_be_assigned():
    src = (
        VALVE
        + """
PROGRAM main
VAR v : FB_Valve; END_VAR
v.Sets := 3;
END_PROGRAM
"""
    )
    got = [(d.code, d.pos.line, d.pos.col) for d in diagnostics(src)]
    assert got == [("E147", 28, 1)]


def test_an_inherited_property_and_an_override():
    src = (
        VALVE
        + """
FUNCTION_BLOCK FB_Slow EXTENDS FB_Valve
PROPERTY Position : REAL
GET Position := SUPER^.Position; END_GET
SET SUPER^.Position := Position / 2.0; END_SET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM main
VAR s : FB_Slow; p : REAL; n : INT; END_VAR
s.Position := 80.0;
p := s.Position; n := s.Sets;
END_PROGRAM
"""
    )
    r = run_st(src)
    assert (r.get("p"), r.get("n")) == (40.0, 1)


def test_private_property_is_refused_outside():
    src = """
FUNCTION_BLOCK FB
PROPERTY PRIVATE Inner : INT
GET Inner := 1; END_GET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM main
VAR f : FB; x : INT; END_VAR
x := f.Inner;
END_PROGRAM
"""
    assert [(d.code, d.pos.line) for d in diagnostics(src)] == [("E144", 9)]


def test_a_property_is_not_passed_by_reference():
    src = (
        VALVE
        + """
FUNCTION_BLOCK FB_Out
VAR_OUTPUT y : REAL; END_VAR
VAR_IN_OUT io : REAL; END_VAR
END_FUNCTION_BLOCK
PROGRAM main
VAR v : FB_Valve; o : FB_Out; r : REF_TO REAL; END_VAR
o(io := v.Position, y => v.Position);
r := REF(v.Position);
END_PROGRAM
"""
    )
    got = [(d.code, d.pos.line) for d in diagnostics(src)]
    assert got == [("E147", 32), ("E147", 32), ("E147", 33)]
