"""Modbus RTU and TCP: the master (master.py: one owner per connection,
channels into the image, MODBUS_EXCHANGE for the program), its [[modbus]]
configuration, and simulated devices on a line (line.py: a real pymodbus
server whose units are device models, [[sim]] with modbus and unit).

A device that simulates a Modbus slave gets ``simulator(sim,
ModbusSimContext)`` called and returns its model (unit.SimulatedUnit): sim.at
is its ModbusUnit; the line it joins is the connection's.

Public names: BUS, ModbusDriver, ModbusConnectionConfig, ModbusChannelConfig,
ModbusUnit, ModbusSimContext, SimulatedModbusLine, SimulatedUnit, ModbusRefusal.
"""

from __future__ import annotations

import dataclasses
import socket
from dataclasses import dataclass
from pathlib import Path

from ...plugin.registry import registry
from ...plugin.seams import BuildContext, Bus, Contribution, StLibrary
from .buslog import ModbusWireLog, modbus_log_path
from .config import ModbusAttachment, ModbusChannelConfig, ModbusConnectionConfig, ModbusSection, ModbusUnit
from .exchange import MODBUS_EXCHANGE
from .line import SimulatedModbusLine, UnitOnLine
from .master import ModbusDriver
from .readlog import read_log
from .safe import MODBUS_SAFE_WRITE
from .unit import SILENT, ModbusRefusal, SimulatedUnit


@dataclass
class ModbusSimContext:
    clock: object
    connection: ModbusConnectionConfig
    where: str  # the configuration file, for messages


def _free_tcp_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _lines(config, ctx: BuildContext) -> dict:
    """One simulated line per [[modbus]] connection that has [[sim]] devices:
    a pymodbus server with a model per unit (RTU on a pseudo-terminal cable,
    TCP on 127.0.0.1), or in memory (wire.py): sim_wire, by default memory
    in virtual time and the port in real time."""
    devices = registry().sim_types()
    lines = {}
    for conn in config.modbus:
        units, named = {}, {}
        for sim in config.sims:
            device = devices[sim.type]
            if device.bus == BUS.name and sim.at.connection == conn.name:
                assert device.simulator is not None  # the registry has no simulating device without one
                units[sim.at.unit] = device.simulator(sim, ModbusSimContext(ctx.clock, conn, ctx.where))
                named[sim.at.unit] = sim
        if not units:
            continue
        wire = conn.sim_wire or ("memory" if ctx.clock.virtual else "port")
        if conn.transport == "tcp":
            lines[conn.name] = SimulatedModbusLine(
                conn.name,
                units,
                clock=ctx.clock,
                transport="tcp",
                host=conn.host,
                port=0 if wire == "memory" else conn.port or _free_tcp_port(),
                wire=wire,
            )
        else:
            lines[conn.name] = SimulatedModbusLine(
                conn.name,
                units,
                clock=ctx.clock,
                transport="rtu",
                baud=conn.baud,
                parity=conn.parity,
                stop_bits=conn.stop_bits,
                wire=wire,
            )
        for unit, sim in named.items():
            ctx.simulated(sim, UnitOnLine(lines[conn.name], unit))
    return lines


def _build(config, ctx: BuildContext) -> Contribution:
    if not config.modbus:
        return Contribution()
    lines = _lines(config, ctx)
    connections = []
    servers = {}
    for conn in config.modbus:  # those to simulated devices go to the simulator's end
        line = lines.get(conn.name)
        if line is not None and line.server is not None:
            servers[conn.name] = line.server
        elif line is not None:
            conn = (
                dataclasses.replace(conn, device=line.master_port)
                if line.master_port is not None
                else dataclasses.replace(conn, port=line.port)
            )
        connections.append(conn)
    # the run records its wire: the log first among the drivers, closed after them
    wire = ModbusWireLog(modbus_log_path(Path(ctx.bus_log)), ctx.clock) if ctx.bus_log is not None else None
    driver = ModbusDriver(connections, ctx.addressing, clock=ctx.clock, servers=servers, wire=wire)
    return Contribution(simulators=list(lines.values()), drivers=[wire, driver] if wire is not None else [driver])


BUS = Bus(
    name="modbus",
    order=40,
    sections=(ModbusSection(),),
    attachment=ModbusAttachment(),
    natives=(MODBUS_EXCHANGE, MODBUS_SAFE_WRITE),
    libraries=(StLibrary("softplc.fblocks.comm", "modbus.st"),),
    build=_build,
    read_log=read_log,
)

__all__ = [
    "BUS",
    "ModbusChannelConfig",
    "ModbusConnectionConfig",
    "ModbusDriver",
    "ModbusRefusal",
    "ModbusSimContext",
    "ModbusUnit",
    "SILENT",
    "SimulatedModbusLine",
    "SimulatedUnit",
    "UnitOnLine",
]
