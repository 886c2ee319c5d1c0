"""The pytest plugin installed with softplc (entry point pytest11): the
fixtures plc and plc_factory, the marker softplc (registered, so
--strict-markers passes), the teardown that leaves no thread behind, and the
trace in the report of a failed test."""

from __future__ import annotations

import gc
from pathlib import Path

import pytest

from softplc.runtime.testing import pytest_plugin

pytest_plugins = ["pytester"]

PROGRAM = """
PROGRAM Main
VAR go : BOOL; count : INT; END_VAR
IF go THEN count := count + 1; END_IF;
END_PROGRAM
"""


@pytest.fixture
def suite(pytester: pytest.Pytester):
    pytester.makefile(".st", main=PROGRAM)
    pytester.makeini("[pytest]\naddopts = --strict-markers -p no:cacheprovider\n")
    return pytester


def test_the_marker_builds_the_plc_and_the_teardown_stops_it(suite):
    suite.makepyfile(
        """
        import threading
        import pytest

        BEFORE = set()

        def test_first():
            BEFORE.update(threading.enumerate())

        @pytest.mark.softplc(st="main.st", watch=["Main.count"], cycle="20ms")
        def test_runs(plc):
            plc.write("Main.go", True)
            plc.run_for("1s")
            assert plc["Main.count"] == 50
            assert plc.trace.values("Main.count")[-1] == 50

        def test_factory(plc_factory):
            a = plc_factory(st=["main.st"])
            b = plc_factory(st='''PROGRAM Other VAR x : INT; END_VAR x := x + 2; END_PROGRAM''')
            a.step(3)
            b.step(3)
            assert (a["Main.count"], b["Other.x"]) == (0, 6)

        def test_no_thread_left():
            assert set(threading.enumerate()) <= BEFORE
        """
    )
    result = suite.runpytest_subprocess()
    result.assert_outcomes(passed=4)


def test_a_failed_test_reports_the_trace(suite):
    suite.makepyfile(
        """
        import pytest

        @pytest.mark.softplc(st="main.st", watch=["Main.go", "Main.count"])
        def test_fails(plc):
            plc.script([("30ms", "Main.go", True)])
            plc.run_for("60ms")
            assert plc["Main.count"] == 99
        """
    )
    result = suite.runpytest_subprocess()
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(
        [
            "*softplc trace (PLC 1, t=0.060s)*",
            "time*Main.go*Main.count",
            "0.000s*False*0",
            "0.030s*True*1",
            "0.050s*True*3",
        ]
    )


def test_without_a_marker_plc_is_the_default_plant(suite):
    suite.makepyfile(
        """
        def test_default(plc):
            assert set(plc.sims) == {"ltmr40", "fc28020", "da1_1"}
            assert plc["Motor.state"] == "Stopped"
        """
    )
    result = suite.runpytest_subprocess()
    result.assert_outcomes(passed=1)


def test_a_bad_marker_is_a_usage_error(suite):
    suite.makepyfile(
        """
        import pytest

        @pytest.mark.softplc(config="plant.toml", st="main.st")
        def test_both(plc):
            pass
        """
    )
    result = suite.runpytest_subprocess()
    result.stdout.fnmatch_lines(["*softplc: give config or st, not both*"])
    assert result.ret != 0


@pytest.fixture
def passes():
    """The garbage collector's passes while the test runs (their generations), with it on."""
    seen: list[int] = []

    def count(phase: str, info: dict) -> None:
        if phase == "start":
            seen.append(info["generation"])

    was_on = gc.isenabled()
    gc.enable()
    gc.callbacks.append(count)
    yield seen
    gc.callbacks.remove(count)
    if not was_on:
        gc.disable()


def test_the_build_runs_without_a_garbage_collection(passes, tmp_path: Path, monkeypatch):
    """The imports, the compile and the engine's build allocate mostly what
    stays alive: the collector is held off meanwhile (runtime/collector.py)."""
    during: list[int] = []
    built = pytest_plugin._built

    def observed(*args, **kwargs):
        first = len(passes)  # held off from here (a pass may have come before the build)
        try:
            return built(*args, **kwargs)
        finally:
            during.extend(passes[first:])  # still held off: the pass due comes after the build

    monkeypatch.setattr(pytest_plugin, "_built", observed)
    plc = pytest_plugin._build(tmp_path, st=PROGRAM)
    try:
        plc["Main.go"] = True
        plc.step(2)
        assert plc["Main.count"] == 2
    finally:
        plc.stop()
    assert during == []
    assert gc.isenabled()


def test_the_same_build_would_collect_with_the_collector_on(passes, tmp_path: Path):
    """What the test above proves: a PLC's build allocates enough to set the collector off."""
    gc.collect()
    plc = pytest_plugin._built(tmp_path, st=PROGRAM.replace("Main", "Other"))
    plc.stop()
    assert passes
