"""Runtime faults in a running engine: the faulted task stops with the ST
location, the drivers get the safe output values, the engine goes on
serving (inputs, the other tasks, PLC_DIAG), and a restart resumes."""

from __future__ import annotations

import time

import pytest

from softplc.runtime.engine.clock import RealClock, VirtualClock
from softplc.runtime.image.address import parse_address
from softplc.runtime.io.loopback.driver import LoopbackDriver

from .conftest import MS, compile_st, safe, task

# The program that faults: it drives the outputs every cycle and, from 50 ms
# on while `armed`, executes the statement under test on line 22.
PLANT = """
VAR_GLOBAL
    armed : BOOL := TRUE;
    zero : INT;
    index : INT := 11;
    big : INT := 1000;
    nothing : REF_TO INT;
END_VAR

PROGRAM Machine
VAR
    motor AT %QX0.0 : BOOL;
    setpoint AT %QW1 : INT;
    values : ARRAY[1..10] OF INT;
    percent : INT(0..100);
    x : INT;
    i : DINT;
    cycles : UDINT;
END_VAR
motor := TRUE; setpoint := 1234; cycles := cycles + 1;
IF armed AND TIME() >= T#50ms THEN
    {statement}
END_IF
END_PROGRAM

PROGRAM Monitor
VAR
    motorSeen AT %IX0.0 : BOOL;    (* the outputs, looped back by the driver *)
    setpointSeen AT %IW1 : INT;
    alarm : BOOL;
    kind : STRING;
    where : STRING[200];
    cycles : UDINT;
END_VAR
alarm := PLC_DIAG.Faulted;
kind := PLC_DIAG.FaultKind;
where := PLC_DIAG.FaultWhere;
cycles := cycles + 1;
END_PROGRAM
"""
STATEMENT_LINE = 22

# case: (the statement, the fault's kind, what its message says)
FAULTS = {
    "division": ("x := 10 / zero;", "division", "division by zero"),
    "bounds": ("values[index] := 1;", "bounds", "array index 11 is outside the bounds 1..10"),
    "range": ("percent := big;", "range", "value 1000 is outside the subrange 0..100"),
    "reference": ("nothing^ := 1;", "reference", "invalid reference"),
    "watchdog": ("WHILE TRUE DO x := x + 1; END_WHILE", "watchdog", "longer than 50 ms"),
    # ran for minutes before: FOR loops had no watchdog check
    "watchdog in FOR": ("FOR i := 0 TO 2147483647 DO x := x + 1; END_FOR", "watchdog", "longer than 50 ms"),
    "watchdog in REPEAT": ("REPEAT x := x + 1; UNTIL FALSE END_REPEAT", "watchdog", "longer than 50 ms"),
}


def _plant(case: str, engines, on_fault: str = "task"):
    statement = FAULTS[case][0]
    program = compile_st(PLANT.replace("{statement}", statement))
    loop = LoopbackDriver("loopback", [(parse_address("%QB0"), parse_address("%IB0"), 4)])
    e = engines(
        program,
        [task("Control", 10, "Machine", priority=1, watchdog_ms=50), task("Supervision", 10, "Monitor", priority=2)],
        drivers=[loop],
        on_fault=on_fault,
        safe_outputs=safe(QX0_0=False, QW1=7),
    )
    return e


@pytest.mark.parametrize("case", sorted(FAULTS))
def test_fault_stops_the_task_with_its_st_location_and_outputs_go_safe(engines, case):
    _statement, kind, message = FAULTS[case]
    e = _plant(case, engines)
    e.run(duration_ns=40 * MS)
    # Before the fault: the outputs reach the bus, the monitor sees them.
    assert (e.get("Monitor.motorSeen"), e.get("Monitor.setpointSeen")) == (True, 1234)
    e.run(duration_ns=30 * MS)  # the fault happens at 50 ms

    [record] = e.faults
    assert record.task == "Control" and record.time_ns == 50 * MS
    assert record.fault.kind == kind
    assert message in record.fault.message
    assert (record.fault.pos.file, record.fault.pos.line) == ("plant.st", STATEMENT_LINE)
    control, supervision = e.tasks
    assert control.fault is record.fault and supervision.fault is None
    assert e.get("Machine.cycles") == 6  # 0 .. 50 ms, the last one cut short
    assert e.outputs_safe
    # The drivers were handed the safe values: the loopback shows them.
    assert (e.get("Monitor.motorSeen"), e.get("Monitor.setpointSeen")) == (False, 7)
    # The program's own %Q variables keep what it wrote (for the engineer to look at).
    assert e.get("%QW1") == 1234
    # The engine keeps serving: the other task runs and reads PLC_DIAG.
    before = e.get("Monitor.cycles")
    e.run(duration_ns=100 * MS)
    assert e.get("Monitor.cycles") == before + 10
    assert e.get("Machine.cycles") == 6
    assert e.get("Monitor.alarm") is True
    assert e.get("Monitor.kind") == kind
    assert e.get("Monitor.where") == f"plant.st:{STATEMENT_LINE}:5"


def test_restart_resumes_the_faulted_task_and_the_outputs(engines):
    e = _plant("division", engines)
    e.run(duration_ns=70 * MS)  # the fault at 50 ms; the safe value loops back at 60 ms
    assert e.faulted_tasks() and e.get("Monitor.setpointSeen") == 7
    e.set("armed", False)  # the operator fixed the cause
    e.request_restart()  # what SIGUSR1 or `restart` on the terminal does
    e.run(duration_ns=20 * MS)
    assert not e.faulted_tasks() and not e.outputs_safe
    assert e.restarts == 1
    assert e.get("Machine.cycles") == 2  # a fresh instance: counted from 0 again
    assert (e.get("Monitor.motorSeen"), e.get("Monitor.setpointSeen")) == (True, 1234)
    assert e.get("Monitor.alarm") is False
    assert e.get("PLC_DIAG.Restarts") == 1 and e.get("PLC_DIAG.FaultCount") == 1


def test_restart_without_a_fault_changes_nothing(engines):
    e = _plant("division", engines)
    e.set("armed", False)
    e.run(duration_ns=100 * MS)
    assert e.restart() is False
    assert e.get("Machine.cycles") == 10


def test_on_fault_plc_stops_every_task(engines):
    e = _plant("bounds", engines, on_fault="plc")
    e.run(duration_ns=100 * MS)
    assert all(t.fault is not None for t in e.tasks)
    assert e.get("Monitor.cycles") == 5  # 0 .. 40 ms; at 50 ms Control (priority 1) faulted first
    assert e.outputs_safe
    ticks = e.cycle
    e.run(duration_ns=50 * MS)  # still serving the drivers at the fastest interval
    assert e.cycle == ticks + 5


def test_fault_kind_of_every_task_is_counted(engines):
    e = _plant("range", engines)
    e.run(duration_ns=100 * MS)
    control = e.tasks[0]
    assert control.stats.faults == 1 and control.stats.cycles == 5  # completed cycles only


WAIT_PROGRAM = "PROGRAM Waiter\nVAR n : INT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"


def _waiting_engine(engines, clock):
    """A task whose cycle waits 150 ms without computing (as when the host
    deschedules the process), with a 100 ms watchdog."""
    e = engines(WAIT_PROGRAM, [task("Main", 10, "Waiter", watchdog_ms=100)], clock=clock)
    e.tasks[0].calls.append(lambda: time.sleep(0.15))
    return e


def test_in_virtual_time_a_busy_host_is_no_watchdog_fault(engines):
    # The watchdog counts the scan thread's CPU time on a virtual clock: a
    # descheduled process (a loaded CI machine) is not a slow program.
    e = _waiting_engine(engines, VirtualClock())
    e.run(cycles=2)
    assert e.faults == [] and e.get("Waiter.n") == 2


def test_in_virtual_time_a_cycle_that_computes_too_long_is_a_watchdog_fault(engines):
    # The tick counts CPU time from a reading up to a millisecond old (the
    # first cycles come within microseconds of one another): a cycle that
    # spends 150 ms of CPU on a 100 ms watchdog is late.
    e = engines(WAIT_PROGRAM, [task("Main", 10, "Waiter", watchdog_ms=100)], clock=VirtualClock())
    cycle = iter(range(100))

    def compute():
        if next(cycle) == 3:
            end = time.thread_time() + 0.15
            while time.thread_time() < end:
                pass

    e.tasks[0].calls.append(compute)
    e.run(cycles=6)
    [record] = e.faults
    assert record.fault.kind == "watchdog" and "longer than 100 ms" in record.fault.message
    assert e.get("Waiter.n") == 4  # the fourth cycle was late: the task stopped after it


def test_on_the_real_clock_a_cycle_that_waits_too_long_is_a_watchdog_fault(engines):
    e = _waiting_engine(engines, RealClock())
    e.run(cycles=1)
    [record] = e.faults
    assert record.fault.kind == "watchdog" and "longer than 100 ms" in record.fault.message
