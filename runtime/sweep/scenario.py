"""One scenario of a sweep: the configuration's tables with the scenario's
values in them, run in virtual time for the sweep's duration through the
testing API, and its result row.

A Job holds everything a worker needs (the tables, where relative paths
resolve, the duration, the expressions), so run_job is a plain function of
picklable data: the same row in this process, in a pool's, on a Dask
worker of another machine (which must have softplc and the configuration's
files at the same paths).
"""

from __future__ import annotations

import copy
import json
import threading
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..config.errors import ConfigError
from ..config.load import config_from_dict, load_config
from .expr import Scope, check, evaluate
from .matrix import Scenario, Sweep, SweepError

ASSERTIONS_SHOWN = 5  # a scenario's failed assertions in its row, the first ones
#: the result row's own columns, before the values
SCENARIO, PASSED, FAILED, FAULT, RECORDS = "scenario", "passed", "failed", "fault", "records"


@dataclass(frozen=True)
class Job:
    index: int
    params: dict
    tables: dict  # the configuration's, with the scenario's values in
    base_dir: str
    duration_ns: int
    values: tuple
    expect: tuple


def jobs(sweep: Sweep, config: str | Path) -> list:
    """A Job per scenario; SweepError (a key that goes nowhere) or ConfigError
    (a value the configuration refuses), naming the scenario, before any runs."""
    path = Path(config)
    cfg = load_config(path)  # ConfigError for a file that is not a configuration, TOML included
    names = {sim.name.upper(): i for i, sim in enumerate(cfg.sims)}
    tables = tomllib.loads(path.read_text(encoding="utf-8"))
    out = []
    for scenario in sweep.scenarios:
        data = place(tables, scenario, names, sweep.file)
        try:
            config_from_dict(data, path)
        except ConfigError as e:
            raise SweepError(sweep.file, f"scenario {scenario.index} ({scenario.id})", str(e)) from None
        out.append(
            Job(scenario.index, scenario.params, data, str(path.parent), sweep.duration_ns, sweep.values, sweep.expect)
        )
    return out


def place(tables: dict, scenario: Scenario, sim_names: dict, file: str) -> dict:
    """The tables with the scenario's values at their keys (a copy)."""
    data = copy.deepcopy(tables)
    for key, value in scenario.params.items():
        head, _, rest = key.partition(".")
        if head == "init" and rest:
            data.setdefault("init", {})[rest] = value
            continue
        if head == "sim" and rest:
            name, _, inner = rest.partition(".")
            if name.upper() not in sim_names or not inner:
                known = ", ".join(n.lower() for n in sim_names) or "none"
                raise SweepError(file, key, f"no simulated device {name!r} with a key (the [[sim]] names: {known})")
            _set(data["sim"][sim_names[name.upper()]], inner.split("."), value, key, file)
            continue
        _set(data, key.split("."), value, key, file)
    return data


def _set(table: Any, parts: list, value: Any, key: str, file: str) -> None:
    for part in parts[:-1]:
        table = _step(table, part, key, file)
    if isinstance(table, list):
        raise SweepError(file, key, f"{'.'.join(parts[:-1])} is an array of tables: name one (by name or number)")
    table[parts[-1]] = value


def _step(table: Any, part: str, key: str, file: str) -> Any:
    """The table under part: an array's by its name or number, a table's (made when missing)."""
    if isinstance(table, list):
        for i, item in enumerate(table):
            if (part.isdigit() and int(part) == i) or (
                isinstance(item, dict) and str(item.get("name", "")).upper() == part.upper()
            ):
                return item
        raise SweepError(file, key, f"no table {part!r} in that array (by its name or its number)")
    if not isinstance(table, dict):
        raise SweepError(file, key, f"{part!r}: not a table")
    if part not in table:
        table[part] = {}
    return table[part]


#: one scenario at a time in a process: a configuration's in-process buses
#: (python-can's virtual channels) are named by the file, and two plants
#: of one sweep side by side would share them (a Dask worker's threads)
_ONE_AT_A_TIME = threading.Lock()


def run_job(job: Job) -> dict:
    """The scenario's row: its number, its parameters, passed, what failed,
    the first runtime fault, the values, the records (as JSON text)."""
    with _ONE_AT_A_TIME:
        return _run(job)


def build(job: Job) -> tuple:
    """The scenario's PLC (testing API), not started, and the Recorder of
    its assertions; CompileError or TaskSetupError as softplc run has them."""
    from ..engine.build import build_engine
    from ..program import compile_files
    from ..testing.natives import NATIVES, SERVICE, Recorder
    from ..testing.plc import PLC
    from ..testing.runner import simulated

    cfg = config_from_dict(job.tables, base_dir=job.base_dir)
    # the assertions of softplc test (ASSERT_EQUAL ...) may be in the plant's own programs
    program = compile_files(cfg.programs, profile=cfg.profile, natives=NATIVES, libraries=tuple(cfg.libraries))
    # cold, no retain file: every scenario starts the same, and none writes another's file
    engine = build_engine(cfg, virtual_time=True, start_mode="cold", program=program, retain=False)
    recorder = Recorder(engine.clock, simulated(cfg, engine))
    engine.ctx.services[SERVICE] = recorder
    return PLC(engine, cfg), recorder


def _run(job: Job) -> dict:
    from ..sim.base import records_of

    plc, recorder = build(job)
    try:
        plc.run_for(job.duration_ns)
        faults = plc.engine.faults
        fault = str(faults[0]) if faults else ""
        records = records_of(plc.engine.simulators)
        scope = Scope(plc.read, records, job.params, fault)
        failed = [f"runtime fault: {fault}"] if fault else []
        failed += [_assertion(f) for f in recorder.failures[:ASSERTIONS_SHOWN]]
        failed += [why for why in (check(text, scope) for text in job.expect) if why]
        values = {text: _plain(evaluate(text, scope)) for text in job.values}
    finally:
        plc.stop()
    return {
        SCENARIO: job.index,
        **job.params,
        PASSED: not failed,
        FAILED: "; ".join(failed),
        FAULT: fault,
        **values,
        RECORDS: json.dumps(records, sort_keys=True, default=str),
    }


def _plain(value: Any) -> Any:
    """A value for a table cell: numbers, text, booleans as they are; the rest as text."""
    if value is None or type(value) in (bool, int, float, str):
        return value
    if isinstance(value, str):  # an enumerator: its name
        return str(value)
    if hasattr(value, "total_seconds"):  # TIME
        return value.total_seconds()
    return str(value)


def _assertion(failure) -> str:
    """A failed ASSERT_... of the program, on one line."""
    said = f": {failure.message}" if failure.message else ""
    return (
        f"{failure.site}: {failure.function} failed{said} (expected {failure.expected}, actual {failure.actual}, "
        f"at {failure.time_ns / 1e9:g} s)"
    )
