"""Log lines of a bus, rate limited: what a bus logs is driven by what
arrives on the wire, and a device that floods the bus (an EMCY every
0.1 ms, a stream of malformed frames, a slave that keeps failing) must not
flood the log.

    limited = RateLimitedLog(logging.getLogger(__name__), clock.now_ns)
    limited.warning(("emcy", node_id, code), "node %d: emergency 0x%04X", node_id, code)
    limited.flush()        # now and then (a driver's service): the summaries due

Two limits, both per `interval` of the clock given (the engine's: virtual
time in a test, so a flood of 10,000 frames gives the same lines every run):

  * per key (messages that are "similar": by default the same format
    string; a caller may pass a finer key, such as a node and an error
    code): at most `burst` lines per window. A window starts with a key's
    first line and lasts `interval`; what comes after the burst inside it
    is counted, not logged.
  * per limiter: at most `budget` lines per interval over all keys, so that
    many keys (a flood of EMCYs with a new error code each time) cannot
    flood it either; the lines over budget are counted too, together. A key
    is remembered only while its window lasts, so the limiter holds at most
    about twice `budget` keys, whatever comes.

A window that held lines back ends with one line, at the level of the
lines it held back:

    suppressed 9999 similar messages in 10 s; the last: node 5: emergency 0x8130

written when the key's next line comes or at the next flush() after the
window ended, whichever is first. So nothing is lost without a trace, and
the numbers add up: lines written + the numbers in "suppressed" lines = the
calls made (at a level the logger had enabled).

Thread-safe: a bus logs from its receive thread, its service thread and
its workers.

``PeerLogFilter`` does the same for a library's loggers (a server's:
uvicorn, asyncua), as a logging filter on a logger or a handler, and
writes each record on one line, its exception's type and message in place
of a traceback.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable, Hashable
from dataclasses import dataclass, field

from ..config.values import cut

#: the default window: one line per key per this much time
INTERVAL_NS = 10_000_000_000
#: the default most lines of one limiter per interval, over all keys
BUDGET = 20
_OVER_BUDGET = object()  # the key of the lines over the budget


def monotonic_ns() -> int:
    return time.monotonic_ns()


@dataclass
class _Window:
    start_ns: int
    level: int
    written: int = 0
    held: int = 0
    last: tuple = field(default=("", ()))  # (format, args) of the last line held back


class RateLimitedLog:
    def __init__(
        self,
        logger: logging.Logger,
        clock: Callable[[], int] = monotonic_ns,
        *,
        interval_ns: int = INTERVAL_NS,
        burst: int = 1,
        budget: int = BUDGET,
    ) -> None:
        self.logger = logger
        self.clock = clock
        self.interval_ns = interval_ns
        self.burst = burst
        self.budget = budget
        self.written = 0  # lines written, summaries included
        self.suppressed = 0  # calls held back so far (each appears in a summary once its window ends)
        self._windows: dict[Hashable, _Window] = {}
        self._budget_start = 0
        self._budget_used = 0
        self._next_flush_ns: int | None = None  # the earliest end of a window that held lines back
        self._lock = threading.Lock()

    # ------------------------------------------------------------------ logging

    def debug(self, key: Hashable | None, msg: str, *args) -> bool:
        return self.log(logging.DEBUG, key, msg, *args)

    def info(self, key: Hashable | None, msg: str, *args) -> bool:
        return self.log(logging.INFO, key, msg, *args)

    def warning(self, key: Hashable | None, msg: str, *args) -> bool:
        return self.log(logging.WARNING, key, msg, *args)

    def error(self, key: Hashable | None, msg: str, *args) -> bool:
        return self.log(logging.ERROR, key, msg, *args)

    def exception(self, key: Hashable | None, msg: str, *args) -> bool:
        """An error with the traceback of the exception being handled (only
        on the lines written, never per call)."""
        return self.log(logging.ERROR, key, msg, *args, exc_info=True)

    def log(self, level: int, key: Hashable | None, msg: str, *args, exc_info=None) -> bool:
        """Write the line unless its key or the budget is used up for now;
        True if it was written. key None: the format string is the key."""
        if not self.logger.isEnabledFor(level):
            return False
        now = self.clock()
        with self._lock:
            summaries = self._due(now)
            allowed = self._admit(msg if key is None else key, level, msg, args, now)
        self._write(summaries)
        if allowed:
            self.logger.log(level, msg, *args, exc_info=exc_info)
        return allowed

    def flush(self, now_ns: int | None = None) -> None:
        """Write the summaries of the windows that have ended. Cheap when
        none is due: a driver may call it at every tick."""
        due = self._next_flush_ns
        if due is None:
            return
        now = self.clock() if now_ns is None else now_ns
        if now < due and now >= due - self.interval_ns:  # (a clock that went back: flush all)
            return
        with self._lock:
            summaries = self._due(now)
        self._write(summaries)

    # ------------------------------------------------------------------ the windows (lock held)

    def _admit(self, key: Hashable, level: int, msg: str, args: tuple, now: int) -> bool:
        window = self._windows.get(key)
        if window is None or window.written < self.burst:
            if self._spend(now):
                if window is None:
                    window = self._windows[key] = _Window(now, level)
                window.written += 1
                self.written += 1
                return True
            window = self._windows.get(_OVER_BUDGET)  # the key has room, the limiter has not
            if window is None:
                window = self._windows[_OVER_BUDGET] = _Window(now, level)
        window.held += 1
        window.level = max(window.level, level)
        window.last = (msg, args)
        self.suppressed += 1
        end = window.start_ns + self.interval_ns
        if self._next_flush_ns is None or end < self._next_flush_ns:
            self._next_flush_ns = end
        return False

    def _spend(self, now: int) -> bool:
        if now - self._budget_start >= self.interval_ns or now < self._budget_start:
            self._budget_start, self._budget_used = now, 0
        if self._budget_used >= self.budget:
            return False
        self._budget_used += 1
        return True

    def _due(self, now: int) -> list:
        """Take the windows that ended (or that a clock going back ended):
        the summaries to write."""
        due = self._next_flush_ns
        if due is None or (now < due and now >= due - self.interval_ns):
            return []
        summaries = []
        next_due = None
        for key, window in list(self._windows.items()):
            end = window.start_ns + self.interval_ns
            if now >= end or now < window.start_ns:
                del self._windows[key]
                if window.held:
                    summaries.append((key is _OVER_BUDGET, window))
            elif window.held and (next_due is None or end < next_due):
                next_due = end
        self._next_flush_ns = next_due
        self.written += len(summaries)
        return summaries

    def _write(self, summaries: list) -> None:
        for level, msg, args in self._summaries(summaries):
            self.logger.log(level, msg, *args)

    def _summaries(self, summaries: list) -> list:
        """(level, format, args) of each summary line due."""
        out = []
        for over_budget, window in summaries:
            msg, args = window.last
            seconds = self.interval_ns / 1e9
            what = "more messages (over the limit of this log)" if over_budget else "similar messages"
            out.append(
                (window.level, "suppressed %d %s in %g s; the last: " + msg, (window.held, what, seconds, *args))
            )
        return out

    def admit(self, level: int, key: Hashable, msg: str, args: tuple = ()) -> tuple:
        """For a caller that writes its lines itself (PeerLogFilter): (True if
        this line may be written, [(level, format, args) of the summaries due])."""
        now = self.clock()
        with self._lock:
            summaries = self._due(now)
            allowed = self._admit(key, level, msg, args, now)
        return allowed, self._summaries(summaries)


#: a record's attribute: PeerLogFilter let it through already
_ADMITTED = "softplc_admitted"


class PeerLogFilter(logging.Filter):
    """On a logger or a handler that a peer's requests reach (a server
    library's: uvicorn, asyncua): every record rate limited as RateLimitedLog
    limits lines, per logger and format string, and written as one line,
    its exception's type and message (cut) in place of a traceback. So no
    client, however it fails, makes the PLC's log grow faster than the
    budget, nor write a traceback."""

    def __init__(
        self,
        clock: Callable[[], int] = monotonic_ns,
        *,
        interval_ns: int = INTERVAL_NS,
        burst: int = 1,
        budget: int = BUDGET,
    ) -> None:
        super().__init__()
        self.limiter = RateLimitedLog(
            logging.getLogger(__name__), clock, interval_ns=interval_ns, burst=burst, budget=budget
        )

    def filter(self, record: logging.LogRecord) -> bool:
        if getattr(record, _ADMITTED, False):
            return True
        text = one_line(record)
        allowed, summaries = self.limiter.admit(record.levelno, (record.name, str(record.msg)), "%s", (text,))
        setattr(record, _ADMITTED, True)
        for level, msg, args in summaries:
            logger = logging.getLogger(record.name)
            summary = logger.makeRecord(record.name, level, record.pathname, record.lineno, msg, args, None)
            setattr(summary, _ADMITTED, True)
            logger.handle(summary)
        if not allowed:
            return False
        record.msg, record.args = text, None
        record.exc_info = record.exc_text = record.stack_info = None
        return True


def one_line(record: logging.LogRecord) -> str:
    """The record's message with its exception's type and message instead of
    the traceback, on one line, cut (config/values.py cut)."""
    try:
        text = record.getMessage()
    except Exception:  # a library's format and arguments that do not agree
        text = f"{record.msg!r} {record.args!r}"
    exc = record.exc_info[1] if record.exc_info else None
    if exc is not None:
        text += f": {type(exc).__name__}: {exc}"
    return cut(" ".join(text.split()))
