"""What a device declares to be driven on plain CAN (its own protocol of raw
11-bit frames, no CANopen): a PlainCanKind in its Device's `node_kind`.

    KIND = PlainCanKind(
        options=Mpu2sNodeOptions,           # its own [[plaincan]] keys (NodeOptions)
        build=lambda cfg, ctx: Mpu2sNode(cfg, ctx),
    )

The bus (driver.py) owns the frames: it receives every frame of the [[can]]
bus through the PLC's shared CanPort, hands a node the frames whose CAN-ID
it listed in `receives`, counts what a node refuses as malformed and logs
it (one line per node and CAN-ID every 10 s, rate limited), and calls the
node at the cycle boundary. A node never waits on the bus (what it sends
goes out once the lock is released); everything it does runs under the
driver's lock (`NodeContext.lock`), from the receive
thread (on_frame), the driver's service (advance) or the scan thread
(read_inputs, write_outputs, its native functions' services).
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from ...config.relations import Relations
from ...config.values import Model
from ...image.memory import ProcessImage
from ...plugin.driver import DriverStatus
from ..ratelog import RateLimitedLog


class MalformedFrame(ValueError):
    """A frame a node cannot take (wrong length, bad checksum ...): counted
    and dropped; the reason is logged, once per node and CAN-ID every 10 s."""


class NodeOptions(Model):
    """A device's own [[plaincan]] keys: a model for pass 1, a check for
    pass 2, and what the node gets (build)."""

    @classmethod
    def check(cls, here: tuple, table: dict, ctx: Relations) -> None:
        """Pass 2 of the device's keys in one [[plaincan]] table."""

    @classmethod
    def ids(cls, table: dict) -> tuple[set[int], set[int]]:
        """From the raw table: the CAN-IDs the node receives and sends, for
        the collision check against the other protocols on the bus."""
        return set(), set()

    @classmethod
    def default_name(cls, kind: str, table: dict) -> str | None:
        """The node's name when the table gives none (None: not knowable)."""
        return None

    def build(self) -> Any:
        return self


@dataclass
class PlainCanNodeConfig:
    type: str  # the device name
    name: str
    key: str  # "plaincan[0]"
    bus: str  # its [[can]] bus
    options: Any  # what its NodeOptions built


@dataclass
class NodeContext:
    """What a node gets besides its configuration."""

    clock: Any
    addressing: str
    where: str  # the configuration file, for messages
    send: Callable[[int, bytes], bool]  # a frame for the bus, sent once the lock is released (False: bus down)
    lock: threading.RLock  # the driver's: held around every call into the node
    shared: dict  # the dict every driver of the engine shares (one service object per device kind ...)
    lines: RateLimitedLog  # the driver's rate-limited log: what a node logs goes through it


class PlainCanNode(Protocol):
    name: str
    receives: frozenset[int]  # the CAN-IDs it takes
    services: dict  # native-function services it offers, by service name

    def on_frame(self, can_id: int, data: bytes, now_ns: int) -> None:
        """One received frame; MalformedFrame for one it cannot take."""

    def advance(self, now_ns: int) -> None:
        """Timers: request timeouts and pacing, staleness."""

    def read_inputs(self, image: ProcessImage, now_ns: int) -> None:
        """Cycle start: what arrived, into %I (and its diagnostics)."""

    def write_outputs(self, image: ProcessImage) -> None:
        """Cycle end."""

    def bind_program(self, globals_obj) -> None:
        """The program's globals, for diagnostic structs."""

    def status(self) -> DriverStatus:
        """Its word on the status line."""

    def stop(self) -> None:
        """The bus is about to close."""


@dataclass(frozen=True)
class PlainCanKind:
    options: type[NodeOptions]
    build: Callable[[PlainCanNodeConfig, NodeContext], PlainCanNode]
    #: `softplc log`: a frame of the bus in the device's words, for a node
    #: of this kind ((its options, can id, data) -> text, or None: not its)
    frame_text: Callable[[Any, int, bytes], str | None] | None = None
