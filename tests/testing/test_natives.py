"""The assertion functions: what they accept at compile time, what a
failure records (file:line:column, both values as ST literals)."""

from __future__ import annotations

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.faults import STFault
from softplc.runtime.testing.natives import NATIVES, SERVICE, Recorder

DECLS = """\
TYPE E_Light : (Off, Green, Red); END_TYPE
PROGRAM main
VAR
    i : INT := 41; d : DINT := 41; r : REAL := 2.5; lr : LREAL := 0.1; s : STRING := 'abc';
    t : TIME := T#1s500ms; e : E_Light := Green; w : WORD := 16#FF; ok : BOOL;
END_VAR
"""


def run(body: str, cycles: int = 1) -> tuple:
    """Run body (it starts on line 7) under a Recorder; (recorder, runner)."""
    program = compile_files([], texts={"t.st": DECLS + body + "\nEND_PROGRAM\n"}, natives=NATIVES)
    runner = program.runner("main")
    recorder = Recorder()
    runner.ctx.services[SERVICE] = recorder
    runner.run(cycles)
    return recorder, runner


@pytest.mark.parametrize(
    "call",
    [
        "ASSERT_TRUE(i = 41, 'm')",
        "ASSERT_FALSE(i = 42, 'm')",
        "ASSERT_EQUAL(41, i, 'm')",
        "ASSERT_EQUAL(i, d, 'm')",
        "ASSERT_EQUAL(2.5, r, 'm')",
        "ASSERT_EQUAL(T#1.5s, t, 'm')",
        "ASSERT_EQUAL('abc', s, 'm')",
        "ASSERT_EQUAL(E_Light#Green, e, 'm')",
        "ASSERT_EQUAL(16#FF, w, 'm')",
        "ASSERT_EQUAL(TRUE, i > 0, 'm')",
        "ASSERT_NOT_EQUAL(0, i, 'm')",
        "ASSERT_NEAR(2.4, r, 0.1001, 'm')",
        "ASSERT_NEAR(0.3, lr * 3.0, 1.0E-9, 'm')",
        "ASSERT_NEAR(41, i, 0, 'm')",
    ],
)
def test_an_assertion_that_holds_records_nothing_and_returns_true(call):
    recorder, runner = run(f"ok := {call};")
    assert recorder.failures == [] and recorder.asserts == 1
    assert runner.get("ok") is True


@pytest.mark.parametrize(
    "call, expected, actual",
    [
        ("ASSERT_TRUE(i > 41, 'msg')", "TRUE", "FALSE"),
        ("ASSERT_FALSE(i = 41, 'msg')", "FALSE", "TRUE"),
        ("ASSERT_EQUAL(42, i, 'msg')", "42", "41"),
        ("ASSERT_EQUAL(2.25, r, 'msg')", "2.25", "2.5"),
        ("ASSERT_EQUAL(T#2s, t, 'msg')", "T#2s", "T#1s500ms"),
        ("ASSERT_EQUAL('abd', s, 'msg')", "'abd'", "'abc'"),
        ("ASSERT_EQUAL(E_Light#Red, e, 'msg')", "E_Light#Red", "E_Light#Green"),
        ("ASSERT_NOT_EQUAL(41, i, 'msg')", "not 41", "41"),
        ("ASSERT_NEAR(2.0, r, 0.25, 'msg')", "2.0 +/- 0.25", "2.5"),
    ],
)
def test_a_failed_assertion_records_where_the_message_and_both_values(call, expected, actual):
    recorder, runner = run(f"ok := TRUE;\n    ok := {call};")
    (failure,) = recorder.failures
    assert (str(failure.site), failure.message) == ("t.st:8:11", "msg")
    assert (failure.expected, failure.actual) == (expected, actual)
    assert failure.function == call.split("(")[0]
    assert runner.get("ok") is False
    assert failure.describe() == (
        f"t.st:8:11: {failure.function} failed: msg\n  expected: {expected}\n  actual:   {actual}"
    )


def test_every_failure_of_a_cycle_is_recorded_and_test_finished_is_seen():
    recorder, _ = run("ASSERT_EQUAL(1, i, 'one');\nASSERT_EQUAL(2, i, 'two');\nTEST_FINISHED();")
    assert [(f.site.line, f.message) for f in recorder.failures] == [(7, "one"), (8, "two")]
    assert recorder.finished


def test_a_nan_is_never_near():
    recorder, _ = run("lr := 0.0; lr := lr / lr;\nASSERT_NEAR(0.0, lr, 1.0E30, 'nan');")
    assert [(f.expected, f.actual) for f in recorder.failures] == [("0.0 +/- 1.0E+30", "NAN")]


@pytest.mark.parametrize(
    "call, message",
    [
        ("ASSERT_EQUAL(e, i, 'm')", "arguments of types E_Light and INT do not match"),
        ("ASSERT_TRUE(i, 'm')", "ASSERT_TRUE: the condition (argument 1) must be a BOOL"),
        ("ASSERT_NEAR(t, t, t, 'm')", "ASSERT_NEAR: Expected (argument 1) must be a REAL or LREAL"),
        ("ASSERT_EQUAL(1, i)", "ASSERT_EQUAL takes 3 positional arguments"),
        ("ASSERT_TRUE(ok, 5)", "ASSERT_TRUE: the message (argument 2) must be a STRING"),
    ],
)
def test_a_wrong_assertion_is_a_compile_error_at_its_place(call, message):
    diags, _ = check_files([], texts={"t.st": DECLS + f"ok := {call};\nEND_PROGRAM\n"}, natives=NATIVES)
    errors = [(d.message, d.pos.line) for d in diags if d.is_error]
    assert (message, 7) in errors, errors


def test_the_assertions_exist_only_where_the_runner_compiles_them():
    diags, _ = check_files([], texts={"t.st": DECLS + "ASSERT_TRUE(ok, 'm');\nEND_PROGRAM\n"})
    assert [(d.code, d.message) for d in diags if d.is_error] == [("E043", "unknown function 'ASSERT_TRUE'")]


def test_without_the_runner_an_assertion_is_a_runtime_fault_that_says_so():
    program = compile_files([], texts={"t.st": DECLS + "ASSERT_TRUE(ok, 'm');\nEND_PROGRAM\n"}, natives=NATIVES)
    with pytest.raises(STFault, match="runs only under the test runner"):
        program.runner("main").run(1)
