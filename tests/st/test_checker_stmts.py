"""The checker's statements (runtime/st/checker_stmts.py) and what an
assignment may write to."""

from __future__ import annotations

from .conftest import codes, diagnostics, prog


def test_assignments_to_constants_inputs_and_foreign_outputs_are_rejected():
    src = """
FUNCTION_BLOCK Fb
VAR_INPUT i : INT; END_VAR
VAR_OUTPUT o : INT; END_VAR
i := 1;
END_FUNCTION_BLOCK
PROGRAM main
VAR CONSTANT k : INT := 1; END_VAR
VAR f : Fb; END_VAR
k := 2;
f.o := 3;
f.i := 4;
END_PROGRAM
"""
    ds = diagnostics(src)
    assert [(d.code, d.pos.line) for d in ds] == [("E030", 5), ("E030", 10), ("E030", 11)]


def test_for_variable_must_not_be_assigned_in_the_loop():
    assert codes(prog("i : INT;", "FOR i := 1 TO 3 DO i := 5; END_FOR")) == ["E072"]
