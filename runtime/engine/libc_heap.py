"""glibc's malloc set for a PLC that runs for months (softplc run): the
memory Python frees is used again, or goes back to the system, instead of
piling up in one arena per thread.

Found by the live soak (benchmarks/bench_soak_live.py --without faults
--change-every 60: the default plant, its web page, OPC UA and Modbus
servers, their clients, an online change a minute). The PLC's RSS grew by
1 to 3 MB at each change while the objects alive stayed the same
(sys.getallocatedblocks() some 1,000 more a change, gc's frozen objects
the same), and malloc_trim() gave back no more than 3 MB. Each change
reads a program back (1.5 MB of pickle, 60,000 objects) in the thread
that asked for it: the file watcher's or a server call's. glibc gives
every thread an arena of its own (up to 8 per core), and after the first
1.5 MB buffer was freed it raised its mmap threshold to that size, so the
next buffers came from those arenas too, and the arenas fragmented. Two
arenas and a fixed threshold of 128 kB (glibc's default, no longer moved):
the RSS flat over the same changes (0.1 MB a change).

    steady_malloc()     # True when glibc took the settings

A parameter the environment sets (MALLOC_ARENA_MAX, MALLOC_MMAP_THRESHOLD_)
is the user's choice: kept. Another C library (musl, macOS): nothing done.
"""

from __future__ import annotations

import ctypes
import os
import sys

#: mallopt's parameters (glibc's malloc.h)
M_MMAP_THRESHOLD, M_ARENA_MAX = -3, -8
#: what softplc run asks for (see the module's docstring)
ARENAS = 2
MMAP_THRESHOLD = 128 * 1024

_SETTINGS = (
    ("MALLOC_ARENA_MAX", M_ARENA_MAX, ARENAS),
    ("MALLOC_MMAP_THRESHOLD_", M_MMAP_THRESHOLD, MMAP_THRESHOLD),
)


def _mallopt():
    """glibc's mallopt, or None under another C library."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        if not os.confstr("CS_GNU_LIBC_VERSION"):
            return None
        return ctypes.CDLL(None).mallopt
    except (ValueError, OSError, AttributeError):  # no such confstr name, no libc symbols
        return None


def steady_malloc() -> bool:
    """glibc's arenas limited to ARENAS and its mmap threshold fixed at
    MMAP_THRESHOLD (each unless the environment sets it). False under
    another C library, or when glibc refused a setting."""
    mallopt = _mallopt()
    if mallopt is None:
        return False
    ok = True
    for variable, parameter, value in _SETTINGS:
        if variable not in os.environ:
            ok = bool(mallopt(parameter, value)) and ok
    return ok


__all__ = ["ARENAS", "MMAP_THRESHOLD", "steady_malloc"]
