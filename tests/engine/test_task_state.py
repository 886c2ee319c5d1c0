"""The engine's tasks and date as a program's library functions see them
(runtime/program/context.py TaskState, ExecContext.date_ns): the index of
the task in the configuration's order, its cycles, its release time, the
virtual clock's calendar."""

from __future__ import annotations

from softplc.runtime.engine.clock import VirtualClock
from softplc.runtime.program import Library, compile_files
from softplc.runtime.program.context import VIRTUAL_EPOCH_NS

from .conftest import MS, task

SOURCE = """
PROGRAM Fast
VAR idx : DINT; cycles : UDINT; released : LINT; END_VAR
idx := TASK_INDEX(); cycles := TASK_CYCLES(); released := TASK_RELEASE_NS();
END_PROGRAM

PROGRAM Slow
VAR idx : DINT; cycles : UDINT; released : LINT; stamp : LINT; END_VAR
idx := TASK_INDEX(); cycles := TASK_CYCLES(); released := TASK_RELEASE_NS(); stamp := DATE_NS();
END_PROGRAM
"""


def program(tmp_path):
    lib = Library(tmp_path, "Probe", functions="tests.program.context_library")
    return compile_files([], texts={"plant.st": SOURCE}, libraries=[lib])


def test_each_program_sees_the_task_it_runs_in_by_its_configured_index(engines, tmp_path):
    # Slow is configured second but runs first (higher priority): its index stays 2
    e = engines(program(tmp_path), [task("fast", 10, "Fast", priority=5), task("slow", 30, "Slow", priority=1)])
    e.run(cycles=7)  # ticks at 0, 10 .. 60 ms
    assert (e.get("Fast.idx"), e.get("Fast.cycles"), e.get("Fast.released")) == (1, 7, 60 * MS)
    assert (e.get("Slow.idx"), e.get("Slow.cycles"), e.get("Slow.released")) == (2, 3, 60 * MS)


def test_the_date_follows_the_virtual_clock_from_its_epoch(engines, tmp_path):
    epoch = VIRTUAL_EPOCH_NS + 86_400 * 10**9  # 2000-01-02
    e = engines(program(tmp_path), [task("slow", 30, "Slow")], clock=VirtualClock(epoch_ns=epoch))
    e.run(cycles=4)
    assert e.get("Slow.stamp") == epoch + 90 * MS
