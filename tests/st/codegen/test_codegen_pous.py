"""Generated classes, functions and initial values
(runtime/st/codegen/codegen_pous.py)."""

from __future__ import annotations

import pytest

from softplc.runtime.program import compile_files

from ..conftest import prog, run_st


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


def test_arrays_are_built_from_runs_however_many_elements_they_have():
    src = prog(
        "big : ARRAY[1..200, 1..100, 1..10] OF INT := [100000(1), 7, 99999(2)];\n"
        "pts : ARRAY[1..3, 1..4] OF Point := [(x := 1), 6((x := 5))];",
        "big[200, 100, 10] := big[1, 1, 1] + big[101, 1, 1];",
    )
    src = "TYPE Point : STRUCT x : INT; y : INT := 2; END_STRUCT END_TYPE\n" + src
    program = compile_files([], texts={"test.st": src})
    # the Python that builds the array is as long as its runs, not its elements
    [line] = [ln for ln in program.python_source.splitlines() if "self.v_big =" in ln]
    assert len(line) < 200, line
    r = program.runner("main")
    r.run(1)
    big = r.get("big")
    assert [len(big), len(big[0]), len(big[0][0])] == [200, 100, 10]
    assert (big[99][99][9], big[100][0][0], big[100][0][1], big[199][99][9]) == (1, 7, 2, 8)
    assert big[0][0] is not big[0][1]  # every row its own list
    pts = r.get("pts")
    assert [[p.f_x for p in row] for row in pts] == [[1, 5, 5, 5], [5, 5, 5, 0], [0, 0, 0, 0]]
    assert all(p.f_y == 2 for row in pts for p in row) and pts[0][1] is not pts[0][2]


@pytest.mark.parametrize(
    "body,result",
    [
        ("IF go THEN RETURN; END_IF F := 5;", 0),  # RETURN before the store
        ("F := F + 5;", 5),  # read before the store
        ("n := F + 1; F := n;", 1),
        ("IF go THEN JMP out; END_IF F := 5; out: n := 1;", 0),  # a jump past it
        ("n := 3; F := n * 2;", 6),  # stored first: no default needed
        ("IF go THEN n := 1; END_IF F := n;", 1),
        ("WHILE n < 3 DO n := n + 1; END_WHILE F := n;", 3),
    ],
)
def test_a_functions_result_is_its_default_on_every_way_out_before_it_is_stored(body, result):
    # the default is left out only where the body stores the result first (codegen_locals.stored_first)
    assert _result_of_f(body) == result


def _result_of_f(body: str, n: int = 0) -> int:
    """F(go := TRUE) of a FUNCTION F : INT with the body, an input go, a
    local n starting at n, and an output o if the body stores one."""
    output = "o :=" in body
    src = f"""
FUNCTION F : INT
VAR_INPUT go : BOOL; END_VAR
{"VAR_OUTPUT o : INT; END_VAR" if output else ""}
VAR n : INT := {n}; END_VAR
{body}
END_FUNCTION
PROGRAM main
VAR r : INT; out : INT; END_VAR
r := F(go := TRUE{", o => out" if output else ""});
END_PROGRAM
"""
    return run_st(src).get("r")


@pytest.mark.parametrize(
    "body,result",
    [
        ("F := n + 2;", 3),  # the last statement: returned at once
        ("IF go THEN F := 7; RETURN; END_IF F := 9;", 7),  # before RETURN, and last
        ("IF NOT go THEN F := 7; RETURN; END_IF F := 9;", 9),
        ("F := 4; IF go THEN F := F * 10; END_IF", 40),  # last in a branch: stored, then returned
        ("F := 4; o := F + 1;", 4),  # a VAR_OUTPUT is set before the return
        ("F := 4; WHILE n < 3 DO n := n + 1; F := n; END_WHILE", 3),
    ],
)
def test_a_result_stored_just_before_the_return_is_the_result(body, result):
    assert _result_of_f(body, n=1) == result


def test_a_method_returns_its_last_store_without_a_result_variable():
    src = """
FUNCTION_BLOCK Acc
VAR sum : DINT; END_VAR
METHOD Step : DINT
VAR_INPUT x : DINT; END_VAR
sum := sum + x;
Step := sum;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM main
VAR a : Acc; r : DINT; END_VAR
r := a.Step(x := 5) + a.Step(x := 2);
END_PROGRAM
"""
    program = compile_files([], texts={"test.st": src})
    [step] = [part for part in program.python_source.split("def ") if part.startswith("m_step")]
    assert "r_result" not in step and "return self.v_sum" in step
    r = program.runner("main")
    r.run(1)
    assert r.get("r") == 12  # 5, then 7
