"""Generated expressions and references (runtime/st/codegen_exprs.py):
truncating division, MOD's sign, REAL division, bounds, AND/OR evaluation,
REF and pointers."""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import prog, run_st


@pytest.mark.parametrize("a,b,quot,rem", [(-7, 2, -3, -1), (7, -2, -3, 1), (7, 2, 3, 1), (-7, -2, 3, -1)])
def test_integer_division_truncates_and_mod_takes_the_dividends_sign(a, b, quot, rem):
    r = run_st(prog(f"a : DINT := {a}; b : DINT := {b}; q : DINT; m : DINT;", "q := a / b; m := a MOD b;"))
    assert (r.get("q"), r.get("m")) == (quot, rem)


def test_real_division_by_zero_gives_infinity_not_a_fault():
    r = run_st(prog("a : REAL := 1.0; z : REAL; q : REAL;", "q := a / z;"))
    assert r.get("q") == float("inf")


def test_integer_division_by_zero_is_a_fault_with_the_st_location():
    src = prog("a : INT := 1; z : INT; q : INT;", "q := 5;\nq := a / z;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "division"
    assert (err.value.pos.file, err.value.pos.line) == ("test.st", 6)
    assert "test.st:6:" in str(err.value) and "division by zero" in str(err.value)


def test_array_index_out_of_bounds_is_a_fault_not_a_wraparound():
    src = prog("a : ARRAY[1..3] OF INT; i : INT := 0;", "a[i] := 7;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "bounds" and err.value.pos.line == 5
    assert "0" in err.value.message and "1..3" in err.value.message


def test_array_with_non_zero_lower_bound_and_two_dimensions():
    src = prog(
        "a : ARRAY[-2..2, 1..3] OF INT; i : INT; j : INT; s : INT;",
        "FOR i := -2 TO 2 DO FOR j := 1 TO 3 DO a[i, j] := i * 10 + j; END_FOR END_FOR\ns := a[-2, 1] + a[2, 3];",
    )
    r = run_st(src)
    assert r.get("s") == -19 + 23
    assert r.get("a")[0][0] == -19 and r.get("a")[4][2] == 23


def test_and_or_evaluate_both_sides_in_codesys_and_short_circuit_with_and_then():
    src = """
FUNCTION bump : BOOL
VAR_IN_OUT n : INT; END_VAR
n := n + 1; bump := TRUE;
END_FUNCTION
PROGRAM main
VAR n1 : INT; n2 : INT; f : BOOL; x : BOOL; END_VAR
x := f AND bump(n1);
x := f AND_THEN bump(n2);
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("n1") == 1  # evaluated although f is FALSE (CODESYS)
    assert r.get("n2") == 0  # AND_THEN short-circuits


def test_references_and_pointers():
    src = """
PROGRAM main
VAR x : INT := 5; r : REF_TO INT; p : POINTER TO INT; y : INT; isnull : BOOL; arr : ARRAY[1..3] OF INT; END_VAR
r := REF(x); r^ := r^ + 1;
p := ADR(arr[2]); p^ := 42;
y := x;
isnull := r = 0;
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("y") == 6 and r.get("arr") == [0, 42, 0] and r.get("isnull") is False


def test_null_reference_is_a_fault():
    src = prog("r : REF_TO INT; y : INT;", "y := r^;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "reference" and err.value.pos.line == 5
