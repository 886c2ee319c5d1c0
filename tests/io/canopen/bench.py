"""A test bench for simulated CANopen devices: python-can's in-process
virtual bus, a VirtualClock and one BusPump; the test is the CANopen master,
a CanEndpoint of its own that sends raw frames and records every frame it
receives. Time moves only through Bench.run_ms, in 10 ms steps, as the
engine would move it; nothing sleeps."""

from __future__ import annotations

import itertools

import pytest

from softplc.runtime.devices.ltmr.sim import LtmrSimulator
from softplc.runtime.engine.clock import VirtualClock
from softplc.runtime.io.can.bus import BusPump, BusSettings, CanEndpoint, open_bus

MS = 1_000_000
MASTER_NODE = 0x7F
_channels = itertools.count()


class Bench:
    def __init__(self) -> None:
        self.clock = VirtualClock()
        self.pump = BusPump()
        self.settings = BusSettings("virtual", f"test-sim-{next(_channels)}")
        self.frames: list = []  # (time ns, COB-ID, data) as the master received them
        self.master = CanEndpoint(open_bus(self.settings), name="test master", pump=self.pump)
        self.master.add_handler(
            lambda msg: self.frames.append((self.clock.now_ns(), msg.arbitration_id, bytes(msg.data)))
        )
        self.master.start()
        self.devices: list = []
        self.master_heartbeat_ms = 0  # the master's own heartbeat (0x77F), 0 = none
        self._next_master_heartbeat = 0
        self.last_master_heartbeat_ns = None

    # ---------------------------------------------------------------- devices

    def add(self, device):
        """Start a device (its boot-up frame goes out) and keep it advancing with the bench."""
        device.start()
        self.devices.append(device)
        self.pump.settle()
        return device

    def ltmr(self, node_id: int = 40, **kwargs) -> LtmrSimulator:
        return self.add(LtmrSimulator(node_id, settings=self.settings, clock=self.clock, pump=self.pump, **kwargs))

    # ---------------------------------------------------------------- time

    @property
    def now_ms(self) -> float:
        return self.clock.now_ns() / MS

    def run_ms(self, ms: float, step_ms: float = 10) -> None:
        end = self.clock.now_ns() + round(ms * MS)
        step = round(step_ms * MS)
        while self.clock.now_ns() < end:
            now = min(end, self.clock.now_ns() + step)
            self.clock.sleep_until(now)
            if self.master_heartbeat_ms and now >= self._next_master_heartbeat:
                self._next_master_heartbeat = now + self.master_heartbeat_ms * MS
                self.master.send(0x700 + MASTER_NODE, bytes([0x05]))
                self.last_master_heartbeat_ns = now
            for device in self.devices:
                device.advance_to(now)
            self.pump.settle()

    def run_until(self, predicate, limit_ms: float, what: str, step_ms: float = 10) -> float:
        start = self.now_ms
        while not predicate():
            if self.now_ms - start >= limit_ms:
                raise AssertionError(f"{what}: not within {limit_ms} ms of virtual time")
            self.run_ms(step_ms, step_ms)
        return self.now_ms - start

    # ---------------------------------------------------------------- frames

    def send(self, can_id: int, data) -> None:
        """A raw frame from the master (hex text or bytes), delivered at once."""
        self.master.send(can_id, bytes.fromhex(data) if isinstance(data, str) else bytes(data))
        self.pump.settle()

    def frames_with(self, can_id: int) -> list:
        return [data for _t, cid, data in self.frames if cid == can_id]

    def times_of(self, can_id: int) -> list:
        return [t for t, cid, _d in self.frames if cid == can_id]

    def clear(self) -> None:
        self.frames.clear()

    def sdo(self, node_id: int, request) -> bytes:
        """One expedited SDO exchange: the request to 0x600+n, the one response from 0x580+n."""
        self.clear()
        self.send(0x600 + node_id, request)
        responses = self.frames_with(0x580 + node_id)
        assert len(responses) == 1, f"expected one SDO response, got {[r.hex(' ') for r in responses]}"
        return responses[0]

    def sdo_write(self, node_id: int, index: int, sub: int, value: int, size: int) -> bytes:
        command = {1: 0x2F, 2: 0x2B, 4: 0x23}[size]  # CiA 301 expedited download
        request = bytes([command, index & 0xFF, index >> 8, sub]) + value.to_bytes(size, "little").ljust(4, b"\0")
        return self.sdo(node_id, request)

    def sdo_read(self, node_id: int, index: int, sub: int) -> bytes:
        return self.sdo(node_id, bytes([0x40, index & 0xFF, index >> 8, sub, 0, 0, 0, 0]))

    def nmt(self, command: int, node_id: int) -> None:
        self.send(0x000, bytes([command, node_id]))

    def guard(self, node_id: int) -> list:
        """One node-guarding request (an RTR at 0x700 + node id); the replies."""
        self.clear()
        self.master.send(0x700 + node_id, b"", remote=True)
        self.pump.settle()
        return self.frames_with(0x700 + node_id)

    def close(self) -> None:
        for device in self.devices:
            device.stop()
        self.master.stop()


def abort_frame(index: int, sub: int, code: int) -> bytes:
    """CiA 301 SDO abort: 0x80, index, sub-index, the abort code (little-endian)."""
    return bytes([0x80, index & 0xFF, index >> 8, sub]) + code.to_bytes(4, "little")


def write_ok(index: int, sub: int) -> bytes:
    """CiA 301 download confirmation (digest 001 §3.4: 0x60, not the manual's 0x40, A3)."""
    return bytes([0x60, index & 0xFF, index >> 8, sub, 0, 0, 0, 0])


@pytest.fixture
def bench():
    made = Bench()
    yield made
    made.close()
