"""Where the tasks come from (TOML, an ST CONFIGURATION, or the default
MainTask), the errors when they cannot run, and the watchdog sensitivity."""

from __future__ import annotations

import re

import pytest

from softplc.runtime.engine.tasks import TaskSetupError, plan_tasks

from .conftest import MS, compile_st, task

PROGRAMS = """
PROGRAM Fast
VAR n : INT; END_VAR
n := n + 1;
END_PROGRAM

PROGRAM Slow
VAR n : INT; END_VAR
n := n + 1;
END_PROGRAM
"""

CONFIGURATION = (
    PROGRAMS
    + """
CONFIGURATION Plant
    RESOURCE Cpu ON PLC
        TASK Quick(INTERVAL := T#5ms, PRIORITY := 0);
        TASK Lazy(INTERVAL := T#50ms, PRIORITY := 3);
        PROGRAM A WITH Quick : Fast;
        PROGRAM B WITH Lazy : Slow;
        PROGRAM C WITH Quick : Slow;
    END_RESOURCE
END_CONFIGURATION
"""
)


def test_tasks_from_the_st_configuration(engines):
    program = compile_st(CONFIGURATION)
    tasks = plan_tasks(program, [])
    assert [(t.name, t.interval_ns, t.priority, [p.instance for p in t.programs]) for t in tasks] == [
        ("Quick", 5 * MS, 0, ["A", "C"]),
        ("Lazy", 50 * MS, 3, ["B"]),
    ]
    e = engines(program, tasks)
    e.run(duration_ns=100 * MS)
    assert (e.get("A.n"), e.get("C.n"), e.get("B.n")) == (20, 20, 2)


def test_without_tasks_every_program_runs_in_a_10ms_main_task(engines):
    program = compile_st(PROGRAMS)
    [main] = plan_tasks(program, [])
    assert (main.name, main.interval_ns, [p.instance for p in main.programs]) == ("MainTask", 10 * MS, ["Fast", "Slow"])
    e = engines(program, [main])
    e.run(duration_ns=100 * MS)
    assert (e.get("Fast.n"), e.get("Slow.n")) == (10, 10)


def test_tasks_in_both_places_are_refused():
    with pytest.raises(TaskSetupError, match="plant.toml: task: the ST sources declare CONFIGURATION Plant"):
        plan_tasks(compile_st(CONFIGURATION), [task("T", 10, "Fast")], "plant.toml")


def test_a_task_naming_no_program_of_the_files():
    with pytest.raises(TaskSetupError, match=r"plant.toml: test Slwo: 'Slwo' is not a PROGRAM .*did you mean 'Slow'"):
        plan_tasks(compile_st(PROGRAMS), [task("T", 10, "Slwo")], "plant.toml")


@pytest.mark.parametrize(
    "original, replacement, message",
    [
        (
            "TASK Lazy(INTERVAL := T#50ms, PRIORITY := 3);",
            "TASK Lazy(PRIORITY := 3);",
            "plant.st:15:9: task Lazy: event tasks (SINGLE, or no INTERVAL) are not supported",
        ),
        ("PROGRAM B WITH Lazy : Slow;", "PROGRAM B : Slow;", "program instance B has no task"),
        (
            "TASK Quick(INTERVAL := T#5ms, PRIORITY := 0);",
            "TASK Quick(INTERVAL := LTIME#500us, PRIORITY := 0);",
            "plant.st:14:9: task Quick: INTERVAL T#500us is below the least interval, 1ms",
        ),
    ],
)
def test_st_configurations_the_engine_cannot_run(original, replacement, message):
    with pytest.raises(TaskSetupError, match=re.escape(message)):
        plan_tasks(compile_st(CONFIGURATION.replace(original, replacement)), [])


def test_no_program_at_all():
    with pytest.raises(TaskSetupError, match="no PROGRAM"):
        plan_tasks(compile_st("FUNCTION F : INT\nF := 1;\nEND_FUNCTION\n"), [])


def test_no_program_is_fine_for_a_caller_with_tasks_of_its_own():
    # the ST test runner: the test files may declare no PROGRAM
    assert plan_tasks(compile_st("FUNCTION F : INT\nF := 1;\nEND_FUNCTION\n"), [], none_ok=True) == []
    planned = plan_tasks(compile_st(PROGRAMS), [], none_ok=True)
    assert [inst.program for inst in planned[0].programs] == ["Fast", "Slow"]


def test_watchdog_sensitivity_counts_overlong_cycles_in_a_row(engines):
    # A 1 ns watchdog: every cycle is "too long", whatever the machine, so the
    # count is deterministic. Sensitivity 3 faults at the end of the third.
    e = engines(PROGRAMS, [task("T", 10, "Fast", watchdog_ms=1e-6, sensitivity=3)])
    e.run(duration_ns=100 * MS)
    [record] = e.faults
    assert record.fault.kind == "watchdog" and "3 cycle(s) in a row longer than" in record.fault.message
    assert record.time_ns == 20 * MS and e.get("Fast.n") == 3


def test_an_endless_loop_is_stopped_by_the_watchdog_not_a_hang(engines):
    src = PROGRAMS.replace(
        "n := n + 1;\nEND_PROGRAM\n\nPROGRAM Slow",
        "n := n + 1;\nWHILE n > 2 DO n := n + 1; IF n > 30000 THEN n := 3; END_IF END_WHILE\n"
        "END_PROGRAM\n\nPROGRAM Slow",
    )
    e = engines(src, [task("T", 10, "Fast", watchdog_ms=50), task("Other", 10, "Slow")])
    e.run(duration_ns=100 * MS)
    [record] = e.faults
    assert record.fault.kind == "watchdog" and record.fault.pos.line == 5
    assert e.get("Slow.n") == 10  # the other task kept running
