"""A fake device that plugs in through the public seam, as a third-party
package would: a relay on a Modbus line, with one function block (RELAY in
relay.st), one register (the coil, offset 0) and a simulator (RelayUnit),
and one [[sim]] key of its own (closed, the coil at start).

    [[sim]]
    type = "relay"
    unit = 3
    closed = true

An installed package names DEVICE under the entry point group
softplc.devices; tests register it with registry.extended(DEVICE).
"""

from __future__ import annotations

from pydantic import Field

from softplc.runtime.config import SimOptions
from softplc.runtime.io.modbus import ModbusRefusal
from softplc.runtime.plugin.seams import Device, StLibrary

COIL = 0  # the one register: PDO address 0 ("40001")


class RelayUnit:
    """The relay as its Modbus unit: reads and writes of register 0 only."""

    functions = (3, 6)

    def __init__(self, closed: bool = False) -> None:
        self.closed = closed
        self.switchings = 0
        self.telegrams = 0

    def telegram(self, now_ns: int) -> None:
        self.telegrams += 1

    def serve_read(self, address: int, count: int, now_ns: int) -> list[int]:
        if address != COIL or count != 1:
            raise ModbusRefusal(2, f"the relay has one register, at {COIL}")
        return [int(self.closed)]

    def serve_write(self, address: int, values: list[int], now_ns: int) -> None:
        if address != COIL:
            raise ModbusRefusal(2, f"the relay has one register, at {COIL}")
        if values[0] not in (0, 1):
            raise ModbusRefusal(3, "the coil is 0 (open) or 1 (closed)")
        if bool(values[0]) != self.closed:
            self.switchings += 1
        self.closed = bool(values[0])

    def advance(self, now_ns: int) -> None:
        pass


class RelayOptions(SimOptions):
    closed: bool = Field(False, description="true or false")


def _simulator(sim, ctx) -> RelayUnit:
    return RelayUnit(closed=sim.options.closed)


DEVICE = Device(
    name="relay",
    bus="modbus",
    sim_types=("relay",),
    sim_options=RelayOptions,
    simulator=_simulator,
    libraries=(StLibrary(__name__, "relay.st"),),
)
