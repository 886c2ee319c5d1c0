"""SFC in its textual form: parsing and the checker's diagnostics
(runtime/st/syntax/build_sfc.py, checker_sfc.py; IEC 61131-3 ed.3 6.7)."""

from __future__ import annotations

import pytest

from .conftest import check_st, codes


def sfc(network: str, decls: str = "x : BOOL; n : INT; lamp : BOOL;", kind: str = "PROGRAM") -> str:
    return f"{kind} main\nVAR\n{decls}\nEND_VAR\n{network}\nEND_{kind}\n"


GOOD = """
INITIAL_STEP idle: lamp(N); END_STEP
STEP run: count(N); blink(L, T#2s); END_STEP
TRANSITION FROM idle TO run := x; END_TRANSITION
TRANSITION go_back FROM run TO idle : go_back := n > 3; END_TRANSITION
ACTION count: n := n + 1; END_ACTION
ACTION blink: lamp := NOT lamp; END_ACTION
"""


def test_a_network_with_steps_transitions_and_actions_checks_clean():
    checked, diags = check_st(sfc(GOOD))
    assert diags == []
    main = next(p for p in checked.pous if p.name == "main")
    assert [s.name for s in main.sfc.steps] == ["idle", "run"]
    assert [a.name for a in main.sfc.actions] == ["count", "blink", "lamp"]
    # the steps are variables of the program, of the step type (X, T)
    assert {"IDLE", "RUN"} <= set(main.vars)


def test_the_sfc_keywords_stay_names_in_statements():
    # soft keywords: a variable called step or action is still a variable
    src = sfc("step := step + 1; action := step > 2; transition := action;", "step : INT; action, transition : BOOL;")
    assert check_st(src)[1] == []


def test_a_function_block_may_have_an_sfc_body_a_function_may_not():
    assert check_st(sfc(GOOD, kind="FUNCTION_BLOCK"))[1] == []
    src = "FUNCTION f : INT\nINITIAL_STEP a: END_STEP\nEND_FUNCTION\n"
    assert "E005" in codes(src)


@pytest.mark.parametrize(
    ("network", "code", "words"),
    [
        ("STEP a: END_STEP", "E150", "no INITIAL_STEP"),
        (
            "INITIAL_STEP a: END_STEP INITIAL_STEP b: END_STEP TRANSITION FROM a TO b := x; END_TRANSITION",
            "E150",
            "second INITIAL_STEP 'b'",
        ),
        ("INITIAL_STEP a: END_STEP TRANSITION FROM a TO c := x; END_TRANSITION", "E151", "'c', which is not a step"),
        ("INITIAL_STEP a: END_STEP TRANSITION FROM (a, zz) TO a := x; END_TRANSITION", "E151", "'zz'"),
        ("INITIAL_STEP a: END_STEP STEP a: END_STEP", "E152", "'a' is declared twice"),
        ("INITIAL_STEP x: END_STEP", "E152", "'x' is declared twice"),
        (
            "INITIAL_STEP a: END_STEP STEP b: END_STEP TRANSITION FROM a TO b := n; END_TRANSITION",
            "E153",
            "must be BOOL, not INT",
        ),
        ("INITIAL_STEP a: nothing(N); END_STEP", "E154", "no action 'nothing'"),
        ("INITIAL_STEP a: n(N); END_STEP", "E154", "'n' is INT"),
        ("INITIAL_STEP a: lamp(Q); END_STEP", "E155", "starts with its qualifier"),
        ("INITIAL_STEP a: lamp(L); END_STEP", "E155", "L takes a duration"),
        ("INITIAL_STEP a: lamp(SD); END_STEP", "E155", "SD takes a duration"),
        ("INITIAL_STEP a: lamp(D, n); END_STEP", "E155", "must be TIME, not INT"),
        ("INITIAL_STEP a: lamp(N, T#1s); END_STEP", "E155", "N takes no duration"),
        ("INITIAL_STEP a: END_STEP STEP b: END_STEP", "W150", "'b' is never reached"),
        ("INITIAL_STEP a: END_STEP ACTION act: a.X := TRUE; END_ACTION", "E157", "'a' is an SFC step"),
        ("INITIAL_STEP a: act(N); END_STEP ACTION act: IF x THEN RETURN; END_IF END_ACTION", "E156", "in an ACTION"),
        ("INITIAL_STEP a: END_STEP TRANSITION t FROM a TO a : RETURN; END_TRANSITION", "E156", "in a TRANSITION"),
    ],
)
def test_diagnostics(network, code, words):
    _checked, diags = check_st(sfc(network))
    found = [d for d in diags if d.code == code]
    assert found, [str(d) for d in diags]
    assert words in found[0].message + " " + (found[0].hint or "")


def test_a_convergence_is_reached_only_when_all_its_steps_are():
    # c needs a and b active together; b is never reached, so neither is c
    net = """
    INITIAL_STEP a: END_STEP
    STEP b: END_STEP
    STEP c: END_STEP
    TRANSITION FROM (a, b) TO c := x; END_TRANSITION
    """
    unreachable = sorted(d.message for d in check_st(sfc(net))[1] if d.code == "W150")
    assert unreachable == [
        "step 'b' is never reached from the initial step",
        "step 'c' is never reached from the initial step",
    ]


def test_a_statement_transition_needs_a_name():
    net = "INITIAL_STEP a: END_STEP TRANSITION FROM a TO a : x := TRUE; END_TRANSITION"
    assert "E001" in codes(sfc(net))


def test_a_step_is_read_with_its_flags():
    net = """
    INITIAL_STEP a: END_STEP
    STEP b: END_STEP
    TRANSITION FROM a TO b := a.T >= T#1s AND NOT b.X; END_TRANSITION
    TRANSITION FROM b TO a := b.Y; END_TRANSITION
    """
    diags = check_st(sfc(net))[1]
    assert [(d.code, d.message) for d in diags] == [("E013", "SFC_STEP has no field 'Y'")]
