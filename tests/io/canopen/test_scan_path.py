"""The scan never waits behind the CANopen master's bus side (issue 31): a
send the adapter holds (a full transmit queue: tests/io/can/gated_adapter.py)
in the middle of the service, of a frame's handling or of a node's boot
leaves read_inputs, write_outputs, status and details free to return.

The held send runs in a thread of the test, as the service thread, the
receive thread and the SDO worker run in real time; the scan's calls run in
another. Nothing is timed: the join's timeout is only there so that a scan
that does block fails the test instead of hanging it."""

from __future__ import annotations

import threading

import pytest

from softplc.runtime.io.canopen.node import NodeState

from ..can import gated_adapter
from .plant import Plant, plant_config
from .test_master import WATCH

MS = 1_000_000
NEVER_S = 30.0  # far beyond a scan's calls, however loaded the machine


@pytest.fixture
def gated(tmp_path, monkeypatch):
    """A plant (the master, the simulated LTMR, the spy) on a gated adapter,
    node 40 operational; the gate open again at the end."""
    gated_adapter.register(monkeypatch)
    data = plant_config(tmp_path, WATCH, program="Watch")
    data["can"][0]["interface"] = "gated"
    plant = Plant(data, tmp_path)
    gate = gated_adapter.gate(data["can"][0]["channel"])
    try:
        plant.run_until(lambda: plant.get("Watch.operational"), 200, "node 40 operational")
        yield plant, gate
    finally:
        gate.open()
        plant.stop()


def _held(gate, work) -> threading.Thread:
    """work() in a thread of its own, once it is held in a send."""
    gate.shut()
    thread = threading.Thread(target=work, daemon=True)
    thread.start()
    assert gate.waiting.wait(NEVER_S), "the bus side sent nothing"
    return thread


def _scan_returns(plant) -> dict:
    """The calls the scan makes on a driver, from another thread: what they returned."""
    master, image = plant.master, plant.engine.image
    seen: dict = {}

    def scan() -> None:
        master.read_inputs(image)
        master.write_outputs(image)
        seen["status"] = master.status()
        seen["details"] = master.details()

    thread = threading.Thread(target=scan, daemon=True)
    thread.start()
    thread.join(NEVER_S)
    assert not thread.is_alive(), "the scan waited behind a send of the bus side"
    return seen


def test_the_scan_does_not_wait_for_a_send_of_the_service(gated):
    plant, gate = gated
    master = plant.master
    # the service, its heartbeat due, holds in that send (as the service thread would)
    service = _held(gate, lambda: master.service(plant.engine.clock.now_ns() + 200 * MS))
    seen = _scan_returns(plant)
    assert seen["status"].ok and seen["details"]["nodes"][0]["state"] == "OPERATIONAL"
    gate.open()
    service.join(NEVER_S)
    assert not service.is_alive()


def test_the_scan_does_not_wait_for_the_reset_a_bogus_heartbeat_calls_for(gated):
    """A heartbeat reporting pre-operational: the receive path resets the
    node, and that NMT frame is held."""
    plant, gate = gated
    plant.spy.send(0x728, b"\x7f")
    receive = _held(gate, plant.pump.pump_once)  # the receive thread's part, held in the reset
    seen = _scan_returns(plant)
    # the scan sees the node booting again: the state the supervisor went to before its send
    assert not seen["status"].ok and seen["details"]["nodes"][0]["state"] == "BOOTING"
    gate.open()
    receive.join(NEVER_S)
    assert not receive.is_alive()
    plant.run_until(lambda: plant.get("Watch.operational"), 2000, "node 40 operational again")


def test_the_scan_does_not_wait_for_a_boot_held_in_its_configuration(gated):
    """Node 40 reset and booted again: its configuration (SDO writes, in the
    SDO worker) is held at its first write; the scan goes on, keeping the
    node's outputs to itself until it is operational again."""
    plant, gate = gated
    master = plant.master
    plant.spy.send(0x000, bytes([0x81, 40]))  # reset node 40: it sends its boot-up
    plant.pump.settle()
    assert master.node_state(40) == NodeState.CONFIGURING
    rpdos = len(plant.frames_with(0x228))
    worker = _held(gate, master.worker.run_pending)  # the configuration, held in its first SDO request
    for _ in range(3):
        seen = _scan_returns(plant)
        assert not seen["status"].ok and seen["details"]["nodes"][0]["state"] == "CONFIGURING"
    gate.open()
    worker.join(NEVER_S)
    assert not worker.is_alive()
    plant.pump.settle()
    assert len(plant.frames_with(0x228)) == rpdos  # no RPDO to a node not yet started
    plant.run_until(lambda: plant.get("Watch.operational"), 2000, "node 40 operational again")
    assert master.status().ok
