"""The checker's operators (runtime/st/check/checker_operators.py): the type and
folded value of each operation."""

from __future__ import annotations

from softplc.runtime.st import types as T

from ..conftest import check_st, codes, diagnostics, pou_body, prog, run_st


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
    assert [(d.code, d.message) for d in diagnostics(prog("u : UINT;", "u := -5;"), "iec")] == [
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


# ---------------------------------------------------------------- the operators' function forms
# IEC 61131-3 ed.3 Table 29 (arithmetic: ADD and MUL extensible, SUB, DIV,
# MOD, EXPT, MOVE), Table 30 (ADD/SUB on durations, TOD and DT) and Table 31
# (bitwise Boolean: AND, OR, XOR extensible, NOT). Formal inputs IN1, IN2 ...
# (IN for NOT and MOVE).


def test_operator_functions_compute_what_the_operators_compute():
    src = prog(
        "i : INT := 5; d : DINT := 100000; r : REAL := 2.0; w : WORD := 16#00FF; b : BOOL := TRUE;\n"
        "sum : DINT; prod : DINT; diff : INT; q : INT; qr : REAL; m : INT; mneg : INT; e : REAL; mv : INT;\n"
        "a3 : BOOL; o3 : BOOL; x3 : BOOL; nb : BOOL; wa : WORD; wo : WORD; wx : WORD; wn : WORD;",
        "sum := ADD(i, d, 3);\n"  # INT + DINT is DINT: no INT overflow
        "prod := MUL(i, d, 2);\n"
        "diff := SUB(i, 7);\n"
        "q := DIV(-7, 2);\n"  # integer division truncates toward zero
        "qr := DIV(7.0, r);\n"
        "m := MOD(7, 3);\n"
        "mneg := MOD(-7, 3);\n"  # the sign of the dividend, as the MOD operator
        "e := EXPT(r, 3);\n"
        "mv := MOVE(i);\n"
        "a3 := AND(b, TRUE, FALSE);\n"
        "o3 := OR(FALSE, FALSE, b);\n"
        "x3 := XOR(b, b, b);\n"
        "nb := NOT(b);\n"
        "wa := AND(w, 16#0F0F, 16#FFF3);\n"
        "wo := OR(IN1 := w, IN2 := 16#F000);\n"
        "wx := XOR(IN1 := w, IN2 := 16#0F0F, IN3 := 16#0001);\n"
        "wn := NOT(IN := w);",
    )
    r = run_st(src)
    got = {n: r.get(n) for n in ("sum", "prod", "diff", "q", "qr", "m", "mneg", "e", "mv")}
    assert got == {
        "sum": 100008,
        "prod": 1000000,
        "diff": -2,
        "q": -3,
        "qr": 3.5,
        "m": 1,
        "mneg": -1,
        "e": 8.0,
        "mv": 5,
    }
    assert [r.get(n) for n in ("a3", "o3", "x3", "nb")] == [False, True, True, False]
    assert [r.get(n) for n in ("wa", "wo", "wx", "wn")] == [0x0003, 0xF0FF, 0x0FF1, 0xFF00]


def test_operator_functions_have_the_operators_result_types_and_fold():
    checked, found = check_st(
        prog(
            "i : INT; d : DINT; w : WORD; y : BYTE; t : TIME; clock : TOD;\n"
            "vd : DINT; vw : WORD; vt : TIME; vtod : TOD; vc : INT;",
            "vd := ADD(i, d);\nvw := AND(w, y);\nvt := MUL(t, 2);\nvtod := ADD(clock, t);\nvc := SUB(MUL(2, 3, 4), 4);",
        )
    )
    assert found == []
    values = [s.value for s in pou_body(checked)]
    assert [v.ty for v in values] == [T.DINT, T.WORD, T.TIME, T.TOD, T.INT]
    assert values[-1].const == 20  # folded like (2 * 3 * 4) - 4


def test_operator_functions_fold_where_a_constant_is_needed():
    src = (
        "PROGRAM main\nVAR CONSTANT N : INT := MUL(2, 4); END_VAR\n"
        "VAR a : ARRAY[0..ADD(N, 1)] OF INT; total : DINT; END_VAR\n"
        "a[9] := 7;\ntotal := SIZEOF(a) + a[9];\nEND_PROGRAM\n"
    )
    assert run_st(src).get("total") == 27  # 10 INTs of 2 bytes, and a[9]


def test_operator_functions_report_arity_and_type_errors_where_they_are():
    src = prog(
        "i : INT; r : REAL; b : BOOL; w : WORD;",
        "i := ADD(1);\n"
        "i := SUB(1, 2, 3);\n"
        "i := NOT(w, w);\n"
        "i := MOD(r, 2);\n"
        "b := AND(r, TRUE);\n"
        "i := ADD(b, 1);\n"
        "i := MUL(IN1 := 2, IN3 := 3);\n"
        "i := DIV(i, 0);",
    )
    assert [(d.code, d.message, d.pos.line, d.pos.col) for d in diagnostics(src)] == [
        ("E041", "ADD takes at least 2 argument(s), 1 given", 5, 6),
        ("E041", "SUB takes 2 argument(s), 3 given", 6, 6),
        ("E041", "NOT takes 1 argument(s), 2 given", 7, 6),
        ("E023", "MOD needs integers", 8, 6),
        ("E023", "AND needs BOOL or bit-string operands, not REAL and BOOL", 9, 6),
        ("E023", "ADD needs numbers, not BOOL", 10, 10),
        ("E041", "MUL: parameter 'IN2' is missing", 11, 6),
        ("E027", "division by the constant zero", 12, 13),
    ]


def test_the_operator_forms_are_unchanged():
    """a AND (b) is still the operator; NOT (x) is the operator's value."""
    src = prog(
        "a : BOOL := TRUE; b : BOOL; w : WORD := 16#F00F; c : BOOL; d : BOOL; m : INT; v : WORD;",
        "c := a AND (b) OR NOT (b) AND a;\nd := NOT (a) OR NOT(b);\nm := 17 MOD (5);\nv := w AND (NOT (w) OR 16#00F0);",
    )
    r = run_st(src)
    assert (r.get("c"), r.get("d"), r.get("m"), r.get("v")) == (True, True, 2, 0)
