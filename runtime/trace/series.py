"""Traces held in memory: a Series of samples per signal, in engine time.

A Series keeps only the samples where its value changed and, before each
change, the last sample of the value held: steps and lines drawn through
them are the same as through every scan's sample, in a fraction of the
memory (a BOOL that toggles twice in an hour is four samples, not 360 000).
"""

from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass, field
from pathlib import Path

from .events import EVENTS_COLUMN, column_marks

KINDS = ("bool", "int", "real", "enum", "text")
DIGITAL = ("bool", "enum")  # drawn as steps, in lanes of their own
ANALOGUE = ("int", "real")  # drawn as lines, one axis per unit


class TraceFileError(ValueError):
    """A trace file that cannot be read; the message names the file (and the line)."""


@dataclass
class Series:
    """One signal: kind is one of KINDS; levels, for an enum, the
    enumerators in declared order (or in order of appearance when the file
    does not say); times in seconds of engine time. stepped: the samples
    are only the changes (a VCD), so a REAL is drawn as steps, not lines."""

    name: str
    kind: str
    type_name: str = ""
    levels: tuple = ()
    stepped: bool = False
    times: list = field(default_factory=list)
    values: list = field(default_factory=list)
    _held_at: float | None = None  # the last sample, when it repeated the value before it

    def add(self, t: float, value) -> None:
        if self.values and _same(self.values[-1], value):
            self._held_at = t
            return
        if self._held_at is not None:
            self.times.append(self._held_at)
            self.values.append(self.values[-1])
            self._held_at = None
        self.times.append(t)
        self.values.append(value)

    def finish(self) -> None:
        """Keep the last sample (the value held to the end of the trace)."""
        if self._held_at is not None:
            self.times.append(self._held_at)
            self.values.append(self.values[-1])
            self._held_at = None


def _same(a, b) -> bool:
    return a == b or (isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b))


@dataclass
class Trace:
    series: list
    source: str = ""
    #: (seconds, text): what the simulated devices recorded (trace/events.py)
    marks: list = field(default_factory=list)

    def names(self) -> list:
        return [s.name for s in self.series]

    def select(self, names: list) -> Trace:
        """Only the named signals, in the order given; KeyError names an unknown one."""
        by_name = {s.name: s for s in self.series}
        missing = [n for n in names if n not in by_name]
        if missing:
            raise KeyError(
                f"no signal {', '.join(missing)} in {self.source or 'the trace'} (it has: {', '.join(by_name)})"
            )
        return Trace([by_name[n] for n in names], self.source, self.marks)


class Recorder:
    """An after_tick callback: samples the watched values every scan into a
    Trace, for a plot at the end of the run; with events (a SimEvents), the
    simulators' events as its marks."""

    def __init__(self, watch, events=None) -> None:
        self.watch = watch
        self.series = [Series(i.path, i.kind, i.type_name, i.levels) for i in watch.signals()]
        self.events = events if events is not None and events.sources else None
        self.marks: list = []

    def __call__(self, engine) -> None:
        t = engine.clock.now_ns() / 1e9
        for series, value in zip(self.series, self.watch.raw()):
            series.add(t, value)
        if self.events is not None:
            self.marks += [(at / 1e9, f"{name}: {text}") for at, name, text in self.events.take(engine.clock.now_ns())]

    def trace(self, source: str = "") -> Trace:
        for series in self.series:
            series.finish()
        return Trace(self.series, source, self.marks)


_NAME = re.compile(r"^[A-Za-z_][A-Za-z0-9_]*$")


def read_csv(path: str | Path) -> Trace:
    """A CSV trace of `softplc run`: time_ms, cycle, then a column per
    watched value. Its kinds are guessed from the values: only 0 and 1 is a
    BOOL, whole numbers an integer, other numbers a REAL, names an
    enumeration (levels in order of appearance), anything else text. A
    last column EVENTS_COLUMN holds the simulators' events: the marks."""
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        raise TraceFileError(f"{path}: cannot read: {e.strerror or e}") from None
    except UnicodeDecodeError:
        raise TraceFileError(f"{path}: not a CSV trace (not UTF-8 text)") from None
    if not rows or rows[0][:2] != ["time_ms", "cycle"]:
        raise TraceFileError(f"{path}: not a CSV trace of softplc run (the first line must start time_ms,cycle)")
    names = rows[0][2:]
    events = names[-1] == EVENTS_COLUMN if names else False
    names = names[:-1] if events else names
    times: list = []
    columns: list = [[] for _ in names]
    for lineno, row in enumerate(rows[1:], start=2):
        if len(row) != len(names) + 2 + events:
            raise TraceFileError(f"{path}:{lineno}: {len(row)} values, the header names {len(names) + 2 + events}")
        try:
            times.append(float(row[0]) / 1e3)
        except ValueError:
            raise TraceFileError(f"{path}:{lineno}: time_ms {row[0]!r} is not a number") from None
        for column, text in zip(columns, row[2:]):
            column.append(text)
    series = [_column_series(name, column, times) for name, column in zip(names, columns)]
    return Trace(series, str(path), column_marks([row[-1] for row in rows[1:]]) if events else [])


def _column_series(name: str, texts: list, times: list) -> Series:
    numbers = []
    for text in texts:
        try:
            numbers.append(float(text))
        except ValueError:
            break
    if len(numbers) == len(texts):
        if all(n in (0.0, 1.0) for n in numbers):
            series = Series(name, "bool", "BOOL")
            values: list = [int(n) for n in numbers]
        elif all(n.is_integer() and "." not in t for n, t in zip(numbers, texts)):
            series, values = Series(name, "int"), [int(t) for t in texts]
        else:
            series, values = Series(name, "real"), numbers
    elif all(_NAME.match(t) for t in texts):
        series = Series(name, "enum", levels=tuple(dict.fromkeys(texts)))
        values = texts
    else:
        series, values = Series(name, "text"), texts
    for t, v in zip(times, values):
        series.add(t, v)
    series.finish()
    return series
