"""From a configuration to a ready engine: compile the ST files, plan the
tasks, let every registered bus make its drivers and simulated devices, and
make the retain store. Names no bus and no device: the registry does; a
configuration with no bus section and no [[sim]] table is built without
loading it (a bus none of whose sections a file has, and on which no device
is simulated, adds nothing)."""

from __future__ import annotations

from pathlib import Path

from ..config import ConfigError, PlcConfig
from ..plugin.driver import DriverError
from ..plugin.registry import loaded, plugin_sections, registry
from ..plugin.seams import BuildContext
from ..program import compile_files
from ..st.profile import get_profile
from .clock import RealClock, VirtualClock
from .retain_file import RetainStore
from .scan import Engine
from .scenario import Scenario
from .sim_schedule import SimSchedule
from .tasks import plan_tasks


def make_drivers(config: PlcConfig, clock=None, by_name: dict | None = None, bus_log: Path | None = None) -> list:
    """The drivers and simulated devices of config, in the order the engine
    serves them: every bus's simulators first (in virtual time they move on
    to the tick's time before the drivers read the bus), then the bus
    drivers, each in registry order; the scheduled faults of [[sim]] tables
    after the simulators. The engine stops them in reverse: bus drivers
    before the simulated devices they talk to. by_name: filled with the
    simulators by [[sim]] name; bus_log: the file every bus records its
    wire in, or beside (BuildContext.bus_log)."""
    clock = clock if clock is not None else RealClock()
    where = str(config.path) if config.path else "<config>"
    ctx = BuildContext(clock, get_profile(config.profile).addressing, where, bus_log=bus_log)
    if by_name is not None:
        ctx.simulators = by_name
    simulators, drivers = [], []
    for bus in _buses(config):
        if bus.build is not None:
            try:
                part = bus.build(config, ctx)
            except DriverError as exc:  # a key of the file that cannot work: the file named first
                text = str(exc)
                raise DriverError(text if text.startswith(ctx.where) else f"{ctx.where}: {text}") from None
            simulators += part.simulators
            drivers += part.drivers
    if any(sim.faults for sim in config.sims):
        simulators.append(SimSchedule(clock, config.sims, ctx.simulators))
    return simulators + drivers


def _buses(config: PlcConfig) -> list:
    """The registered buses, or none when config has nothing any bus builds
    and the registry is not loaded (no bus or device imported for it)."""
    if loaded() or config.sims or any(config.sections.get(key) for key, _many in plugin_sections()):
        return registry().buses
    return []


def build_engine(
    config: PlcConfig,
    *,
    virtual_time: bool = False,
    start_mode: str | None = None,
    program=None,
    extra_tasks: tuple = (),
    retain: bool = True,
    bus_log: Path | None = None,
) -> Engine:
    """An Engine for config, not started. Raises CompileError for errors in
    the ST files and TaskSetupError for tasks that cannot run. program: an
    already compiled Program (tests compile once and build many engines);
    extra_tasks: TaskConfigs run beside the configured ones (a test's);
    retain=False: no retain file is read or written (a test's plant);
    bus_log: every bus records its wire in this file or beside it."""
    if program is None:
        program = compile_files(config.programs, profile=config.profile, libraries=tuple(config.libraries))
    where = str(config.path) if config.path else "<config>"
    tasks = plan_tasks(program, config.tasks, where, none_ok=bool(extra_tasks)) + list(extra_tasks)
    scenario = Scenario(config.init, config.schedule)
    if scenario:  # [init], [[schedule]], --set: their paths and values, in an engine of the program alone
        errors = scenario.check(Engine(program, tasks, clock=VirtualClock()))
        if errors:
            raise ConfigError(where, errors)
    retain_store = RetainStore(config.retain.file) if config.retain and retain else None
    clock = (
        VirtualClock()
        if virtual_time
        else RealClock(spin_ns=config.spin_ns, realtime_priority=config.realtime_priority)
    )
    simulators: dict = {}
    drivers = make_drivers(config, clock, simulators, bus_log)
    engine = Engine(
        program,
        tasks,
        clock=clock,
        drivers=drivers,
        simulators=simulators,
        on_fault=config.on_fault,
        safe_outputs=config.safe_outputs,
        retain_store=retain_store,
        retain_period_ns=config.retain.period_ns if config.retain else 1_000_000_000,
        start_mode=start_mode or config.start,
    )
    if scenario:
        scenario.install(engine)
        engine.scenario = scenario
    return engine
