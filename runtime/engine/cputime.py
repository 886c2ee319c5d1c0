"""The scan thread's CPU time less the garbage collector's, which the
watchdog judges in virtual time (engine/scan.py)."""

from __future__ import annotations

import gc
import time


class CollectorTime:
    """CPU time the garbage collector has taken (any thread, ns). In virtual
    time the watchdog judges the program's own CPU time: a full collection
    of a large heap (a test process that has run thousands of tests) can
    take half a second, and is no fault of the program."""

    def __init__(self) -> None:
        self.total_ns = 0
        self._start_ns = 0
        gc.callbacks.append(self._phase)

    def _phase(self, phase: str, _info: dict) -> None:
        if phase == "start":
            self._start_ns = time.thread_time_ns()
        else:
            self.total_ns += max(0, time.thread_time_ns() - self._start_ns)

    def cpu_ns(self) -> int:
        """This thread's CPU time less the collector's."""
        return time.thread_time_ns() - self.total_ns

    def cpu_s(self) -> float:
        return self.cpu_ns() * 1e-9


#: the one instance: it registers itself in gc.callbacks
COLLECTOR = CollectorTime()
