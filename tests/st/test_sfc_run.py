"""SFC execution (runtime/st/rtlib/rt_sfc.py, codegen_sfc.py), RuSTy-style: a
program and the values it has after N cycles, in virtual time (10 ms a
cycle, the first at t = 0). The rules are IEC 61131-3 ed.3 6.7.5 (rules of
evolution) and 6.7.4 (actions and their control; ed.2 2.6.5, 2.6.4)."""

from __future__ import annotations

from softplc.runtime.program.variables import locate

from .conftest import run_st


def sfc(network: str, decls: str) -> str:
    return f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{network}\nEND_PROGRAM\n"


def put(r, path: str, value) -> None:
    holder, attr, _ty = locate(path, (r.instance,))
    setattr(holder, attr, value)


def active(r, *steps: str) -> list:
    return [s for s in steps if r.get(f"{s}.X")]


CHAIN = """
INITIAL_STEP a: END_STEP
STEP b: END_STEP
STEP c: END_STEP
TRANSITION FROM a TO b := TRUE; END_TRANSITION
TRANSITION FROM b TO c := TRUE; END_TRANSITION
TRANSITION FROM c TO a := go; END_TRANSITION
"""


def test_the_initial_step_is_active_before_the_first_cycle():
    r = run_st(sfc(CHAIN, "go : BOOL;"), cycles=0)
    assert active(r, "a", "b", "c") == ["a"]


def test_one_evolution_per_cycle():
    # ed.3 6.7.5: the transitions are evaluated with the steps active as the
    # cycle starts; a -> b -> c takes two cycles even with both conditions TRUE
    r = run_st(sfc(CHAIN, "go : BOOL;"), cycles=1)
    assert active(r, "a", "b", "c") == ["b"]
    r.run(1)
    assert active(r, "a", "b", "c") == ["c"]
    r.run(3)
    assert active(r, "a", "b", "c") == ["c"]
    put(r, "go", True)
    r.run(1)
    assert active(r, "a", "b", "c") == ["a"]


def test_step_t_is_the_time_since_activation_and_holds_after_clearing():
    net = """
    INITIAL_STEP a: END_STEP
    STEP b: END_STEP
    TRANSITION FROM a TO b := a.T >= T#50ms; END_TRANSITION
    TRANSITION FROM b TO a := go; END_TRANSITION
    """
    r = run_st(sfc(net, "go : BOOL;"), cycles=5)  # t = 0 .. 40
    assert r.get("a.T") == 40 and active(r, "a", "b") == ["a"]
    r.run(1)  # t = 50: a.T reaches 50 ms, b is activated at T#0s
    assert active(r, "a", "b") == ["b"]
    assert (r.get("a.T"), r.get("b.T")) == (50, 0)
    r.run(3)
    assert (r.get("a.T"), r.get("b.T")) == (50, 30)
    put(r, "go", True)
    r.run(1)  # t = 90: back to a, whose T starts again
    assert (r.get("a.T"), r.get("b.T")) == (0, 40)


def test_simultaneous_divergence_and_convergence():
    net = """
    INITIAL_STEP a: END_STEP
    STEP b1: END_STEP
    STEP b2: END_STEP
    STEP c: END_STEP
    STEP d: END_STEP
    TRANSITION FROM a TO (b1, c) := start; END_TRANSITION
    TRANSITION FROM b1 TO b2 := more; END_TRANSITION
    TRANSITION FROM (b2, c) TO d := TRUE; END_TRANSITION
    TRANSITION FROM d TO a := TRUE; END_TRANSITION
    """
    steps = ("a", "b1", "b2", "c", "d")
    r = run_st(sfc(net, "start, more : BOOL;"), cycles=2)
    assert active(r, *steps) == ["a"]
    put(r, "start", True)
    r.run(1)
    assert active(r, *steps) == ["b1", "c"]
    r.run(2)  # the convergence waits for b2
    assert active(r, *steps) == ["b1", "c"]
    put(r, "more", True)
    r.run(1)
    assert active(r, *steps) == ["b2", "c"]
    r.run(1)  # both active: cleared together
    assert active(r, *steps) == ["d"]


def test_a_selection_divergence_takes_the_highest_priority():
    # lower PRIORITY first; without one, the transitions keep their order (left to right)
    net = """
    INITIAL_STEP a: END_STEP
    STEP b: END_STEP
    STEP c: END_STEP
    STEP e: END_STEP
    TRANSITION (PRIORITY := 2) FROM a TO b := TRUE; END_TRANSITION
    TRANSITION (PRIORITY := 1) FROM a TO c := TRUE; END_TRANSITION
    TRANSITION FROM c TO e := TRUE; END_TRANSITION
    TRANSITION FROM c TO b := TRUE; END_TRANSITION
    """
    r = run_st(sfc(net, ""), cycles=1)
    assert active(r, "a", "b", "c", "e") == ["c"]
    r.run(1)
    assert active(r, "a", "b", "c", "e") == ["e"]


def test_a_transition_that_is_not_enabled_is_not_evaluated():
    # b is never active, so n / zero is never computed (no division fault)
    net = """
    INITIAL_STEP a: END_STEP
    STEP b: END_STEP
    TRANSITION FROM a TO b := FALSE; END_TRANSITION
    TRANSITION FROM b TO a := n / zero > 0; END_TRANSITION
    """
    r = run_st(sfc(net, "n, zero : INT;"), cycles=3)
    assert active(r, "a", "b") == ["a"]


def test_a_transition_written_as_statements():
    net = """
    INITIAL_STEP a: tick(N); END_STEP
    STEP b: END_STEP
    TRANSITION enough FROM a TO b :
        enough := FALSE;
        IF n >= 3 THEN enough := TRUE; END_IF
    END_TRANSITION
    ACTION tick: n := n + 1; END_ACTION
    """
    r = run_st(sfc(net, "n : INT;"), cycles=3)
    assert active(r, "a", "b") == ["a"]
    r.run(1)  # the condition sees n = 3 from the cycles before
    assert active(r, "a", "b") == ["b"]


# ---------------------------------------------------------------- actions

STEPPER = """
INITIAL_STEP a: {a} END_STEP
STEP b: {b} END_STEP
STEP c: {c} END_STEP
TRANSITION FROM a TO b := go_b; END_TRANSITION
TRANSITION FROM b TO c := go_c; END_TRANSITION
TRANSITION FROM c TO a := go_a; END_TRANSITION
ACTION count: n := n + 1; END_ACTION
"""
STEPPER_VARS = "go_b, go_c, go_a, lamp : BOOL; n : INT; hold : TIME := T#30ms;"


def stepper(a: str = "", b: str = "", c: str = "", cycles: int = 0):
    return run_st(sfc(STEPPER.format(a=a, b=b, c=c), STEPPER_VARS), cycles=cycles)


def trace(r, path: str, cycles: int) -> list:
    out = []
    for _ in range(cycles):
        r.run(1)
        out.append(r.get(path))
    return out


def test_n_runs_while_the_step_is_active_and_once_more_after():
    # ed.2 2.6.4 / CODESYS, TwinCAT: an action is executed one last time
    # when its control Q falls
    r = stepper(a="count(N);", cycles=3)
    assert r.get("n") == 3
    put(r, "go_b", True)
    r.run(1)
    assert r.get("n") == 4
    r.run(3)
    assert r.get("n") == 4


def test_a_bool_variable_as_action_follows_q():
    r = stepper(b="lamp(N);")
    put(r, "go_b", True)
    assert trace(r, "lamp", 2) == [True, True]
    put(r, "go_c", True)
    assert trace(r, "lamp", 2) == [False, False]


def test_s_stores_until_r():
    r = stepper(a="lamp(S);", c="lamp(R);", cycles=1)
    assert r.get("lamp") is True
    put(r, "go_b", True)
    r.run(2)  # in b: still set
    assert active(r, "a", "b", "c") == ["b"] and r.get("lamp") is True
    put(r, "go_c", True)
    r.run(1)  # c resets it
    assert r.get("lamp") is False


def test_l_is_limited_to_its_duration():
    # 30 ms: TRUE at t = 0, 10, 20 of the step's activity
    r = stepper(a="lamp(L, T#30ms);")
    assert trace(r, "lamp", 5) == [True, True, True, False, False]


def test_d_is_delayed_by_its_duration_a_variable_duration_works_too():
    r = stepper(a="lamp(D, hold);")
    assert trace(r, "lamp", 5) == [False, False, False, True, True]
    put(r, "go_b", True)
    assert trace(r, "lamp", 1) == [False]


def test_p_pulses_once_and_its_action_runs_twice():
    r = stepper(b="lamp(P); count(P);")
    put(r, "go_b", True)
    assert trace(r, "lamp", 3) == [True, False, False]
    assert r.get("n") == 2  # the pulse and the last execution (CODESYS: "exactly two times")


def test_p1_pulses_on_activation_p0_on_deactivation():
    r = stepper(b="lamp(P0);")
    put(r, "go_b", True)
    assert trace(r, "lamp", 2) == [False, False]
    put(r, "go_c", True)
    assert trace(r, "lamp", 2) == [True, False]
    r = stepper(b="lamp(P1);")
    put(r, "go_b", True)
    assert trace(r, "lamp", 2) == [True, False]


def test_sd_is_stored_then_delayed_and_keeps_running_after_the_step():
    r = stepper(a="lamp(SD, T#30ms);", c="lamp(R);", cycles=1)
    assert r.get("lamp") is False
    put(r, "go_b", True)
    # a is active only in the first cycle (t = 0); the delay runs on in b
    assert trace(r, "lamp", 4) == [False, False, True, True]
    put(r, "go_c", True)
    assert trace(r, "lamp", 1) == [False]


def test_ds_is_delayed_while_the_step_is_active_then_stored():
    r = stepper(a="lamp(DS, T#20ms);", c="lamp(R);")
    assert trace(r, "lamp", 3) == [False, False, True]
    put(r, "go_b", True)
    assert trace(r, "lamp", 2) == [True, True]  # stored
    put(r, "go_c", True)
    assert trace(r, "lamp", 1) == [False]
    # a DS step left before its delay stores nothing
    r = stepper(a="lamp(DS, T#20ms);", cycles=1)
    put(r, "go_b", True)
    assert trace(r, "lamp", 4) == [False, False, False, False]


def test_sl_is_stored_and_limited():
    r = stepper(a="lamp(SL, T#30ms);", cycles=1)
    assert r.get("lamp") is True
    put(r, "go_b", True)  # stored: runs on in b for the rest of its 30 ms
    assert trace(r, "lamp", 4) == [True, True, False, False]


def test_an_action_of_two_steps_runs_once_a_cycle():
    # the association inputs are ORed into one control block (ed.3 6.7.4)
    net = """
    INITIAL_STEP a: END_STEP
    STEP b1: count(N); END_STEP
    STEP b2: count(N); END_STEP
    TRANSITION FROM a TO (b1, b2) := TRUE; END_TRANSITION
    ACTION count: n := n + 1; END_ACTION
    """
    r = run_st(sfc(net, "n : INT;"), cycles=4)
    assert r.get("n") == 4  # not 8


def test_function_block_instances_have_their_own_sequence():
    src = """
FUNCTION_BLOCK Blink
VAR_INPUT enable : BOOL; END_VAR
VAR_OUTPUT out : BOOL; END_VAR
INITIAL_STEP off: END_STEP
STEP on: out(N); END_STEP
TRANSITION FROM off TO on := enable AND off.T >= T#20ms; END_TRANSITION
TRANSITION FROM on TO off := on.T >= T#20ms; END_TRANSITION
END_FUNCTION_BLOCK
PROGRAM main
VAR b1, b2 : Blink; o1, o2 : BOOL; END_VAR
b1(enable := TRUE);
b2(enable := FALSE);
o1 := b1.out;
o2 := b2.out;
END_PROGRAM
"""
    r = run_st(src, cycles=0)
    seen = [(r.run(1), r.get("o1"), r.get("o2"))[1:] for _ in range(8)]
    # off for 20 ms (the initial step counts from the first cycle), on for 20 ms
    assert [o1 for o1, _ in seen] == [False, False, True, True, False, False, True, True]
    assert not any(o2 for _, o2 in seen)
