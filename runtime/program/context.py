"""What generated code reaches at run time: the task clock, the watchdog,
the process image and the services of native functions (st/native.py).

The cooperative watchdog. Generated code reaches it on loop back-edges,
cheaply: ``loop_budget`` is the number of loop iterations left before the
next check, shared by every loop of the cycle. A FOR loop charges its whole
length when it starts (no cost per iteration) and, once the budget is spent,
runs in slices of ``LOOP_CHECK_EVERY`` with a check between them; WHILE and
REPEAT count down a local copy of the budget per iteration and charge what
they used when they end. A check raises WatchdogFault once the cycle is past
its deadline and StopRequested once a stop was asked for (a signal), so a
long loop ends the cycle within about LOOP_CHECK_EVERY passes of either,
whatever nests it (the bound grows by that much per
level of loops that have not ended yet). benchmarks/bench_loops.py measures
what the checks cost.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from itertools import chain

from ..image.memory import ProcessImage
from ..st import types as T
from ..st.faults import LOOP_CHECK_EVERY, StopRequested, WatchdogFault
from ..st.native import CLOCK
from ..st.rtlib import rtlib

#: the date of a virtual clock's zero, UTC nanoseconds since 1970-01-01:
#: 2000-01-01 00:00:00. Virtual time runs the same way every time, so its
#: calendar starts at a fixed date; the real clock's is the host's.
VIRTUAL_EPOCH_NS = 946_684_800 * 1_000_000_000


@dataclass
class TaskState:
    """The task a program runs in, as the program may ask for it (TwinCAT's
    _TaskInfo and GETCURTASKINDEX, fblocks/libs/tc2_system): the engine
    keeps one per task and hands it to the context when the task's cycle
    starts. index: 1.. in the configuration's order of tasks; interval_ns
    0 for a freewheeling task; cycles: the cycles started, this one
    included; release_ns: when this cycle was due on the engine clock;
    last_exec_ns: how long the previous cycle ran; overran: it ran past
    the interval."""

    index: int = 1
    name: str = ""
    interval_ns: int = 0
    priority: int = 0
    cycles: int = 0
    release_ns: int = 0
    last_exec_ns: int = 0
    overran: bool = False


class ExecContext:
    """What generated code reaches at run time: the task clock, the
    watchdog, the process image and communication services; the date and
    the running task for the functions that read them (StdFunc context)."""

    def __init__(self, image: ProcessImage, watchdog_s: float = 1.0) -> None:
        self.now_ns = 0
        #: the date at engine time 0, UTC ns since 1970-01-01 (the engine
        #: takes its clock's): date_ns() is this plus the engine clock
        self.epoch_ns = VIRTUAL_EPOCH_NS
        #: local time is the host's zone (real time) or UTC (virtual time,
        #: the same on every machine)
        self.local_zone = False
        #: reads the engine clock now: the task clock (virtual time stands
        #: still within a cycle); the engine gives it its real clock's
        self.clock_ns = lambda: self.now_ns
        #: the task whose cycle runs (begin_task), and every task of the PLC
        self.task = TaskState()
        self.tasks: list = [self.task]
        self.image = image
        self.watchdog_s = watchdog_s
        self.deadline = float("inf")
        # the clock the watchdog reads, in seconds: wall time on the real
        # clock; on a virtual clock the engine gives it the scan thread's CPU
        # time, so a loaded machine that deschedules the process never faults
        # a simulated task (the verdict stays the program's, not the host's)
        self.timer = time.perf_counter
        # the same deadline on perf_counter, when the timer is another clock:
        # a thread's CPU time never runs ahead of the wall clock, so the
        # check reads the timer (a system call for CPU time) only once wall
        # time is past it; -inf: no such shortcut, the timer is always read
        self.wall_deadline = float("-inf")
        #: loop iterations left before the next check (see the module's doc)
        self.loop_budget = LOOP_CHECK_EVERY
        #: why the run is stopping (e.g. "SIGTERM"), set from a signal handler:
        #: a running loop ends its cycle at its next check; None while running
        self.stop_reason: str | None = None
        # native function services (st/native.py) by name, bound by the drivers;
        # the clock's is the context's own
        self.services: dict = {CLOCK: _Clock(self)}
        self.namespaces: list = []  # loaded modules that read the clock

    def set_time(self, now_ns: int) -> None:
        """Set the task clock. TIME() and LTIME() are constant within a cycle,
        so the loaded modules get the value once instead of a call per use."""
        self.now_ns = now_ns
        ms, ns = self.time_ms(), self.time_ns()
        for namespace in self.namespaces:
            namespace["_NOW_MS"] = ms
            namespace["_NOW_NS"] = ns

    def begin_task(self, task: TaskState) -> None:
        """A cycle of task starts: the functions that ask which task runs
        see it, and the loaded modules' task hooks (a library's task
        information, fblocks/libs) are told."""
        self.task = task
        for namespace in self.namespaces:
            for hook in namespace.get("_TASK_HOOKS", ()):
                hook(namespace, self)

    def date_ns(self) -> int:
        """The date now, UTC nanoseconds since 1970-01-01, on the engine's
        clock (in virtual time it advances with the virtual clock)."""
        return self.epoch_ns + self.clock_ns()

    def utc_offset_s(self, utc_s: int) -> int:
        """Seconds local time is ahead of UTC at that moment: the host's
        zone in real time, 0 in virtual time."""
        if not self.local_zone:
            return 0
        try:
            return time.localtime(utc_s).tm_gmtoff
        except (OverflowError, OSError, ValueError):
            return 0

    def call_native(self, fn, *args):
        """A native function call: to the service bound under its name, or
        the declaration's fallback when no driver offers one."""
        return self.services.get(fn.service, fn.fallback).request(fn.name, *args)

    def time_ms(self) -> int:
        return rtlib.wrap(T.TIME, self.now_ns // 1_000_000)

    def time_ns(self) -> int:
        return rtlib.wrap(T.LTIME, self.now_ns)

    def arm_watchdog(self) -> None:
        self.deadline = self.timer() + self.watchdog_s
        self.wall_deadline = time.perf_counter() + self.watchdog_s

    def check_watchdog(self) -> int:
        """The check on a loop back-edge (``_watchdog()`` in generated code):
        raises StopRequested or WatchdogFault, else renews the loop budget
        and returns it (a WHILE or REPEAT loop counts down from it)."""
        if self.stop_reason is not None:
            raise StopRequested(self.stop_reason)
        if time.perf_counter() > self.wall_deadline and self.timer() > self.deadline:
            raise WatchdogFault(f"watchdog: the cycle ran longer than {self.watchdog_s * 1000:g} ms (endless loop?)")
        self.loop_budget = LOOP_CHECK_EVERY
        return LOOP_CHECK_EVERY

    def loop_range(self, rng: range):
        """A FOR loop's range when the loop budget is spent (``_loop(r)`` in
        generated code): checks now; a range longer than the budget comes
        back in slices with a check between them, a short one as it is."""
        self.check_watchdog()
        if len(rng[: LOOP_CHECK_EVERY + 1]) <= LOOP_CHECK_EVERY:  # len(rng) may not fit a C integer
            self.loop_budget -= len(rng)
            return rng
        return chain.from_iterable(self._slices(rng))

    def _slices(self, rng: range):
        every = LOOP_CHECK_EVERY
        start = 0
        while True:
            part = rng[start : start + every]
            if not part:
                return
            yield part
            start += every
            self.check_watchdog()


class _Clock:
    """The service st.native.CLOCK: the date of the task clock in ms since
    1970-01-01 00:00 UTC (constant within a cycle, as TIME() is): the
    engine clock's date at its zero (epoch_ns) plus the task clock."""

    def __init__(self, ctx: ExecContext) -> None:
        self.ctx = ctx

    def request(self, name: str, *args) -> int:
        return (self.ctx.epoch_ns + self.ctx.now_ns) // 1_000_000
