"""Engines built from ST text, on the virtual clock; an engine scanning in
a thread of its own (Scanning), for tests of what other threads see of it;
wait_until, for a condition another thread makes true."""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

import pytest

from softplc.runtime.config import ProgramInstance, SafeOutput, TaskConfig, default_watchdog_ns
from softplc.runtime.engine.clock import VirtualClock
from softplc.runtime.engine.scan import Engine
from softplc.runtime.image.address import parse_address
from softplc.runtime.program import compile_files

MS = 1_000_000


def task(
    name: str,
    interval_ms,
    *programs,
    priority: int = 1,
    watchdog_ms="default",
    sensitivity: int = 1,
    pause_ms: float = 1,
) -> TaskConfig:
    """A TaskConfig; programs are PROGRAM type names or (instance, type) pairs.
    interval_ms None makes a freewheeling task."""
    interval_ns = None if interval_ms is None else round(interval_ms * MS)
    watchdog_ns = (
        default_watchdog_ns(interval_ns)
        if watchdog_ms == "default"
        else (None if watchdog_ms is None else round(watchdog_ms * MS))
    )
    insts = [
        ProgramInstance(p, p, f"test {p}") if isinstance(p, str) else ProgramInstance(p[0], p[1], f"test {p[0]}")
        for p in programs
    ]
    return TaskConfig(
        name=name,
        interval_ns=interval_ns,
        pause_ns=round(pause_ms * MS),
        priority=priority,
        watchdog_ns=watchdog_ns,
        sensitivity=sensitivity,
        programs=insts,
        key=f"task {name}",
    )


def safe(**values) -> list:
    """safe(QX0_0=True, QW1=5) -> SafeOutputs for %QX0.0 and %QW1."""
    out = []
    for key, value in values.items():
        text = "%" + key.replace("_", ".")
        out.append(SafeOutput(parse_address(text), value, f"outputs.safe.{text}"))
    return out


def compile_st(source: str, profile: str = "codesys"):
    return compile_files([], profile=profile, texts={"plant.st": source})


def make_engine(source_or_program, tasks: list, **kwargs) -> Engine:
    program = compile_st(source_or_program) if isinstance(source_or_program, str) else source_or_program
    kwargs.setdefault("clock", VirtualClock())
    engine = Engine(program, tasks, **kwargs)
    engine.start()
    return engine


@pytest.fixture
def engines():
    """Engines made through this fixture are stopped after the test."""
    made = []

    def factory(*args, **kwargs):
        e = make_engine(*args, **kwargs)
        made.append(e)
        return e

    yield factory
    for e in made:
        e.stop()


class Scanning:
    """engine.run() in a thread until stop(); in virtual time each scan
    waits pause_s of wall time (0: none), so the scan does not eat a core
    and a client can follow it."""

    def __init__(self, engine, pause_s: float = 0.002) -> None:
        self.engine = engine
        if pause_s:
            engine.after_tick.append(lambda _e: time.sleep(pause_s))
        self.thread = threading.Thread(target=engine.run, name="test-scan", daemon=True)

    def start(self) -> Scanning:
        self.thread.start()
        return self

    def stop(self, timeout: float = 10.0) -> None:
        self.engine.request_stop("test over")
        self.thread.join(timeout)
        assert not self.thread.is_alive(), "the scan did not stop"


def wait_until(check: Callable[[], Any], what: str, timeout: float = 20.0, poll_s: float = 0.01) -> Any:
    """check()'s first true result, polled; fails naming what was awaited after timeout."""
    deadline = time.monotonic() + timeout
    while True:
        result = check()
        if result:
            return result
        if time.monotonic() > deadline:
            pytest.fail(f"not within {timeout} s: {what} (last: {result!r})")
        time.sleep(poll_s)
