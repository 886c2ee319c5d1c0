"""What generated code reaches at run time: the task clock, the watchdog,
the process image and the services of native functions (st/native.py)."""

from __future__ import annotations

import time

from ..image.memory import ProcessImage
from ..st import rtlib
from ..st import types as T
from ..st.faults import WatchdogFault


class ExecContext:
    """What generated code reaches at run time: the task clock, the
    watchdog, the process image and communication services."""

    def __init__(self, image: ProcessImage, watchdog_s: float = 1.0) -> None:
        self.now_ns = 0
        self.image = image
        self.watchdog_s = watchdog_s
        self.deadline = float("inf")
        # the clock the watchdog reads, in seconds: wall time on the real
        # clock; on a virtual clock the engine gives it the scan thread's CPU
        # time, so a loaded machine that deschedules the process never faults
        # a simulated task (the verdict stays the program's, not the host's)
        self.timer = time.perf_counter
        # native function services (st/native.py) by name, bound by the drivers
        self.services: dict = {}
        self.namespaces: list = []  # loaded modules that read the clock

    def set_time(self, now_ns: int) -> None:
        """Set the task clock. TIME() and LTIME() are constant within a cycle,
        so the loaded modules get the value once instead of a call per use."""
        self.now_ns = now_ns
        ms, ns = self.time_ms(), self.time_ns()
        for namespace in self.namespaces:
            namespace["_NOW_MS"] = ms
            namespace["_NOW_NS"] = ns

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

    def check_watchdog(self) -> None:
        if self.timer() > self.deadline:
            raise WatchdogFault(f"watchdog: the cycle ran longer than {self.watchdog_s * 1000:g} ms (endless loop?)")
