"""A fake plain-CAN device that plugs in through the public seam, as a
third-party package would: a beacon that sends a counter in 8-byte frames
on CAN-ID 0x180 + its number (byte 0 = 0xB0, bytes 1-2 the counter, big
endian). Its node puts the counter into a %IW word of the configuration's
choosing and, with poll = true, asks for it (an empty frame on 0x100 + its
number) at every advance of the driver and at every cycle end.

    [[plaincan]]
    type = "beacon"
    number = 5
    input = "%IW10"

Tests register it with registry.extended(DEVICE).
"""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import Field

from softplc.runtime.config.values import int_range
from softplc.runtime.io.plaincan import MalformedFrame, NodeOptions, PlainCanKind
from softplc.runtime.plugin.driver import DriverStatus
from softplc.runtime.plugin.seams import Device

BASE_ID = 0x180
POLL_ID = 0x100
MARK = 0xB0


class BeaconOptions(NodeOptions):
    number: Annotated[int, int_range(1, 15)] = Field(description="the beacon's number, 1 to 15")
    input: Any = Field(description='where its counter lands, such as "%IW10"')
    poll: bool = Field(False, description="ask for the counter at every advance and cycle end")

    @classmethod
    def check(cls, here, table, ctx) -> None:
        if "input" in table:
            ctx.address(here + ("input",), table["input"], '"%IW10"')

    @classmethod
    def ids(cls, table):
        number = table.get("number")
        if not isinstance(number, int):
            return set(), set()
        return {BASE_ID + number}, ({POLL_ID + number} if table.get("poll") else set())

    @classmethod
    def default_name(cls, kind, table):
        number = table.get("number")
        return f"beacon{number}" if isinstance(number, int) else None


class BeaconNode:
    def __init__(self, cfg, ctx) -> None:
        self.name = cfg.name
        self.number = cfg.options.number
        self.receives = frozenset({BASE_ID + self.number})
        self.services: dict = {}
        self.input = cfg.options.input
        self.counter: int | None = None
        self.frames = 0
        self.poll = cfg.options.poll
        self.send = ctx.send

    def on_frame(self, can_id: int, data: bytes, now_ns: int) -> None:
        if len(data) != 8:
            raise MalformedFrame(f"{len(data)} bytes, not 8")
        if data[0] != MARK:
            raise MalformedFrame(f"byte 0 is 0x{data[0]:02X}, not 0x{MARK:02X}")
        self.counter = int.from_bytes(data[1:3], "big")
        self.frames += 1

    def advance(self, now_ns: int) -> None:
        if self.poll:
            self.send(POLL_ID + self.number, b"")

    def read_inputs(self, image, now_ns: int) -> None:
        if self.counter is not None:
            image.write(self.input, self.counter)

    def write_outputs(self, image) -> None:
        if self.poll:
            self.send(POLL_ID + self.number, b"")

    def bind_program(self, globals_obj) -> None:
        pass

    def status(self) -> DriverStatus:
        return DriverStatus(self.counter is not None, "" if self.counter is not None else f"{self.name}: silent")

    def stop(self) -> None:
        pass


DEVICE = Device(name="beacon", order=90, node_kind=PlainCanKind(options=BeaconOptions, build=BeaconNode))
