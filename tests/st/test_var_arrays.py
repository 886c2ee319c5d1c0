"""Variable-length arrays: ARRAY[*] parameters with LOWER_BOUND and
UPPER_BOUND (runtime/st/check/checker_arrays.py, rt_varray.py).

IEC 61131-3 ed.3 6.5.4 and CODESYS/TwinCAT ("Array with variable length"):
an ARRAY[*] is declared in VAR_IN_OUT of a FUNCTION, FUNCTION_BLOCK or
method; it takes an array of any bounds with its element type and number
of dimensions, is indexed with the caller's indices, and LOWER_BOUND(arr,
dim) / UPPER_BOUND(arr, dim) give those bounds (DINT). CODESYS 3.5.14 and
later accept the two operators on fixed arrays too.
"""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import codes, diagnostics, prog, run_st

SUM = """
FUNCTION SumOf : DINT
VAR_IN_OUT arr : ARRAY[*] OF INT; END_VAR
VAR i : DINT; END_VAR
FOR i := LOWER_BOUND(arr, 1) TO UPPER_BOUND(arr, 1) DO
    SumOf := SumOf + arr[i];
END_FOR
arr[LOWER_BOUND(arr, 1)] := 0;  (* by reference: the caller's first element *)
END_FUNCTION
"""


def test_a_function_sums_arrays_of_any_bounds_with_their_own_indices():
    src = SUM + prog(
        "a : ARRAY[1..3] OF INT := [1, 2, 3]; b : ARRAY[-2..2] OF INT := [10, 20, 30, 40, 50];"
        "sa : DINT; sb : DINT; lo : DINT; hi : DINT;",
        "sa := SumOf(a);\nsb := SumOf(arr := b);\nlo := LOWER_BOUND(b, 1);\nhi := UPPER_BOUND(b, 1);",
    )
    runner = run_st(src)
    assert (runner.get("sa"), runner.get("sb")) == (6, 150)
    # a[1] and b[-2], the first elements, are 0 now
    assert (runner.get("a"), runner.get("b")) == ([0, 2, 3], [0, 20, 30, 40, 50])
    assert (runner.get("lo"), runner.get("hi")) == (-2, 2)


def test_two_dimensions_and_a_function_block_passing_it_on():
    src = """
FUNCTION_BLOCK Grid
VAR_IN_OUT m : ARRAY[*, *] OF REAL; END_VAR
VAR_OUTPUT rows : DINT; cols : DINT; corner : REAL; total : DINT; END_VAR
rows := UPPER_BOUND(m, 1) - LOWER_BOUND(m, 1) + 1;
cols := UPPER_BOUND(m, 2) - LOWER_BOUND(m, 2) + 1;
corner := m[UPPER_BOUND(m, 1), UPPER_BOUND(m, 2)];
m[LOWER_BOUND(m, 1), LOWER_BOUND(m, 2)] := 9.5;
total := Cells(m);
END_FUNCTION_BLOCK

FUNCTION Cells : DINT
VAR_IN_OUT x : ARRAY[*, *] OF REAL; END_VAR
Cells := (UPPER_BOUND(x, 1) - LOWER_BOUND(x, 1) + 1) * (UPPER_BOUND(x, 2) - LOWER_BOUND(x, 2) + 1);
END_FUNCTION
""" + prog(
        "g : Grid; m : ARRAY[0..1, 5..7] OF REAL := [1.0, 2.0, 3.0, 4.0, 5.0, 6.0];",
        "g(m := m);",
    )
    runner = run_st(src)
    assert (runner.get("g.rows"), runner.get("g.cols"), runner.get("g.corner"), runner.get("g.total")) == (
        2,
        3,
        6.0,
        6,
    )
    assert runner.get("m")[0][0] == 9.5  # m[0, 5]


def test_an_index_outside_the_callers_bounds_is_a_bounds_fault():
    src = """
FUNCTION At : INT
VAR_IN_OUT arr : ARRAY[*] OF INT; END_VAR
VAR_INPUT i : DINT; END_VAR
At := arr[i];
END_FUNCTION
""" + prog("a : ARRAY[1..3] OF INT := [5, 6, 7]; r : INT; n : DINT := 1;", "r := At(a, n);\nn := n + 3;")
    runner = run_st(src)
    assert runner.get("r") == 5
    with pytest.raises(STFault) as err:
        runner.run(1)  # At(a, 4): beyond 1..3
    assert err.value.kind == "bounds" and err.value.pos.line == 5
    assert "4" in err.value.message and "1..3" in err.value.message


def test_bounds_of_a_fixed_array_are_constants():
    src = prog(
        "a : ARRAY[3..9, -1..1] OF BOOL; l2 : DINT; u1 : DINT;", "l2 := LOWER_BOUND(a, 2);\nu1 := UPPER_BOUND(a, 1);"
    )
    runner = run_st(src)
    assert (runner.get("l2"), runner.get("u1")) == (-1, 9)


def test_bounds_errors_are_coded():
    src = prog(
        "a : ARRAY[1..3] OF INT; i : INT; d : INT := 1;",
        "i := LOWER_BOUND(a, 2);\ni := UPPER_BOUND(i, 1);\ni := LOWER_BOUND(a, d);\ni := UPPER_BOUND(a);",
    )
    found = [(d.code, d.pos.line, d.pos.col) for d in diagnostics(src)]
    assert found == [("E057", 5, 21), ("E057", 6, 18), ("E057", 7, 21), ("E041", 8, 6)]
    assert all(d.hint for d in diagnostics(src))


def test_array_star_outside_var_in_out_is_e050():
    src = "FUNCTION F : INT\nVAR_INPUT a : ARRAY[*] OF INT; END_VAR\nF := 1;\nEND_FUNCTION\n"
    assert codes(src) == ["E050"]
