"""A plant on python-can's virtual bus, in virtual time: the CANopen master
(the real driver, built from a configuration as `softplc run` builds it),
simulated devices (real canopen LocalNodes) and a spy endpoint that records
every frame on the bus, all delivered by one BusPump."""

from __future__ import annotations

import copy
import itertools
from pathlib import Path

import pytest

from softplc.runtime.config import config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.can.bus import BusSettings, CanEndpoint, open_bus
from softplc.runtime.io.canopen.slave import SimulatedCanopenSlave
from softplc.runtime.program import locate

MS = 1_000_000
_channels = itertools.count()

# The LTMR's PDOs as io_config/default.toml maps them.
LTMR_NODE = {
    "name": "motor",
    "id": 40,
    "eds": "ltmr",
    "heartbeat": "100ms",
    "heartbeat_timeout": "300ms",
    "master_timeout": "500ms",
    "sdo": [{"object": "2007:21", "value": 2}],  # 682 fallback: LO1, LO2 off
    "tpdo": [
        {
            "number": 1,
            "configure": False,  # the factory mapping (digest 001 A1)
            "map": [
                {"object": "2004:06", "address": "%IW100"},
                {"object": "2004:07", "address": "%IW101"},
                {"object": "2004:08", "address": "%IW102"},
                {"object": "2004:0A", "address": "%IW103"},
            ],
        },
        {
            "number": 2,  # mapped at boot: 451, 460, 465, 466
            "map": [
                {"object": "2004:02", "address": "%IW104"},
                {"object": "2004:0B", "address": "%IW105"},
                {"object": "2004:10", "address": "%IW106"},
                {"object": "2004:11", "address": "%IW107"},
            ],
        },
    ],
    "rpdo": [
        {
            "number": 1,
            "configure": False,
            "map": [
                {"object": "2008:05", "address": "%QW100"},
                {"object": "2008:04", "address": "%QW101"},
                {"object": "2008:01", "address": "%QW102"},
            ],
        },
    ],
}


def plant_config(
    tmp_path: Path,
    source,
    *,
    program,
    nodes=None,
    sims=None,
    profile="codesys",
    interval="10ms",
    canopen_extra=None,
    outputs=None,
) -> dict:
    """source: ST text, or a list of ST files; program: a PROGRAM name or a
    list; outputs: an [outputs] table (safe values)."""
    if isinstance(source, str):
        st = tmp_path / "plant.st"
        st.write_text(source)
        files = [str(st)]
    else:
        files = [str(f) for f in source]
    channel = f"test-plant-{next(_channels)}"
    canopen = {
        "node_id": 127,
        "heartbeat": "100ms",
        # SDO answers cross threads in real time even on the virtual clock: the
        # timeout must outlast a loaded machine (a node that answers never waits
        # for it; only the test of an absent node does, once).
        "sdo_timeout": "1s",
        "boot_timeout": "500ms",
        "retry": "1s",
        "node": copy.deepcopy(nodes if nodes is not None else [LTMR_NODE]),
    }
    canopen.update(canopen_extra or {})
    data = {
        "plc": {"profile": profile, "programs": files},
        "task": [
            {"name": "Main", "interval": interval, "programs": [program] if isinstance(program, str) else list(program)}
        ],
        "can": [{"name": "can0", "interface": "virtual", "channel": channel}],
        "canopen": canopen,
        "sim": sims if sims is not None else [{"type": "ltmr", "node_id": 40, "registers": {"682": 2}}],
    }
    if outputs is not None:
        data["outputs"] = outputs
    return data


class Plant:
    def __init__(self, data: dict, tmp_path: Path) -> None:
        self.config = config_from_dict(data, tmp_path / "plant.toml")
        self.engine = build_engine(self.config, virtual_time=True)
        self.master = next(d for d in self.engine.drivers if d.name == "canopen")
        self.sims = {d.node_id: d for d in self.engine.drivers if isinstance(d, SimulatedCanopenSlave)}
        self.pump = self.master.pump
        bus = self.config.can[0]
        self.frames: list = []  # (time ns, can id, bytes)
        self.remote: list = []  # (time ns, can id) of the remote frames (RTR: node guarding)
        self.spy = CanEndpoint(
            open_bus(BusSettings(bus.interface, bus.channel, bus.bitrate)), name="spy", pump=self.pump
        )
        self.spy.add_handler(self._record)
        self.spy.start()
        self.engine.start()

    def _record(self, msg) -> None:
        if msg.is_remote_frame:
            self.remote.append((self.engine.clock.now_ns(), msg.arbitration_id))
        else:
            self.frames.append((self.engine.clock.now_ns(), msg.arbitration_id, bytes(msg.data)))

    @property
    def now_ms(self) -> float:
        return self.engine.clock.now_ns() / MS

    def run_ms(self, ms: float) -> None:
        """Move virtual time on by ms (scanning at each release before the end)."""
        self.engine.run(duration_ns=round(ms * MS))

    def scan(self, n: int = 1) -> None:
        """Exactly n scans, whatever time they take."""
        self.engine.run(cycles=n)

    def run_until(self, predicate, limit_ms: float, what: str) -> float:
        """Scan until predicate() holds; the virtual time it took, in ms."""
        start = self.now_ms
        while not predicate():
            if self.now_ms - start > limit_ms:
                raise AssertionError(f"{what}: not within {limit_ms} ms of virtual time")
            self.engine.run(cycles=1)
        return self.now_ms - start

    def get(self, path: str):
        return self.engine.get(path)

    def set(self, path: str, value) -> None:
        self.engine.set(path, value)

    def node_diag(self, node_id: int, field: str):
        holder, attr, _ty = locate("CANOPEN_NODE", (self.engine.ns["_G"],))
        struct = getattr(holder, attr)[node_id]
        return getattr(struct, locate(field, (struct,))[1])

    def frames_with(self, can_id: int) -> list:
        return [data for _t, cid, data in self.frames if cid == can_id]

    def stop(self) -> None:
        self.engine.stop()
        self.spy.stop()


@pytest.fixture
def plants(tmp_path):
    made = []

    def factory(source, **kwargs) -> Plant:
        plant = Plant(plant_config(tmp_path, source, **kwargs), tmp_path)
        made.append(plant)
        return plant

    yield factory
    for plant in made:
        plant.stop()
