"""Which tasks run which program instances: from the TOML configuration,
from the ST CONFIGURATION/RESOURCE/TASK, or the default (plan_tasks); and a
task at run time (Task: its instances, next release, statistics).

Scheduling policy (docs/guide/running.md "Tasks"): every task is released at t = 0 and
then every interval. At each tick the engine reads inputs, runs every task
that is due in priority order (0 first; equal priorities in declaration
order), then writes outputs. A task whose cycle runs past its next release
skips the activations it missed (counted as overruns) rather than running
them back to back. A freewheeling task is released again `pause` after its
previous cycle ended.
"""

from __future__ import annotations

import difflib

from ..config import DEFAULT_PAUSE_NS, ProgramInstance, TaskConfig, default_watchdog_ns
from ..config.plc import MIN_INTERVAL_NS, MIN_INTERVAL_TEXT
from ..config.values import cut
from ..program import TaskState
from ..st.faults import STFault
from .stats import TaskStats

DEFAULT_INTERVAL_NS = 10_000_000  # CODESYS's MainTask: 10 ms


class TaskSetupError(Exception):
    """The tasks cannot be set up; the message names where (file and key or
    ST position) and what to change, a long name in it cut as in a
    configuration error."""

    def __init__(self, message: str) -> None:
        super().__init__(cut(message))


def plan_tasks(program, configured: list, config_file: str = "", *, none_ok: bool = False) -> list:
    """The TaskConfig list to run. configured: tasks from the TOML file.
    none_ok: sources without a PROGRAM give no task instead of an error
    (the caller runs tasks of its own)."""
    programs = {name.upper(): name for name, kind in program.pous.items() if kind == "PROGRAM"}
    st_configs = program.checked.configurations
    if configured:
        if st_configs:
            raise TaskSetupError(
                f"{config_file}: task: the ST sources declare CONFIGURATION "
                f"{st_configs[0].name} with its own tasks; declare the tasks in one place "
                "(remove the [[task]] tables or the CONFIGURATION)"
            )
        for task in configured:
            for inst in task.programs:
                _check_program(inst.program, programs, f"{config_file}: {inst.key}")
        return list(configured)
    if st_configs:
        return _from_st_configuration(program, st_configs)
    if not programs:
        if none_ok:
            return []
        raise TaskSetupError("the ST sources declare no PROGRAM: nothing to run")
    # No tasks anywhere: every PROGRAM in one 10 ms task, in declaration order.
    return [
        TaskConfig(
            name="MainTask",
            interval_ns=DEFAULT_INTERVAL_NS,
            pause_ns=DEFAULT_PAUSE_NS,
            priority=1,
            watchdog_ns=default_watchdog_ns(DEFAULT_INTERVAL_NS),
            sensitivity=1,
            programs=[ProgramInstance(name, name, f"default task, PROGRAM {name}") for name in programs.values()],
            key="default task",
        )
    ]


def _check_program(name: str, programs: dict, where: str) -> None:
    if name.upper() in programs:
        return
    close = difflib.get_close_matches(name.upper(), list(programs), n=1, cutoff=0.6)
    hint = (
        f" (did you mean '{programs[close[0]]}'?)"
        if close
        else (f" (the PROGRAMs are: {', '.join(programs.values())})" if programs else "")
    )
    raise TaskSetupError(f"{where}: '{name}' is not a PROGRAM of the loaded ST files{hint}")


def _from_st_configuration(program, configs: list) -> list:
    if len(configs) > 1:
        raise TaskSetupError(
            f"{configs[1].node.pos}: only one CONFIGURATION can run at a time "
            f"(found {', '.join(c.name for c in configs)})"
        )
    cfg = configs[0]
    tasks: dict = {}
    for t in cfg.tasks:
        if t["single"] is not None or t["interval_ms"] is None:
            raise TaskSetupError(
                f"{t['pos']}: task {t['name']}: event tasks (SINGLE, or no INTERVAL) "
                "are not supported; give it an INTERVAL"
            )
        interval_ns = round(t["interval_ms"] * 1_000_000)
        if interval_ns < MIN_INTERVAL_NS:
            raise TaskSetupError(
                f"{t['pos']}: task {t['name']}: INTERVAL T#{t['interval_ms'] * 1000:g}us is below the least "
                f"interval, {MIN_INTERVAL_TEXT}: a scan runs Python, a shorter period only overruns"
            )
        tasks[t["name"].upper()] = TaskConfig(
            name=t["name"],
            interval_ns=interval_ns,
            pause_ns=DEFAULT_PAUSE_NS,
            priority=t["priority"],
            watchdog_ns=default_watchdog_ns(interval_ns),
            sensitivity=1,
            programs=[],
            key=f"TASK {t['name']}",
        )
    for p in cfg.programs:
        binding = p["binding"]
        if binding.inputs or binding.outputs or binding.inouts:
            raise TaskSetupError(
                f"{p['pos']}: program instance {p['name']}: arguments in the "
                "CONFIGURATION are not supported yet; use located variables "
                "(AT %I.., AT %Q..) in the PROGRAM instead"
            )
        if p["task"] is None:
            raise TaskSetupError(
                f"{p['pos']}: program instance {p['name']} has no task; write PROGRAM <name> WITH <task> : <type>"
            )
        tasks[p["task"].upper()].programs.append(ProgramInstance(p["name"], p["type"].name, f"PROGRAM {p['name']}"))
    active = [t for t in tasks.values() if t.programs]  # a task with no program has nothing to do
    if not active:
        raise TaskSetupError(f"{cfg.node.pos}: CONFIGURATION {cfg.name} assigns no PROGRAM to a task")
    return active


class Task:
    """A task at run time: its configuration, program instances, next release and statistics."""

    def __init__(self, spec, order: int) -> None:
        self.spec = spec
        self.name = spec.name
        self.order = order
        self.interval_ns = spec.interval_ns  # None: freewheeling
        self.pause_ns = spec.pause_ns
        self.priority = spec.priority
        self.watchdog_ns = spec.watchdog_ns
        self.sensitivity = spec.sensitivity
        # The cooperative check on loop back-edges faults a single cycle at
        # once when it runs longer than time x sensitivity (as CODESYS).
        self.budget_s = float("inf") if spec.watchdog_ns is None else spec.watchdog_ns * spec.sensitivity / 1e9
        self.instances: list = []  # (instance name, POUInfo, object)
        self.calls: list = []
        self.next_ns = 0
        self.late_cycles = 0  # consecutive cycles longer than the watchdog time
        self.fault: STFault | None = None
        self.stats = TaskStats()
        #: what a program asks of its task (ExecContext.begin_task): index in the configuration's order
        self.state = TaskState(order + 1, spec.name, spec.interval_ns or 0, spec.priority)

    def describe(self) -> str:
        every = (
            f"every {self.interval_ns / 1e6:g} ms"
            if self.interval_ns is not None
            else f"freewheeling (pause {self.pause_ns / 1e6:g} ms)"
        )
        wd = (
            "no watchdog" if self.watchdog_ns is None else f"watchdog {self.watchdog_ns / 1e6:g} ms x{self.sensitivity}"
        )
        names = ", ".join(name for name, _info, _obj in self.instances)
        return f"task {self.name}: {every}, priority {self.priority}, {wd}: {names}"
