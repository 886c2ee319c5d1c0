"""Generated expressions and references (runtime/st/codegen/codegen_exprs.py):
truncating division, MOD's sign, REAL division, bounds, AND/OR evaluation,
REF and pointers."""

from __future__ import annotations

import json

import pytest

from softplc.runtime.st.faults import STFault

from ...test_cli import softplc
from ..conftest import prog, run_st


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


def test_an_if_on_the_for_variable_bounds_its_indices_and_nothing_else():
    # inside IF i >= 2 THEN, a[i - 2] is in bounds (no check needed); in the ELSE it is not
    ok = prog(
        "a : ARRAY[0..9] OF INT; s : INT; i : INT;",
        "FOR i := 0 TO 9 DO a[i] := i * i; END_FOR\n"
        "FOR i := 0 TO 9 DO IF i >= 2 AND 7 > i THEN s := s + a[i - 2]; END_IF END_FOR",
    )
    assert run_st(ok).get("s") == sum(k * k for k in range(5))
    bad = prog(
        "a : ARRAY[0..9] OF INT; s : INT; i : INT;",
        "FOR i := 0 TO 9 DO\nIF i >= 2 THEN s := s + a[i - 2]; ELSE s := s + a[i - 2]; END_IF\nEND_FOR",
    )
    with pytest.raises(STFault) as err:
        run_st(bad)
    assert err.value.kind == "bounds" and err.value.pos.line == 6
    assert "-2" in err.value.message and "0..9" in err.value.message


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


def test_and_or_read_a_property_on_the_right_even_when_the_left_decides():
    """A property's getter is a call: CODESYS evaluates both operands of AND
    and OR, so a getter with an effect runs although the left side decides."""
    src = """
FUNCTION_BLOCK Counter
VAR reads : INT; END_VAR
PROPERTY Ready : BOOL
GET
reads := reads + 1;
Ready := TRUE;
END_GET
END_PROPERTY
END_FUNCTION_BLOCK
PROGRAM main
VAR c : Counter; f : BOOL; t : BOOL := TRUE; x : BOOL; y : BOOL; z : BOOL; n : INT; END_VAR
x := f AND c.Ready;
y := t OR c.Ready;
z := f AND_THEN c.Ready;
n := c.reads;
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("n") == 2  # AND and OR read it; AND_THEN does not
    assert (r.get("x"), r.get("y"), r.get("z")) == (False, True, False)


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


def test_null_is_assigned_and_compared_and_zero_means_null():
    src = prog(
        "x : INT := 5; y : INT := 5; r : REF_TO INT; s : REF_TO INT; seen : ARRAY[1..8] OF BOOL;",
        "seen[1] := r = NULL; seen[2] := r = 0;\n"
        "r := REF(x); s := REF(y);\n"
        "seen[3] := r <> NULL; seen[4] := NULL <> r; seen[5] := r = s;\n"
        "s := REF(x); seen[6] := r = s;\n"
        "r := NULL; s := 0; seen[7] := r = NULL AND s = NULL; seen[8] := r <> 0;",
    )
    r = run_st(src)
    assert r.get("seen") == [True, True, True, True, False, True, True, False]
    assert r.get("r") is None and r.get("s") is None


def test_references_to_two_arrays_of_equal_values_differ():
    src = prog(
        "a : ARRAY[1..2] OF INT; b : ARRAY[1..2] OF INT; ra : REF_TO ARRAY[1..2] OF INT;"
        "rb : REF_TO ARRAY[1..2] OF INT; same : BOOL; other : BOOL; v AT %MW2 : INT; m1 : REF_TO INT; m2 : REF_TO INT;"
        "w : BOOL;",
        "ra := REF(a); rb := REF(b); same := ra = REF(a); other := ra = rb;\nm1 := REF(v); m2 := REF(v); w := m1 = m2;",
    )
    r = run_st(src)
    assert (r.get("same"), r.get("other"), r.get("w")) == (True, False, True)


def test_null_as_a_function_argument_and_result():
    src = """
FUNCTION pick : REF_TO INT
VAR_INPUT r : REF_TO INT; END_VAR
IF r = NULL THEN pick := NULL; ELSE pick := r; END_IF
END_FUNCTION
PROGRAM main
VAR x : INT; a : BOOL; b : BOOL; END_VAR
a := pick(NULL) = NULL;
b := pick(REF(x)) = REF(x);
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("a"), r.get("b")) == (True, True)


def test_null_through_the_command_line_runs_instead_of_crashing(tmp_path):
    path = tmp_path / "null.st"
    path.write_text(prog("x : INT; r : REF_TO INT := REF(x); gone : BOOL;", "r := NULL; gone := r = NULL;"))
    for command in ("check", "compile"):
        proc = softplc(command, path)
        assert proc.returncode == 0, proc.stderr
        assert "Traceback" not in proc.stderr + proc.stdout
    proc = softplc("exec", path)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout) == {"x": 0, "r": None, "gone": True}
