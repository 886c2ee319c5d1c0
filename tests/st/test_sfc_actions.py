"""SFC actions as a program sees them (checker_sfc.py, codegen_sfc.py,
rt_sfc.ActionFlags), RuSTy-style: a program and its values after N cycles
(10 ms a cycle). The flags are IEC 61131-3 ed.3 6.7.4's: an action's Q (the
output of its action control) and A (the action is executed this cycle:
while Q, and once more as Q falls, its final scan); CODESYS and TwinCAT show
the same as the implicit ``_action.x`` of an IEC action. An ACTION of an
SFC network is an action of its POU too: ``Act();`` inside it and
``inst.Act();`` on an instance run its statements once, as for any ACTION
(CODESYS "Object: Action")."""

from __future__ import annotations

from softplc.runtime.program.variables import locate

from .conftest import codes, diagnostics, run_st


def sfc(network: str, decls: str, body_kind: str = "PROGRAM") -> str:
    return f"{body_kind} main\nVAR\n{decls}\nEND_VAR\n{network}\nEND_{body_kind}\n"


def put(r, path: str, value) -> None:
    holder, attr, _ty = locate(path, (r.instance,))
    setattr(holder, attr, value)


def trace(r, *paths: str, cycles: int) -> list:
    out = []
    for _ in range(cycles):
        r.run(1)
        out.append(tuple(r.get(p) for p in paths))
    return out


FILLING = """
INITIAL_STEP idle: END_STEP
STEP fill: pump(N); END_STEP
TRANSITION FROM idle TO fill := go; END_TRANSITION
TRANSITION FROM fill TO idle := NOT go; END_TRANSITION
ACTION pump:
    runs := runs + 1;
    seen_q := pump.Q;
    seen_a := pump.A;
    IF NOT pump.Q THEN finals := finals + 1; END_IF
END_ACTION
"""
FILLING_VARS = "go, seen_q, seen_a : BOOL; runs, finals : INT;"


def test_q_and_a_follow_the_action_control_and_the_final_scan_sees_q_false():
    # ed.3 6.7.4 / CODESYS: the action runs while Q is TRUE and once more
    # (A TRUE, Q FALSE) in the cycle its Q falls; then neither.
    r = run_st(sfc(FILLING, FILLING_VARS), cycles=2)
    assert (r.get("pump.Q"), r.get("pump.A"), r.get("runs")) == (False, False, 0)
    put(r, "go", True)
    assert trace(r, "pump.Q", "pump.A", "runs", cycles=3) == [(True, True, 1), (True, True, 2), (True, True, 3)]
    put(r, "go", False)
    assert trace(r, "pump.Q", "pump.A", "runs", cycles=2) == [(False, True, 4), (False, False, 4)]
    # inside the action: Q TRUE in the three active cycles, FALSE in its final scan
    assert (r.get("seen_q"), r.get("seen_a"), r.get("finals")) == (False, True, 1)


def test_a_stored_action_keeps_q_after_its_step_and_r_gives_its_final_scan():
    net = """
    INITIAL_STEP a: pump(S); END_STEP
    STEP b: END_STEP
    STEP c: pump(R); END_STEP
    TRANSITION FROM a TO b := a.T >= T#10ms; END_TRANSITION
    TRANSITION FROM b TO c := stop; END_TRANSITION
    ACTION pump: runs := runs + 1; END_ACTION
    """
    r = run_st(sfc(net, "stop : BOOL; runs : INT;"), cycles=3)
    # a at t = 0 and 10 ms sets pump; stored, it runs on in b
    assert (r.get("pump.Q"), r.get("runs"), r.get("b.X")) == (True, 3, True)
    put(r, "stop", True)
    assert trace(r, "pump.Q", "pump.A", "runs", cycles=2) == [(False, True, 4), (False, False, 4)]


def test_a_transition_reads_an_actions_flags():
    net = """
    INITIAL_STEP a: blink(L, T#30ms); END_STEP
    STEP b: END_STEP
    TRANSITION FROM a TO b := a.T >= T#10ms AND NOT blink.Q; END_TRANSITION
    ACTION blink: n := n + 1; END_ACTION
    """
    r = run_st(sfc(net, "n : INT;"), cycles=4)
    # L, 30 ms: Q at t = 0, 10, 20, the final scan at t = 30 (Q FALSE)
    assert (r.get("n"), r.get("a.X")) == (4, True)
    r.run(1)  # t = 40: the transition sees Q FALSE
    assert (r.get("n"), r.get("b.X"), r.get("blink.A")) == (4, True, False)


def test_an_sfc_action_is_called_inside_its_pou_and_on_an_instance():
    # CODESYS: an action of a POU (IEC action of the chart or not) is called
    # like any action; the call runs its statements once, whatever its flags
    src = """
FUNCTION_BLOCK Seq
VAR_INPUT go : BOOL; END_VAR
VAR_OUTPUT n : INT; END_VAR
INITIAL_STEP idle: END_STEP
STEP busy: count(N); END_STEP
TRANSITION FROM idle TO busy := go; END_TRANSITION
TRANSITION FROM busy TO idle := NOT go; END_TRANSITION
ACTION count: n := n + 1; END_ACTION
ACTION reset: n := 0; END_ACTION
END_FUNCTION_BLOCK
PROGRAM main
VAR s : Seq; n : INT; clear : BOOL; END_VAR
s(go := TRUE);
IF clear THEN s.reset(); clear := FALSE; END_IF
s.count();
n := s.n;
END_PROGRAM
"""
    r = run_st(src, cycles=3)
    # each cycle: the chart counts once (busy from the first cycle on), the call once more
    assert r.get("n") == 6
    put(r, "clear", True)
    r.run(1)
    assert r.get("n") == 1  # the chart's count, the reset, then the call's count
    assert r.get("s.reset.Q") is False and r.get("s.count.Q") is True


def test_an_action_calls_another_action_of_the_chart():
    net = """
    INITIAL_STEP a: outer(N); END_STEP
    ACTION outer: inner(); inner(); END_ACTION
    ACTION inner: n := n + 1; END_ACTION
    """
    r = run_st(sfc(net, "n : INT;"), cycles=3)
    assert r.get("n") == 6 and r.get("inner.Q") is False


def test_action_flags_cannot_be_written_and_need_their_name_free():
    net = """
    INITIAL_STEP a: act(N); END_STEP
    ACTION act: act.Q := FALSE; END_ACTION
    """
    found = [(d.code, d.message) for d in diagnostics(sfc(net, "n : INT;"))]
    assert found == [("E157", "'act' is an SFC action: its flags Q and A are set by the action control")]
    # the action's name is its flags variable: a variable of that name is E152
    net = "INITIAL_STEP a: act(N); END_STEP\nACTION act: n := 1; END_ACTION\n"
    assert codes(sfc(net, "n : INT; act : BOOL;")) == ["E152"]
    # a step and an action of one name too
    net = "INITIAL_STEP a: END_STEP\nACTION a: n := 1; END_ACTION\n"
    assert codes(sfc(net, "n : INT;")) == ["E152"]


def test_the_actions_of_an_sfc_pou_may_stand_outside_it_as_codesys_exports_them():
    # CODESYS and TwinCAT export each action of an SFC POU as an object of
    # its own: ACTION Pou.Name: ... END_ACTION after the POU
    src = sfc("INITIAL_STEP a: act(N); END_STEP\n", "n : INT;")
    src += "ACTION main.act: n := n + 2; END_ACTION\n"
    r = run_st(src, cycles=3)
    assert (r.get("n"), r.get("act.Q")) == (6, True)
    # the same name inside and outside is E152
    src = sfc("INITIAL_STEP a: act(N); END_STEP\nACTION act: n := 1; END_ACTION\n", "n : INT;")
    assert codes(src + "ACTION main.act: n := 2; END_ACTION\n") == ["E152"]


def test_a_network_may_open_with_its_actions():
    # the textual SFC elements come in any order (ed.3 6.7, Table 54-56
    # textual forms); an ACTION before the first step is one of the chart's
    net = """
    ACTION count: n := n + 1; END_ACTION
    INITIAL_STEP a: count(N); END_STEP
    """
    r = run_st(sfc(net, "n : INT;"), cycles=3)
    assert (r.get("n"), r.get("count.Q")) == (3, True)


def test_an_action_written_in_sfc_and_statements_before_a_network_are_e158():
    # CODESYS lets an action be an SFC chart of its own; here a POU's body
    # is its only network: E158 with the way around it
    src = sfc("INITIAL_STEP a: seq(N); END_STEP\nACTION seq: INITIAL_STEP x: END_STEP END_ACTION\n", "n : INT;")
    [d] = diagnostics(src)
    assert (d.code, d.pos.line, d.message) == (
        "E158",
        6,
        "ACTION seq is written in SFC: an action's SFC network is not supported",
    )
    assert d.hint == "make the sequence the body of a FUNCTION_BLOCK and call an instance of it in the action"
    src = "FUNCTION_BLOCK fb\nACTION seq:\nINITIAL_STEP x: END_STEP\nEND_ACTION\nEND_FUNCTION_BLOCK\n"
    assert codes(src) == ["E158"]
    src = sfc("n := 1;\nINITIAL_STEP a: END_STEP\n", "n : INT;")
    [d] = diagnostics(src)
    assert (d.code, d.pos.line) == ("E158", 5)
    assert d.message == "statements before an SFC network: a POU's body is either statements or an SFC network"
