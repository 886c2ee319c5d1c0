"""The PLC's one connection to a [[can]] bus (runtime/io/can/port.py): every
protocol driver on the bus shares one endpoint, opened by the first and
closed by the last, on python-can's virtual interface."""

from __future__ import annotations

import itertools

import can

from softplc.runtime.io.can.bus import BusPump, BusSettings, CanEndpoint, open_bus
from softplc.runtime.io.can.port import CanPort, shared_port

_channels = itertools.count()


def test_two_drivers_share_one_bus_object_and_each_gets_every_frame():
    settings = BusSettings("virtual", f"test-port-{next(_channels)}", 125_000)
    pump = BusPump()
    port = CanPort(settings, pump)
    first, second = [], []
    ep1 = port.acquire()
    ep1.add_handler(lambda msg: first.append(msg.arbitration_id))
    ep2 = port.acquire()
    ep2.add_handler(lambda msg: second.append(msg.arbitration_id))
    assert ep1 is ep2 and port.users == 2
    peer = CanEndpoint(open_bus(settings), name="peer", pump=pump)
    peer.start()
    peer.send(0x321, bytes(8))
    peer.send(0x705, b"\x05")
    pump.settle()
    assert first == second == [0x321, 0x705]
    peer.stop()


def test_the_last_release_closes_the_bus():
    settings = BusSettings("virtual", f"test-port-{next(_channels)}", 125_000)
    port = CanPort(settings, BusPump())
    seen: list = []

    def handler(msg: can.Message) -> None:
        seen.append(msg)

    endpoint = port.acquire()
    endpoint.add_handler(handler)
    port.acquire()
    port.release(handler)
    assert port.endpoint is endpoint and port.users == 1
    port.release()
    assert port.endpoint is None and port.users == 0
    assert port.acquire() is not endpoint  # opened afresh
    port.release()


def test_one_port_per_bus_and_engine():
    shared: dict = {}
    a = BusSettings("virtual", "a")
    assert shared_port(shared, "can0", a, None) is shared_port(shared, "can0", a, None)
    assert shared_port(shared, "can1", a, None) is not shared_port(shared, "can0", a, None)
    assert shared_port({}, "can0", a, None) is not shared_port(shared, "can0", a, None)
