"""FB_init, FB_exit, FB_reinit (runtime/st/check/checker_oop.py, codegen_oop.py,
rt_oop.py). CODESYS help "Method: FB_Init, FB_Reinit, FB_Exit" and TwinCAT
"Behavior with derived function blocks": FB_init(bInitRetains, bInCopyCode)
runs when an instance is initialised, after its variables have their
initial values and before the first cycle, the base's before the derived
one's; FB_exit(bInCopyCode) runs when the program is taken down, the
derived one's before the base's; FB_reinit is called explicitly here (the
engine has no online change that copies instances)."""

from __future__ import annotations

from .conftest import diagnostics, run_st

LIFE = """
VAR_GLOBAL log : STRING(80); exits : INT; END_VAR
FUNCTION_BLOCK FB_Base
VAR_OUTPUT level : INT := 5; retains, copy : BOOL; END_VAR
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; END_VAR
level := level * 10;            (* the initial value is there already *)
retains := bInitRetains; copy := bInCopyCode;
log := CONCAT(log, 'B');
END_METHOD
METHOD FB_exit : BOOL
VAR_INPUT bInCopyCode : BOOL; END_VAR
exits := exits * 10 + 1;
END_METHOD
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Derived EXTENDS FB_Base
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; bInCopyCode : BOOL; END_VAR
level := level + 1;
log := CONCAT(log, 'D');
END_METHOD
METHOD FB_exit : BOOL
VAR_INPUT bInCopyCode : BOOL; END_VAR
exits := exits * 10 + 2;
END_METHOD
METHOD FB_reinit : BOOL
level := 0;
END_METHOD
END_FUNCTION_BLOCK
PROGRAM main
VAR d : FB_Derived; first : INT; seen : STRING(80); cycles : INT; END_VAR
cycles := cycles + 1;
IF cycles = 1 THEN first := d.level; seen := log; END_IF
END_PROGRAM
"""


def test_fb_init_runs_before_the_first_cycle_base_first():
    r = run_st(LIFE, cycles=2)
    assert r.get("first") == 51 and r.get("seen") == "BD"
    assert (r.get("d.retains"), r.get("d.copy")) == (True, False)
    assert r.get("log") == "BD"  # once, not every cycle


def test_fb_exit_runs_when_the_program_is_taken_down_derived_first():
    r = run_st(LIFE, cycles=1)
    assert r.get("exits") == 0
    r.exit()
    assert r.get("exits") == 21


def test_fb_reinit_is_a_method_to_call():
    src = LIFE.replace("IF cycles = 1", "IF cycles = 2 THEN d.FB_reinit(); END_IF\nIF cycles = 1")
    r = run_st(src, cycles=2)
    assert r.get("d.level") == 0


def test_fb_init_needs_its_two_inputs():
    src = """
FUNCTION_BLOCK FB
METHOD FB_init : BOOL
VAR_INPUT bInitRetains : BOOL; END_VAR
END_METHOD
METHOD FB_exit : BOOL
END_METHOD
END_FUNCTION_BLOCK
"""
    got = [(d.code, d.pos.line) for d in diagnostics(src)]
    assert got == [("E149", 3), ("E149", 6)]
