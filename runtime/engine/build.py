"""From a configuration to a ready engine: compile the ST files, plan the
tasks, make the drivers and the retain store. The one place that knows
which config section becomes which driver."""
from __future__ import annotations

from typing import Optional

from ..config import PlcConfig
from ..io.loopback import LoopbackDriver
from ..st.loader import compile_files
from ..st.profile import get_profile
from .clock import RealClock, VirtualClock
from .retain import RetainStore
from .scan import Engine
from .tasks import plan_tasks


def make_drivers(config: PlcConfig) -> list:
    addressing = get_profile(config.profile).addressing
    drivers = []
    if config.loopback:
        drivers.append(LoopbackDriver("loopback", [(link.source, link.target, link.nbytes)
                                                   for link in config.loopback], addressing))
    return drivers


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
    return Engine(program, tasks,
                  clock=VirtualClock() if virtual_time else RealClock(),
                  drivers=make_drivers(config),
                  on_fault=config.on_fault,
                  safe_outputs=config.safe_outputs,
                  retain_store=retain_store,
                  retain_period_ns=config.retain.period_ns if config.retain else 1_000_000_000,
                  start_mode=start_mode or config.start)
