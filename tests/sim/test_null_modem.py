"""The serial null modem (runtime/sim/null_modem.py): bytes written at one
end come out at the other, and the cable's record of them stays bounded."""

from __future__ import annotations

import os
import select

from softplc.runtime.sim.null_modem import RECORD_BYTES, NullModem


def _read_exactly(fd: int, n: int) -> bytes:
    got = bytearray()
    while len(got) < n:
        ready, _, _ = select.select([fd], [], [], 30)
        assert ready, f"only {len(got)} of {n} bytes came through"
        got += os.read(fd, n - len(got))
    return bytes(got)


def test_the_record_keeps_the_newest_bytes_and_stays_bounded():
    """Found by the soak benchmark (benchmarks/bench_soak.py): the cable kept
    every byte that went through it, so a simulated line run for days grew
    without bound. It keeps the newest RECORD_BYTES at least, twice that at
    most."""
    cable = NullModem()
    master = os.open(cable.master_port, os.O_RDWR | os.O_NOCTTY)
    slave = os.open(cable.slave_port, os.O_RDWR | os.O_NOCTTY)
    try:
        chunk = bytes(range(256)) * 16  # 4 kB
        sent = 0
        for i in range(3 * RECORD_BYTES // len(chunk) + 1):
            data = bytes([i % 256]) + chunk[1:]
            os.write(master, data)
            assert _read_exactly(slave, len(data)) == data
            sent += len(data)
        record = cable.sent_by_master()
        assert RECORD_BYTES <= len(record) <= 2 * RECORD_BYTES < sent
        assert record.endswith(data)
        assert cable.sent_by_slave() == b""
    finally:
        os.close(master)
        os.close(slave)
        cable.close()
