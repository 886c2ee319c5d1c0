"""A PLC with its Modbus TCP server on 127.0.0.1 (a free port), its engine
scanning on the virtual clock in a thread of its own, and a real pymodbus
client talking to it."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import pytest
from pymodbus.client import ModbusTcpClient

from softplc.runtime.config.servers import ServerConfig
from softplc.runtime.engine.access import Access, Permission
from softplc.runtime.engine.scan import Engine
from softplc.runtime.surfaces.host import Surfaces

from ...engine.conftest import Scanning, make_engine, task

SRC = """
PROGRAM Main
VAR
    count AT %QW2 : INT;        (* holding register 2 *)
    start AT %QX0.3 : BOOL;     (* coil 3: the HMI writes it *)
    running AT %QX1.0 : BOOL;   (* coil 8: follows coil 3 *)
    setpoint AT %MW5 : WORD;    (* holding register 1029: the HMI writes it *)
    doubled AT %MW6 : WORD;     (* holding register 1030: twice the setpoint *)
    level AT %IW4 : INT;        (* input register 4 *)
    level_shown AT %QW10 : INT; (* holding register 10: the level plus one *)
    sensor AT %IX0.2 : BOOL;    (* discrete input 2 *)
    lamp AT %QX0.5 : BOOL;      (* coil 5: the sensor *)
END_VAR
IF count < 1000 THEN count := count + 1; END_IF
running := start;
doubled := setpoint * 2;
level_shown := level + 1;
lamp := sensor;
END_PROGRAM
"""

TIMEOUT_S = 20.0


@dataclass
class Running:
    engine: Engine
    surfaces: Surfaces
    handle: Any
    client: ModbusTcpClient
    test: Access  # what a driver would do: set inputs

    @property
    def port(self) -> int:
        return self.handle.port


def server_config(**options) -> ServerConfig:
    writable = options.pop("writable", ("%Q*", "%M*"))
    return ServerConfig(
        key="modbus_server",
        host="127.0.0.1",
        port=options.pop("port", 0),
        writable=tuple(writable),
        period_ns=20_000_000,
        options=options,
        where="[modbus_server] writable",
    )


@pytest.fixture
def plc():
    """plc(**options) starts the PLC, its server and a connected client; all stopped after the test."""
    stack: list[Callable[[], None]] = []

    def factory(source: str = SRC, **options) -> Running:
        engine = make_engine(source, [task("Main", 10, "Main")])
        stack.append(engine.stop)
        surfaces = Surfaces(engine, {"modbus_server": server_config(**options)})
        surfaces.start()
        stack.append(surfaces.stop)
        test = Access(engine, {"test": Permission(("*",))})
        stack.append(Scanning(engine, pause_s=0).start().stop)
        handle = surfaces.handles["modbus_server"]
        client = ModbusTcpClient("127.0.0.1", port=handle.port, timeout=5, retries=0)
        assert client.connect()
        stack.append(client.close)
        surfaces.hub.wait_fresh(timeout=TIMEOUT_S)
        return Running(engine, surfaces, handle, client, test)

    yield factory
    for undo in reversed(stack):
        undo()
