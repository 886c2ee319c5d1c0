"""From a configuration to a ready engine: compile the ST files, plan the
tasks, make the drivers and the retain store. The one place that knows
which config section becomes which driver."""
from __future__ import annotations

import dataclasses
import socket
from typing import Optional

from ..config import PlcConfig
from ..io.canbus import BusPump, BusSettings
from ..io.canopen_master import CanopenDriver
from ..io.driver import DriverError
from ..io.loopback import LoopbackDriver
from ..io.modbus_master import ModbusDriver
from ..program import compile_files
from ..st.profile import get_profile
from .clock import RealClock, VirtualClock
from .retain import RetainStore
from .scan import Engine
from .tasks import plan_tasks


def make_drivers(config: PlcConfig, clock=None, pump: Optional[BusPump] = None) -> list:
    """The drivers and simulated devices of config, in the order the engine
    serves them: simulators first (in virtual time they move on to the
    tick's time before the master reads the bus), then the bus drivers.
    pump: the virtual-time BusPump every CAN endpoint shares (None: real time)."""
    addressing = get_profile(config.profile).addressing
    clock = clock if clock is not None else RealClock()
    buses = {bus.name: bus for bus in config.can}
    drivers = [make_simulator(sim, buses[sim.bus], clock, pump) for sim in config.sims if sim.modbus is None]
    if config.modbus:
        drivers = make_modbus_drives(config, clock) + drivers
    if config.canopen is not None:
        drivers.append(CanopenDriver(config.canopen, buses[config.canopen.bus], clock=clock, pump=pump,
                                     addressing=addressing))
    if config.modbus:
        drivers.append(ModbusDriver(_with_simulated_ports(config.modbus, drivers), addressing, clock=clock))
    if config.loopback:
        drivers.append(LoopbackDriver("loopback", [(link.source, link.target, link.nbytes)
                                                   for link in config.loopback], addressing))
    return drivers


def make_modbus_drives(config: PlcConfig, clock) -> list:
    """One simulated line per [[modbus]] connection that has [[sim]] drives:
    a pymodbus server with a drive model per unit (RTU on a pseudo-terminal
    cable, TCP on 127.0.0.1)."""
    from ..devices.eaton import Family
    from ..sim.eaton_drive import EatonDriveSimulator
    from ..sim.eaton_drive_model import EatonDriveModel
    lines = []
    for conn in config.modbus:
        drives = {}
        for sim in config.sims:
            if sim.modbus == conn.name:
                family = Family.DE1 if sim.type == "de11" else Family[sim.type.upper()]
                try:
                    drives[sim.unit] = EatonDriveModel(family, de11=sim.type == "de11",
                                                       registers=dict(sim.registers))
                except ValueError as exc:    # a register the drive does not have
                    raise DriverError(f"{config.path or '<config>'}: {sim.key}.registers: {exc}") from None
        if not drives:
            continue
        if conn.transport == "tcp":
            lines.append(EatonDriveSimulator(conn.name, drives, clock=clock, transport="tcp", host=conn.host,
                                             port=conn.port or _free_tcp_port()))
        else:
            lines.append(EatonDriveSimulator(conn.name, drives, clock=clock, transport="rtu", baud=conn.baud,
                                             parity=conn.parity, stop_bits=conn.stop_bits))
    return lines


def _free_tcp_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _with_simulated_ports(connections: list, drivers: list) -> list:
    """The connections, those to simulated drives pointed at the simulator:
    its end of the serial cable, or the TCP port it listens on."""
    from ..sim.eaton_drive import EatonDriveSimulator
    lines = {d.name: d for d in drivers if isinstance(d, EatonDriveSimulator)}
    out = []
    for conn in connections:
        line = lines.get(conn.name)
        if line is not None:
            conn = dataclasses.replace(conn, device=line.master_port) if line.cable is not None \
                else dataclasses.replace(conn, port=line.port)
        out.append(conn)
    return out


def make_simulator(sim, bus, clock, pump):
    """A simulated device of a [[sim]] table on its [[can]] bus."""
    settings = BusSettings(bus.interface, str(bus.channel), bus.bitrate, dict(bus.options))
    if sim.type == "ltmr":
        from ..sim.ltmr import LtmrSimulator
        return LtmrSimulator(sim.node_id, settings=settings, clock=clock, pump=pump, name=sim.name,
                             registers=dict(sim.registers))
    raise ValueError(f"{sim.key}.type: no simulator called {sim.type!r}")


def build_engine(config: PlcConfig, *, virtual_time: bool = False, start_mode: Optional[str] = None,
                 program=None) -> Engine:
    """An Engine for config, not started. Raises CompileError for errors in
    the ST files and TaskSetupError for tasks that cannot run. program: an
    already compiled Program (tests compile once and build many engines)."""
    if program is None:
        program = compile_files(config.programs, profile=config.profile)
    where = str(config.path) if config.path else "<config>"
    tasks = plan_tasks(program, config.tasks, where)
    retain_store = RetainStore(config.retain.file) if config.retain else None
    clock = VirtualClock() if virtual_time else RealClock()
    pump = BusPump() if virtual_time else None
    return Engine(program, tasks,
                  clock=clock,
                  drivers=make_drivers(config, clock, pump),
                  on_fault=config.on_fault,
                  safe_outputs=config.safe_outputs,
                  retain_store=retain_store,
                  retain_period_ns=config.retain.period_ns if config.retain else 1_000_000_000,
                  start_mode=start_mode or config.start)
