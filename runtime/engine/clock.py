"""The engine's clocks. Both count nanoseconds from the moment they were
made, so TIME() in a program starts at T#0s whichever clock drives it.

RealClock    the wall (monotonic) clock: sleeps until `spin_ns` before a
             deadline, then spins the last stretch, because the kernel's
             wake-up from sleep is late by 50 µs .. several ms on a loaded PC
             while a spin on perf_counter is late by about a microsecond.
             The spin costs CPU (spin_ns per release) and holds the GIL, so
             it is short and configurable ([plc] spin; the figures of
             benchmarks/bench_spin.py in benchmarks/README.md). With
             realtime_priority the scan thread runs under SCHED_FIFO
             ([plc] realtime_priority): no process of normal priority
             delays its wake-up.
VirtualClock jumps straight to the next deadline: a 10-minute sequence runs
             in milliseconds and always the same way. Simulators read the
             same clock.

Each has a date (epoch_ns: UTC nanoseconds since 1970 at its zero) for the
functions that read the calendar (TwinCAT's F_GetSystemTime): the host's
clock for the real one, 2000-01-01 for the virtual one unless it is given
(program/context.py VIRTUAL_EPOCH_NS), so that virtual time runs the same
way on every day too.
PeriodicService  a real-time thread that serves a bus or a simulated
             device each time the scan goes idle, and every period when
             none does (in virtual time the engine advances them at each
             tick instead).
"""

from __future__ import annotations

import logging
import os
import threading
import time
from collections.abc import Callable

from ..config import DEFAULT_SPIN_NS
from ..program.context import VIRTUAL_EPOCH_NS
from .lock_share import scan_sleeps

log = logging.getLogger(__name__)


def _threads() -> list[int]:
    """The native ids of this process's threads (Linux), the caller's alone elsewhere."""
    try:
        return [int(tid) for tid in os.listdir("/proc/self/task")]
    except OSError:
        return [threading.get_native_id()]


class VirtualClock:
    virtual = True

    def __init__(self, start_ns: int = 0, epoch_ns: int = VIRTUAL_EPOCH_NS) -> None:
        self._now = start_ns
        self.epoch_ns = epoch_ns  # the date of the clock's zero

    def claim_thread(self) -> None:
        """Virtual time needs no priority: nothing waits for the wall clock."""

    def now_ns(self) -> int:
        return self._now

    def sleep_until(self, deadline_ns: int) -> None:
        if deadline_ns > self._now:
            self._now = deadline_ns


class RealClock:
    virtual = False

    def __init__(self, spin_ns: int = DEFAULT_SPIN_NS, realtime_priority: int = 0) -> None:
        self.spin_ns = spin_ns
        self.realtime_priority = realtime_priority
        self._t0 = time.perf_counter_ns()
        self.epoch_ns = time.time_ns()  # the date now, at the clock's zero
        self._claimed: set = set()  # the threads given the priority (or told they cannot have it)
        self._idle: tuple[Callable[[], None], ...] = ()  # on_idle's callbacks
        self._idle_lock = threading.Lock()

    def claim_thread(self) -> None:
        """With realtime_priority: the calling thread (the scan's) under
        SCHED_FIFO at that priority and every other thread of the process
        (buses, simulators, the web page) one below, once. A thread started
        later inherits its starter's. The process's threads all take turns
        at Python's interpreter lock: one of them left at normal priority
        would make the scan wait behind every other program of the machine
        while it holds the lock. A warning when the system refuses (it takes
        root or CAP_SYS_NICE: deploy/softplc.service grants it); the scan
        then runs at normal priority."""
        ident = threading.get_ident()
        if not self.realtime_priority or ident in self._claimed:
            return
        self._claimed.add(ident)
        scan = threading.get_native_id()
        try:
            for tid in _threads():
                priority = self.realtime_priority if tid == scan else max(1, self.realtime_priority - 1)
                try:
                    os.sched_setscheduler(tid, os.SCHED_FIFO, os.sched_param(priority))
                except ProcessLookupError:  # a thread that ended meanwhile
                    continue
        except (OSError, AttributeError) as exc:  # AttributeError: not Linux
            log.warning(
                "[plc] realtime_priority = %d: the scan runs at normal priority (%s; it takes root or CAP_SYS_NICE)",
                self.realtime_priority,
                getattr(exc, "strerror", None) or exc,
            )
            return
        log.info("the PLC runs under SCHED_FIFO, the scan at priority %d", self.realtime_priority)

    def now_ns(self) -> int:
        return time.perf_counter_ns() - self._t0

    def on_idle(self, callback: Callable[[], None], add: bool = True) -> None:
        """Call callback (or no longer, add=False) each time the scan goes
        idle, before it sleeps until its next release (PeriodicService.wake).
        Background work waits for the same moment (lock_share.scan_sleeps)."""
        with self._idle_lock:  # (from any thread: the scan reads the tuple, never this lock)
            idle = tuple(c for c in self._idle if c != callback)
            self._idle = (*idle, callback) if add else idle

    def sleep_until(self, deadline_ns: int) -> None:
        for wake in self._idle:
            wake()
        target = deadline_ns + self._t0
        scan_sleeps(target - self.spin_ns)  # background work may run until shortly before the scan wakes
        counter = time.perf_counter_ns
        remaining = target - counter()
        if remaining > self.spin_ns:
            time.sleep((remaining - self.spin_ns) / 1e9)
        while counter() < target:
            pass


class PeriodicService:
    """Real time: calls service(now_ns) from its own daemon thread, now_ns
    read from the engine's clock: each time the scan goes idle (the clock's
    on_idle), when wake() is called, and every period_s when neither came.
    (In virtual time the engine calls advance_to at each tick instead, and
    no thread runs.) An exception in service is logged and the loop goes on:
    a peer on a bus must survive a bad frame or a bug in one step.

    Why at the scan's idle (issue 31): the services share Python's lock
    with the scan. Served on their own timers, at 1 kHz or 200 Hz, they were
    often running at the moment a scan was released, one after the other,
    and the scan waited for the lock behind them. Served as the scan goes
    idle, they run while it sleeps; the period is a fallback for when no
    scan runs (or the tasks are slow), not a rate."""

    def __init__(self, name: str, clock, service: Callable[[int], None], period_s: float = 0.02) -> None:
        self.name = name
        self.clock = clock
        self.service = service
        self.period_s = period_s
        self._stop = False
        self._wake = threading.Event()
        self._thread: threading.Thread | None = None

    def start(self) -> None:
        self._stop = False
        self._wake.clear()
        self._thread = threading.Thread(target=self._run, name=self.name, daemon=True)
        self._thread.start()
        on_idle = getattr(self.clock, "on_idle", None)
        if on_idle is not None:
            on_idle(self.wake)

    def wake(self) -> None:
        """Run the service now rather than at the end of its period."""
        self._wake.set()

    def stop(self) -> None:
        on_idle = getattr(self.clock, "on_idle", None)
        if on_idle is not None:
            on_idle(self.wake, add=False)
        self._stop = True
        self._wake.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
            self._thread = None

    def _run(self) -> None:
        wake = self._wake
        while not self._stop:
            try:
                self.service(self.clock.now_ns())
            except Exception:
                log.exception("%s: service step failed", self.name)
            wake.wait(self.period_s)
            wake.clear()
