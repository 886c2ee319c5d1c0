"""The plain-CAN driver of one [[can]] bus: the devices of its [[plaincan]]
tables, on the PLC's CanPort (io/can/port.py), which it shares with the
CANopen master when both are on one bus.

    receive thread  (real time) or the BusPump (virtual time): every frame of
                    the bus; a node's CAN-ID goes to that node under the lock
                    (into its shadow), anything else is someone else's
    advance         the nodes' timers (requests, timeouts, staleness): a
                    service thread every 5 ms in real time, the engine's
                    tick in virtual time (then the pump delivers the answers)
    read_inputs     cycle start: each node copies its shadow into %I
    write_outputs   cycle end

No thread waits on the bus while it holds the lock, so the scan's calls
(read_inputs, write_outputs, status) never wait behind a send or a reopen
(issue 31): a node's frames (send(), under the lock) go to an outbox that
the service sends once the lock is released (io/can/outbox.py: one thread
at a time, in order); in virtual time the scan's own requests go out at the end of
write_outputs, the engine's thread doing all the bus work there.

A frame a node refuses (MalformedFrame) is counted on the node and dropped;
one per node and CAN-ID is logged with the frame and its reason every 10 s
of engine time, the ones held back meanwhile in a "suppressed N" line
(runtime/io/ratelog.py, which every line of the driver goes through). A send
that fails marks the bus down (status line, logged) and the PLC's port
(io/can/port.py) opens it again with back-off, as it does an adapter that
was missing at the start.
"""

from __future__ import annotations

import logging
import threading

import can

from ...engine.clock import PeriodicService
from ...image.memory import ProcessImage
from ...plugin.driver import Driver, DriverError, DriverStatus
from ..can.outbox import Outbox
from ..can.port import CanPort
from ..ratelog import RateLimitedLog
from .kind import MalformedFrame, PlainCanNode

log = logging.getLogger(__name__)

SERVICE_PERIOD_S = 0.005


class PlainCanDriver(Driver):
    def __init__(self, bus: str, port: CanPort, *, clock) -> None:
        self.name = f"plaincan {bus}"
        self.bus = bus
        self.port = port
        self.clock = clock
        self.lock = threading.RLock()
        self.nodes: list[PlainCanNode] = []
        self._by_id: dict[int, PlainCanNode] = {}
        self.services: dict = {}
        self.malformed: dict[str, int] = {}  # node name -> frames refused
        self.lines = RateLimitedLog(log, clock.now_ns)  # what the driver logs, rate limited
        self.foreign = 0  # frames of the bus that are no node's (CANopen's ...)
        self._service: PeriodicService | None = None
        self._started = False
        self._outbox = Outbox(self._put)  # the nodes' frames (COB-ID, data), sent by its flush

    def add(self, node: PlainCanNode) -> None:
        for can_id in node.receives:
            other = self._by_id.get(can_id)
            if other is not None:  # config pass 2 refuses this; a second line of defence
                raise DriverError(f"{self.name}: CAN-ID 0x{can_id:03X} is both {other.name}'s and {node.name}'s")
            self._by_id[can_id] = node
        self.nodes.append(node)
        self.malformed[node.name] = 0
        for key, service in node.services.items():
            self.services.setdefault(key, service)

    # ------------------------------------------------------------ life cycle

    def start(self) -> None:
        endpoint = self.port.acquire(self.clock.now_ns())  # the adapter may be missing: the port waits
        endpoint.add_handler(self._on_frame)
        self._started = True
        self.lines.info(None, "%s: %d device(s) on %s", self.name, len(self.nodes), self.port.settings.describe())
        if not self.clock.virtual:
            self._service = PeriodicService(f"{self.name} service", self.clock, self._advance, SERVICE_PERIOD_S)
            self._service.start()

    def stop(self) -> None:
        if not self._started:
            return
        if self._service is not None:
            self._service.stop()
            self._service = None
        with self.lock:
            for node in self.nodes:
                node.stop()
        self._outbox.flush()
        self.port.release(self._on_frame)
        self._started = False

    def advance_to(self, now_ns: int) -> None:
        self._advance(now_ns)
        if self.port.pump is not None:
            self.port.pump.settle()

    def _advance(self, now_ns: int) -> None:
        self.lines.flush(now_ns)
        if self._started:
            self.port.try_open(now_ns)  # the bus down: open it again when due (port.py)
        with self.lock:
            for node in self.nodes:
                node.advance(now_ns)
        self._outbox.flush()

    def bind_program(self, globals_obj) -> None:
        for node in self.nodes:
            node.bind_program(globals_obj)

    # ------------------------------------------------------------ frames

    def send(self, can_id: int, data: bytes) -> bool:
        """For the nodes (under the lock): one frame into the outbox, sent
        once the lock is released; False when the bus is not open."""
        if not self.port.is_open:
            return False
        self._outbox.add(can_id, bytes(data))
        return True

    def _put(self, can_id: int, data: bytes) -> None:
        endpoint = self.port.endpoint
        if endpoint is None:
            return
        if endpoint.send(can_id, data) or not endpoint.connected:
            return
        if self.port.is_open:
            self.lines.error(
                "cannot send",
                "%s: cannot send: %s; opening the bus again with back-off",
                self.name,
                endpoint.last_error,
            )
            self.port.failed(self.clock.now_ns(), endpoint.last_error)

    def _on_frame(self, msg: can.Message) -> None:
        node = self._by_id.get(msg.arbitration_id)
        if node is None or msg.is_extended_id or msg.is_remote_frame:
            self.foreign += 1
            return
        data = bytes(msg.data)
        with self.lock:
            try:
                node.on_frame(msg.arbitration_id, data, self.clock.now_ns())
            except MalformedFrame as exc:
                self.malformed[node.name] += 1
                self.lines.warning(
                    ("malformed", node.name, msg.arbitration_id),
                    "%s: %s: frame 0x%03X [%s] dropped: %s",
                    self.name,
                    node.name,
                    msg.arbitration_id,
                    data.hex(" "),
                    exc,
                )

    # ------------------------------------------------------------ the scan

    def read_inputs(self, image: ProcessImage) -> None:
        now = self.clock.now_ns()
        with self.lock:
            for node in self.nodes:
                node.read_inputs(image, now)

    def write_outputs(self, image: ProcessImage) -> None:
        with self.lock:
            for node in self.nodes:
                node.write_outputs(image)
        if self.port.pump is not None:  # virtual time: the engine's thread does the bus work (real time: the service)
            self._outbox.flush()

    def status(self) -> DriverStatus:
        if self._started and not self.port.is_open:
            return DriverStatus(False, f"{self.name}: bus down ({self.port.describe_down(self.clock.now_ns())})")
        with self.lock:
            states = [node.status() for node in self.nodes]
        up = sum(1 for s in states if s.ok)
        problems = [s.message for s in states if not s.ok and s.message]
        text = f"{self.name}: {up}/{len(states)} up"
        bad = sum(self.malformed.values())
        if bad:
            text += f", {bad} malformed"
        if problems:
            text += " (" + "; ".join(problems) + ")"
        return DriverStatus(up == len(states), text)
