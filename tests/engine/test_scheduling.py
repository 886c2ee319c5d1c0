"""Task scheduling on the virtual clock: priority order at each tick,
intervals, several program instances per task, freewheeling tasks, and IEC
timers reading the clock of the task they run in; the real clock's spin."""

from __future__ import annotations

import pytest

from softplc.runtime.config import DEFAULT_SPIN_NS, load_config
from softplc.runtime.engine.build import build_engine
from softplc.runtime.engine.clock import RealClock

from .conftest import MS, task

RECORDER = """
VAR_GLOBAL
    who : ARRAY[0..99] OF INT;     (* program ids in the order they ran *)
    stamp : ARRAY[0..99] OF TIME;  (* TIME() when they ran *)
    n : INT;
END_VAR

FUNCTION Log : BOOL
VAR_INPUT id : INT; END_VAR
IF n <= 99 THEN
    who[n] := id;
    stamp[n] := TIME();
    n := n + 1;
END_IF
END_FUNCTION

PROGRAM A
Log(1);
END_PROGRAM

PROGRAM B
Log(2);
END_PROGRAM

PROGRAM C
Log(3);
END_PROGRAM
"""


def _log(engine) -> list:
    n = engine.get("n")
    who, stamp = engine.get("who"), engine.get("stamp")
    return [(stamp[i], who[i]) for i in range(n)]


def test_due_tasks_run_in_priority_order_then_declaration_order(engines):
    # Slow has the higher priority (0) and runs first whenever both are due;
    # Fast runs its two programs in the order they are listed.
    e = engines(RECORDER, [task("Fast", 10, "B", "C", priority=2), task("Slow", 30, "A", priority=0)])
    e.run(duration_ns=60 * MS)
    assert _log(e) == [
        (0, 1),
        (0, 2),
        (0, 3),
        (10, 2),
        (10, 3),
        (20, 2),
        (20, 3),
        (30, 1),
        (30, 2),
        (30, 3),
        (40, 2),
        (40, 3),
        (50, 2),
        (50, 3),
    ]
    assert e.clock.now_ns() == 60 * MS


def test_equal_priorities_run_in_declaration_order(engines):
    e = engines(RECORDER, [task("T2", 10, "B", priority=3), task("T1", 10, "A", priority=3)])
    e.run(cycles=2)
    assert [who for _t, who in _log(e)] == [2, 1, 2, 1]


def test_interval_counts_over_one_second(engines):
    e = engines(RECORDER, [task("Fast", 10, "A"), task("Slow", 30, "B")])
    e.run(duration_ns=1000 * MS)
    # Fast: releases 0, 10, ... 990 ms; Slow: 0, 30, ... 990 ms
    assert [t.stats.cycles for t in e.tasks] == [100, 34]
    # The virtual clock is never late and a cycle takes no virtual time.
    assert all(t.stats.jitter_max_ns == 0 and t.stats.overruns == 0 for t in e.tasks)
    assert e.cycle == 100  # ticks: every Slow release coincides with a Fast one (0, 30, 60 ...)


def test_ticks_happen_at_the_union_of_the_releases(engines):
    e = engines(RECORDER, [task("T7", 7, "A"), task("T5", 5, "B")])
    e.run(duration_ns=21 * MS)
    assert _log(e) == [(0, 1), (0, 2), (5, 2), (7, 1), (10, 2), (14, 1), (15, 2), (20, 2)]


def test_several_instances_of_one_program_keep_their_own_state(engines):
    src = """
    PROGRAM Counter
    VAR n : INT; END_VAR
    n := n + 1;
    END_PROGRAM
    """
    e = engines(src, [task("Fast", 10, ("Left", "Counter")), task("Slow", 20, ("Right", "Counter"))])
    e.run(duration_ns=100 * MS)
    assert e.get("Left.n") == 10
    assert e.get("Right.n") == 5


def test_freewheeling_task_runs_again_after_its_pause(engines):
    e = engines(RECORDER, [task("Cyclic", 10, "A", priority=0), task("Free", None, "B", priority=5, pause_ms=3)])
    e.run(duration_ns=12 * MS)
    assert _log(e) == [(0, 1), (0, 2), (3, 2), (6, 2), (9, 2), (10, 1)]


TIMERS = """
VAR_GLOBAL
    doneAt10, doneAt20, doneAt30 : TIME;
END_VAR

PROGRAM P10
VAR t : TON; END_VAR
t(IN := TRUE, PT := T#50ms);
IF t.Q AND doneAt10 = T#0s THEN doneAt10 := TIME(); END_IF
END_PROGRAM

PROGRAM P20
VAR t : TON; END_VAR
t(IN := TRUE, PT := T#50ms);
IF t.Q AND doneAt20 = T#0s THEN doneAt20 := TIME(); END_IF
END_PROGRAM

PROGRAM P30
VAR t : TON; ET : TIME; END_VAR
t(IN := TRUE, PT := T#50ms);
ET := t.ET;
IF t.Q AND doneAt30 = T#0s THEN doneAt30 := TIME(); END_IF
END_PROGRAM
"""


def test_timers_read_the_clock_of_their_task(engines):
    # The same T#50ms TON elapses at the first release of its task at or
    # after 50 ms: 50 ms in a 10 ms task, 60 ms in 20 ms and 30 ms tasks.
    e = engines(TIMERS, [task("T10", 10, "P10"), task("T20", 20, "P20"), task("T30", 30, "P30")])
    e.run(duration_ns=35 * MS)
    assert e.get("P30.ET") == 30  # its second call, at 30 ms
    e.run(duration_ns=65 * MS)
    assert (e.get("doneAt10"), e.get("doneAt20"), e.get("doneAt30")) == (50, 60, 60)


@pytest.mark.realtime  # on the real clock
def test_real_clock_runs_the_same_schedule():
    # Counts only: how late the real clock is never decides this test.
    from .conftest import make_engine

    e = make_engine(RECORDER, [task("Fast", 2, "A"), task("Slow", 4, "B")], clock=RealClock())
    try:
        e.run(cycles=4)
    finally:
        e.stop()
    assert sum(t.stats.cycles for t in e.tasks) >= 5
    assert [who for _t, who in _log(e)][:2] == [1, 2]


@pytest.mark.parametrize("spin, ns", [(None, DEFAULT_SPIN_NS), ('"0.2ms"', 200_000), ("0", 0)])
def test_the_real_clock_spins_as_long_as_plc_spin_says(tmp_path, spin, ns):
    (tmp_path / "a.st").write_text("PROGRAM A\nEND_PROGRAM\n")
    (tmp_path / "plant.toml").write_text('[plc]\nprograms = ["a.st"]\n' + (f"spin = {spin}\n" if spin else ""))
    engine = build_engine(load_config(tmp_path / "plant.toml"))
    assert isinstance(engine.clock, RealClock) and engine.clock.spin_ns == ns
    assert build_engine(load_config(tmp_path / "plant.toml"), virtual_time=True).clock.virtual


def test_the_first_scan_is_released_when_the_scans_begin_not_at_start():
    """softplc run starts the engine (the program, the drivers) and then sets
    up its servers, traces and file watcher before the first scan: each
    task's first release was start()'s time, so that set-up counted as
    overruns of every task at each start (the live soak: a life's first
    ticks late by 20 ms). Now the first release is when run() begins."""
    import time

    from .conftest import make_engine

    e = make_engine(RECORDER, [task("Slow", 100, "A")], clock=RealClock())
    try:
        e.start()
        time.sleep(0.35)  # the set-up: three and a half periods
        e.run(cycles=1)
    finally:
        e.stop()
    assert e.tasks[0].stats.cycles == 1
    assert e.tasks[0].stats.overruns == 0
