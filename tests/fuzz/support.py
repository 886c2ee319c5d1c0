"""What the fuzz harness shares: its two runs, the bounds every input runs
under, and the check that nothing was logged with a traceback.

Two runs of every property (test_*.py defines both with `short` and `long`):

  * short: in the normal suite, a few dozen examples, derandomized (the same
    examples in every run, CI reproducible);
  * long:  marked `fuzz`, left out unless the -m expression names fuzz
    (conftest.py), seeded by --hypothesis-seed:

        pytest -m fuzz --hypothesis-seed=1 -p no:randomly tests/fuzz

    The totals are 100,000 ST inputs, 10,000 configurations, 100,000 bus
    frames, 10,000 imported files and 10,000 server requests, shared among
    the tests of each area; SOFTPLC_FUZZ_ST, SOFTPLC_FUZZ_CONFIGS,
    SOFTPLC_FUZZ_FRAMES, SOFTPLC_FUZZ_IMPORTS and SOFTPLC_FUZZ_REQUESTS set
    other totals. Each long
    test runs in SOFTPLC_FUZZ_SHARDS shards (default 10; conftest.py
    parametrizes `shard`), each a tenth of its inputs from a seed of its own
    (the --hypothesis-seed, the test and the shard), so a long run spreads
    over cores (pytest-xdist's -n) and can be run, and its figures kept, a
    part at a time (-k shard3).

Every input runs under `bounded()`: SOFTPLC_FUZZ_LIMIT_S seconds of the
process's CPU time (default 20; SIGPROF raises Hang in the main thread), as a
backstop for an input that blocks SOFTPLC_FUZZ_WALL_FACTOR times that in wall
time (default 10; SIGALRM), and at most
SOFTPLC_FUZZ_MEMORY_MB more address space (default 2048; RLIMIT_AS makes a
runaway allocation a MemoryError instead of taking the machine's memory).
"""

from __future__ import annotations

import contextlib
import logging
import os
import resource
import signal
import threading
import zlib
from dataclasses import dataclass

import pytest
from hypothesis import HealthCheck, seed, settings

TOTALS = {
    "st": ("SOFTPLC_FUZZ_ST", 100_000),
    "configs": ("SOFTPLC_FUZZ_CONFIGS", 10_000),
    "frames": ("SOFTPLC_FUZZ_FRAMES", 100_000),
    "imports": ("SOFTPLC_FUZZ_IMPORTS", 10_000),
    "requests": ("SOFTPLC_FUZZ_REQUESTS", 10_000),
}
LIMIT_S = float(os.environ.get("SOFTPLC_FUZZ_LIMIT_S", "20"))
# A CPU-time limit does not fire because the host is busy (a shard sharing
# its cores with other work took more than 20 s of wall time to compile the
# library); the wall-time one, this many times longer, catches a blocked input.
WALL_FACTOR = float(os.environ.get("SOFTPLC_FUZZ_WALL_FACTOR", "10"))
MEMORY_MB = int(os.environ.get("SOFTPLC_FUZZ_MEMORY_MB", "2048"))
SHARDS = max(1, int(os.environ.get("SOFTPLC_FUZZ_SHARDS", "10")))
_HEALTH = [HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.filter_too_much]


def total(area: str) -> int:
    """The long run's inputs of an area ("st", "configs", "frames", "imports")."""
    var, default = TOTALS[area]
    return int(os.environ.get(var, default))


def short(examples: int):
    """The normal suite's run: derandomized, a few dozen examples."""
    return settings(
        max_examples=examples, deadline=None, derandomize=True, database=None, suppress_health_check=_HEALTH
    )


@dataclass(frozen=True)
class Shard:
    """One part of a long test (conftest.py's `shard` parameter): index of
    count, and the run's --hypothesis-seed (None: a random run)."""

    test: str
    index: int
    count: int
    base_seed: object

    def seed(self) -> int | None:
        if self.base_seed is None:
            return None
        return zlib.crc32(f"{self.base_seed}/{self.test}/{self.index}".encode())


def long(area: str, share: float, shard: Shard, per_example: float = 1.0):
    """The long run: this shard's part of the area's share, per_example
    inputs an example (a frame sequence holds several frames), seeded by
    --hypothesis-seed, the test and the shard (the shards of one test must
    not draw the same inputs, as one seed for all would make them)."""
    examples = max(1, round(total(area) * share / per_example / shard.count))
    configured = settings(
        max_examples=examples, deadline=None, derandomize=False, database=None, suppress_health_check=_HEALTH
    )
    shard_seed = shard.seed()

    def apply(test):
        test = configured(test)
        return test if shard_seed is None else seed(shard_seed)(test)

    return apply


fuzz = pytest.mark.fuzz


class Hang(Exception):
    """An input ran longer than the harness allows."""


@contextlib.contextmanager
def bounded(
    what: str = "input", limit_s: float | None = None, memory_mb: int | None = None, wall_factor: float = WALL_FACTOR
):
    """Run a block under a CPU-time limit (Hang), a wall-time backstop
    wall_factor times longer (Hang) and an address-space limit
    (MemoryError). The time limits need the main thread (signals); elsewhere
    only the memory limit applies."""
    limit = LIMIT_S if limit_s is None else limit_s
    extra = (MEMORY_MB if memory_mb is None else memory_mb) << 20
    main = threading.current_thread() is threading.main_thread()
    fired: list = []
    old_handlers: list = []
    if main:

        def expired(sig, _frame):
            kind = "CPU" if sig == signal.SIGPROF else "wall"
            fired.append(
                f"{what}: not done within {limit if kind == 'CPU' else limit * wall_factor:g} s of {kind} time"
            )
            raise Hang(fired[0])

        for sig, timer, seconds in (
            (signal.SIGPROF, signal.ITIMER_PROF, limit),
            (signal.SIGALRM, signal.ITIMER_REAL, limit * wall_factor),
        ):
            old_handlers.append((sig, timer, signal.signal(sig, expired)))
            signal.setitimer(timer, seconds)
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    cap = _address_space() + extra
    if hard != resource.RLIM_INFINITY:
        cap = min(cap, hard)
    resource.setrlimit(resource.RLIMIT_AS, (cap, hard))
    try:
        yield
    except Exception as exc:
        if fired and not isinstance(exc, Hang):  # the code under test caught the Hang and went on
            raise Hang(fired[0]) from exc
        raise
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))
        for sig, timer, handler in old_handlers:
            signal.setitimer(timer, 0)
            signal.signal(sig, handler)


def _address_space() -> int:
    """This process's virtual memory now, in bytes (Linux /proc)."""
    with open("/proc/self/statm") as f:
        return int(f.read().split()[0]) * resource.getpagesize()


class LogWatch(logging.Handler):
    """Every log record of a block that reaches the root logger (warnings and
    above, unless a logger says otherwise): a record with a traceback
    (exc_info) is a Python exception that something caught and logged, a
    crash in disguise."""

    def __init__(self) -> None:
        super().__init__(logging.DEBUG)
        self.records: list[logging.LogRecord] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append(record)

    def tracebacks(self) -> list[str]:
        return [f"{r.name}: {r.getMessage()}\n{self.format(r)}" for r in self.records if r.exc_info]

    def __enter__(self) -> LogWatch:
        logging.getLogger().addHandler(self)
        return self

    def __exit__(self, *exc) -> None:
        logging.getLogger().removeHandler(self)


def assert_no_tracebacks(watch: LogWatch, what: str) -> None:
    found = watch.tracebacks()
    assert not found, f"{what}: {len(found)} log record(s) with a Python traceback; the first:\n{found[0]}"
