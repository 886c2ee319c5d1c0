"""A Modbus plant in virtual time: the Modbus master (the real driver, built
from a configuration as `softplc run` builds it) and simulated Eaton drives
behind pymodbus's framers and request handling in memory (the default in
virtual time), or, with wire="port", behind a real pymodbus server on a
pseudo-terminal cable (RTU) or on 127.0.0.1 (TCP)."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.config import config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.modbus.line import SimulatedModbusLine
from softplc.runtime.io.modbus.master import ModbusDriver
from softplc.runtime.st.valuejson import encode_value

MS = 1_000_000
REPO = Path(__file__).resolve().parents[3]
DRIVE_PROGRAM = REPO / "st_programs" / "eaton_drive.st"


# In memory, a timeout is virtual time like any other. On a port, answers
# cross a socket or a pseudo-terminal in real time even on the virtual clock:
# the timeout must outlast the slowest answer of a loaded machine (a drive
# that answers never waits for it; 500 ms lost two answers of the RTU
# sequence in ten suite runs at a load of 30), and tests that make a drive
# silent pass SILENT_TIMEOUT, so that the many requests that then time out
# cost little real time.
TIMEOUT = "100ms"
PORT_TIMEOUT = "10s"
SILENT_TIMEOUT = "30ms"
WIRES = ("memory", "port")


def connection(transport: str, wire: str = "memory", **extra) -> dict:
    """A [[modbus]] table named "drives" to the simulated drives, in memory
    or on a real port (wire = "port": a pseudo-terminal or a TCP socket)."""
    table = {
        "name": "drives",
        "transport": transport,
        "sim_wire": wire,
        "timeout": PORT_TIMEOUT if wire == "port" else TIMEOUT,
        "retries": 0,
        "reconnect": "100ms",
        "reconnect_max": "400ms",
    }
    table.update({"device": "sim", "baud": 115200} if transport == "rtu" else {"port": 0})
    table.update(extra)
    return table


def plant_config(
    tmp_path: Path, source, *, program, transport="tcp", sims=None, channels=(), interval="10ms", **conn_extra
) -> dict:
    """source: ST text or a list of ST files; program: PROGRAM names (or
    {instance, program} tables) for the one task."""
    if isinstance(source, str):
        st = tmp_path / "plant.st"
        st.write_text(source)
        files = [str(st)]
    else:
        files = [str(f) for f in source]
    conn = connection(transport, **conn_extra)
    conn["channel"] = list(channels)
    return {
        "plc": {"programs": files},
        "task": [
            {
                "name": "Main",
                "interval": interval,
                "programs": [program] if isinstance(program, (str, dict)) else list(program),
            }
        ],
        "modbus": [conn],
        "sim": sims if sims is not None else [{"type": "da1", "unit": 1}],
    }


class Plant:
    def __init__(self, data: dict, tmp_path: Path) -> None:
        self.config = config_from_dict(data, tmp_path / "plant.toml")
        self.engine = build_engine(self.config, virtual_time=True)
        self.master = next(d for d in self.engine.drivers if isinstance(d, ModbusDriver))
        self.line = next(d for d in self.engine.drivers if isinstance(d, SimulatedModbusLine))
        self.engine.start()

    def drive(self, unit: int = 1):
        return self.line.unit(unit)

    @property
    def now_ms(self) -> float:
        return self.engine.clock.now_ns() / MS

    def __getitem__(self, path: str):
        """A variable's value (an enumeration's as its name, "RunForward") or an address's."""
        if path.startswith("%"):
            return self.engine.get(path)
        holder, attr, ty = self.engine.variable(path)
        value = encode_value(ty, getattr(holder, attr))
        return value if isinstance(value, str) else self.engine.get(path)

    def channel(self, index: int, field: str):
        """MODBUS_CHANNEL[index].<field>, as the program reads it."""
        holder, attr, _ty = self.engine.variable("MODBUS_CHANNEL")
        struct = getattr(holder, attr)[index]
        for st_name, py_attr, _t, _section in type(struct)._VARS_:
            if st_name.upper() == field.upper():
                return getattr(struct, py_attr)
        raise KeyError(field)

    def run_ms(self, ms: float) -> None:
        self.engine.run(duration_ns=int(ms * MS))

    def run_until(self, condition, timeout_ms: float, step_ms: float = 10) -> float:
        """Run until condition() holds; the virtual time it took (ms)."""
        start = self.now_ms
        while not condition():
            if self.now_ms - start > timeout_ms:
                raise AssertionError(f"not reached within {timeout_ms} ms of virtual time")
            self.run_ms(step_ms)
        return self.now_ms - start

    def stop(self) -> None:
        self.engine.stop()


@pytest.fixture
def plants(tmp_path):
    made: list = []

    def make(data: dict) -> Plant:
        plant = Plant(data, tmp_path)
        made.append(plant)
        return plant

    yield make
    for plant in made:
        plant.stop()
