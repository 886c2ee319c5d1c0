"""The PLC's one connection to a [[can]] bus (runtime/io/can/port.py): every
protocol driver on the bus shares one endpoint, opened by the first and
closed by the last, on python-can's virtual interface."""

from __future__ import annotations

import itertools

import can
import pytest

from softplc.runtime.engine.clock import VirtualClock
from softplc.runtime.io.can.bus import BusPump, BusSettings, CanEndpoint, open_bus
from softplc.runtime.io.can.port import CanPort, shared_port
from softplc.runtime.plugin.driver import DriverError

from . import late_adapter

MS = 1_000_000

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


# ---------------------------------------------------------------------------- an adapter that comes up late


@pytest.fixture
def late(monkeypatch):
    """The interface "late": a channel in late_adapter.ABSENT cannot be opened."""
    late_adapter.register(monkeypatch)
    channel = f"test-late-{next(_channels)}"
    late_adapter.ABSENT.add(channel)
    yield channel
    late_adapter.ABSENT.discard(channel)


def test_a_missing_adapter_is_tried_again_with_back_off_until_it_comes(late):
    clock = VirtualClock()
    port = CanPort(BusSettings("late", late, 125_000), BusPump(), clock=clock)
    endpoint = port.acquire(0)  # no exception: the PLC starts without its bus
    assert not port.is_open and "no CAN adapter on channel" in port.error
    assert not endpoint.send(0x123, b"\x01")  # nothing goes out, nothing raises
    tries = []
    for ms in range(0, 40_000, 10):  # 40 s of virtual time, as a driver's service would ask
        if ms == 30_000:
            late_adapter.ABSENT.discard(late)  # plugged in at 30 s
        before = late_adapter.ATTEMPTS[late]
        opened = port.try_open(ms * MS)
        if late_adapter.ATTEMPTS[late] > before:
            tries.append(ms)
        if opened:
            break
    # 0.5 s after the start, then doubling up to 10 s
    assert tries == [500, 1_500, 3_500, 7_500, 15_500, 25_500, 35_500]
    assert port.is_open and ms == 35_500 and port.error == ""
    peer = CanEndpoint(open_bus(BusSettings("virtual", late, 125_000)), name="peer", pump=port.pump)
    peer.start()
    seen = []
    endpoint.add_handler(lambda msg: seen.append(msg.arbitration_id))
    peer.send(0x185, bytes(8))
    assert endpoint.send(0x205, bytes(8))
    port.pump.settle()
    assert seen == [0x185]
    peer.stop()
    port.release()


def test_fail_fast_raises_at_once_naming_the_adapter(late):
    port = CanPort(BusSettings("late", late, 125_000), BusPump(), clock=VirtualClock(), fail_fast=True)
    with pytest.raises(DriverError, match=r"cannot open CAN bus \(late channel .* no CAN adapter.*missing_adapter"):
        port.acquire(0)
    assert port.endpoint is None and port.users == 0


# ---------------------------------------------------------------------------- softplc run, as a user sees it

RUN_CONFIG = """
[plc]
programs = ["p.st"]

[[can]]
interface = "socketcan"
channel = "nosuchcan0"     # no such adapter on any machine
{extra}

[canopen]
"""


def _run(tmp_path, extra: str):
    from ...test_cli import softplc

    (tmp_path / "p.st").write_text("PROGRAM Main\nEND_PROGRAM\n")
    cfg = tmp_path / "plant.toml"
    cfg.write_text(RUN_CONFIG.format(extra=extra))
    return cfg, softplc("run", cfg, "--virtual-time", "--duration", "3s")


@pytest.mark.slow
def test_softplc_run_waits_for_a_missing_adapter_by_default(tmp_path):
    _cfg, proc = _run(tmp_path, "")
    assert proc.returncode == 0, proc.stderr
    assert "softplc ERROR: can0: cannot open CAN bus (socketcan channel 'nosuchcan0' at 250 kbit/s)" in proc.stderr
    assert "trying again in 0.5 s" in proc.stderr
    assert "canopen: bus down" in proc.stderr  # the last status line
    assert "Traceback" not in proc.stderr


@pytest.mark.slow
def test_softplc_run_fails_fast_with_exit_code_2(tmp_path):
    _cfg, proc = _run(tmp_path, 'missing_adapter = "fail"')
    assert proc.returncode == 2
    last = proc.stderr.splitlines()[-1]
    assert last.startswith("softplc: can0: cannot open CAN bus (socketcan channel 'nosuchcan0' at 250 kbit/s): ")
    assert last.endswith('(missing_adapter = "fail"; the default, "retry", waits for it)')
    assert "Traceback" not in proc.stderr
