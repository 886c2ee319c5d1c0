"""From a configuration to a ready engine: compile the ST files, plan the
tasks, make the drivers and the retain store. The one place that knows
which config section becomes which driver."""
from __future__ import annotations

from typing import Optional

from ..config import PlcConfig
from ..io.canbus import BusPump, BusSettings
from ..io.canopen_master import CanopenDriver
from ..io.loopback import LoopbackDriver
from ..st.loader import compile_files
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
    drivers = [make_simulator(sim, buses[sim.bus], clock, pump) for sim in config.sims]
    if config.canopen is not None:
        drivers.append(CanopenDriver(config.canopen, buses[config.canopen.bus], clock=clock, pump=pump,
                                     addressing=addressing))
    if config.loopback:
        drivers.append(LoopbackDriver("loopback", [(link.source, link.target, link.nbytes)
                                                   for link in config.loopback], addressing))
    return drivers


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
