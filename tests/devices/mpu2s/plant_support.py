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

from softplc.testing import PLC

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
    """The genset example as a PLC (softplc.testing) with its simulated
    MPU2-S; the state and the message are watched, so a timeout shows how
    the sequence got there."""

    def __init__(self, plc: PLC) -> None:
        self.plc = plc
        self.sim = plc.sim("mpu2s1")
        plc.watch("Genset.State", "Genset.sync.STATE", "Genset.Message")

    def get(self, path: str):
        """The value as the program holds it (TIME in ms, states as numbers)."""
        return self.plc.engine.get(path)

    def set(self, path: str, value) -> None:
        self.plc.write(path, value)

    @property
    def state(self) -> str:
        return STATES[int(self.get("Genset.State"))]

    def run_ms(self, ms: float) -> None:
        self.plc.run_for(int(ms * MS))

    def run_until(self, done: Callable[[], bool], limit_ms: float, what: str) -> float:
        """Scan until done(); the virtual ms it took."""
        start = self.plc.now_ns
        self.plc.run_until(done, timeout=int(limit_ms * MS), what=what)
        return (self.plc.now_ns - start) / MS
