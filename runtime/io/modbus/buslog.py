"""The Modbus wire recorded (`softplc run --bus-log FILE`): every request
the PLC's connections sent and the answer to it, as the bytes crossed the
line (RTU: address, PDU, CRC-16; TCP: the MBAP header and the PDU), in
STEM.modbus.log beside FILE (FILE itself is the CAN buses' python-can log),
one line per frame with its time in engine seconds:

    # softplc Modbus log: engine time (s), connection, TX (sent) or RX (received), the frame's bytes
    12.340000 drives TX 01 03 00 05 00 01 94 0B
    12.342105 drives RX 01 03 02 00 2A 38 5B

A request answered by nothing has no RX line; a request repeated by
pymodbus's retries is written once, with the last attempt's answer. The
times: the request when the connection's worker sent it, the answer that
plus its response time (in virtual time the modelled time on the line).

    log = ModbusWireLog(path, clock)      # DriverError: cannot write it
    link.wire = log.connection("drives")  # link.py calls it after each request
    log.stop()                            # with the drivers
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TextIO

from ...plugin.driver import DriverError, WireLog

HEADER = "# softplc Modbus log: engine time (s), connection, TX (sent) or RX (received), the frame's bytes\n"

#: what a link calls after a request: (engine ns it was sent, the frame sent, the answer or b"", its response time in s)
Record = Callable[[int, bytes, bytes, float], None]


def modbus_log_path(bus_log: Path) -> Path:
    """Where the Modbus frames of `--bus-log FILE` go: STEM.modbus.log beside FILE."""
    return bus_log.with_name(f"{bus_log.stem}.modbus.log")


class ModbusWireLog(WireLog):
    """One file for every [[modbus]] connection of an engine."""

    def __init__(self, path: Path, clock) -> None:
        super().__init__("modbus bus log", path)
        self._clock = clock
        try:
            self._file: TextIO = open(path, "w", encoding="ascii")  # closed by stop(), with the drivers
        except OSError as exc:
            raise DriverError(f"--bus-log: cannot write {path}: {exc.strerror or exc}") from None
        self._file.write(HEADER)

    def connection(self, name: str) -> Record:
        """What the link of the [[modbus]] connection name calls after each request."""

        def record(sent_ns: int, sent: bytes, received: bytes, response_s: float) -> None:
            lines = [f"{sent_ns / 1e9:.6f} {name} TX {sent.hex(' ').upper()}\n"] if sent else []
            if received:
                lines.append(f"{sent_ns / 1e9 + response_s:.6f} {name} RX {received.hex(' ').upper()}\n")
            with self.lock:
                if not self.closed and lines:
                    self._file.writelines(lines)
                    self.frames += len(lines)

        return record

    def close(self) -> None:
        self._file.close()


__all__ = ["HEADER", "ModbusWireLog", "Record", "modbus_log_path"]
