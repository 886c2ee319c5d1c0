"""The CAN wire recorded (`softplc run --bus-log FILE`): every frame the
PLC's ports send and receive, in python-can's own writers, the format
chosen by FILE's ending (.asc Vector ASCII, .blf Vector binary, .log
candump, .trc PCAN, .csv; python-can's list), with time stamps in engine
time (seconds since the engine's start: virtual time in a test).

What is recorded is what a candump on the PLC's adapter shows: the frames
the PLC sends (Tx) and every frame it receives (Rx), once, whatever the
number of simulated devices on the bus (they have endpoints of their own,
which record nothing). A frame dropped while the PLC's endpoint is
unplugged is not on its wire and not in the log.

Each [[can]] bus is a channel, numbered in the file's order of [[can]]
tables from 0 (python-can's numbering: ASC and BLF show it plus 1, candump
as can0, can1 ...); an ASC file names them in events at time 0, which also
makes its times engine time (ASC counts from its first entry).

    wire = CanWireLog(path, clock, ["plant", "genset"])   # DriverError: a format python-can cannot write
    endpoint.wire = wire.channel("plant")                  # the port's endpoint (port.py)
    wire.stop()                                            # with the drivers: the file complete
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import can
from can.io.asc import ASCWriter
from can.io.generic import MessageWriter
from can.io.logger import MESSAGE_WRITERS

from ...plugin.driver import DriverError, WireLog

#: what an endpoint calls for a frame: (can id, data, remote, extended, received)
Record = Callable[[int, bytes, bool, bool, bool], None]


class CanWireLog(WireLog):
    """One file for every [[can]] bus of an engine."""

    def __init__(self, path: Path, clock, buses: list[str]) -> None:
        super().__init__("can bus log", path)
        self._clock = clock
        self._numbers = {name: i for i, name in enumerate(buses)}
        try:
            self._writer: MessageWriter = can.Logger(str(path))
        except ValueError:
            endings = ", ".join(sorted(MESSAGE_WRITERS))
            raise DriverError(
                f"--bus-log {path}: python-can writes no {path.suffix or 'such'} file (the ending says how: {endings})"
            ) from None
        except OSError as exc:
            raise DriverError(f"--bus-log {path}: cannot write it: {exc.strerror or exc}") from None
        if isinstance(self._writer, ASCWriter):  # its times count from its first entry: this one, at 0
            for name, number in self._numbers.items():
                self._writer.log_event(f"softplc: channel {number + 1} is [[can]] {name}", 0.0)

    def channel(self, bus: str) -> Record:
        """What the PLC's endpoint on the [[can]] bus named bus calls for each frame."""
        number = self._numbers.setdefault(bus, len(self._numbers))

        def record(can_id: int, data: bytes, remote: bool, extended: bool, received: bool) -> None:
            msg = can.Message(
                timestamp=self._clock.now_ns() / 1e9,
                arbitration_id=can_id,
                is_extended_id=extended,
                is_remote_frame=remote,
                dlc=len(data) if not remote else 0,
                data=None if remote else bytes(data),
                channel=number,
                is_rx=received,
            )
            with self.lock:
                if not self.closed:
                    self._writer.on_message_received(msg)
                    self.frames += 1

        return record

    def close(self) -> None:
        self._writer.stop()


def wire_log_of(ctx, buses: list[str]) -> CanWireLog | None:
    """The engine's one CanWireLog (BuildContext.shared), made at the first
    call when the run records its wire (ctx.bus_log), else None."""
    if ctx.bus_log is None:
        return None
    if "can.wire" not in ctx.shared:
        ctx.shared["can.wire"] = CanWireLog(Path(ctx.bus_log), ctx.clock, buses)
    return ctx.shared["can.wire"]


__all__ = ["CanWireLog", "Record", "wire_log_of"]
