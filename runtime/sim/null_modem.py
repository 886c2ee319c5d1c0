"""A serial cable between two programs on this machine: two pseudo-terminal
pairs joined by a relay thread, like `socat pty pty` with a pair of scissors.

    cable = NullModem()
    cable.master_port    # "/dev/pts/7": the Modbus master opens it as a serial port
    cable.slave_port     # "/dev/pts/8": the simulated slave's port
    cable.cut()          # the line goes silent in both directions
    cable.mend()
    cable.sent_by_master(), cable.sent_by_slave()   # the bytes that went through
                                                    # (the newest RECORD_BYTES at least)

Both ends are real ttys opened through pyserial by their users, so the
master's RTU code path is the one it takes on /dev/ttyUSB0; only the baud
rate has no effect on the speed.
"""

from __future__ import annotations

import os
import pty
import select
import threading
import tty

#: what a cable keeps of the bytes each way: the newest RECORD_BYTES at least,
#: 2 * RECORD_BYTES at most, so that a plant run for days does not grow
RECORD_BYTES = 1 << 16


def keep_recent(record: bytearray) -> None:
    """Drop a record's oldest bytes once it holds twice RECORD_BYTES."""
    if len(record) > 2 * RECORD_BYTES:
        del record[: len(record) - RECORD_BYTES]


class NullModem:
    def __init__(self, name: str = "null modem") -> None:
        self._ends = []
        paths = []
        for _ in range(2):
            master, slave = pty.openpty()
            tty.setraw(slave)  # no echo, no line discipline: bytes go through as they are
            self._ends.append((master, slave))
            paths.append(os.ttyname(slave))
        self.master_port, self.slave_port = paths
        self._wire = {0: bytearray(), 1: bytearray()}
        self._lock = threading.Lock()
        self._cut = False
        self._closing = False
        self._wake_r, self._wake_w = os.pipe()
        self._thread = threading.Thread(target=self._relay, name=name, daemon=True)
        self._thread.start()

    # ---------------------------------------------------------------- the cable

    def cut(self) -> None:
        """Nothing goes through any more (bytes sent meanwhile are lost)."""
        self._cut = True

    def mend(self) -> None:
        self._cut = False

    def sent_by_master(self) -> bytes:
        with self._lock:
            return bytes(self._wire[0])

    def sent_by_slave(self) -> bytes:
        with self._lock:
            return bytes(self._wire[1])

    def clear(self) -> None:
        with self._lock:
            self._wire[0].clear()
            self._wire[1].clear()

    # ---------------------------------------------------------------- relay

    def _relay(self) -> None:
        a, b = self._ends[0][0], self._ends[1][0]
        other = {a: (b, 0), b: (a, 1)}
        while not self._closing:
            ready, _, _ = select.select([a, b, self._wake_r], [], [])
            for fd in ready:
                if fd == self._wake_r:
                    continue
                try:
                    data = os.read(fd, 4096)
                except OSError:  # the other side closed its end
                    continue
                if self._cut or not data:
                    continue
                target, side = other[fd]
                with self._lock:
                    self._wire[side] += data
                    keep_recent(self._wire[side])
                os.write(target, data)

    def close(self) -> None:
        self._closing = True
        os.write(self._wake_w, b"x")
        self._thread.join(timeout=2)
        for master, slave in self._ends:
            os.close(master)
            os.close(slave)
        os.close(self._wake_r)
        os.close(self._wake_w)
