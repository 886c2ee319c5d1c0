"""CAN endpoints: one node's connection to a CAN bus, shared by every CAN
protocol (the CANopen master, the simulated devices, plain-CAN devices such
as the MPU2-S later).

An endpoint owns one python-can bus object and hands every received frame to
its handlers, in order. Who calls the handlers depends on the clock:

    real time       a can.Notifier thread per endpoint, as on a plant PC
    virtual time    a BusPump shared by every endpoint of the engine: the
                    engine's thread delivers all pending frames at each tick
                    (BusPump.settle), so a sequence runs the same way every
                    time and no frame is still in flight when inputs are read

Everything above the endpoint (canopen's Network, the simulators) is the same
code in both modes.

    bus = open_bus(BusSettings("virtual", "plant", 250_000))
    ep = CanEndpoint(bus, name="master", pump=pump)   # pump=None: real time
    ep.add_handler(lambda msg: ...)
    ep.start(); ep.send(0x000, b"\\x01\\x28"); ep.stop()

An endpoint can be unplugged (a cut cable, a device switched off): it then
drops frames both ways until plugged again. Tests and the simulators use it.
An endpoint may also have no bus yet (bus None: the adapter was missing when
the PLC started, port.py): it sends and receives nothing until reopen()
gives it one.
"""

from __future__ import annotations

import logging
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import can
from can.interfaces.virtual import VirtualBus

from ...config.values import cut, got
from ...plugin.driver import DriverError
from ..ratelog import RateLimitedLog

log = logging.getLogger(__name__)
#: what an endpoint or the pump logs (a handler that fails on every frame ...), rate limited
lines = RateLimitedLog(log)

Handler = Callable[[can.Message], None]


@dataclass(frozen=True)
class BusSettings:
    """What python-can needs to open a bus. Nothing is hard-coded: any
    interface python-can knows (socketcan, pcan, kvaser, ixxat, vector,
    virtual ...), with its channel, bitrate and interface-specific options."""

    interface: str
    channel: str
    bitrate: int = 250_000
    options: dict = field(default_factory=dict)

    def describe(self) -> str:
        """For the log: the interface and the channel (a long one cut, as a configuration error cuts it)."""
        return f"{cut(self.interface)} channel {got(self.channel)} at {self.bitrate // 1000} kbit/s"


def open_bus(settings: BusSettings) -> can.BusABC:
    """A python-can bus, or DriverError naming the interface and the reason."""
    try:
        return can.Bus(
            interface=settings.interface, channel=settings.channel, bitrate=settings.bitrate, **settings.options
        )
    except (can.CanError, OSError, ValueError, ImportError, NotImplementedError) as exc:
        raise DriverError(f"cannot open CAN bus ({settings.describe()}): {exc}") from None


class CanEndpoint:
    def __init__(self, bus: can.BusABC | None, *, name: str = "", pump: BusPump | None = None) -> None:
        self.bus = bus
        self.name = name
        self.pump = pump
        self.connected = True
        self.sent = 0  # frames handed to the bus
        self.received = 0  # frames handed to the handlers
        self.send_errors = 0
        self.last_error = ""
        #: the PLC's endpoint of a run that records its wire (wire.py): called for each frame sent and received
        self.wire: Callable[[int, bytes, bool, bool, bool], None] | None = None
        self._handlers: list[Handler] = []
        self._notifier: can.Notifier | None = None
        self._started = False
        self._virtual = _is_plain_virtual(bus)

    # ------------------------------------------------------------ set-up

    def add_handler(self, handler: Handler) -> None:
        # a new list, not an append: the receive thread may be iterating the old one
        self._handlers = [*self._handlers, handler]

    def remove_handler(self, handler: Handler) -> None:
        self._handlers = [h for h in self._handlers if h is not handler]

    def start(self) -> None:
        if self._started:
            return
        self._started = True
        if self.pump is not None:
            self.pump.register(self)
            if self._virtual:
                setattr(self.bus.queue, _PUMPED, True)  # type: ignore[union-attr]
        elif self.bus is not None:
            self._notifier = can.Notifier(self.bus, [self._dispatch], timeout=0.1)

    def stop(self) -> None:
        """Stop receiving and close the bus."""
        if not self._started:
            return
        self._started = False
        if self.pump is not None:
            self.pump.unregister(self)
        if self._notifier is not None:
            self._notifier.stop(timeout=1.0)
            self._notifier = None
        try:
            if self.bus is not None:
                self.bus.shutdown()
        except Exception as exc:  # a bus that dies on close has nothing more to lose
            lines.debug(None, "%s: bus shutdown: %s", self.name, exc)

    def reopen(self, bus: can.BusABC) -> None:
        """Swap in a freshly opened bus after the old one failed (adapter
        unplugged, interface down) or for the first time (the adapter was
        missing at the start): the handlers stay, the counters go on."""
        old = self.bus
        if self._notifier is not None:
            self._notifier.stop(timeout=0.5)
            self._notifier = None
        try:
            if old is not None:
                old.shutdown()
        except Exception as exc:
            lines.debug(None, "%s: shutting the failed bus down: %s", self.name, exc)
        self.bus = bus
        self._virtual = _is_plain_virtual(bus)
        if self._virtual and self._started and self.pump is not None:
            setattr(bus.queue, _PUMPED, True)  # type: ignore[attr-defined]
        if self._started and self.pump is None:
            self._notifier = can.Notifier(self.bus, [self._dispatch], timeout=0.1)

    # ------------------------------------------------------------ frames

    def send(self, can_id: int, data=b"", *, remote: bool = False) -> bool:
        """Put one frame on the bus. False when it was not sent (unplugged,
        bus error); the error is counted and kept in last_error, never raised,
        because a lost bus must not stop the thread that sends."""
        if not self.connected:
            return False
        if self.bus is None:
            self.last_error = "the CAN bus is not open"
            return False
        try:
            if self._virtual:
                _virtual_send(self.bus, can_id, bytes(data), remote)
            else:
                msg = can.Message(
                    arbitration_id=can_id,
                    data=bytes(data),
                    is_extended_id=can_id > 0x7FF,
                    is_remote_frame=remote,
                    dlc=len(data) if not remote else 0,
                )
                self.bus.send(msg)
        except (can.CanError, OSError) as exc:
            self.send_errors += 1
            self.last_error = str(exc)
            return False
        self.sent += 1
        if self.wire is not None:
            self.wire(can_id, bytes(data), remote, can_id > 0x7FF, False)
        return True

    def poll(self) -> bool:
        """Pumped endpoints: receive one waiting frame, if any, and hand it
        to the handlers. True when a frame was taken from the bus."""
        bus = self.bus
        if bus is None:
            return False
        if self._virtual:
            # python-can's virtual bus: recv(timeout=0) is a get from its
            # receive queue (most polls find it empty) and the bus's filters.
            # A frame the filters drop is taken all the same (True): recv()
            # would answer None for it, and the pump would stop there with
            # the frames behind it still waiting.
            # Only the pump takes frames from this queue (no thread waits on
            # it), so they come straight off its deque, without the queue's
            # lock and notifications (see _virtual_send).
            waiting = bus.queue.queue  # type: ignore[attr-defined]
            if not waiting:
                return False
            try:
                bus._check_if_open()  # type: ignore[attr-defined]
                msg = waiting.popleft()
            except can.CanError as exc:
                self.last_error = str(exc)
                return False
            except IndexError:
                return False
            if bus._filters is None or bus._matches_filters(msg):
                self._dispatch(msg)
            return True
        try:
            msg = bus.recv(timeout=0)
        except (can.CanError, OSError) as exc:
            self.last_error = str(exc)
            return False
        if msg is None:
            return False
        self._dispatch(msg)
        return True

    def _dispatch(self, msg: can.Message) -> None:
        if not self.connected or msg.is_error_frame:
            return
        self.received += 1
        if self.wire is not None:
            self.wire(msg.arbitration_id, bytes(msg.data), msg.is_remote_frame, msg.is_extended_id, True)
        for handler in self._handlers:
            try:
                handler(msg)
            except Exception:  # one bad handler must not starve the others
                key = (self.name, getattr(handler, "__qualname__", None))
                lines.exception(key, "%s: handler failed on frame 0x%03X", self.name, msg.arbitration_id)


#: the mark of a pumped endpoint's receive queue (virtual time): only the
#: pump reads it, and no thread waits on it, so a frame for it goes straight
#: onto its deque (an atomic append) instead of through Queue.put, whose
#: lock and notification cost more than the rest of the delivery
_PUMPED = "_softplc_pumped"

_VIRTUAL_BUS_PARTS = ("queue", "channel", "channel_id", "receive_own_messages", "preserve_timestamps", "_check_if_open")


def _is_plain_virtual(bus: can.BusABC | None) -> bool:
    """python-can's in-process virtual bus, as this module knows its insides
    (a receive queue per bus, a list of them per channel, its filters): the
    endpoint then sends and receives on those queues directly."""
    return type(bus) is VirtualBus and all(
        hasattr(bus, part) for part in (*_VIRTUAL_BUS_PARTS, "_filters", "_matches_filters")
    )


def _virtual_send(bus, can_id: int, data: bytes, remote: bool) -> None:
    """What VirtualBus.send does with a frame (into the receive queue of
    every other bus on the channel, stamped now), without first building a
    Message and deep-copying it for each of them: the other buses share one
    Message (what they receive is read, not changed, by every handler
    here; python-can copies so that a user's change to a sent Message does
    not reach the receivers, and ours are built here, from bytes)."""
    bus._check_if_open()
    timestamp = time.time()  # preserve_timestamps: our frames carry no timestamp of their own (0.0)
    if bus.preserve_timestamps:
        timestamp = 0.0
    own = bus.queue
    received: can.Message | None = None  # one frame for every other bus: a receiver only reads it
    for receiver in bus.channel:
        if receiver is own:
            if bus.receive_own_messages:
                receiver.put(_message(bus, can_id, data, remote, timestamp, rx=False))
            continue
        if received is None:
            received = _message(bus, can_id, data, remote, timestamp, rx=True)
        if getattr(receiver, _PUMPED, False):
            receiver.queue.append(received)
        else:
            receiver.put(received)


def _message(bus, can_id: int, data: bytes, remote: bool, timestamp: float, *, rx: bool) -> can.Message:
    return can.Message(
        timestamp=timestamp,
        arbitration_id=can_id,
        is_extended_id=can_id > 0x7FF,
        is_remote_frame=remote,
        dlc=0 if remote else len(data),
        data=data,
        channel=bus.channel_id,
        is_rx=rx,
    )


class BusPump:
    """Virtual time: the engine's thread delivers the frames of every
    registered endpoint until the bus is quiet.

    "Quiet" means no endpoint has a frame waiting and no registered worker
    is busy. Workers (the CANopen master's SDO thread) may block on a reply
    that only the pump can deliver, so settle() keeps pumping while any of
    them is busy, giving them the CPU between rounds. A worker that never
    finishes (a bug) is reported after limit_s of real time instead of
    hanging the engine."""

    def __init__(self) -> None:
        self._endpoints: list[CanEndpoint] = []
        self._busy: list[Callable[[], bool]] = []
        self._lock = threading.Lock()

    def register(self, endpoint: CanEndpoint) -> None:
        with self._lock:
            self._endpoints.append(endpoint)

    def unregister(self, endpoint: CanEndpoint) -> None:
        with self._lock:
            if endpoint in self._endpoints:
                self._endpoints.remove(endpoint)

    def add_busy(self, check: Callable[[], bool]) -> None:
        with self._lock:
            self._busy.append(check)

    def remove_busy(self, check: Callable[[], bool]) -> None:
        with self._lock:
            if check in self._busy:
                self._busy.remove(check)

    def pump_once(self) -> int:
        """Deliver every frame waiting now; returns how many."""
        with self._lock:
            endpoints = list(self._endpoints)
        moved = 0
        for endpoint in endpoints:
            while endpoint.poll():
                moved += 1
        return moved

    def _quiet(self) -> bool:
        """Nothing to do, known without a receive: no worker registered and
        every endpoint a python-can virtual bus with an empty queue."""
        if self._busy:
            return False
        for endpoint in self._endpoints:
            bus = endpoint.bus
            if type(bus) is not VirtualBus or bus.queue.queue:
                return False
        return True

    def settle(self, limit_s: float = 10.0) -> bool:
        """Pump until quiet. False (and a log line) if still busy after limit_s."""
        if self._quiet():
            return True  # most settles in virtual time: the round below would move nothing
        deadline = time.monotonic() + limit_s
        was_busy = False
        while True:
            moved = self.pump_once()
            with self._lock:
                busy = any(check() for check in self._busy)
            if moved == 0 and not busy:
                # A worker that was busy may have sent a last frame as it
                # finished; one more empty round then proves the bus quiet.
                if not was_busy:
                    return True
                was_busy = False
                continue
            was_busy = busy
            if moved == 0:
                if time.monotonic() > deadline:
                    lines.error(None, "CAN bus not quiet after %.1f s: a worker is stuck", limit_s)
                    return False
                time.sleep(0.0001)  # let the busy worker run
