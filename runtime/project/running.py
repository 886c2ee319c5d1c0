"""A project run as a PLC (`softplc run PROJECT`): its programs, with the
tasks it declares itself (TwinCAT's .TcTTO objects, else the CONFIGURATION
of its sources, else every PROGRAM in one 10 ms task), and no bus: the
configuration a TOML file would give, made from the project."""

from __future__ import annotations

from pathlib import Path

from ..config import DEFAULT_PAUSE_NS, PlcConfig, ProgramInstance, TaskConfig, config_from_dict, default_watchdog_ns
from ..program.loaded import Program
from .analysis import Analysis


class ProjectRunError(Exception):
    """The project's tasks cannot run (a task calls no PROGRAM that compiled)."""


def project_config(analysis: Analysis, program: Program) -> PlcConfig:
    """The configuration of a run of the project: its files and profile,
    and its tasks (.TcTTO) with the PROGRAMs of program they call."""
    project = analysis.project
    files = [str(Path(f).resolve()) for f in project.files]
    cfg = config_from_dict(
        {"plc": {"profile": analysis.profile.name, "programs": files}},
        project.path,
        base_dir=project.root,
    )
    known = {name.upper(): name for name, kind in program.pous.items() if kind == "PROGRAM"}
    tasks = []
    for i, spec in enumerate(project.tasks):
        where = f"{spec.pos}"
        calls = [
            ProgramInstance(known[name.upper()], known[name.upper()], f"{pos}")
            for name, pos in spec.programs
            if name.upper() in known
        ]
        if not calls:
            continue
        tasks.append(
            TaskConfig(
                name=spec.name,
                interval_ns=spec.interval_ns,
                pause_ns=DEFAULT_PAUSE_NS,
                priority=spec.priority,
                watchdog_ns=default_watchdog_ns(spec.interval_ns),
                sensitivity=1,
                programs=calls,
                key=where or f"task[{i}]",
            )
        )
    if project.tasks and not tasks:
        names = ", ".join(n for t in project.tasks for n, _pos in t.programs) or "nothing"
        raise ProjectRunError(f"{project.tasks[0].pos}: the project's tasks call {names}: no PROGRAM that compiled")
    cfg.tasks = tasks
    return cfg
