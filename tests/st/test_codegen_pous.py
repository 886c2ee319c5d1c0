"""Generated classes, functions and initial values
(runtime/st/codegen_pous.py)."""

from __future__ import annotations

from .conftest import prog, run_st


def test_array_initialiser_with_repetition():
    r = run_st(prog("a : ARRAY[0..5] OF INT := [1, 2, 3(7)];", ""))
    assert r.get("a") == [1, 2, 7, 7, 7, 0]


def test_var_temp_starts_afresh_at_every_call_and_var_output_keeps_its_value():
    src = """
FUNCTION_BLOCK Cnt
VAR_TEMP t : INT := 5; END_VAR
VAR_OUTPUT keep : INT; END_VAR
t := t + 1; keep := keep + t;
END_FUNCTION_BLOCK
PROGRAM main
VAR c : Cnt; k : INT; END_VAR
c(); k := c.keep;
END_PROGRAM
"""
    r = run_st(src, cycles=2)
    assert r.get("k") == 12


REF_INITIALISERS = """
VAR_GLOBAL
    inst : Holder;
    gx : INT := 7;
    gr : REF_TO INT := REF(gx);
    table : ARRAY[1..3] OF INT := [1, 2, 3];
END_VAR
FUNCTION_BLOCK Holder
VAR_OUTPUT
    own : REF_TO INT := REF(x);
    x : INT := 3;
    elem : REF_TO INT := REF(a[2]);
    a : ARRAY[1..3] OF INT := [4, 5, 6];
    whole : REF_TO ARRAY[1..3] OF INT := REF(table);
END_VAR
own^ := own^ + 1;
END_FUNCTION_BLOCK
FUNCTION Twice : INT
VAR
    r : REF_TO INT := REF(y);
    y : INT := 20;
END_VAR
r^ := r^ * 2;
Twice := y;
END_FUNCTION
PROGRAM main
VAR
    r : REF_TO INT := REF(x);
    x : INT := 5;
    h : Holder;
    got : ARRAY[1..6] OF INT;
END_VAR
VAR_TEMP
    t : REF_TO INT := REF(x);
END_VAR
h();
got[1] := r^; got[2] := h.x; got[3] := h.elem^; got[4] := h.whole^[3]; got[5] := Twice(); got[6] := gr^ + t^;
IF inst.whole = REF(table) AND inst.own <> NULL THEN x := x + 100; END_IF
END_PROGRAM
"""


def test_a_reference_initialiser_points_at_its_variable_from_the_start():
    r = run_st(REF_INITIALISERS)
    assert r.get("got") == [5, 4, 5, 3, 40, 12]
    assert r.get("x") == 105  # the global instance's references point into itself and at the global table
