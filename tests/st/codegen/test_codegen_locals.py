"""A PROGRAM's scalars in Python locals while its body runs
(runtime/st/codegen/codegen_locals.py): whatever ends the body (its end,
RETURN, a fault), every variable is stored when it ends, and anything that
could read or write a variable while the body runs (an action, a method, a
property, a reference) keeps it in its slot."""

from __future__ import annotations

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.st.faults import STFault

from ..conftest import prog, run_st


def body_of(text: str) -> str:
    """The Python of main's body."""
    src = compile_files([], texts={"test.st": text}).python_source
    cls = src[src.index("class P_main") :].split("\nclass ")[0]
    return cls[cls.index("def __call__") :]


def test_the_loop_works_on_locals_and_stores_them_when_the_body_ends():
    text = prog("i, n : INT; total : DINT;", "n := n + 1; FOR i := 1 TO 10 DO total := total + i * n; END_FOR")
    code = body_of(text)
    # read once when the body starts, stored once in its finally
    assert code.count("self.v_total") == 2 and "finally:\n" in code
    assert "_l_v_total = self.v_total" in code and "self.v_total = _l_v_total" in code
    r = run_st(text, cycles=3)
    assert (r.get("n"), r.get("total"), r.get("i")) == (3, 55 * 6, 11)


def test_a_fault_in_the_body_leaves_what_it_stored_before():
    text = prog(
        "i, n, zero, q : INT;",
        "n := 0;\nFOR i := 1 TO 10 DO\n  n := n + 1;\n  IF i = 5 THEN q := 10 / zero; END_IF\nEND_FOR",
    )
    runner = compile_files([], texts={"test.st": text}).runner("main")
    with pytest.raises(STFault, match="test.st:8:17"):
        runner.run(1)
    assert runner.get("n") == 5


def test_return_stores_the_variables():
    r = run_st(prog("n, m : INT;", "n := 7; m := n + 1;\nIF n > 0 THEN RETURN; END_IF\nn := 8;"))
    assert (r.get("n"), r.get("m")) == (7, 8)


def test_an_action_of_the_program_sees_and_changes_the_variables_at_once():
    text = """
PROGRAM main
VAR n, seen : INT; END_VAR
n := 5;
Show();
n := n + seen;
END_PROGRAM
ACTION main.Show:
seen := n;
n := 100;
END_ACTION
"""
    assert "_l_" not in body_of(text)
    r = run_st(text)
    assert (r.get("seen"), r.get("n")) == (5, 105)


def test_a_method_of_the_program_sees_the_variables_at_once():
    text = """
PROGRAM main
VAR n, m : INT; END_VAR
METHOD Get : INT
Get := n;
END_METHOD
n := 5;
m := Get();
n := n + m;
END_PROGRAM
"""
    r = run_st(text)
    assert (r.get("m"), r.get("n")) == (5, 10)


def test_a_variable_reached_through_its_address_stays_in_its_slot():
    text = prog("n, m : INT; p : POINTER TO INT;", "n := 5; p := ADR(n); p^ := 9; m := n; n := n + 1;")
    assert "_l_v_n" not in body_of(text)
    r = run_st(text)
    assert (r.get("m"), r.get("n")) == (9, 10)
