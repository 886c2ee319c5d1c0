"""The checker's statements (runtime/st/check/checker_stmts.py) and what an
assignment may write to."""

from __future__ import annotations

import pytest

from ..conftest import codes, diagnostics, prog

ASSIGNS = """
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


def test_assignments_to_constants_inputs_and_foreign_outputs_are_rejected():
    ds = diagnostics(ASSIGNS, "iec")
    assert [(d.code, d.pos.line) for d in ds] == [("E030", 5), ("E030", 10), ("E030", 11)]
    assert ds[0].message == "'i' is an input of Fb and cannot be assigned inside it"
    assert ds[0].hint == (
        "copy it into a local VAR and change that (the matiec, codesys, twincat and schneider profiles allow it)"
    )


@pytest.mark.parametrize("profile", ["matiec", "codesys", "twincat", "schneider"])
def test_an_input_assigned_inside_its_own_pou_is_a_warning_where_the_dialect_allows_it(profile):
    # CODESYS, TwinCAT and MatIEC accept i := 1 inside the FB that declares
    # i (OSCAT's port to Beremiz does it; IEC 61131-3 reads inputs only); a
    # CONSTANT and another block's output stay read-only everywhere.
    ds = diagnostics(ASSIGNS, profile)
    assert [(d.code, d.severity, d.pos.line) for d in ds] == [
        ("W130", "warning", 5),
        ("E030", "error", 10),
        ("E030", "error", 11),
    ]
    assert ds[0].message == "'i' is an input of Fb: assigning it inside changes what the caller passed"


def test_for_variable_must_not_be_assigned_in_the_loop():
    assert codes(prog("i : INT;", "FOR i := 1 TO 3 DO i := 5; END_FOR")) == ["E072"]
