"""The collector is off while a program is checked or compiled, and as it
was before once that ends, errors or not."""

import gc

import pytest

from softplc.runtime.collector import collector_off
from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import CompileError

GOOD = "PROGRAM Main VAR n : INT; END_VAR n := n + 1; END_PROGRAM"
BAD = "PROGRAM Main VAR n : INT; END_VAR n := nope + 1; END_PROGRAM"


@pytest.fixture
def collector_on():
    was = gc.isenabled()
    gc.enable()
    yield
    if not was:
        gc.disable()


def test_off_inside_and_on_again_after(collector_on):
    with collector_off():
        assert not gc.isenabled()
    assert gc.isenabled()


def test_left_off_when_it_was_off(collector_on):
    gc.disable()
    with collector_off():
        assert not gc.isenabled()
    assert not gc.isenabled()


def test_on_again_when_the_block_raises(collector_on):
    with pytest.raises(ZeroDivisionError), collector_off():
        _ = 1 / 0
    assert gc.isenabled()


def test_a_compile_runs_with_it_off_and_leaves_it_on(collector_on):
    seen = []
    gc.callbacks.append(lambda phase, info: seen.append(phase))
    try:
        program = compile_files([], texts={"main.st": GOOD})
        during = list(seen)
    finally:
        gc.callbacks.pop()
    # none while it compiled; one may come as it ends, for what it left
    assert during.count("start") <= 1
    runner = program.runner("Main")
    runner.run(3)
    assert runner.get("n") == 3
    assert gc.isenabled()


def test_a_failed_compile_and_a_check_leave_it_on(collector_on):
    with pytest.raises(CompileError):
        compile_files([], texts={"main.st": BAD})
    assert gc.isenabled()
    diagnostics, _sources = check_files([], texts={"main.st": BAD})
    assert [d.code for d in diagnostics if d.is_error]
    assert gc.isenabled()
