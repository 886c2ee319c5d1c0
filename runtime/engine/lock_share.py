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
"""

from __future__ import annotations

import sys
import threading
from collections.abc import Iterator
from contextlib import contextmanager

SWITCH_S = 0.0005  # the switch interval while background work runs

_lock = threading.Lock()
_running = 0  # the background() blocks under way, in every thread
_saved = 0.0  # the interval before the first of them


@contextmanager
def background(seconds: float = SWITCH_S) -> Iterator[None]:
    """The interpreter's switch interval at most seconds meanwhile (see the module docstring)."""
    global _running, _saved
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
