"""A whole genset plant in virtual time for the tests: an example
configuration (io_config/examples/genset*.toml) with its program, the
plain-CAN driver, the MPU2-S node and the simulated MPU2-S with its genset,
busbar and breaker on python-can's virtual bus."""

from __future__ import annotations

import itertools
import re
import tomllib
from collections.abc import Callable
from pathlib import Path

from softplc.runtime.config import config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.plaincan import PlainCanDriver

ROOT = Path(__file__).resolve().parents[3]
EXAMPLES = ROOT / "io_config" / "examples"
PROGRAM = ROOT / "st_programs" / "genset_sync.st"
MS = 1_000_000
_channels = itertools.count()


def states(type_name: str = "E_GensetState") -> list[str]:
    m = re.search(rf"TYPE {type_name} : \(([^)]*)\)", PROGRAM.read_text())
    assert m is not None
    return [s.strip() for s in m.group(1).split(",")]


STATES = states()
IDLE, CHECK, SYNCHRONISING, DEAD_BUS, CLOSING, CLOSED, OPENING, FAULT = range(8)  # GENSET_STATE_*


def example(name: str = "genset.toml", *, sim: dict | None = None, drop_wiring: tuple[str, ...] = ()) -> dict:
    """The example's tables with the program path made absolute, its own
    virtual channel, and the [[sim]] keys replaced by `sim`."""
    data = tomllib.loads((EXAMPLES / name).read_text())
    data["plc"]["programs"] = [str(PROGRAM)]
    data["can"][0]["channel"] = f"test-genset-{next(_channels)}"
    table = data["sim"][0]
    table.update(sim or {})
    for signal in drop_wiring:
        del table["wiring"][signal]
    return data


class Plant:
    def __init__(self, data: dict, where: Path) -> None:
        self.engine = build_engine(config_from_dict(data, where / "genset.toml"), virtual_time=True)
        self.driver = next(d for d in self.engine.drivers if isinstance(d, PlainCanDriver))
        self.sim = self.engine.simulators["mpu2s1"]
        self.engine.start()

    def get(self, path: str):
        return self.engine.get(path)

    def set(self, path: str, value) -> None:
        self.engine.set(path, value)

    @property
    def state(self) -> str:
        return STATES[int(self.get("Genset.State"))]

    def run_ms(self, ms: float, watch: Callable[[], None] | None = None) -> None:
        end = self.engine.now_ns() + int(ms * MS)
        while self.engine.now_ns() < end:
            self.engine.run(cycles=1)
            if watch is not None:
                watch()

    def run_until(self, done: Callable[[], bool], limit_ms: float, what: str, watch=None) -> float:
        """Scan until done(); the virtual ms it took."""
        start = self.engine.now_ns()
        while not done():
            if self.engine.now_ns() - start > limit_ms * MS:
                raise AssertionError(
                    f"not {what} after {limit_ms} ms (state {self.state}, {self.get('Genset.Message')})"
                )
            self.engine.run(cycles=1)
            if watch is not None:
                watch()
        return (self.engine.now_ns() - start) / MS

    def stop(self) -> None:
        self.engine.stop()
