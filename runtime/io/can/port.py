"""The PLC's own connection to a [[can]] bus, shared by every protocol driver
on that bus: the CANopen master and the plain-CAN devices (io/plaincan) send
and receive through one CanEndpoint, so one python-can bus object and one
receive thread (or, in virtual time, one pumped endpoint) serve them all, as
one CAN adapter serves every protocol on a plant PC.

    port = port_of(ctx, bus_config)          # io/can: the same object for every driver of one engine
    endpoint = port.acquire()                # opened and started by the first driver
    endpoint.add_handler(my_frames)
    ...
    port.release(my_frames)                  # closed when the last driver lets go

Simulated devices are other nodes on the bus: they open endpoints of their
own (a simulated device is a separate peer), never the PLC's port.
"""

from __future__ import annotations

import threading

from .bus import BusPump, BusSettings, CanEndpoint, Handler, open_bus


class CanPort:
    def __init__(self, settings: BusSettings, pump: BusPump | None = None, name: str = "plc") -> None:
        self.settings = settings
        self.pump = pump
        self.name = name
        self.endpoint: CanEndpoint | None = None
        self._users = 0
        self._lock = threading.Lock()

    def acquire(self) -> CanEndpoint:
        """The started endpoint; the first caller opens the bus (DriverError
        naming the interface when it cannot)."""
        with self._lock:
            if self.endpoint is None:
                name = f"{self.name} on {self.settings.channel}"
                self.endpoint = CanEndpoint(open_bus(self.settings), name=name, pump=self.pump)
                self.endpoint.start()
            self._users += 1
            return self.endpoint

    def release(self, *handlers: Handler) -> None:
        """A driver is done: its handlers go; the last one closes the bus."""
        with self._lock:
            endpoint = self.endpoint
            if endpoint is None:
                return
            for handler in handlers:
                endpoint.remove_handler(handler)
            self._users -= 1
            if self._users <= 0:
                self._users = 0
                self.endpoint = None
                endpoint.stop()

    @property
    def users(self) -> int:
        return self._users


def shared_port(shared: dict, bus: str, settings: BusSettings, pump: BusPump | None) -> CanPort:
    """The one CanPort of an engine for the [[can]] bus named bus (shared: the
    dict the buses of one engine share, BuildContext.shared)."""
    ports: dict[str, CanPort] = shared.setdefault("can.ports", {})
    port = ports.get(bus)
    if port is None:
        port = ports[bus] = CanPort(settings, pump)
    return port
