"""What every simulated device shares: it is a peer on a bus, started,
advanced and stopped with the engine.

A simulator rides on the driver interface (runtime/plugin/driver.py) so the
engine needs no second list: it reads and writes no process image, but it
starts and stops with the drivers, and in virtual time the engine advances
it at each tick like a driver. In real time it runs its own service thread.

    sim = SomeDevice(..., clock=clock, pump=pump)   # pump: virtual time only
    sim.start()
    sim.advance_to(t)    # virtual time: the device model runs up to t and
                         # every frame it sent is delivered
    sim.stop()

A subclass implements service(now_ns): the device's own time-driven
behaviour (a motor model, heartbeats, timeouts), called with a monotonic
time that never goes backwards.
"""

from __future__ import annotations

from typing import Protocol

from ..engine.clock import PeriodicService
from ..image.memory import ProcessImage
from ..plugin.driver import Driver


class Pump(Protocol):
    """Virtual time: what delivers the frames in flight (a CAN BusPump)."""

    def settle(self) -> object: ...


class SimulatedDevice(Driver):
    #: real time: service() runs each time the scan goes idle, and after this
    #: long without one (PeriodicService). The models integrate over the time
    #: since the last call and frames are answered in their handlers.
    service_period_s = 0.02

    def __init__(self, name: str, *, clock, pump: Pump | None = None) -> None:
        self.name = name
        self.clock = clock
        self.pump = pump
        self._service: PeriodicService | None = None

    # the device's own behaviour ------------------------------------------

    def service(self, now_ns: int) -> None:
        raise NotImplementedError

    def events_since(self, t_ns: int) -> list:
        """What the device recorded after engine time t_ns, as (t_ns, text)
        in time order (the traces' marks: trace/events.py); a device that
        records overrides it, and records() gives the same as JSON data."""
        return []

    def open(self) -> None:
        """Connect to the bus (subclasses); called by start()."""

    def close(self) -> None:
        """Leave the bus (subclasses); called by stop()."""

    # life cycle -------------------------------------------------------------

    def start(self) -> None:
        self.open()
        if not self.clock.virtual:
            self._service = PeriodicService(f"sim {self.name}", self.clock, self.service, self.service_period_s)
            self._service.start()

    def advance_to(self, now_ns: int) -> None:
        self.service(now_ns)
        if self.pump is not None:
            self.pump.settle()

    def stop(self) -> None:
        if self._service is not None:
            self._service.stop()
            self._service = None
        self.close()

    def read_inputs(self, image: ProcessImage) -> None:
        pass

    def write_outputs(self, image: ProcessImage) -> None:
        pass


def records_of(simulators: dict) -> dict:
    """What the simulated devices recorded, by [[sim]] name, those with any:
    --final-json's "[[sim]]" and the testing API's plc.records."""
    found = {}
    for name, sim in simulators.items():
        taken = sim.records() if callable(getattr(sim, "records", None)) else None
        if taken:
            found[name] = taken
    return found
