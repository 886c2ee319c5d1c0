"""The interpreter lock, shared with the scan: work off the scan thread
that computes for milliseconds at a stretch (a program read back from the
compile process, the old one taken apart after an online change, the
watched paths resolved again, a server's call) runs inside background().

A thread that waits for the lock asks its holder to let go after the
switch interval, Python's 5 ms: a scan that wakes while a call thread
resolves a thousand paths starts late by that much, or by a multiple of
it when other threads take the lock first (a live soak's late ticks were
that: docs/architecture.md, "One scan"). Inside background() the interval is
SWITCH_S, so the scan waits about that long; outside, it is Python's
again, so that the scan itself is rarely asked to let go in its own run
(a shorter interval everywhere made more overruns, not fewer).

Counted across threads: the interval is lowered when the first such
work begins and put back when the last one ends, whatever their order.

    with background():
        places = [resolver.place(p) for p in paths]

The lock has no priority, though: when it is let go, whichever thread
the system wakes first takes it. Right after an online change three
threads compute at once (the servers' call thread resolving its watch,
the snapshot copier resolving its paths, the change's own thread) and a
live soak's scan got about a quarter of the turns, late by a period. So
background work also gives way to the scan: the real clock tells the
gate, each time the scan goes idle, until when it sleeps (scan_sleeps),
and background work runs in that window only. It waits at the start of
background() and at each pause() of its loops (a path resolved, a class
taken apart) from shortly before the scan's release until the scan goes
idle again; the scan then finds the lock free but for what one step of
background work takes. A scan that leaves no window (its tasks overrun)
keeps the gate shut for at most STARVE_S after its last window closed
(however long that window was): then background work runs beside it
again, as it did before, until a window comes. A pause() in the scan's
own thread, or with no scan on the real clock, never waits.

    for path in paths:
        pause()                    # never while holding a lock the scan takes
        places[path] = resolver.place(path)
"""

from __future__ import annotations

import math
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager

SWITCH_S = 0.0005  # the switch interval while background work runs
MARGIN_NS = 500_000  # background work stops this long before the scan wakes (a step ends within it)
STARVE_S = 0.1  # the last window closed this long ago: background work runs beside the scan

_gate = threading.Condition(threading.Lock())
_open_until: float = math.inf  # perf_counter_ns() until which background work may run
_scan: int | None = None  # the thread that sleeps in scan_sleeps (its pause() never waits)

_lock = threading.Lock()
_running = 0  # the background() blocks under way, in every thread
_saved = 0.0  # the interval before the first of them


def scan_sleeps(wake_ns: int) -> None:
    """The scan thread goes idle until time.perf_counter_ns() is wake_ns
    (the real clock, before it sleeps): background work may run until
    MARGIN_NS before that. No window when that is past already."""
    global _open_until, _scan
    _scan = threading.get_ident()
    now = time.perf_counter_ns()
    until = wake_ns - MARGIN_NS
    if until > now:
        with _gate:
            _open_until = until
            _gate.notify_all()


def scan_ends() -> None:
    """No more scans on the real clock (engine.run returns): the gate open."""
    global _open_until, _scan
    with _gate:
        _open_until, _scan = math.inf, None
        _gate.notify_all()


def pause(room_ns: int = 0) -> None:
    """Wait while the scan runs or is about to (see the module docstring):
    a step of background work, never while holding a lock the scan takes.
    room_ns: a step that cannot be cut (a C call) and takes about that
    long waits for a window with that much of it left."""
    if time.perf_counter_ns() + room_ns < _open_until or threading.get_ident() == _scan:
        return

    def open_() -> bool:
        now = time.perf_counter_ns()
        return now + room_ns < _open_until or now - _open_until > STARVE_S * 1e9

    with _gate:
        _gate.wait_for(open_, STARVE_S)


@contextmanager
def background(seconds: float = SWITCH_S, paced: bool = True) -> Iterator[None]:
    """The interpreter's switch interval at most seconds meanwhile, once the
    gate lets it begin (paced; see the module docstring): not paced when
    the scan may be waiting for this work."""
    global _running, _saved
    if paced:
        pause()
    with _lock:
        if _running == 0:
            _saved = sys.getswitchinterval()
            sys.setswitchinterval(min(_saved, seconds))
        _running += 1
    try:
        yield
    finally:
        with _lock:
            _running -= 1
            if _running == 0:
                sys.setswitchinterval(_saved)
