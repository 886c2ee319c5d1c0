"""Frames decided under a driver's lock, sent once it is released.

A CAN protocol driver (the CANopen master, the plain CAN driver) decides
frames while it holds the lock its state is under; sending there would make
whoever waits for that lock (the scan, for a copy) wait behind the bus.
So the frame goes into an Outbox and the driver calls flush() after it lets
the lock go:

    self._outbox = Outbox(self._put)     # put(*frame): one frame on the bus
    with self._lock:
        self._outbox.add(can_id, data)   # decided
    self._outbox.flush()                 # sent, in the order decided

One thread at a time sends (the frames keep their order); a thread that
finds another sending leaves its frames to it, which looks at the outbox
again after it lets go, so none is left behind.
"""

from __future__ import annotations

import threading
from collections import deque
from collections.abc import Callable
from typing import Any


class Outbox:
    def __init__(self, put: Callable[..., Any]) -> None:
        self._put = put
        self._frames: deque[tuple] = deque()
        self._sending = threading.Lock()  # held by the thread emptying the outbox

    def add(self, *frame: Any) -> None:
        """A frame decided: put(*frame) at the next flush()."""
        self._frames.append(frame)

    def flush(self) -> None:
        """Send what waits, in order, holding no lock but the outbox's own."""
        while self._frames:
            if not self._sending.acquire(blocking=False):
                return  # the sender takes these too
            try:
                while self._frames:
                    self._put(*self._frames.popleft())
            finally:
                self._sending.release()
