"""The checker's operators (runtime/st/checker_operators.py): the type and
folded value of each operation."""

from __future__ import annotations

from softplc.runtime.st import types as T

from .conftest import check_st, codes, diagnostics, pou_body, prog, run_st


def test_type_errors_in_conditions_and_operators():
    src = prog(
        "i : INT; s : STRING; b : BOOL; r : REAL;", "IF i THEN END_IF\nb := s + 1;\nr := r MOD 2.0;\nb := b < s;"
    )
    assert codes(src) == ["E020", "E023", "E023", "E020"]


def test_operator_errors():
    src = prog("x : INT; b : BOOL; r : REAL;", "x := 10 / 0;\nb := b AND_THEN 1;\nx := -x;\nr := NOT r;")
    assert [(d.code, d.message, d.pos.line) for d in diagnostics(src)] == [
        ("E027", "division by the constant zero", 5),
        ("E023", "AND_THEN needs BOOL operands", 6),
        ("E023", "NOT needs BOOL or a bit string, not REAL", 8),
    ]


def test_constant_operations_are_folded_with_iec_results():
    checked, found = check_st(
        prog(
            "x : DINT; b : BOOL; w : WORD; i : INT;",
            "x := (2 + 3) * 4 - 10 MOD 3;\nb := 3 < 4 AND NOT FALSE;\nw := 16#F0F0 XOR 16#FF00;\ni := 7 / -2;",
        )
    )
    assert found == []
    assert [(s.value.const, s.value.ty) for s in pou_body(checked)] == [
        (19, T.INT),
        (True, T.BOOL),
        (0x0FF0, T.DINT),
        (-3, T.INT),
    ]


def test_the_smallest_lint_is_a_lint_literal_beside_a_lint():
    """Found by the fuzz harness (tests/fuzz): -9223372036854775808 compared
    with a LINT was taken as the negation of a ULINT ("cannot compare LINT
    with ULINT"), though assigned to one it was a LINT."""
    src = prog(
        "v : LINT := -5; a : BOOL; b : BOOL; c : BOOL; u : UINT;",
        "a := v > (-9223372036854775808);\nb := (1 > (-9223372036854775808));\nc := v > -9223372036854775807;",
    )
    assert codes(src) == []
    runner = run_st(src)
    assert (runner.get("a"), runner.get("b"), runner.get("c")) == (True, True, True)
    assert [(d.code, d.message) for d in diagnostics(prog("u : UINT;", "u := -5;"))] == [
        ("E022", "-5 does not fit UINT (0..65535)")
    ]


SHARED_ENUMERATORS = """TYPE E_Pump : (Idle, Running, Faulted); END_TYPE
TYPE E_Fan : (Off, Idle, Faulted); END_TYPE
"""


def test_an_enumerator_of_several_types_takes_the_type_of_the_other_operand():
    src = SHARED_ENUMERATORS + prog(
        "pump : E_Pump := Faulted; fan : E_Fan; a : BOOL; b : BOOL; c : BOOL;",
        "a := pump <> Idle;\nb := Faulted = pump;\nc := fan = Idle;",
    )
    runner = run_st(src)
    assert (runner.get("a"), runner.get("b"), runner.get("c")) == (True, True, False)


def test_an_enumerator_with_no_typed_side_stays_ambiguous():
    src = SHARED_ENUMERATORS + prog("b : BOOL;", "b := Idle = Faulted;")
    assert [(d.code, d.message, d.hint) for d in diagnostics(src)][0] == (
        "E010",
        "'Idle' is an enumerator of several types",
        "qualify it, e.g. E_Pump#Idle",
    )
