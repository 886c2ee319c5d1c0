"""A scenario's data in the configuration: initial values and writes at
given engine times, so that a test engineer varies a run from the file
(or `softplc run --set PATH=VALUE`) without touching the ST.

    [init]                               # at the first scan, over the initial
    Main.Setpoint = 40                   # and retained values; a dotted key is
    "Line.parts[2].weight" = 1.5         # a path, brackets need quotes
    Motor.Auto = false

    [[schedule]]                         # at 5 s of engine time (from the first
    at = "5s"                            # scan), at the start of the scan then
    set = "Main.Setpoint"
    value = 60

A value is what the testing API's plc.write takes for the path's ST type
(an int, a float, true/false, an ST literal such as "T#2s" or an
enumerator's name, a list for an ARRAY, a table for a STRUCT). The paths
and values are checked once the program is compiled (engine/scenario.py):
an error names the file and the key, as every other error of the file.
"""

from __future__ import annotations

import dataclasses
import datetime
import tomllib
from dataclasses import dataclass
from typing import Any

from pydantic import ConfigDict, Field

from .errors import key_text
from .relations import Relations
from .section import Section
from .values import Duration, Model, cut, got


@dataclass(frozen=True)
class ScenarioWrite:
    """One write of a scenario: key says where it was given, for messages
    ('init."Main.Setpoint"', 'schedule[0]', '--set Main.Setpoint')."""

    key: str
    path: str
    value: Any
    at_ns: int = 0  # engine time from the first scan; 0: at the first scan ([init], --set)
    value_key: str = ""  # where the value was given, when not at key ([[schedule]]'s value)

    @property
    def where_value(self) -> str:
        return self.value_key or self.key


class _Init(Model):
    """Any path = value (pass 2 reads the keys)."""

    model_config = ConfigDict(extra="allow", strict=True)


class _Scheduled(Model):
    at: Duration = Field(description='engine time from the first scan, such as "5s"')
    set: str = Field(description='the variable\'s path, such as "Main.Setpoint"')
    value: Any = Field(description="the value, as [init] takes it")


def _refused(value: Any) -> str | None:
    """Why a TOML value cannot be an ST value, or None. TOML's dates and
    times are Python's; ST's are literals."""
    if isinstance(value, (datetime.date, datetime.time)):  # datetime is a date
        return f'expected an ST literal string such as "D#2024-01-02" or "TOD#12:00:00" (got {value})'
    if isinstance(value, list):
        return next((why for why in map(_refused, value) if why), None)
    if isinstance(value, dict):
        return next((why for why in map(_refused, value.values()) if why), None)
    return None


def _same_variable(path: str) -> str:
    """The one key of the paths that name the same variable: names are
    case-insensitive, and blanks around dots and indices mean nothing."""
    return "".join(path.split()).upper()


def _flattened(table: dict, prefix: str = "") -> list:
    """(path, value) of each leaf: a dotted key (Main.Setpoint = 40) is a
    table in TOML, and a path here; a STRUCT's table is its fields, each a
    path of its own (the same writes)."""
    out = []
    for key, value in table.items():
        path = f"{prefix}.{key}" if prefix else str(key)
        if isinstance(value, dict) and value:
            out.extend(_flattened(value, path))
        else:
            out.append((path, value))
    return out


class InitSection(Section):
    key = "init"
    model = _Init
    description = "an [init] table"

    def check(self, value: Any, ctx: Relations) -> None:
        if not isinstance(value, dict):
            return
        writes = ctx.state.setdefault(self.key, [])
        seen: dict = {}
        for path, leaf in _flattened(value):
            loc = ("init", path)
            why = _refused(leaf)
            same = seen.setdefault(_same_variable(path), loc)
            if why is not None:
                ctx.error(loc, why)
            elif same != loc:
                ctx.error(loc, f"the same variable as {key_text(same)}")
            else:
                writes.append(ScenarioWrite(key_text(loc), path, leaf))

    def build(self, model: Any, ctx: Relations) -> list:
        return list(ctx.state.get(self.key, []))


class ScheduleSection(Section):
    key = "schedule"
    many = True
    model = _Scheduled
    description = "[[schedule]] tables"

    def check(self, value: Any, ctx: Relations) -> None:
        if not isinstance(value, list):
            return
        for i, table in enumerate(value):
            if not isinstance(table, dict):
                continue
            path = table.get("set")
            if isinstance(path, str) and not path.strip():
                ctx.error(
                    ("schedule", i, "set"), f'expected a variable\'s path such as "Main.Setpoint" (got {got(path)})'
                )
            if "value" in table:
                why = _refused(table["value"])
                if why is not None:
                    ctx.error(("schedule", i, "value"), why)

    def build(self, model: Any, ctx: Relations) -> list:
        writes = [
            ScenarioWrite(f"schedule[{i}].set", entry.set.strip(), entry.value, entry.at, f"schedule[{i}].value")
            for i, entry in enumerate(model)
        ]
        return sorted(writes, key=lambda w: w.at_ns)  # stable: the file's order at the same time


SCENARIO_SECTIONS = (InitSection(), ScheduleSection())


def cli_value(text: str) -> Any:
    """--set's VALUE as TOML reads it (40, 1.5, false, [1, 2], {x = 1},
    "text"), else the text itself (an ST literal: T#2s, Running, 16#FF)."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except (tomllib.TOMLDecodeError, RecursionError, ValueError):
        return text


def with_sets(config: Any, sets: list) -> Any:
    """config (a PlcConfig) with --set's PATH=VALUE items over its [init]
    (an entry of the same path replaced). ValueError names an item that
    is no PATH=VALUE."""
    added = []
    for item in sets:
        path, eq, text = item.partition("=")
        if not eq or not path.strip():
            raise ValueError(f"{got(item)}: expected VAR=VALUE, such as Main.Setpoint=40")
        path = path.strip()
        added.append(ScenarioWrite(f"--set {cut(path)}", path, cli_value(text.strip())))
    given = {_same_variable(w.path) for w in added}
    kept = [w for w in config.init if _same_variable(w.path) not in given]
    return dataclasses.replace(config, init=kept + added)
