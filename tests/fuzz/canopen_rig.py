"""A CANopen bus for the fuzz harness, in virtual time, on python-can's
`virtual` interface (a channel of its own per rig): the real master
(CanopenDriver, configured as io_config/default.toml configures the LTMR),
the real simulated LTMR at node 40 (a canopen LocalNode), and a hostile
node 41 played by the harness: it answers every SDO request of the master
with the next planned response and puts any frame on the bus.

    rig = Rig(sdo_plans, answer)      # canopen_frames: what node 41 answers
    rig.inject(0x1A8, b"...")         # a frame from the hostile endpoint
    rig.run_ms(30)                    # time moves: the engine's tick, 10 ms steps
    rig.close()

An EDS is parsed by canopen.import_od once per file and node id; each rig's
master and slave get a copy of that parse (pickled and unpickled: the same
objects as a fresh parse, a twentieth of the time), so a rig costs what its
bus traffic costs, not what configparser costs.
"""

from __future__ import annotations

import atexit
import functools
import itertools
import pickle
import shutil
import tempfile
from pathlib import Path
from unittest import mock

import canopen

from softplc.runtime.config import config_from_dict
from softplc.runtime.devices.ltmr.sim import LtmrSimulator
from softplc.runtime.engine.clock import VirtualClock
from softplc.runtime.image.memory import ProcessImage
from softplc.runtime.io.can.bus import BusPump, BusSettings, CanEndpoint, open_bus
from softplc.runtime.io.canopen.master import CanopenDriver

MS = 1_000_000
LTMR, HOSTILE, MASTER = 40, 41, 127
_channels = itertools.count()

_TPDO = [
    {"object": "2004:06", "address": "%IW100"},
    {"object": "2004:07", "address": "%IW101"},
    {"object": "2004:08", "address": "%IW102"},
    {"object": "2004:0A", "address": "%IW103"},
]
_RPDO = [{"object": "2008:05", "address": "%QW100"}, {"object": "2008:04", "address": "%QW101"}]


def _node(name: str, node_id: int, words: int) -> dict:
    """A node on the LTMR's EDS: TPDO1 (its factory mapping) to %IW<words>..,
    TPDO2 mapped at boot, RPDO1 from %QW<words>.."""
    tpdo1 = [dict(m, address=f"%IW{words + i}") for i, m in enumerate(_TPDO)]
    tpdo2 = [{"object": "2004:02", "address": f"%IW{words + 4}"}]
    rpdo1 = [dict(m, address=f"%QW{words + i}") for i, m in enumerate(_RPDO)]
    return {
        "name": name,
        "id": node_id,
        "eds": "ltmr",
        "heartbeat": "100ms",
        "heartbeat_timeout": "300ms",
        "tpdo": [{"number": 1, "configure": False, "map": tpdo1}, {"number": 2, "map": tpdo2}],
        "rpdo": [{"number": 1, "configure": False, "map": rpdo1}],
    }


@functools.cache
def canopen_config():
    """The [canopen] section of the rig, loaded once through the real
    configuration code."""
    tmp = Path(tempfile.mkdtemp(prefix="softplc-fuzz-canopen-"))
    atexit.register(shutil.rmtree, tmp, True)
    (tmp / "p.st").write_text("PROGRAM P\nEND_PROGRAM\n")
    data = {
        "plc": {"programs": [str(tmp / "p.st")]},
        "can": [{"name": "can0", "interface": "virtual", "channel": "unused"}],
        "canopen": {
            "node_id": MASTER,
            "heartbeat": "100ms",
            "sdo_timeout": "50ms",
            "boot_timeout": "200ms",
            "retry": "200ms",
            "node": [_node("motor", LTMR, 100), _node("rogue", HOSTILE, 110)],
        },
    }
    return config_from_dict(data, tmp / "plant.toml").canopen


_import_od = canopen.import_od


@functools.cache
def _parsed(source: str, node_id: int) -> bytes:
    return pickle.dumps(_import_od(source, node_id))


def _import_od_once(source, node_id=None):
    return pickle.loads(_parsed(str(source), node_id))


class Rig:
    def __init__(self, sdo_plans: list, answer) -> None:
        self.clock = VirtualClock()
        self.pump = BusPump()
        self.settings = BusSettings("virtual", f"fuzz-canopen-{next(_channels)}")
        self.image = ProcessImage("iec")
        with mock.patch.object(canopen, "import_od", _import_od_once):
            self.master = CanopenDriver(canopen_config(), self.settings, clock=self.clock, pump=self.pump)
            self.ltmr = LtmrSimulator(LTMR, settings=self.settings, clock=self.clock, pump=self.pump)
        self.hostile = CanEndpoint(open_bus(self.settings), name="hostile node", pump=self.pump)
        self.sdo_plans = list(sdo_plans)  # what node 41 answers, request by request
        self._answer = answer  # (request bytes, plan) -> the answer or None
        self.sent = 0  # frames the hostile endpoint put on the bus
        self.hostile.add_handler(self._on_frame)
        self.hostile.start()
        self.master.start()
        self.ltmr.start()
        self.pump.settle()

    def _on_frame(self, msg) -> None:
        if msg.arbitration_id == 0x600 + HOSTILE and self.sdo_plans:
            data = self._answer(bytes(msg.data), self.sdo_plans.pop(0))
            if data is not None:
                self.send(0x580 + HOSTILE, data)

    def send(self, can_id: int, data: bytes, remote: bool = False) -> None:
        self.hostile.send(can_id, data, remote=remote)
        self.sent += 1

    def inject(self, can_id: int, data: bytes, remote: bool = False) -> None:
        """A frame from the hostile endpoint, delivered at once."""
        self.send(can_id, data, remote)
        self.pump.settle()

    def scan(self) -> None:
        """The scan's side of the master: inputs in, outputs out."""
        self.master.read_inputs(self.image)
        self.master.write_outputs(self.image)

    def run_ms(self, ms: int) -> None:
        end = self.clock.now_ns() + ms * MS
        while self.clock.now_ns() < end:
            now = min(end, self.clock.now_ns() + 10 * MS)
            self.clock.sleep_until(now)
            self.master.advance_to(now)
            self.ltmr.advance_to(now)
            self.pump.settle()
            self.scan()

    def close(self) -> None:
        self.master.stop()
        self.ltmr.stop()
        self.hostile.stop()
