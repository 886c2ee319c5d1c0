"""The engine's clocks. Both count nanoseconds from the moment they were
made, so TIME() in a program starts at T#0s whichever clock drives it.

RealClock    the wall (monotonic) clock: sleeps until `spin_ns` before a
             deadline, then spins the last stretch, because the kernel's
             wake-up from sleep is late by 50 µs .. several ms on a loaded PC
             while a spin on perf_counter is late by about a microsecond.
             The spin costs CPU (spin_ns per release) and holds the GIL, so
             it is short and configurable ([plc] spin; the figures of
             benchmarks/bench_spin.py in benchmarks/README.md).
VirtualClock jumps straight to the next deadline: a 10-minute sequence runs
             in milliseconds and always the same way. Simulators read the
             same clock.
PeriodicService  a real-time thread that serves a bus or a simulated
             device every period on a clock (in virtual time the engine
             advances them at each tick instead).
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable

from ..config import DEFAULT_SPIN_NS

log = logging.getLogger(__name__)


class VirtualClock:
    virtual = True

    def __init__(self, start_ns: int = 0) -> None:
        self._now = start_ns

    def now_ns(self) -> int:
        return self._now

    def sleep_until(self, deadline_ns: int) -> None:
        if deadline_ns > self._now:
            self._now = deadline_ns


class RealClock:
    virtual = False

    def __init__(self, spin_ns: int = DEFAULT_SPIN_NS) -> None:
        self.spin_ns = spin_ns
        self._t0 = time.perf_counter_ns()

    def now_ns(self) -> int:
        return time.perf_counter_ns() - self._t0

    def sleep_until(self, deadline_ns: int) -> None:
        target = deadline_ns + self._t0
        counter = time.perf_counter_ns
        remaining = target - counter()
        if remaining > self.spin_ns:
            time.sleep((remaining - self.spin_ns) / 1e9)
        while counter() < target:
            pass


class PeriodicService:
    """Real time: calls service(now_ns) every period_s from its own daemon
    thread, now_ns read from the engine's clock. (In virtual time the engine
    calls advance_to at each tick instead, and no thread runs.) An exception
    in service is logged and the loop goes on: a peer on a bus must survive
    a bad frame or a bug in one step."""

    def __init__(self, name: str, clock, service: Callable[[int], None], period_s: float = 0.001) -> None:
        self.name = name
        self.clock = clock
        self.service = service
        self.period_s = period_s
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None

    def start(self) -> None:
        self._stop.clear()
        self._thread = threading.Thread(target=self._run, name=self.name, daemon=True)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
            self._thread = None

    def _run(self) -> None:
        while not self._stop.is_set():
            try:
                self.service(self.clock.now_ns())
            except Exception:
                log.exception("%s: service step failed", self.name)
            self._stop.wait(self.period_s)
