"""Facts along a body (runtime/st/codegen/codegen_facts.py): what earlier
statements tell of an integer's value lets a store skip its wrap, and an
index its bounds check. Each test below would store a value outside the
variable's type, or miss an out-of-bounds fault, if a fact outlived what it
was true for: a call that reaches the variable, a loop's back edge, a jump,
a join of branches."""

from __future__ import annotations

import re

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.st.faults import STFault

from ..conftest import prog, run_st


def source(text: str) -> str:
    return compile_files([], texts={"test.st": text}).python_source


def test_a_sum_of_straight_line_increments_is_stored_without_a_wrap():
    # the benchmarks' timers program: 0 plus at most one per IF
    text = prog(
        "t1, t2 : TON; running : INT; total : DINT; c : CTU;",
        "running := 0; total := 0;\n"
        "t1(IN := TRUE, PT := T#1ms); c(CU := t1.Q, PV := 3);\n"
        "IF t1.Q THEN running := running + 1; END_IF\n"
        "t2(IN := TRUE, PT := T#1ms);\n"
        "IF t2.Q THEN running := running + 1; END_IF\n"
        "total := total + c.CV;",
    )
    code = source(text)
    # in its slot or in a local (codegen_locals.py), stored without a wrap
    assert re.search(r"(\S*v_running) = \(\1 \+ 1\)\n", code)
    assert re.search(r"(\S*v_total) = \(\1 \+ \S+v_cv\)\n", code)
    r = run_st(text, cycles=3)
    assert (r.get("running"), r.get("total")) == (2, 1)


def test_a_guard_bounds_the_value_in_its_branch():
    # CTU (fblocks/iec): ELSIF ... CV < 32767 THEN CV := CV + 1 needs no wrap
    code = source(prog("c : CTU;", "c(CU := TRUE);"))
    assert "self.v_cv = (self.v_cv + 1)" in code
    text = prog("x : INT := 32760; n : INT;", "IF n > 100 THEN n := 0; ELSIF x < 32767 THEN x := x + 1; END_IF")
    assert run_st(text, cycles=10).get("x") == 32767


@pytest.mark.parametrize(
    "body,x",
    [
        # the join of IF and CASE: the way taken (go is TRUE) stores 32767, the others less
        ("x := 32767; IF NOT go THEN x := 0; END_IF x := x + 1;", -32768),
        ("IF go THEN x := 32767; ELSE x := 5; END_IF x := x + 1;", -32768),
        ("IF go THEN x := 32767; ELSIF NOT go THEN x := 5; END_IF x := x + 1;", -32768),
        ("CASE k + 2 OF 2: x := 32767; 1: x := 5; END_CASE x := x + 1;", -32768),
        ("CASE k + 2 OF 2: x := 32767; ELSE x := 5; END_CASE x := x + 1;", -32768),
        # a loop runs its body again with what it stored
        ("x := 0; WHILE k < 2 DO x := x + 16384; k := k + 1; END_WHILE", -32768),
        ("x := 0; REPEAT x := x + 16384; k := k + 1; UNTIL k >= 2 END_REPEAT", -32768),
        ("x := 0; FOR j := 1 TO 2 DO x := x + 16384; END_FOR", -32768),
        # a jump comes back to its label with another value
        ("x := 0; IF go THEN again: x := x + 1; IF k < 1 THEN k := 1; x := 32767; JMP again; END_IF END_IF", -32768),
        # a bit written into x is a store to x: -32768, less one
        ("x := 0; x.15 := TRUE; x := x - 1;", 32767),
    ],
)
def test_what_a_branch_loop_or_jump_stores_is_not_forgotten(body, x):
    r = run_st(prog("x, k, j : INT; go : BOOL := TRUE;", body))
    assert r.get("x") == x


def block_n(members: str, body: str, before: str = "", var: str = "") -> int:
    """n of an FB_Acc with the members and body given (n : INT declared),
    after one call from main."""
    text = f"""{before}
FUNCTION_BLOCK FB_Acc
VAR n : INT; {var} END_VAR
{members}
{body}
END_FUNCTION_BLOCK
PROGRAM main
VAR a : FB_Acc; x : INT; END_VAR
a();
x := a.n;
END_PROGRAM
"""
    return run_st(text).get("x")


def test_a_method_call_forgets_what_was_known_of_the_blocks_variables():
    assert block_n("METHOD Fill\nn := 32767;\nEND_METHOD", "n := 0; THIS^.Fill(); n := n + 1;") == -32768


def test_a_property_setter_forgets_what_was_known_of_the_blocks_variables():
    prop = "PROPERTY Level : INT\nGET Level := n; END_GET\nSET n := 32767; END_SET\nEND_PROPERTY"
    assert block_n(prop, "n := 0; Level := 1; n := n + 1;") == -32768


def test_a_call_through_a_reference_to_the_instance_forgets_its_variables():
    # B holds a reference to the block and fills its counter while the block's body runs
    helper = "FUNCTION_BLOCK FB_B\nVAR owner : REFERENCE TO FB_Acc; END_VAR\nowner.Fill();\nEND_FUNCTION_BLOCK"
    body = "helper.owner REF= THIS^; n := 0; helper(); n := n + 1;"
    assert block_n("METHOD Fill\nn := 32767;\nEND_METHOD", body, before=helper, var="helper : FB_B;") == -32768


def test_a_programs_action_or_method_may_change_its_variables():
    action = """
PROGRAM main
VAR x : INT; END_VAR
x := 0;
Fill();
x := x + 1;
END_PROGRAM
ACTION main.Fill:
x := 32767;
END_ACTION
"""
    assert run_st(action).get("x") == -32768
    method = """
PROGRAM main
VAR x : INT; END_VAR
METHOD Fill
x := 32767;
END_METHOD
x := 0;
Fill();
x := x + 1;
END_PROGRAM
"""
    assert run_st(method).get("x") == -32768


def test_a_variable_passed_by_reference_keeps_no_fact():
    text = """
FUNCTION Fill : BOOL
VAR_IN_OUT v : INT; END_VAR
v := 32767;
Fill := TRUE;
END_FUNCTION
PROGRAM main
VAR x : INT; p : POINTER TO INT; y : INT; END_VAR
x := 0;
Fill(v := x);
x := x + 1;
y := 0;
p := ADR(y);
p^ := 32767;
y := y + 1;
END_PROGRAM
"""
    r = run_st(text)
    assert (r.get("x"), r.get("y")) == (-32768, -32768)


def test_an_assignment_inside_a_condition_forgets_what_was_known():
    text = prog("x : INT; ok : BOOL;", "x := 0; IF (x := 32767) > 0 AND x < 10 THEN ok := TRUE; END_IF x := x + 1;")
    r = run_st(text)
    assert (r.get("x"), r.get("ok")) == (-32768, False)


def test_a_condition_that_calls_code_narrows_nothing():
    method = "METHOD Fill : BOOL\nn := 32767;\nFill := TRUE;\nEND_METHOD"
    assert block_n(method, "n := 0;\nIF n < 10 AND Fill() THEN\n    n := n + 1;\nEND_IF") == -32768


def test_an_index_known_in_range_is_read_and_one_maybe_out_of_range_is_checked():
    ok = prog("a : ARRAY[0..9] OF INT; i : INT; v : INT;", "i := 3; a[i] := 7; v := a[i];")
    assert "_out_of_bounds" not in source(ok).split("class P_main")[1]
    assert run_st(ok).get("v") == 7
    bad = prog("a : ARRAY[0..9] OF INT; i : INT; go : BOOL := TRUE;", "i := 3; IF go THEN i := 10; END_IF a[i] := 1;")
    with pytest.raises(STFault, match="10"):
        run_st(bad)
