"""The core sections of a configuration: [plc] (profile, ST files, fault
policy, start mode, the real clock's spin), [retain], [[task]] and [outputs]
(safe values)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

from pydantic import Field, PlainValidator, model_validator

from ..durations import EXAMPLES as DURATION_EXAMPLES
from ..image import address as _address
from ..program.shipped import is_shipped_name
from ..st.ast import LocatedAddress
from ..st.profile import DEFAULT as _DEFAULT_PROFILE
from ..st.profile import PROFILES
from .errors import key_text
from .relations import Relations
from .section import Section
from .values import (
    SPIN_EXPECTED,
    Duration,
    LibraryPath,
    Model,
    StFile,
    Watchdog,
    area_name,
    choice,
    data_file,
    fail,
    got,
    identifier,
    int_range,
    is_ident,
    positive_duration,
    shipped_library,
    spin_duration,
)

DEFAULT_PAUSE_NS = 1_000_000
#: the least interval of a cyclic task. A scan is Python: some 50-200 us for
#: the inputs, the smallest program and the outputs, more with a bus, and the
#: kernel wakes a thread some 50-100 us late; a shorter period only overruns
#: (1 us gave 2.3 million overruns in 3 s and a busy core). CODESYS and
#: TwinCAT go down to 50-250 us, on a real-time kernel and native code.
MIN_INTERVAL_NS = 1_000_000
MIN_INTERVAL_TEXT = "1ms"
#: the real clock busy-waits this last stretch before each release: twice
#: the kernel's usual wake-up lateness, some 2 % of a core at a 10 ms task
#: (benchmarks/bench_spin.py: lateness against CPU for several settings)
DEFAULT_SPIN_NS = 200_000
DEFAULT_RETAIN_PERIOD_NS = 1_000_000_000
PRIORITY_MAX = 31
#: [plc] realtime_priority: Linux's SCHED_FIFO priorities are 1 .. 99
REALTIME_MAX = 99


@dataclass
class ProgramInstance:
    instance: str
    program: str
    key: str  # "task[0].programs[1]", for messages


@dataclass
class TaskConfig:
    name: str
    interval_ns: int | None  # None: freewheeling
    pause_ns: int  # freewheeling: the gap after a cycle
    priority: int  # 0 (highest) .. 31
    watchdog_ns: int | None  # None: no watchdog
    sensitivity: int  # overruns in a row before the watchdog fires
    programs: list[ProgramInstance]
    key: str  # "task[0]", for messages


@dataclass
class RetainConfig:
    file: Path
    period_ns: int


@dataclass
class SafeOutput:
    address: LocatedAddress
    value: bool | int | float  # bool for a bit address
    key: str  # 'outputs.safe."%QX0.0"'


def default_watchdog_ns(interval_ns: int | None) -> int:
    """Watchdog time when a task gives none: ten intervals but at least
    100 ms for a cyclic task; 1 s for a freewheeling one."""
    if interval_ns is None:
        return 1_000_000_000
    return max(10 * interval_ns, 100_000_000)


# ---------------------------------------------------------------- pass 1


class _Plc(Model):
    profile: Annotated[str, choice(PROFILES)] = Field(
        _DEFAULT_PROFILE.name, description=f"one of {', '.join(PROFILES)}"
    )
    programs: list[StFile] = Field(
        min_length=1, description='an array of ST files such as ["../st_programs/conveyor.st"]'
    )
    libraries: list[_Library] = Field(
        default_factory=list, description='an array of library folders such as ["../libs/oscat"]'
    )
    on_fault: Annotated[str, choice(("task", "plc"))] = Field("task", description="'task' or 'plc'")
    start: Annotated[str, choice(("warm", "cold"))] = Field("warm", description="'warm' or 'cold'")
    spin: Annotated[int, PlainValidator(spin_duration)] = Field(DEFAULT_SPIN_NS, description=SPIN_EXPECTED)
    realtime_priority: Annotated[int, int_range(0, REALTIME_MAX)] = Field(
        0, description=f"0 (off) or a SCHED_FIFO priority from 1 to {REALTIME_MAX}"
    )


class _Library(Model):
    path: LibraryPath | None = Field(None, description='the path of a library folder such as "../libs/oscat"')
    #: a library softplc ships, by name (program/shipped.py): "Tc2_System"
    shipped: Annotated[str, PlainValidator(shipped_library)] | None = Field(
        None, description='the name of a library softplc ships, such as "Tc2_System"'
    )
    namespace: Annotated[str, identifier("a namespace")] | None = Field(
        None, description='a namespace such as "OSCAT" (default: the folder\'s name)'
    )
    profile: Annotated[str, choice(PROFILES)] | None = Field(None, description=f"one of {', '.join(PROFILES)}")

    @model_validator(mode="before")
    @classmethod
    def _short_form(cls, value):
        if isinstance(value, str):
            # a bare name of a shipped library is that library; anything else a path
            return {"shipped": value} if is_shipped_name(value) else {"path": value}
        if not isinstance(value, dict):
            raise fail(
                'a folder such as "../libs/oscat", a library softplc ships such as "Tc2_System", '
                'or a table { path = "...", namespace = "OSCAT" }',
                value,
            )
        return value

    @model_validator(mode="after")
    def _one_of(self):
        if (self.path is None) == (self.shipped is None):
            raise fail('a path = "..." or the name of a library softplc ships', None)
        return self


class _Retain(Model):
    file: Annotated[Path, PlainValidator(data_file)] = Field(description='a file name such as "plant.retain"')
    period: Duration = Field(DEFAULT_RETAIN_PERIOD_NS, description=f"a duration such as {DURATION_EXAMPLES}")


class _ProgramEntry(Model):
    instance: Annotated[str, identifier("an instance name")] = Field(description='an instance name such as "Line2"')
    program: Annotated[str, identifier("a PROGRAM name")] = Field(description='a PROGRAM name such as "Conveyor"')

    @model_validator(mode="before")
    @classmethod
    def _short_form(cls, value):
        if isinstance(value, str):
            if not is_ident(value):
                raise fail("a PROGRAM name (an IEC identifier)", value)
            return {"instance": value, "program": value}
        if not isinstance(value, dict):
            raise fail(
                'a PROGRAM name such as "Conveyor" or a table { instance = "Line2", program = "Conveyor" }', value
            )
        return value


def task_interval(value) -> int:
    """A cyclic task's interval in ns: a duration of at least MIN_INTERVAL_NS."""
    ns = positive_duration(value)
    if ns < MIN_INTERVAL_NS:
        raise fail(
            f"an interval of at least {MIN_INTERVAL_TEXT}: a scan runs Python, a shorter period only overruns "
            "(freewheeling = true runs the cycles back to back)",
            value,
        )
    return ns


class _Task(Model):
    name: Annotated[str, identifier("a task name")] = Field(description='a task name such as "Fast"')
    interval: Annotated[int, PlainValidator(task_interval)] | None = Field(
        None, description=f"a duration such as {DURATION_EXAMPLES}"
    )
    freewheeling: bool = Field(False, description="true or false")
    pause: Duration | None = Field(None, description=f"a duration such as {DURATION_EXAMPLES}")
    priority: Annotated[int, int_range(0, PRIORITY_MAX)] = Field(1, description=f"an integer from 0 to {PRIORITY_MAX}")
    watchdog: Watchdog | None = Field(None, description="a duration, or false")
    sensitivity: Annotated[int, int_range(1)] = Field(1, description="an integer >= 1")
    programs: list[_ProgramEntry] = Field(
        min_length=1,
        description='an array of PROGRAM names or { instance = "...", program = "..." } tables, such as ["Conveyor"]',
    )


class _Outputs(Model):
    safe: dict[str, Any] = Field(
        default_factory=dict, description='a table of %Q address = value, such as { "%QX0.0" = false }'
    )


# ---------------------------------------------------------------- pass 2


def _check_tasks(tasks: list, ctx: Relations) -> None:
    names: dict = {}
    instances: dict = {}
    for i, task in enumerate(tasks):
        if not isinstance(task, dict):
            continue
        here = ("task", i)
        _check_timing(here, task, ctx)
        name = task.get("name")
        if is_ident(name):
            first = names.setdefault(name.upper(), i)
            if first != i:
                ctx.error(
                    here + ("name",), f"duplicate task name '{name}' (task[{first}] has it; names are case-insensitive)"
                )
        programs = task.get("programs")
        if not isinstance(programs, list):
            continue
        for j, entry in enumerate(programs):
            instance: object
            loc: tuple
            if isinstance(entry, str):
                instance, loc = entry, here + ("programs", j)
            elif isinstance(entry, dict):
                instance, loc = entry.get("instance"), here + ("programs", j, "instance")
            else:
                continue
            if not is_ident(instance):
                continue
            first = instances.setdefault(instance.upper(), loc)
            if first != loc:
                hint = (
                    f'; give one its own instance name: {{ instance = "{instance}2", program = "{entry}" }}'
                    if isinstance(entry, str)
                    else ""
                )
                ctx.error(
                    loc,
                    f"duplicate program instance '{instance}' (also at {key_text(first)}; "
                    f"instance names are unique across tasks, case-insensitive){hint}",
                )


def _check_timing(here: tuple, task: dict, ctx: Relations) -> None:
    if not isinstance(task.get("freewheeling", False), bool):
        return  # pass 1 reports it; whether the task is cyclic is unknown
    has_interval = "interval" in task
    freewheeling = task.get("freewheeling") is True
    if has_interval and freewheeling:
        ctx.error(here + ("freewheeling",), "a task has either an interval or freewheeling = true, not both")
    elif not has_interval and not freewheeling:
        ctx.error(here, 'expected interval = "10ms" (a cyclic task) or freewheeling = true (got neither)')
    if "pause" in task and has_interval and not freewheeling:
        ctx.error(here + ("pause",), "only for a freewheeling task (this one has an interval)")
    if "sensitivity" in task and task.get("watchdog") is False:
        ctx.error(here + ("sensitivity",), "only meaningful with a watchdog (this task has watchdog = false)")


class PlcSection(Section):
    key = "plc"
    model = _Plc
    description = 'a [plc] table with at least programs = ["file.st"]'

    def build(self, model: Any, ctx: Relations) -> Any:
        return model


class RetainSection(Section):
    key = "retain"
    model = _Retain
    description = "a [retain] table"

    def build(self, model: Any, ctx: Relations) -> RetainConfig | None:
        return RetainConfig(model.file, model.period) if model is not None else None


class TaskSection(Section):
    key = "task"
    many = True
    model = _Task
    description = "[[task]] tables"

    def check(self, value: Any, ctx: Relations) -> None:
        if isinstance(value, list):
            _check_tasks(value, ctx)

    def build(self, model: Any, ctx: Relations) -> list[TaskConfig]:
        tasks = []
        for i, t in enumerate(model):
            key = f"task[{i}]"
            interval = t.interval
            watchdog: int | None
            if t.watchdog is None:
                watchdog = default_watchdog_ns(interval)
            else:
                watchdog = None if t.watchdog is False else t.watchdog
            programs = [
                ProgramInstance(p.instance, p.program, f"{key}.programs[{j}]") for j, p in enumerate(t.programs)
            ]
            tasks.append(
                TaskConfig(
                    name=t.name,
                    interval_ns=interval,
                    pause_ns=t.pause if t.pause is not None else DEFAULT_PAUSE_NS,
                    priority=t.priority,
                    watchdog_ns=watchdog,
                    sensitivity=t.sensitivity,
                    programs=programs,
                    key=key,
                )
            )
        return tasks


class OutputsSection(Section):
    key = "outputs"
    model = _Outputs
    description = "an [outputs] table"

    def check(self, value: Any, ctx: Relations) -> None:
        if isinstance(value, dict) and isinstance(value.get("safe"), dict):
            self._safe(value["safe"], ctx)

    def _safe(self, safe: dict, ctx: Relations) -> None:
        seen: dict = {}
        outputs: list = ctx.state.setdefault(self.key, [])
        for text, value in safe.items():
            loc = ("outputs", "safe", text)
            addr = ctx.address(loc, text, "%QX0.0, %QW2")
            if addr is None:
                continue
            if addr.area != "Q":
                ctx.error(loc, f"expected a %Q output address (got {area_name(addr)})")
                continue
            if addr.table is not None:
                ctx.error(
                    loc,
                    "expected a single bit, byte, word, dword or lword (got a word table); list the words one by one",
                )
                continue
            if ctx.image_bits(loc, addr) is None:
                continue  # past the end of the image: the error says so
            ident = (addr.size if addr.size != "" else "X", addr.indices, addr.bit)
            if ident in seen:
                ctx.error(loc, f"the same address as {key_text(seen[ident])}")
                continue
            seen[ident] = loc
            checked = self._safe_value(loc, addr, value, ctx)
            if checked is not None:
                outputs.append(SafeOutput(addr, checked[0], key_text(loc)))

    @staticmethod
    def _safe_value(loc: tuple, addr: LocatedAddress, value, ctx: Relations) -> tuple | None:
        if addr.bit is not None or addr.size in ("", "X"):
            if isinstance(value, bool):
                return (value,)
            if isinstance(value, int) and value in (0, 1):
                return (bool(value),)
            ctx.error(loc, f"expected true or false (or 0 / 1) for a bit address (got {got(value)})")
            return None
        bits = _address.SIZE_BITS[addr.size]
        what = {8: "a byte", 16: "a word", 32: "a dword", 64: "an lword"}[bits]
        lo, hi = -(1 << (bits - 1)), (1 << bits) - 1
        if isinstance(value, int) and not isinstance(value, bool):
            if lo <= value <= hi:
                return (value,)
            ctx.error(loc, f"expected an integer from {lo} to {hi} for {what} address (got {value})")
            return None
        if isinstance(value, float) and bits >= 32:
            if bits == 32 and math.isfinite(value) and abs(value) > 3.4028234663852886e38:
                ctx.error(loc, f"expected a REAL (at most 3.4e38) for a dword address (got {value!r})")
                return None
            return (value,)
        if isinstance(value, float):
            ctx.error(
                loc,
                f"expected an integer for {what} address (got {value!r}; a REAL needs a "
                "%QD address, an LREAL a %QL address)",
            )
            return None
        kind = "an integer or a float" if bits >= 32 else "an integer"
        ctx.error(loc, f"expected {kind} for {what} address (got {got(value)})")
        return None

    def build(self, model: Any, ctx: Relations) -> list[SafeOutput]:
        """The safe outputs (parsed by check: their type depends on the address)."""
        return list(ctx.state.get(self.key, []))


def with_safe_defaults(configured: list[SafeOutput], ctx: Relations) -> list[SafeOutput]:
    """The safe outputs: those [outputs] safe configures, then the safe
    values the devices give the %Q addresses mapped to their objects
    (Relations.safe_defaults) where the file sets none of their bits."""
    taken = [ctx.image_bits((), out.address) for out in configured]
    out = list(configured)
    for loc, addr, value in ctx.safe_defaults:
        span = ctx.image_bits(loc, addr)
        if span is None or any(t is not None and span[0] <= t[1] and t[0] <= span[1] for t in taken):
            continue
        taken.append(span)
        out.append(SafeOutput(addr, value, key_text(loc)))
    return out


#: the core sections, in the order of the file's documentation
CORE_SECTIONS = (PlcSection(), RetainSection(), TaskSection(), OutputsSection())
