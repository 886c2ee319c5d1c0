"""Statistics per task, as CODESYS shows them in its task monitor.

Cycle times are execution times measured on perf_counter in both clock
modes (what the CPU really spent); wake-up jitter is the lateness of a task's
start against its scheduled release, on the engine's clock (always 0 on the
virtual clock, which is never late)."""

from __future__ import annotations


class TaskStats:
    __slots__ = (
        "cycles",
        "last_ns",
        "min_ns",
        "max_ns",
        "total_ns",
        "jitter_last_ns",
        "jitter_max_ns",
        "jitter_total_ns",
        "overruns",
        "faults",
    )

    def __init__(self) -> None:
        self.cycles = 0
        self.last_ns = 0
        self.min_ns = 0
        self.max_ns = 0
        self.total_ns = 0
        self.jitter_last_ns = 0
        self.jitter_max_ns = 0
        self.jitter_total_ns = 0
        self.overruns = 0  # activations missed because a cycle ran past the next release
        self.faults = 0

    def record(self, exec_ns: int, jitter_ns: int) -> None:
        n = self.cycles = self.cycles + 1
        self.last_ns = exec_ns
        self.total_ns += exec_ns
        if exec_ns > self.max_ns:
            self.max_ns = exec_ns
        if exec_ns < self.min_ns or n == 1:
            self.min_ns = exec_ns
        self.jitter_last_ns = jitter_ns
        self.jitter_total_ns += jitter_ns
        if jitter_ns > self.jitter_max_ns:
            self.jitter_max_ns = jitter_ns

    @property
    def mean_ns(self) -> float:
        return self.total_ns / self.cycles if self.cycles else 0.0

    @property
    def jitter_mean_ns(self) -> float:
        return self.jitter_total_ns / self.cycles if self.cycles else 0.0

    def as_dict(self) -> dict:
        """Figures in microseconds, for logs and JSON."""
        return {
            "cycles": self.cycles,
            "last_us": self.last_ns / 1e3,
            "min_us": self.min_ns / 1e3,
            "max_us": self.max_ns / 1e3,
            "mean_us": round(self.mean_ns / 1e3, 3),
            "jitter_last_us": self.jitter_last_ns / 1e3,
            "jitter_max_us": self.jitter_max_ns / 1e3,
            "jitter_mean_us": round(self.jitter_mean_ns / 1e3, 3),
            "overruns": self.overruns,
            "faults": self.faults,
        }
