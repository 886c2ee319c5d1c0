"""While the scan runs on the real clock, Python's switch interval is
SCAN_SWITCH_S (engine/clock.py RealClock.scanning): a thread that computes
lets go of the interpreter lock 1 ms after the scan asked for it, not 5 ms
(benchmarks/bench_soak_live.py measures what it does to the late ticks). It
is the caller's again once run() returns, and virtual time leaves it alone."""

from __future__ import annotations

import sys

import pytest

from softplc.runtime.engine.clock import SCAN_SWITCH_S, RealClock

from .conftest import task

SRC = "PROGRAM Main\nVAR n : DINT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"


@pytest.fixture
def default_switch():
    before = sys.getswitchinterval()
    sys.setswitchinterval(0.005)  # Python's default, whatever an earlier test left
    yield 0.005
    sys.setswitchinterval(before)


def _seen_while_scanning(engine) -> list:
    seen: list = []
    engine.before_tick.append(lambda _e: seen.append(sys.getswitchinterval()))
    engine.run(cycles=3)
    return seen


def test_the_real_clock_s_scan_runs_with_a_1_ms_switch_interval_and_gives_it_back(engines, default_switch):
    engine = engines(SRC, [task("Main", 1, "Main")], clock=RealClock())
    assert SCAN_SWITCH_S == pytest.approx(0.001)
    assert _seen_while_scanning(engine) == [pytest.approx(SCAN_SWITCH_S)] * 3
    assert sys.getswitchinterval() == pytest.approx(default_switch)


def test_a_shorter_interval_of_the_caller_s_is_kept(engines, default_switch):
    sys.setswitchinterval(0.0002)
    engine = engines(SRC, [task("Main", 1, "Main")], clock=RealClock())
    assert _seen_while_scanning(engine) == [pytest.approx(0.0002, abs=2e-6)] * 3  # kept in whole µs


def test_virtual_time_leaves_the_switch_interval_alone(engines, default_switch):
    engine = engines(SRC, [task("Main", 1, "Main")])
    assert _seen_while_scanning(engine) == [pytest.approx(default_switch)] * 3
