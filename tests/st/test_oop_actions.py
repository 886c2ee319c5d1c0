"""ACTIONs inherited through EXTENDS (runtime/st/check/oop.py find_action,
checker_actions.py, codegen_oop.py _action_invoke).

CODESYS "Extension of a Function Block": the derived block receives its
base's methods, actions, properties and transitions and may overwrite
them ("overwriting methods, actions, attributes, and transitions that are
inherited by the base block"). So `derived.BaseAction()` and
`BaseAction()` inside the derived block run the base's action on the
derived instance; an action the derived block overwrites runs in its
place (also from the base's body, as a method would), and
`SUPER^.Action()` runs the base's own."""

from __future__ import annotations

from .conftest import diagnostics, run_st

BLOCKS = """
FUNCTION_BLOCK FB_Base
VAR_INPUT k : INT; END_VAR
VAR_OUTPUT n : INT; END_VAR
Bump();
ACTION Reset:
n := 0;
END_ACTION
ACTION Bump:
n := n + 1;
END_ACTION
ACTION AddK:
n := n + k;
END_ACTION
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Derived EXTENDS FB_Base
VAR_OUTPUT m : INT; END_VAR
SUPER^();                         (* the base's body: its Bump() is this block's *)
m := n;
ACTION Bump:                      (* overwrites FB_Base.Bump *)
n := n + 100;
END_ACTION
ACTION ResetAndBaseBump:
Reset();                          (* inherited *)
SUPER^.Bump();                    (* the base's own *)
END_ACTION
END_FUNCTION_BLOCK
"""


def test_inherited_actions_run_on_the_derived_instance():
    src = (
        BLOCKS
        + """
PROGRAM main
VAR b : FB_Base; d : FB_Derived; a1, a2, a3, a4, bn : INT; END_VAR
d.Reset();
d();                              (* SUPER^() -> Bump() of FB_Derived: + 100 *)
a1 := d.m;
d.AddK(k := 5);                   (* an inherited action with the block's inputs *)
a2 := d.n;
d.ResetAndBaseBump();
a3 := d.n;
d.Bump();
a4 := d.n;
b(); bn := b.n;                   (* the base alone keeps its own Bump *)
END_PROGRAM
"""
    )
    r = run_st(src, cycles=2)
    assert (r.get("a1"), r.get("a2"), r.get("a3"), r.get("a4"), r.get("bn")) == (100, 105, 1, 101, 2)


def test_an_action_no_block_of_the_chain_has_is_still_refused():
    src = (
        BLOCKS
        + """
PROGRAM main
VAR b : FB_Base; END_VAR
b.ResetAndBaseBump();             (* FB_Derived's, not FB_Base's *)
END_PROGRAM
"""
    )
    assert [(d.code, d.pos.line) for d in diagnostics(src)] == [("E013", 31)]
