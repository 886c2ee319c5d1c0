"""The engine's clocks. Both count nanoseconds from the moment they were
made, so TIME() in a program starts at T#0s whichever clock drives it.

RealClock    the wall (monotonic) clock: sleeps until shortly before a
             deadline, then spins the last stretch, because the kernel's
             wake-up from sleep is late by 50 µs .. several ms on a loaded PC
             while a spin on perf_counter is late by about a microsecond.
VirtualClock jumps straight to the next deadline: a 10-minute sequence runs
             in milliseconds and always the same way. Simulators of later
             issues read the same clock.
"""
from __future__ import annotations

import time

DEFAULT_SPIN_NS = 1_000_000  # DESIGN.md: spin the last ~1 ms


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
