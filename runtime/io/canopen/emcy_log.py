"""Emergencies (EMCY) of the nodes in the log: in the words of the node's
device where it has them (Device.emcy_text), and rate limited, so that a
node that repeats an emergency cannot flood the log.

Per node and error code, one line at most every LOG_INTERVAL of engine
time; the next line says how many were held back. An all-zero EMCY (CiA
301 "error reset or no error") is logged as the end of the emergency.
"""

from __future__ import annotations

import logging
from collections.abc import Callable

log = logging.getLogger(__name__)

#: per node and code, the least engine time between two log lines
LOG_INTERVAL_NS = 10_000_000_000

EmcyText = Callable[[int, int, bytes], str]


class EmcyLog:
    def __init__(self, interval_ns: int = LOG_INTERVAL_NS) -> None:
        self.interval_ns = interval_ns
        self._last: dict[tuple[int, int], int] = {}  # (node id, code) -> engine time of its last line
        self._held: dict[tuple[int, int], int] = {}  # (node id, code) -> lines held back since

    def emergency(
        self, name: str, node_id: int, code: int, register: int, data: bytes, now_ns: int, text: EmcyText | None
    ) -> bool:
        """Log one EMCY unless one of the same code was logged less than the
        interval ago; True if a line was written."""
        key = (node_id, code)
        last = self._last.get(key)
        if last is not None and now_ns - last < self.interval_ns:
            self._held[key] = self._held.get(key, 0) + 1
            return False
        self._last[key] = now_ns
        held = self._held.pop(key, 0)
        more = f" ({held} more since the last line)" if held else ""
        if code == 0 and register == 0 and not any(data):
            log.info("canopen: node %s (%d): emergency cleared%s", name, node_id, more)
            return True
        words = text(code, register, data) if text is not None else ""
        log.warning(
            "canopen: node %s (%d) emergency 0x%04X, error register 0x%02X, data %s%s%s",
            name,
            node_id,
            code,
            register,
            data.hex(" "),
            f": {words}" if words else "",
            more,
        )
        return True
