"""The plain-CAN driver (runtime/io/plaincan/driver.py) in an engine in
virtual time: a beacon's frames from a real frame producer on python-can's
virtual bus land in %I at the next scan; a malformed frame is counted,
logged once per 10 s and dropped; the driver shares the PLC's one connection to the
bus with the CANopen master."""

from __future__ import annotations

import itertools
import logging
import threading

import pytest

from softplc.runtime.config import config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.can.bus import BusSettings, CanEndpoint, open_bus
from softplc.runtime.io.canopen.master import CanopenDriver
from softplc.runtime.io.plaincan import PlainCanDriver

from ..can import gated_adapter, late_adapter
from .beacon import MARK, POLL_ID

_channels = itertools.count()
PROGRAM = "PROGRAM Main\nVAR counter AT %IW10 : WORD; seen : WORD; END_VAR\nseen := counter;\nEND_PROGRAM\n"
LTMR = {
    "name": "motor",
    "id": 40,
    "eds": "ltmr",
    "heartbeat": "100ms",
    "tpdo": [{"number": 1, "configure": False, "map": [{"object": "2004:06", "address": "%IW100"}]}],
}


@pytest.fixture
def plant(tmp_path):
    made = []

    def make(with_canopen: bool = False, interface: str = "virtual", absent: bool = False, poll: bool = False):
        """interface "late" (tests/io/can/late_adapter.py), absent: the adapter
        is not there yet; poll: the beacon asks for its counter (beacon.py)."""
        (tmp_path / "main.st").write_text(PROGRAM)
        channel = f"test-plaincan-{next(_channels)}"
        if absent:
            late_adapter.ABSENT.add(channel)
        data = {
            "plc": {"programs": ["main.st"]},
            "task": [{"name": "Main", "interval": "10ms", "programs": ["Main"]}],
            "can": [{"name": "can0", "interface": interface, "channel": channel, "bitrate": 125000}],
            "plaincan": [{"type": "beacon", "number": 5, "input": "%IW10", "poll": poll}],
        }
        if with_canopen:
            data["canopen"] = {"node": [LTMR], "sdo_timeout": "1s"}
            data["sim"] = [{"type": "ltmr", "node_id": 40}]
        engine = build_engine(config_from_dict(data, tmp_path / "plant.toml"), virtual_time=True)
        driver = next(d for d in engine.drivers if isinstance(d, PlainCanDriver))
        engine.start()
        producer = CanEndpoint(
            open_bus(BusSettings("virtual", channel, 125000)), name="beacon 5", pump=driver.port.pump
        )
        producer.start()
        made.append((engine, producer))
        return engine, driver, producer

    yield make
    for engine, producer in made:
        producer.stop()
        engine.stop()
    late_adapter.ABSENT.clear()


def test_frames_land_in_the_image_at_the_next_scan(plant):
    engine, driver, producer = plant()
    engine.run(cycles=1)
    assert engine.get("Main.seen") == 0 and not driver.status().ok  # silent so far
    producer.send(0x185, bytes([MARK, 0x12, 0x34, 0, 0, 0, 0, 0]))
    engine.run(cycles=1)
    assert engine.get("Main.seen") == 0x1234
    assert driver.status().ok and driver.status().message == "plaincan can0: 1/1 up"
    producer.send(0x186, bytes(8))  # no node's: someone else's
    engine.run(cycles=1)
    assert driver.foreign >= 1 and engine.get("Main.seen") == 0x1234


def test_a_malformed_frame_is_counted_logged_once_per_interval_and_dropped(plant, caplog):
    engine, driver, producer = plant()
    producer.send(0x185, bytes([MARK, 0, 7, 0, 0, 0, 0, 0]))
    with caplog.at_level(logging.WARNING, logger="softplc.runtime.io.plaincan.driver"):
        for _ in range(3):
            producer.send(0x185, bytes([0x11, 0xFF, 0xFF, 0, 0, 0, 0, 0]))  # not a beacon frame
        producer.send(0x185, bytes([MARK, 0xFF, 0xFF]))  # short
        engine.run(cycles=1)
        assert engine.get("Main.seen") == 7  # the good one, nothing of the bad ones
        assert driver.malformed == {"beacon5": 4}
        assert driver.status().message == "plaincan can0: 1/1 up, 4 malformed"
        assert [r.getMessage() for r in caplog.records] == [
            "plaincan can0: beacon5: frame 0x185 [11 ff ff 00 00 00 00 00] dropped: byte 0 is 0x11, not 0xB0",
        ]
        engine.run(duration_ns=10_100_000_000)  # the interval ends: what was held back is told
    lines = [r.getMessage() for r in caplog.records]
    assert lines[1:] == [
        "suppressed 3 similar messages in 10 s; the last: "
        "plaincan can0: beacon5: frame 0x185 [b0 ff ff] dropped: 3 bytes, not 8",
    ]


def test_one_connection_to_the_bus_shared_with_the_canopen_master(plant):
    engine, driver, producer = plant(with_canopen=True)
    master = next(d for d in engine.drivers if isinstance(d, CanopenDriver))
    assert master.port is driver.port and driver.port.users == 2
    assert master.endpoint is driver.port.endpoint  # one python-can bus object for both protocols
    producer.send(0x185, bytes([MARK, 0, 42, 0, 0, 0, 0, 0]))
    engine.run(duration_ns=500_000_000)
    assert engine.get("Main.seen") == 42
    assert master.status().ok and "1/1 up" in master.status().message  # the LTMR booted through it
    engine.stop()
    assert driver.port.endpoint is None and driver.port.users == 0


def test_an_adapter_missing_at_start_is_waited_for(plant, monkeypatch):
    late_adapter.register(monkeypatch)
    engine, driver, producer = plant(interface="late", absent=True)
    channel = driver.port.settings.channel
    engine.run(duration_ns=1_000_000_000)
    status = driver.status()
    assert not status.ok and "plaincan can0: bus down" in status.message and "no CAN adapter" in status.message
    producer.send(0x185, bytes([MARK, 0, 9, 0, 0, 0, 0, 0]))  # nobody can hear it: the PLC has no bus yet
    late_adapter.ABSENT.discard(channel)  # plugged in at 1 s; tries at 0.5 s, then 1.5 s
    engine.run(duration_ns=600_000_000)
    assert driver.port.is_open
    producer.send(0x185, bytes([MARK, 0, 7, 0, 0, 0, 0, 0]))
    engine.run(cycles=2)
    assert engine.get("Main.seen") == 7 and driver.status().ok


def test_the_scan_does_not_wait_for_a_send_the_adapter_holds(plant, monkeypatch):
    """Issue 31: the service held in a send (a full transmit queue:
    tests/io/can/gated_adapter.py) leaves read_inputs, write_outputs and
    status free to return; the frames queued meanwhile go out after it, in
    order. The service runs in a thread of the test, as in real time; the
    join's timeout only turns a scan that blocks into a failure."""
    gated_adapter.register(monkeypatch)
    engine, driver, producer = plant(interface="gated", poll=True)
    polls: list = []
    producer.add_handler(lambda msg: polls.append(msg.arbitration_id))
    producer.send(0x185, bytes([MARK, 0, 42, 0, 0, 0, 0, 0]))
    engine.run(cycles=2)
    assert engine.get("Main.seen") == 42 and polls and set(polls) == {POLL_ID + 5}
    driver.port.pump.settle()  # the last cycle's poll delivered
    sent = len(polls)
    gate = gated_adapter.gate(driver.port.settings.channel)
    gate.shut()
    service = threading.Thread(target=driver.advance_to, args=(engine.clock.now_ns() + 5_000_000,), daemon=True)
    try:
        service.start()
        assert gate.waiting.wait(30), "the service sent nothing"
        seen = {}

        def scan() -> None:
            driver.read_inputs(engine.image)
            driver.write_outputs(engine.image)  # its poll waits in the outbox
            seen["status"] = driver.status()

        thread = threading.Thread(target=scan, daemon=True)
        thread.start()
        thread.join(30)
        assert not thread.is_alive(), "the scan waited behind a send of the service"
        assert seen["status"].ok
    finally:
        gate.open()
    service.join(30)
    assert not service.is_alive()
    driver.port.pump.settle()
    assert len(polls) == sent + 2  # the service's poll, then the scan's
