"""METHODs and PROPERTYs of PROGRAMs (runtime/st/check/checker_oop.py
program_named, codegen_oop.py).

CODESYS ("Object Method", "Object Property"): a PROGRAM may have methods
and properties like a FUNCTION_BLOCK; inside it they are called as `M()`,
from any other POU as `Prog.M()` / `Prog.P`. A PROGRAM is one instance in
CODESYS, so `Prog.M()` reaches the instance its task runs; a program that
no task runs exists all the same (created at its first use here)."""

from __future__ import annotations

from softplc.testing import PLC

from .conftest import diagnostics, run_st

COUNTER = """
PROGRAM Counter
VAR n : INT; calls : INT; END_VAR
METHOD Add : INT
VAR_INPUT k : INT; END_VAR
n := n + k;
Add := n;
END_METHOD
METHOD PRIVATE Bump
calls := calls + 1;
END_METHOD
PROPERTY Total : INT
GET Total := n; END_GET
SET n := Total; END_SET
END_PROPERTY
Bump();
Add(k := 100);                   (* a method inside its program *)
END_PROGRAM
"""


def test_program_methods_reach_the_instance_its_task_runs():
    src = (
        COUNTER
        + """
PROGRAM Reader
VAR seen, after : INT; END_VAR
seen := Counter.Total;           (* after Counter's body this cycle *)
after := Counter.Add(k := 1);
Counter.Total := Counter.Total * 2;
END_PROGRAM
CONFIGURATION Plant
  RESOURCE Cpu ON PLC
    TASK Main (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM cnt WITH Main : Counter;
    PROGRAM rd WITH Main : Reader;
  END_RESOURCE
END_CONFIGURATION
"""
    )
    plc = PLC.from_st(src)
    plc.start()
    plc.step()
    # cycle 1: Counter 0 + 100; Reader sees 100, adds 1 (101), doubles (202)
    assert (plc["rd.seen"], plc["rd.after"], plc["cnt.n"]) == (100, 101, 202)
    plc.step()
    # cycle 2: 202 + 100 = 302, + 1 = 303, doubled 606
    assert (plc["rd.seen"], plc["rd.after"], plc["cnt.n"], plc["cnt.calls"]) == (302, 303, 606, 2)


def test_a_program_no_task_runs_is_created_at_its_first_use():
    src = (
        COUNTER
        + """
PROGRAM main
VAR a, t : INT; END_VAR
a := Counter.Add(k := 2);        (* Counter's body never runs: no task calls it *)
t := Counter.Total;
END_PROGRAM
"""
    )
    r = run_st(src, cycles=3)
    assert (r.get("a"), r.get("t")) == (6, 6)


def test_methods_after_end_program_belong_to_it():
    # TwinCAT exports a POU's methods after its END_ keyword
    src = """
PROGRAM main
VAR x : INT; END_VAR
x := Twice(x + 1);
END_PROGRAM
METHOD Twice : INT
VAR_INPUT v : INT; END_VAR
Twice := v * 2;
END_METHOD
"""
    assert run_st(src, cycles=2).get("x") == 6  # (0 + 1) * 2, then (2 + 1) * 2


def test_private_program_methods_and_this_are_refused():
    src = (
        COUNTER
        + """
PROGRAM main
VAR a : INT; END_VAR
Counter.Bump();                  (* PRIVATE: only inside Counter *)
a := THIS^.a;                    (* a PROGRAM has no THIS^ *)
END_PROGRAM
"""
    )
    assert [(d.code, d.pos.line) for d in diagnostics(src)] == [("E144", 22), ("E146", 23)]
