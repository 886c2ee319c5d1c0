"""Stopping a run (Engine.request_stop: what SIGTERM and Ctrl-C do): the run
ends after the current tick; a task inside a long loop ends its cycle at the
loop's next watchdog check instead of finishing it, and that tick already
hands the drivers the safe output values. It is no fault of the program."""

from __future__ import annotations

import logging

import pytest

from softplc.runtime.engine.clock import VirtualClock
from softplc.runtime.image.address import parse_address
from softplc.runtime.io.loopback.driver import LoopbackDriver

from .conftest import MS, safe, task

# In its third cycle Machine starts a loop that would run for minutes (or for
# ever) and would write the setpoint only after it.
MACHINE = """
PROGRAM Machine
VAR
    motor AT %QX0.0 : BOOL;
    setpoint AT %QW1 : INT;
    i, n : DINT;
    cycles : UDINT;
END_VAR
cycles := cycles + 1; motor := TRUE; setpoint := 1234;
IF cycles = 3 THEN
    setpoint := 99;
    {loop}
    setpoint := 1234;
END_IF
END_PROGRAM
"""
LOOP_LINE = 12

LOOPS = {
    "FOR": "FOR i := 0 TO 2147483647 DO n := n + 1; END_FOR",
    "WHILE": "WHILE TRUE DO n := n + 1; END_WHILE",
    "REPEAT": "REPEAT n := n + 1; UNTIL n < 0 END_REPEAT",
}


@pytest.mark.parametrize("loop", LOOPS)
def test_a_stop_ends_a_cycle_inside_a_loop_and_the_outputs_go_safe(engines, caplog, loop):
    wire = LoopbackDriver("loopback", [(parse_address("%QB0"), parse_address("%IB0"), 4)])
    # no watchdog: only the stop request can end this loop
    e = engines(
        MACHINE.replace("{loop}", LOOPS[loop]),
        [task("Control", 10, "Machine", watchdog_ms=None)],
        drivers=[wire],
        safe_outputs=safe(QX0_0=False, QW1=7),
    )
    e.run(cycles=2)
    assert e.get("Machine.cycles") == 2 and not e.outputs_safe
    # The stop comes in the third cycle before Machine runs, as a signal may
    # come at any moment: the loop sees it at its next check.
    e.tasks[0].calls.insert(0, lambda: e.request_stop("SIGTERM"))
    with caplog.at_level(logging.WARNING, logger="softplc.engine"):
        ran = e.run(duration_ns=1000 * MS)

    assert ran == 1 and e.get("Machine.cycles") == 3
    assert e.stop_reason == "SIGTERM"
    assert e.faults == [] and e.tasks[0].fault is None  # no fault of the program
    assert f"task Control: SIGTERM: its cycle was ended in the loop at plant.st:{LOOP_LINE}:5" in caplog.text
    assert e.outputs_safe
    # The tick that ended in the loop handed the drivers the safe values, not
    # the half-computed setpoint 99: the wire carries them back.
    wire.read_inputs(e.image)
    assert (e.get("%IX0.0"), e.get("%IW1")) == (False, 7)
    assert e.get("%QW1") == 99  # what the program had written when its cycle was ended


class _SignalWhileSleeping(VirtualClock):
    """A virtual clock during whose third wait for a release a signal asks
    the engine to stop, as SIGTERM does while the real clock sleeps."""

    def __init__(self) -> None:
        super().__init__()
        self.engine = None
        self.waits = 0

    def sleep_until(self, deadline_ns: int) -> None:
        self.waits += 1
        if self.waits == 3:
            self.engine.request_stop("SIGINT")
        super().sleep_until(deadline_ns)


def test_a_stop_while_waiting_for_a_release_runs_no_further_scan(engines):
    clock = _SignalWhileSleeping()
    e = engines(MACHINE.replace("{loop}", ""), [task("Control", 10, "Machine")], clock=clock)
    clock.engine = e
    assert e.run(duration_ns=1000 * MS) == 2
    assert e.get("Machine.cycles") == 2 and e.stop_reason == "SIGINT"
    assert not e.outputs_safe and e.faults == []  # two whole scans: the outputs were live
    e.stop()
    assert e.outputs_safe
