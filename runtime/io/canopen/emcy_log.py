"""Emergencies (EMCY) of the nodes in the log: in the words of the node's
device where it has them (Device.emcy_text), and rate limited, so that a
node that repeats an emergency cannot flood the log.

Per node and error code, one line at most every interval of engine time
(10 s); the emergencies held back meanwhile are counted and the window
ends with a "suppressed N similar messages" line (runtime/io/ratelog.py).
All codes of all nodes together write at most the limiter's budget of lines
per interval, so a flood of ever new codes is bounded too. An all-zero EMCY
(CiA 301 "error reset or no error") is logged as the end of the emergency.
"""

from __future__ import annotations

import logging
from collections.abc import Callable

from ..ratelog import INTERVAL_NS, RateLimitedLog, monotonic_ns

log = logging.getLogger(__name__)

#: per node and code, the least engine time between two log lines
LOG_INTERVAL_NS = INTERVAL_NS

EmcyText = Callable[[int, int, bytes], str]


class EmcyLog:
    def __init__(self, interval_ns: int = LOG_INTERVAL_NS, clock: Callable[[], int] = monotonic_ns) -> None:
        self.lines = RateLimitedLog(log, clock, interval_ns=interval_ns)

    def emergency(self, name: str, node_id: int, code: int, register: int, data: bytes, text: EmcyText | None) -> bool:
        """Log one EMCY unless one of the same code was logged less than the
        interval ago; True if a line was written."""
        key = (node_id, code)
        if code == 0 and register == 0 and not any(data):
            return self.lines.info(key, "canopen: node %s (%d): emergency cleared", name, node_id)
        return self.lines.warning(
            key,
            "canopen: node %s (%d) emergency 0x%04X, error register 0x%02X, data %s%s",
            name,
            node_id,
            code,
            register,
            _Hex(data),
            _Words(text, code, register, data),
        )

    def flush(self, now_ns: int | None = None) -> None:
        self.lines.flush(now_ns)


class _Hex:
    """The data bytes in hex, worked out only if the line is written."""

    def __init__(self, data: bytes) -> None:
        self.data = data

    def __str__(self) -> str:
        return self.data.hex(" ")


class _Words:
    """ ": <the device's words>", worked out only if the line is written (a
    flood of EMCYs costs no text per frame)."""

    def __init__(self, text: EmcyText | None, code: int, register: int, data: bytes) -> None:
        self.args = (text, code, register, data)

    def __str__(self) -> str:
        text, code, register, data = self.args
        words = text(code, register, data) if text is not None else ""
        return f": {words}" if words else ""
