"""JMP and labels (checker_jumps.py, codegen_jumps.py), end to end.

Semantics after CODESYS/TwinCAT ("ST Statement: JMP": ``<label>:
<instructions>`` and ``JMP <label>;``, the label a unique identifier, the
jump forward or back; C0117 "No such label within the scope of the 'JMP'
statement"): a JMP reaches the labels of its own statement list and of the
lists around it, so it may leave an IF, a CASE or a loop but not enter one.
IEC 61131-3 ed.3 has jumps in IL only.
"""

from __future__ import annotations

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.st.faults import STFault

from .conftest import check_st, codes, diagnostics, prog, run_st


def test_a_backward_jump_loops_as_in_the_codesys_example():
    # the CODESYS manual's example: iVar1 counts to 10 through _label1
    src = prog(
        "iVar1 : INT; passes : INT;",
        "iVar1 := 0;\n_label1: iVar1 := iVar1 + 1;\npasses := passes + 1;\n"
        "IF (iVar1 < 10) THEN\n  JMP _label1;\nEND_IF;",
    )
    r = run_st(src, cycles=2)
    assert r.get("iVar1") == 10 and r.get("passes") == 20


def test_a_forward_jump_skips_statements():
    src = prog(
        "a : INT; b : INT; c : INT; skip : BOOL := TRUE;",
        "a := a + 1;\nIF skip THEN JMP later; END_IF;\nb := b + 1;\nlater:\nc := c + 1;\nskip := NOT skip;",
    )
    r = run_st(src, cycles=4)
    assert (r.get("a"), r.get("b"), r.get("c")) == (4, 2, 4)


def test_labels_no_jump_names_change_nothing():
    src = prog("x : INT;", "start: x := x + 1;\nnext_one: x := x * 2;")
    assert run_st(src, cycles=2).get("x") == 6


def test_a_jump_out_of_a_for_loop_keeps_the_loop_variable_like_exit():
    src = prog(
        "i : INT; found : INT; a : ARRAY[1..5] OF INT := [3, 8, 12, 7, 20];",
        "found := 0;\nFOR i := 1 TO 5 DO\n  IF a[i] > 10 THEN JMP done; END_IF;\nEND_FOR;\n"
        "found := -1;\ndone:\nfound := found + i;",
    )
    assert run_st(src).get("found") == 3


def test_a_jump_out_of_nested_loops_back_to_the_start():
    # leaves a WHILE inside a FOR and starts over at the top label
    src = prog(
        "i : INT; k : INT; rounds : INT; total : INT;",
        "rounds := 0; total := 0;\ntop:\nrounds := rounds + 1;\n"
        "FOR i := 1 TO 3 DO\n  k := 0;\n  WHILE k < 5 DO\n    k := k + 1; total := total + 1;\n"
        "    IF k = 2 AND rounds < 3 THEN JMP top; END_IF;\n  END_WHILE;\nEND_FOR;",
    )
    r = run_st(src)
    # rounds 1 and 2 leave after 2 passes each; round 3 runs 3 x 5 passes
    assert (r.get("rounds"), r.get("total"), r.get("i")) == (3, 2 + 2 + 15, 4)


def test_labels_inside_a_loop_body_and_exit_continue_from_there():
    src = prog(
        "i : INT; odd : INT; even : INT;",
        "FOR i := 1 TO 10 DO\n  IF i MOD 2 = 0 THEN JMP is_even; END_IF;\n  odd := odd + 1;\n"
        "  CONTINUE;\n  is_even:\n  even := even + 1;\n  IF i >= 6 THEN EXIT; END_IF;\nEND_FOR;",
    )
    r = run_st(src)
    # 1..6: odd 1, 3, 5; even 2, 4, 6, then EXIT leaves i at 6
    assert (r.get("odd"), r.get("even"), r.get("i")) == (3, 3, 6)


def test_labels_in_an_if_branch_and_a_jump_from_there_to_the_outer_list():
    # the IF branch loops on its own label, then jumps back to the top
    src = prog(
        "n : INT; inner : INT; outer : INT;",
        "top:\nouter := outer + 1;\nIF outer < 3 THEN\n  n := 0;\n  again: n := n + 1; inner := inner + 1;\n"
        "  IF n < 4 THEN JMP again; END_IF;\n  JMP top;\nEND_IF;",
    )
    r = run_st(src)
    assert (r.get("outer"), r.get("inner"), r.get("n")) == (3, 8, 4)


def test_continue_in_a_repeat_from_a_labelled_list_tests_the_condition():
    src = prog(
        "n : INT; hits : INT;",
        "REPEAT\n  n := n + 1;\n  IF n < 3 THEN JMP again; END_IF;\n  CONTINUE;\n  again:\n"
        "  hits := hits + 1;\nUNTIL n >= 5 END_REPEAT;",
    )
    r = run_st(src)
    assert (r.get("n"), r.get("hits")) == (5, 2)


def test_jumps_in_a_function_and_an_fb():
    src = """
FUNCTION fact : DINT
VAR_INPUT n : INT; END_VAR
VAR k : INT; END_VAR
fact := 1; k := n;
again:
IF k <= 1 THEN RETURN; END_IF;
fact := fact * k; k := k - 1;
JMP again;
END_FUNCTION
FUNCTION_BLOCK Skip
VAR_OUTPUT q : INT; END_VAR
JMP over;
q := 100;
over:
q := q + 1;
END_FUNCTION_BLOCK
PROGRAM main
VAR f : DINT; s : Skip; q : INT; END_VAR
f := fact(6);
s();
q := s.q;
END_PROGRAM
"""
    r = run_st(src, cycles=2)
    assert (r.get("f"), r.get("q")) == (720, 2)


def test_an_endless_jump_loop_is_a_watchdog_fault_at_its_label():
    # a backward JMP counts against the loop budget as WHILE does
    r = compile_files([], texts={"w.st": prog("x : DINT;", "x := 0;\nback: x := x + 1;\nJMP back;")}).runner("main")
    r.ctx.watchdog_s = 0.02  # the watchdog counts this thread's CPU time: no host can make it late
    with pytest.raises(STFault) as err:
        r.run(1)
    fault = err.value
    assert fault.kind == "watchdog" and (fault.pos.line, fault.pos.col) == (6, 1)
    assert r.get("x") > 1000


def test_code_without_labels_is_generated_as_before():
    src = prog("x : INT; i : INT;", "FOR i := 1 TO 3 DO x := x + i; END_FOR;")
    text = compile_files([], profile="codesys", texts={"t.st": src}).python_source
    assert "_go" not in text and "_j" not in text


# ---------------------------------------------------------------- errors


def test_a_jump_to_an_unknown_label():
    src = prog("x : INT;", "finish: x := 1;\nJMP finsh;")
    d = next(d for d in diagnostics(src) if d.code == "E075")
    assert (d.pos.line, d.pos.col) == (6, 1)
    assert "no such label" in d.message and "finish" in d.hint


def test_a_jump_into_an_if_is_refused():
    src = prog("x : INT;", "JMP inside;\nIF x > 0 THEN\n  inside: x := 1;\nEND_IF;")
    d = next(d for d in diagnostics(src) if d.code == "E075")
    assert d.pos.line == 5 and "7:3" in d.hint


def test_a_jump_into_a_sibling_if_branch_is_refused():
    src = prog("x : INT;", "IF x > 0 THEN JMP l1; ELSE l1: x := 2; END_IF;")
    assert "E075" in codes(src)


def test_a_label_defined_twice():
    src = prog("x : INT;", "l1: x := 1;\nIF x > 0 THEN\n  l1: x := 2;\nEND_IF;")
    d = next(d for d in diagnostics(src) if d.code == "E076")
    assert d.pos.line == 7 and "5:1" in d.hint


def test_labels_belong_to_one_body_each():
    # the same label in the POU and in its action: two bodies, no clash;
    # a JMP cannot reach from the action into the POU's body
    ok = "PROGRAM main\nVAR x : INT; END_VAR\nl1: x := 1;\nACTION A: l1: x := 2; JMP l1; END_ACTION\nEND_PROGRAM"
    assert codes(ok) == []
    bad = "PROGRAM main\nVAR x : INT; END_VAR\nl1: x := 1;\nACTION A: JMP l1; END_ACTION\nEND_PROGRAM"
    assert codes(bad) == ["E075"]


def test_a_name_and_colon_in_a_case_branch_is_still_a_case_label():
    # after a statement of a CASE branch, 'name:' starts the next branch
    # (an enumerator or constant), as before labels existed
    src = """
TYPE Mode : (Off, Slow, Fast); END_TYPE
PROGRAM main
VAR m : Mode := Slow; x : INT; END_VAR
CASE m OF
Off: x := 0;
Slow: x := 1;
Fast: x := 2;
END_CASE;
END_PROGRAM
"""
    checked, diags = check_st(src)
    assert diags == []
    assert run_st(src).get("x") == 1


@pytest.mark.parametrize("profile", ["iec", "matiec"])
def test_jmp_is_e159_where_the_profile_follows_iec_st(profile):
    # IEC 61131-3 ed.3 7.3.3 (Table 72): ST has no jump statement, only IL
    # has JMP; MatIEC's ST follows the standard. CODESYS, TwinCAT (and
    # Schneider) add it to ST.
    src = prog("n : INT;", "again: n := n + 1;\nIF n < 3 THEN JMP again; END_IF;")
    [d] = diagnostics(src, profile)
    assert (d.code, d.pos.line, d.message) == ("E159", 6, "JMP again: IEC 61131-3 ST has no jumps (only IL has JMP)")
    assert d.hint.endswith("the codesys, twincat and schneider profiles accept JMP")
    assert run_st(src, cycles=1, profile="twincat").get("n") == 3
