"""background(): the switch interval lowered while any background work runs,
Python's again when the last one ends, whatever the order they end in."""

import sys
import threading
import time

import pytest

from softplc.runtime.engine import lock_share
from softplc.runtime.engine.clock import RealClock
from softplc.runtime.engine.lock_share import SWITCH_S, background, pause

from .conftest import task

PROGRAM = """
PROGRAM Main
VAR n : DINT; END_VAR
n := n + 1;
END_PROGRAM
"""


def test_the_interval_is_lowered_inside_and_put_back_after():
    before = sys.getswitchinterval()
    with background():
        assert sys.getswitchinterval() == min(before, SWITCH_S)
    assert sys.getswitchinterval() == before


def test_two_threads_overlapping_leave_the_interval_as_it_was():
    # thread a enters, b enters, a leaves while b still works, then b:
    # two plain save-and-restore blocks left it at 0.5 ms for good
    before = sys.getswitchinterval()
    a_in, b_in, a_out = threading.Event(), threading.Event(), threading.Event()
    seen = {}

    def a() -> None:
        with background():
            a_in.set()
            b_in.wait(5)
        a_out.set()

    def b() -> None:
        a_in.wait(5)
        with background():
            b_in.set()
            a_out.wait(5)
            seen["after a left"] = sys.getswitchinterval()

    threads = [threading.Thread(target=a), threading.Thread(target=b)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(10)
    assert seen["after a left"] == min(before, SWITCH_S)
    assert sys.getswitchinterval() == before


def test_an_exception_inside_puts_the_interval_back():
    before = sys.getswitchinterval()
    try:
        with background():
            raise ValueError("boom")
    except ValueError:
        pass
    assert sys.getswitchinterval() == before


# ---------------------------------------------------------------- the gate: background work in the scan's idle


@pytest.fixture
def gate(monkeypatch):
    """The gate as a scan leaves it; open again afterwards. STARVE_S long:
    here a shut gate stays shut until the test's scan opens it."""
    monkeypatch.setattr(lock_share, "STARVE_S", 60.0)
    yield
    lock_share.scan_ends()


def _shut() -> None:
    """What the scan thread does when it goes idle for 1 ms: the window
    closes at once (MARGIN_NS before it wakes) and stays shut, as while it runs."""
    lock_share.scan_sleeps(time.perf_counter_ns() + lock_share.MARGIN_NS + 1_000_000)
    time.sleep(0.002)


def _paused_in_thread() -> tuple[threading.Thread, threading.Event]:
    went_on = threading.Event()

    def work() -> None:
        with background():
            went_on.set()

    thread = threading.Thread(target=work, daemon=True)
    thread.start()
    return thread, went_on


def test_background_work_waits_while_the_scan_runs_and_goes_on_when_it_sleeps(gate):
    _shut()
    thread, went_on = _paused_in_thread()
    assert not went_on.wait(0.2)  # the scan "runs": it has not gone idle since
    lock_share.scan_sleeps(time.perf_counter_ns() + 10_000_000_000)  # idle for 10 s
    assert went_on.wait(5)
    thread.join(5)


def test_work_begun_in_the_scan_idle_goes_on_step_after_step(gate):
    lock_share.scan_sleeps(time.perf_counter_ns() + 10_000_000_000)  # idle for 10 s
    steps = []

    def work() -> None:
        for n in range(1000):
            pause()
            steps.append(n)

    thread = threading.Thread(target=work, daemon=True)
    thread.start()
    thread.join(5)  # one wait would be STARVE_S: a minute
    assert len(steps) == 1000


def test_the_scan_s_own_thread_never_waits(gate):
    _shut()  # this thread is the scan's now
    with background():  # a program read back by the scan itself, a capture of a test's tick
        pause()
        # (had it waited, STARVE_S: a minute)


def test_the_gate_opens_when_the_engine_stops_scanning(gate):
    _shut()
    thread, went_on = _paused_in_thread()
    assert not went_on.wait(0.1)
    lock_share.scan_ends()
    assert went_on.wait(5)
    thread.join(5)


def test_a_scan_that_leaves_no_window_holds_background_work_back_for_starve_s_only(monkeypatch):
    monkeypatch.setattr(lock_share, "STARVE_S", 0.05)
    try:
        _shut()
        lock_share.scan_sleeps(time.perf_counter_ns() - 1)  # late already: no window, the gate stays shut
        thread, went_on = _paused_in_thread()
        assert went_on.wait(5)  # after 50 ms, beside the scan, as before there was a gate
        thread.join(5)
    finally:
        lock_share.scan_ends()


def test_after_a_long_idle_the_gate_holds_while_the_scan_runs(monkeypatch):
    # a task of a long period (here: 0.6 s idle): its tick ran with the gate
    # open when STARVE_S was counted from the window's opening, not its close
    monkeypatch.setattr(lock_share, "STARVE_S", 0.5)
    try:
        lock_share.scan_sleeps(time.perf_counter_ns() + lock_share.MARGIN_NS + 600_000_000)
        time.sleep(0.65)  # the window closed 50 ms ago, opened 650 ms ago: the scan "runs"
        thread, went_on = _paused_in_thread()
        assert not went_on.wait(0.2)
        assert went_on.wait(5)  # half a second after the close: beside the scan, as before the gate
        thread.join(5)
    finally:
        lock_share.scan_ends()


def test_a_real_time_scan_leaves_the_gate_open_when_it_ends(gate, engines):
    engine = engines(PROGRAM, [task("Main", 10, "Main")], clock=RealClock(spin_ns=0))
    engine.run(cycles=3)
    thread, went_on = _paused_in_thread()
    assert went_on.wait(5)
    thread.join(5)


def test_a_step_that_cannot_be_cut_waits_for_a_window_with_room_for_it(gate):
    # the unpickler's memo freed after a read-back: one C call of some 4 ms
    lock_share.scan_sleeps(time.perf_counter_ns() + lock_share.MARGIN_NS + 50_000_000)  # 50 ms of idle
    went_on = threading.Event()

    def work() -> None:
        pause(room_ns=5_000_000_000)  # 5 s: more than this window has
        went_on.set()

    thread = threading.Thread(target=work, daemon=True)
    thread.start()
    assert not went_on.wait(0.2)
    lock_share.scan_sleeps(time.perf_counter_ns() + 10_000_000_000)  # 10 s of idle: room enough
    assert went_on.wait(5)
    thread.join(5)
