"""canopen's own log lines, through softplc's logging and rate limited.

The canopen library logs under the logger "canopen" ("Transfer aborted by
client with code 0x05040000" at every SDO timeout, "No SDO response
received" at every retry, an SDO server's exception with its traceback).
Nothing in softplc configures that logger, so Python wrote those lines raw
on stderr (its last-resort handler: no time, no level, no "softplc"), one
per event. route_library_log() gives the logger one handler that hands its
warnings and errors to softplc.runtime.io.canopen.library, through a
RateLimitedLog (runtime/io/ratelog.py): they carry the engine time and the
level like every softplc line, similar ones (the same format string) at
most once per 10 s with a "suppressed N" line after, and they reach
nothing else (the "canopen" logger stops propagating).

The CANopen master routes them when it starts, with the engine's clock.
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable

from ..ratelog import RateLimitedLog, monotonic_ns

#: the library's logger
LIBRARY = "canopen"

log = logging.getLogger("softplc.runtime.io.canopen.library")


class _Forward(logging.Handler):
    def __init__(self) -> None:
        super().__init__(logging.WARNING)
        self.lines = RateLimitedLog(log, monotonic_ns)

    def emit(self, record: logging.LogRecord) -> None:
        try:
            text = record.getMessage()
        except Exception:  # a library line with bad arguments: its format, as it is
            text = str(record.msg)
        key = (record.name, str(record.msg))
        self.lines.log(record.levelno, key, "canopen library: %s", text, exc_info=record.exc_info)


_forward: _Forward | None = None
_lock = threading.Lock()


def route_library_log(clock: Callable[[], int] | None = None) -> RateLimitedLog:
    """Route the "canopen" logger through ours (once per process; again if
    someone removed the handler); clock: the engine's, for the rate limit
    (the last one given counts). Returns the limiter."""
    global _forward
    library = logging.getLogger(LIBRARY)
    with _lock:
        if _forward is None:
            _forward = _Forward()
        if _forward not in library.handlers:
            library.addHandler(_forward)
        library.propagate = False
        if clock is not None:
            _forward.lines.clock = clock
        return _forward.lines
