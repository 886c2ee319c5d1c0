"""CAN endpoints on python-can's virtual bus: the pump of virtual time, the
receive thread of real time, unplugging, and a failed bus reopened."""

from __future__ import annotations

import itertools
import threading

import can
import pytest

from softplc.runtime.io.can.bus import BusPump, BusSettings, CanEndpoint, open_bus
from softplc.runtime.plugin.driver import DriverError

_channels = itertools.count()


@pytest.fixture
def channel():
    return f"test-canbus-{next(_channels)}"


def _endpoint(channel, name, pump=None, log=None):
    ep = CanEndpoint(open_bus(BusSettings("virtual", channel)), name=name, pump=pump)
    if log is not None:
        ep.add_handler(lambda msg: log.append((name, msg.arbitration_id, bytes(msg.data))))
    ep.start()
    return ep


def test_the_pump_delivers_everything_in_the_callers_thread(channel):
    pump, log = BusPump(), []
    a = _endpoint(channel, "a", pump, log)
    b = _endpoint(channel, "b", pump, log)
    seen_threads = set()
    # b answers every frame from a, as a node answers an SDO request
    b.add_handler(
        lambda msg: seen_threads.add(threading.get_ident()) or (msg.arbitration_id == 0x601 and b.send(0x581, b"\x60"))
    )
    a.send(0x601, b"\x40\x00\x10\x00")
    assert log == []  # nothing moves until the pump runs
    assert pump.settle()
    assert log == [("b", 0x601, b"\x40\x00\x10\x00"), ("a", 0x581, b"\x60")]
    assert seen_threads == {threading.get_ident()}
    a.stop(), b.stop()


def test_settle_waits_for_a_busy_worker_and_delivers_what_it_sends(channel):
    pump, log = BusPump(), []
    a = _endpoint(channel, "a", pump)
    _endpoint(channel, "b", pump, log)
    go = threading.Event()
    sent = threading.Event()

    def worker():
        go.wait()
        a.send(0x123, b"\x01")
        sent.set()

    thread = threading.Thread(target=worker)
    pump.add_busy(lambda: not sent.is_set())
    thread.start()
    go.set()
    assert pump.settle()
    assert log == [("b", 0x123, b"\x01")]
    thread.join()


def test_an_unplugged_endpoint_drops_frames_both_ways(channel):
    pump, log = BusPump(), []
    a = _endpoint(channel, "a", pump, log)
    b = _endpoint(channel, "b", pump, log)
    b.connected = False
    assert not b.send(0x700, b"\x05")
    a.send(0x000, b"\x01\x00")
    pump.settle()
    assert log == []
    b.connected = True
    a.send(0x000, b"\x01\x00")
    pump.settle()
    assert log == [("b", 0x000, b"\x01\x00")]


def test_real_time_endpoints_receive_in_their_own_thread(channel):
    got = threading.Event()
    frames = []
    a = _endpoint(channel, "a")
    b = _endpoint(channel, "b")
    b.add_handler(lambda msg: frames.append(msg.arbitration_id) or got.set())
    a.send(0x1A8, bytes(8))
    assert got.wait(5.0)
    assert frames == [0x1A8]
    a.stop(), b.stop()


def test_a_failed_bus_reports_errors_and_works_again_after_reopen(channel):
    pump, log = BusPump(), []
    a = _endpoint(channel, "a", pump)
    _endpoint(channel, "b", pump, log)
    a.bus.shutdown()  # the adapter is gone
    assert not a.send(0x100, b"\x01")
    assert a.send_errors == 1 and a.last_error
    a.reopen(open_bus(BusSettings("virtual", channel)))
    assert a.send(0x100, b"\x02")
    pump.settle()
    assert log == [("b", 0x100, b"\x02")]


def test_an_unknown_interface_is_a_driver_error_naming_it():
    with pytest.raises(DriverError, match="no-such-interface"):
        open_bus(BusSettings("no-such-interface", "x"))


def test_error_frames_are_not_handed_to_the_handlers(channel):
    pump, log = BusPump(), []
    a = _endpoint(channel, "a", pump)
    _endpoint(channel, "b", pump, log)
    a.bus.send(can.Message(arbitration_id=0, is_error_frame=True))
    pump.settle()
    assert log == []


def test_a_plain_python_can_bus_on_the_channel_sees_the_endpoints_frames(channel):
    # A pumped endpoint puts its frames into the virtual bus's queues itself:
    # another python-can bus on the channel still receives each one, whole.
    pump = BusPump()
    ep = _endpoint(channel, "ep", pump)
    peer = can.Bus(interface="virtual", channel=channel)
    try:
        ep.send(0x214, b"\x3c\x04\x00\x00")
        ep.send(0x714, b"", remote=True)
        first, second = peer.recv(timeout=1), peer.recv(timeout=1)
        assert (first.arbitration_id, bytes(first.data), first.dlc, first.is_remote_frame) == (
            0x214,
            b"\x3c\x04\x00\x00",
            4,
            False,
        )
        assert (second.arbitration_id, second.dlc, second.is_remote_frame) == (0x714, 0, True)
        assert first.channel == channel and first.is_rx
        assert peer.recv(timeout=0) is None
        peer.send(can.Message(arbitration_id=0x194, data=b"\x07\x0e", is_extended_id=False))
        log = []
        ep.add_handler(lambda msg: log.append((msg.arbitration_id, bytes(msg.data))))
        assert pump.settle()
        assert log == [(0x194, b"\x07\x0e")]
    finally:
        peer.shutdown()
        ep.stop()


def test_a_pumped_endpoint_on_a_filtered_virtual_bus_gets_only_what_passes(channel):
    pump, log = BusPump(), []
    sender = _endpoint(channel, "sender", pump)
    ep = _endpoint(channel, "ep", pump, log)
    ep.bus.set_filters([{"can_id": 0x700, "can_mask": 0x780}])  # heartbeats only
    sender.send(0x194, b"\x01")
    sender.send(0x728, b"\x05")
    assert pump.settle()
    assert log == [("ep", 0x728, b"\x05")]
    sender.stop(), ep.stop()
