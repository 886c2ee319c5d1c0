"""The driver interface: how a bus driver meets the scan.

A driver owns its bus and does all bus work in its own thread (or asyncio
loop). It meets the scan thread only in two short, non-blocking calls:

    read_inputs(image)    at cycle start: copy the newest input data the bus
                          thread has published into the image's %I area
    write_outputs(image)  at cycle end: copy the %Q data the bus should send
                          from the image into the driver's own buffer

Both run in the scan thread and must never wait on the bus: they swap or copy
buffers under a lock that the bus thread holds only as long as a copy takes
(the double buffer of DESIGN.md). The image handed to write_outputs may be
the engine's safe-output view (its %Q area holds the configured safe values
while a task is faulted or the PLC stops); a driver that sends %Q needs not
know. A driver whose devices the program drives by requests rather than %Q
reads image.held_safe to put them in the safe state their blocks declared,
and sends what that queued before stop() closes the bus.

Life cycle, all called from the engine's thread:

    start()   open the bus, start the bus thread; may raise DriverError
    bind_program(globals)
              the program's global variables, for drivers that publish
              diagnostics to it (written in read_inputs, like inputs)
    advance_to(now_ns)
              virtual time only, at each tick before read_inputs: do all the
              bus work due by now_ns (periodic frames, timeouts) and return
              when the bus is quiet, so every run of a sequence is the same
    status()  DriverStatus: ok or not, and a short text for the status line
    stop()    the last write_outputs has happened; close the bus, join the thread

A lost bus is reported through status() (ok=False, message) and recovered by
the driver itself; it never raises from read_inputs / write_outputs.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

from ..image.memory import ProcessImage


class DriverError(Exception):
    """A driver cannot start (bad port, missing interface ...)."""


@dataclass(frozen=True)
class DriverStatus:
    ok: bool = True
    message: str = ""


class Driver:
    """Base class of bus drivers (see the module docstring)."""

    #: the config section and name, for messages: "loopback[0]", "canopen"
    name: str = "driver"
    #: the services this driver offers to native functions (st/native.py),
    #: by service name: the engine binds them to the program's ExecContext
    services: dict = {}

    def start(self) -> None:
        pass

    def advance_to(self, now_ns: int) -> None:
        pass

    def bind_program(self, globals_obj) -> None:
        """The loaded program's globals, once after start-up: a driver that
        shows diagnostics to the program (CANOPEN_NODE ...) keeps them."""

    def details(self) -> dict:
        """What the monitors show of the bus beyond status(): its nodes, their
        states, errors and EMCY history, as JSON data (called from the scan
        thread at a snapshot, so it must be quick)."""
        return {}

    def read_inputs(self, image: ProcessImage) -> None:
        raise NotImplementedError

    def write_outputs(self, image: ProcessImage) -> None:
        raise NotImplementedError

    def status(self) -> DriverStatus:
        return DriverStatus()

    def stop(self) -> None:
        pass


class WireLog(Driver):
    """A bus's log of its wire (`softplc run --bus-log`): a driver only to be
    closed with the drivers, after its bus's (it exchanges nothing with the
    image). A subclass writes under self.lock, counts self.frames, and
    closes its file in close() (called once, by stop())."""

    def __init__(self, name: str, path) -> None:
        self.name = name
        self.path = path
        self.lock = threading.Lock()  # frames come from the scan and the buses' threads
        self.frames = 0
        self.closed = False

    def read_inputs(self, image: ProcessImage) -> None:
        pass

    def write_outputs(self, image: ProcessImage) -> None:
        pass

    def status(self) -> DriverStatus:
        return DriverStatus(True, f"{self.frames} frames to {self.path.name}")

    def close(self) -> None:
        raise NotImplementedError

    def stop(self) -> None:
        with self.lock:
            if self.closed:
                return
            self.closed = True
        self.close()
