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
