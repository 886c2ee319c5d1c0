"""ACTIONs of PROGRAMs and FUNCTION_BLOCKs (checker_actions.py), end to end.

Semantics after CODESYS ("Object: Action"): an action has no variables of
its own and works on those of its POU; it is called ``Act();`` inside the
POU and ``inst.Act(...)`` on an FB instance, where arguments are passed to
the block's inputs and outputs as in a call of the instance
(``Inst.Reset(In := FALSE);``). The textual forms: inside the POU after its
statements (IEC 61131-3 ed.3, Beremiz export) and ``ACTION Pou.Name:`` on
its own (CODESYS/TwinCAT text export).
"""

from __future__ import annotations

from .conftest import codes, diagnostics, run_st

COUNTER = """
FUNCTION_BLOCK Counter
VAR_INPUT step : INT := 1; END_VAR
VAR_OUTPUT count : INT; END_VAR
count := count + step;
ACTION Reset:
    count := 0;
END_ACTION
ACTION Twice:
    count := count + 2 * step;
END_ACTION
END_FUNCTION_BLOCK
"""


def test_an_fb_action_called_on_its_instance_works_on_that_instance():
    src = (
        COUNTER
        + """
PROGRAM main
VAR a : Counter; b : Counter; ra : INT; rb : INT; END_VAR
a();
b(step := 5);
IF a.count = 3 THEN
    a.Reset();
END_IF;
ra := a.count;
rb := b.count;
END_PROGRAM
"""
    )
    r = run_st(src, cycles=4)
    # a counts 1, 2, 3 -> reset to 0 in cycle 3, then 1: b is untouched
    assert r.get("ra") == 1
    assert r.get("rb") == 20


def test_an_action_call_passes_inputs_and_reads_outputs_like_the_instance_call():
    # CODESYS: "arguments can be passed to the input and output variables
    # in the same way as to the function block": Inst.Reset(In := FALSE)
    src = (
        COUNTER
        + """
PROGRAM main
VAR c : Counter; out : INT; END_VAR
c.Twice(step := 10, count => out);
END_PROGRAM
"""
    )
    r = run_st(src, cycles=2)
    assert r.get("out") == 40
    assert r.get("c.step") == 10


def test_an_action_called_inside_its_own_pou_and_from_another_action():
    src = """
PROGRAM main
VAR n : INT; log : INT; END_VAR
n := n + 1;
IF n MOD 2 = 0 THEN
    Even();
END_IF;
ACTION Even:
    log := log + 10;
    Note();
END_ACTION
ACTION Note:
    log := log + 1;
END_ACTION
END_PROGRAM
"""
    r = run_st(src, cycles=5)
    assert r.get("log") == 22  # cycles 2 and 4


def test_top_level_actions_named_with_their_pou_as_codesys_exports_them():
    src = """
FUNCTION_BLOCK Lamp
VAR_OUTPUT on : BOOL; END_VAR
VAR toggles : INT; END_VAR
END_FUNCTION_BLOCK

ACTION Lamp.Toggle:
    on := NOT on;
    toggles := toggles + 1;
END_ACTION

PROGRAM main
VAR l : Lamp; lit : BOOL; cycles : INT; END_VAR
cycles := cycles + 1;
l.Toggle();
lit := l.on;
Count();
END_PROGRAM

ACTION main.Count:
    cycles := cycles + 100;
END_ACTION
"""
    r = run_st(src, cycles=3)
    assert r.get("lit") is True
    assert r.get("cycles") == 303


def test_program_action_qualified_with_its_own_program():
    src = """
PROGRAM main
VAR x : INT; END_VAR
main.Bump();
ACTION Bump: x := x + 7; END_ACTION
END_PROGRAM
"""
    assert run_st(src, cycles=2).get("x") == 14


def test_an_action_with_return_leaves_the_action_only():
    src = """
PROGRAM main
VAR a : INT; b : INT; END_VAR
Part();
b := b + 1;
ACTION Part:
    a := a + 1;
    RETURN;
    a := a + 100;
END_ACTION
END_PROGRAM
"""
    r = run_st(src, cycles=2)
    assert (r.get("a"), r.get("b")) == (2, 2)


def test_a_for_variable_read_by_an_action_called_in_the_loop():
    # the action sees the POU's variables as they are: the loop variable too
    src = """
PROGRAM main
VAR i : INT; s : INT; END_VAR
s := 0;
FOR i := 1 TO 4 DO
    AddI();
END_FOR;
ACTION AddI: s := s + i; END_ACTION
END_PROGRAM
"""
    assert run_st(src).get("s") == 10


def test_var_temp_starts_afresh_in_an_action():
    src = """
FUNCTION_BLOCK Fb
VAR_OUTPUT q : INT; END_VAR
VAR_TEMP t : INT := 5; END_VAR
t := t + 1;
q := t;
ACTION Act:
    t := t + 10;
    q := q + t;
END_ACTION
END_FUNCTION_BLOCK
PROGRAM main
VAR f : Fb; r : INT; END_VAR
f();
f.Act();
r := f.q;
END_PROGRAM
"""
    assert run_st(src).get("r") == 6 + 15


def test_the_word_action_stays_a_name_where_no_action_starts():
    src = """
PROGRAM main
VAR action : INT; jmp : INT; END_VAR
action := action + 1;
jmp := action * 2;
END_PROGRAM
"""
    r = run_st(src, cycles=2)
    assert (r.get("action"), r.get("jmp")) == (2, 4)


# ---------------------------------------------------------------- errors


def _one(src: str, code: str):
    found = [d for d in diagnostics(src) if d.code == code]
    assert found, codes(src)
    return found[0]


def test_unknown_action_of_an_instance():
    d = _one(COUNTER + "PROGRAM main VAR c : Counter; END_VAR c.Reste(); END_PROGRAM", "E013")
    assert "no member 'Reste'" in d.message


def test_top_level_action_of_an_unknown_pou():
    d = _one("FUNCTION_BLOCK Lamp END_FUNCTION_BLOCK\nACTION Lamb.On: ; END_ACTION", "E047")
    assert d.pos.line == 2 and d.pos.col == 8
    assert "no POU 'Lamb'" in d.message and "Lamp" in d.hint


def test_top_level_action_without_its_pou():
    d = _one("ACTION On: ; END_ACTION", "E047")
    assert "ACTION Pou.On" in d.hint


def test_action_of_a_function_is_refused():
    d = _one("FUNCTION f : INT\nf := 1;\nEND_FUNCTION\nACTION f.A: ; END_ACTION", "E047")
    assert "FUNCTION" in d.message


def test_two_actions_of_one_name():
    src = "PROGRAM main\n;\nACTION A: ; END_ACTION\nACTION a: ; END_ACTION\nEND_PROGRAM"
    d = _one(src, "E047")
    assert d.pos.line == 4 and "two actions" in d.message and "3:8" in d.hint


def test_action_named_like_a_variable():
    d = _one("PROGRAM main\nVAR Reset1 : INT; END_VAR\n;\nACTION Reset1: ; END_ACTION\nEND_PROGRAM", "E047")
    assert "a variable and an action" in d.message


def test_qualified_action_inside_a_pou():
    d = _one("PROGRAM main\n;\nACTION main.A: ; END_ACTION\nEND_PROGRAM", "E047")
    assert d.pos.line == 3


def test_arguments_to_an_action_inside_its_pou():
    d = _one("PROGRAM main\nVAR x : INT; END_VAR\nA(x := 1);\nACTION A: ; END_ACTION\nEND_PROGRAM", "E048")
    assert (d.pos.line, d.pos.col) == (3, 1) and "no arguments" in d.message


def test_an_action_call_is_not_a_value():
    src = COUNTER + "PROGRAM main VAR c : Counter; b : BOOL; END_VAR b := c.Reset(); END_PROGRAM"
    d = _one(src, "E048")
    assert "statement" in d.message


def test_a_program_action_from_another_pou():
    # CODESYS allows Prog.Act() anywhere; here programs have no instance a
    # POU can reach (they are started by tasks, E043)
    src = "PROGRAM p\n;\nACTION A: ; END_ACTION\nEND_PROGRAM\nPROGRAM main\np.A();\nEND_PROGRAM"
    d = _one(src, "E048")
    assert d.pos.line == 6 and "inside p" in d.hint


def test_an_action_in_a_function_is_a_syntax_error_that_says_so():
    src = (
        "FUNCTION f : INT\nf := 1;\nACTION A: x := 1; END_ACTION\nEND_FUNCTION\n"
        "PROGRAM main\nVAR y : INT; END_VAR\ny := f();\nEND_PROGRAM"
    )
    [d] = diagnostics(src)  # the parse goes on after END_ACTION
    assert (d.code, d.pos.line) == ("E001", 3)
    assert "only a PROGRAM or FUNCTION_BLOCK has actions" in d.message
