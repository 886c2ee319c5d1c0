"""Runtime faults of ST code, located in the ST source.

Generated code raises ordinary Python exceptions (ZeroDivisionError from an
integer division, RangeFault from a bounds check, AttributeError from a NULL
reference ...). ``fault_from_exception`` turns any of them into an STFault by
mapping the innermost frame of generated code back to the ST statement, so
the engine never lets a Python exception escape.
"""

from __future__ import annotations

import sys

from .ast import Pos

try:
    import resource
except ImportError:  # Windows: no resource module, no limit to show
    resource = None  # type: ignore[assignment]


class STFault(Exception):
    """A runtime fault with its ST location. kind is a short stable word
    ('division', 'bounds', 'range', 'reference', 'watchdog', 'overflow',
    'recursion', 'memory', 'internal'; 'stop' for a cycle ended by a stop
    request, which is no fault of the program)."""

    def __init__(self, kind: str, message: str, pos: Pos | None = None) -> None:
        self.kind = kind
        self.message = message
        self.pos = pos
        super().__init__(str(self))

    def __str__(self) -> str:
        where = f"{self.pos}: " if self.pos else ""
        return f"{where}runtime fault: {self.message}"


class RangeFault(Exception):
    """Raised by generated code for an array index or subrange violation."""

    def __init__(self, kind: str, message: str) -> None:
        self.kind = kind
        super().__init__(message)


#: loop iterations between two checks of the cooperative watchdog (its
#: clock and a stop request): about 20 us .. a few ms of ST, while a check
#: costs well under 1 us (program/context.py does the counting)
LOOP_CHECK_EVERY = 1024


class WatchdogFault(Exception):
    """Raised by the cooperative watchdog check on a loop back-edge."""


class StopRequested(Exception):
    """Raised by the same check once the run is stopping (SIGTERM, Ctrl-C):
    the cycle ends in the loop instead of finishing it. Its text says why."""


NULL_REFERENCE = "invalid reference: a NULL REF_TO/POINTER dereferenced, or an unbound REFERENCE TO used"
NULL_INTERFACE = "invalid interface: it designates no function block instance (it is 0)"
#: the Python names of methods and property accessors (st/check/checker_oop.py)
_OOP_MEMBERS = ("m_", "pg_", "ps_")


def out_of_bounds(index: int, lo: int, hi: int) -> int:
    raise RangeFault("bounds", f"array index {index} is outside the bounds {lo}..{hi}")


def out_of_range(value: int, lo: int, hi: int) -> int:
    raise RangeFault("range", f"value {value} is outside the subrange {lo}..{hi}")


def _classify(exc: BaseException) -> tuple:
    if isinstance(exc, ZeroDivisionError):
        return "division", "division by zero"
    if isinstance(exc, RangeFault):
        return exc.kind, str(exc)
    if isinstance(exc, StopRequested):
        return "stop", f"{exc or 'stop requested'}: the cycle was ended in a loop"
    if isinstance(exc, WatchdogFault):
        return "watchdog", str(exc) or "watchdog: the cycle took too long (endless loop?)"
    if isinstance(exc, AttributeError) and exc.obj is None and (exc.name or "").startswith(_OOP_MEMBERS):
        # a method or property through an interface that holds none: Python's
        # own check (None has no m_step), no test in the generated code
        return "reference", NULL_INTERFACE
    if isinstance(exc, (AttributeError, TypeError)) and "NoneType" in str(exc):
        return "reference", NULL_REFERENCE
    if isinstance(exc, RecursionError):
        return "recursion", "call depth exceeded (recursive calls are not supported)"
    if isinstance(exc, OverflowError):
        return "overflow", f"arithmetic overflow ({exc})"
    if isinstance(exc, MemoryError):
        return "memory", f"out of memory: the process could not get the memory this statement needs{_memory_use()}"
    return "internal", f"internal error {type(exc).__name__}: {exc}"


def _memory_use() -> str:
    """' (peak resident 812 MB, address-space limit 1024 MB)': what the
    process held at most and the limit it hit, where the system says."""
    if resource is None:
        return ""
    try:
        peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
        limit, _hard = resource.getrlimit(resource.RLIMIT_AS)
    except (OSError, ValueError):
        return ""
    peak_mb = peak >> 20 if sys.platform == "darwin" else peak >> 10  # bytes on macOS, KiB elsewhere
    parts = [f"peak resident {peak_mb:,} MB"]
    if limit != resource.RLIM_INFINITY:
        parts.append(f"address-space limit {limit >> 20:,} MB")
    return f" ({', '.join(parts)})"


def fault_from_exception(exc: BaseException, linemaps: dict) -> STFault:
    """linemaps: generated-code filename -> {python line: ast.Pos}."""
    if isinstance(exc, STFault):
        return exc
    kind, message = _classify(exc)
    pos = None
    tb = exc.__traceback__
    while tb is not None:  # the innermost frame in generated code wins
        lines = linemaps.get(tb.tb_frame.f_code.co_filename)
        if lines is not None:
            found = lines.get(tb.tb_lineno)
            if found is not None:
                pos = found
        tb = tb.tb_next
    fault = STFault(kind, message, pos)
    fault.__cause__ = exc
    return fault
