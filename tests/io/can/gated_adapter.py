"""A CAN adapter whose sends can be held: a real python-can bus class
(python-can's virtual bus) registered as the interface "gated" in python-can's
own table of interfaces, as late_adapter.py registers "late". While a
channel's gate is shut, every send on it waits, as a send on a real adapter
waits when its transmit queue is full (socketcan's send blocks until the
kernel takes the frame), until the gate opens again.

    gated_adapter.register(monkeypatch)
    gate = gated_adapter.gate(channel)
    gate.shut(); ... gate.waiting.wait(30)   # a sender is held in send()
    gate.open()
"""

from __future__ import annotations

import threading

import can
import can.interfaces
import can.util
from can.interfaces.virtual import VirtualBus

#: python-can's table entry: interface name -> (module, class)
BACKEND = ("gated", ("tests.io.can.gated_adapter", "GatedBus"))


def register(monkeypatch) -> None:
    """Add "gated" to python-can's interfaces for the test (late_adapter.register)."""
    monkeypatch.setitem(can.interfaces.BACKENDS, *BACKEND)
    monkeypatch.setattr(can.util, "VALID_INTERFACES", can.util.VALID_INTERFACES | {BACKEND[0]})


class Gate:
    def __init__(self) -> None:
        self._open = threading.Event()
        self._open.set()
        self.waiting = threading.Event()  # set when a send found the gate shut
        self.held = 0  # sends that waited

    def shut(self) -> None:
        self.waiting.clear()
        self._open.clear()

    def open(self) -> None:
        self._open.set()

    def pass_through(self) -> None:
        if not self._open.is_set():
            self.held += 1
            self.waiting.set()
            self._open.wait()


_gates: dict[str, Gate] = {}


def gate(channel: str) -> Gate:
    return _gates.setdefault(channel, Gate())


class GatedBus(VirtualBus):
    def __init__(self, channel, **kwargs) -> None:
        super().__init__(channel=channel, **kwargs)
        self._gate = gate(channel)

    def send(self, msg: can.Message, timeout: float | None = None) -> None:
        self._gate.pass_through()
        super().send(msg, timeout)
