"""What a simulated device at a unit id of a Modbus line is (SimulatedUnit),
and how it refuses a request (ModbusRefusal). Pure: no pymodbus, so device
models import it without the server."""

from __future__ import annotations

from typing import Protocol

from ...plugin.seams import SimFault

#: every simulated Modbus unit takes it (io/modbus/line.py UnitOnLine.inject)
SILENT = SimFault("silent", "the unit stops answering (switched off, or its cable cut)", lasting=True)


class ModbusRefusal(Exception):
    """A unit refuses a request: .code is the Modbus exception code (2 illegal
    data address, 3 illegal data value)."""

    def __init__(self, code: int, message: str) -> None:
        super().__init__(message)
        self.code = code
        self.message = message


class SimulatedUnit(Protocol):
    """A device model at one unit id of a SimulatedModbusLine. Addresses are
    PDU addresses (from 0); a refusal raises ModbusRefusal."""

    functions: tuple[int, ...]  # the function codes it answers

    def telegram(self, now_ns: int) -> None: ...

    def serve_read(self, address: int, count: int, now_ns: int) -> list[int]: ...

    def serve_write(self, address: int, values: list[int], now_ns: int) -> None: ...

    def advance(self, now_ns: int) -> None: ...

    def inject(self, fault: str, value, on: bool) -> None:
        """A fault of its device's sim_faults but SILENT (the line's), at the last advanced time."""
