"""The trace of watched values: one row per scan, (engine time, values), and
the rows around a moment formatted for an assertion message."""

from __future__ import annotations

from dataclasses import dataclass
from datetime import timedelta
from typing import Any

from ..durations import format_duration_ns


@dataclass(frozen=True)
class Row:
    """One scan of the trace: the engine time (ns since start), the scan
    number and the watched values, by path as watched."""

    time_ns: int
    cycle: int
    values: dict

    @property
    def time(self) -> timedelta:
        return timedelta(microseconds=self.time_ns / 1000)

    def __getitem__(self, path: str) -> Any:
        return self.values[path]


class Trace:
    """Rows of watched values; ``plc.trace``. A row is recorded after each
    scan in which a watched value changed (and the first), so a long run
    stays small; ``every_scan=True`` records every scan."""

    def __init__(self, limit: int = 100_000) -> None:
        self.paths: list[str] = []
        self.rows: list[Row] = []
        self.limit = limit
        self.every_scan = False

    def __len__(self) -> int:
        return len(self.rows)

    def __iter__(self):
        return iter(self.rows)

    def __getitem__(self, i):
        return self.rows[i]

    def clear(self) -> None:
        self.rows.clear()

    def record(self, time_ns: int, cycle: int, values: dict) -> None:
        if not self.every_scan and self.rows and self.rows[-1].values == values:
            return
        self.rows.append(Row(time_ns, cycle, values))
        if len(self.rows) > self.limit:
            del self.rows[: len(self.rows) - self.limit]

    def column(self, path: str) -> list:
        """(time_ns, value) of every row that has path."""
        return [(row.time_ns, row.values[path]) for row in self.rows if path in row.values]

    def changes(self, path: str) -> list:
        """(time_ns, value) each time path took a new value."""
        out: list = []
        for t, v in self.column(path):
            if not out or out[-1][1] != v:
                out.append((t, v))
        return out

    def values(self, path: str) -> list:
        """The successive different values of path: ['Stopped', 'Forward', ...]."""
        return [v for _t, v in self.changes(path)]

    def around(self, time_ns: int | None = None, rows: int = 8) -> str:
        """The rows before and after time_ns (default: the last ones) as a table."""
        if not self.rows:
            return "(no trace: watch some paths with plc.watch(...))" if not self.paths else "(trace empty)"
        if time_ns is None:
            chosen = self.rows[-2 * rows :]
        else:
            at = next((i for i, r in enumerate(self.rows) if r.time_ns >= time_ns), len(self.rows))
            chosen = self.rows[max(0, at - rows) : at + rows]
        return format_rows(self.paths, chosen)


def format_rows(paths: list, rows: list) -> str:
    head = ["time", *paths]
    body = [[_time(r.time_ns), *(_text(r.values.get(p, "")) for p in paths)] for r in rows]
    widths = [max(len(line[i]) for line in [head, *body]) for i in range(len(head))]
    lines = ["  ".join(cell.ljust(w) for cell, w in zip(line, widths)).rstrip() for line in [head, *body]]
    return "\n".join(lines)


def _time(ns: int) -> str:
    return f"{ns / 1e9:.3f}s"


def _text(v: Any) -> str:
    if isinstance(v, timedelta):
        ns = (v.days * 86_400 + v.seconds) * 1_000_000_000 + v.microseconds * 1000
        return "T#" + format_duration_ns(ns) if ns >= 0 else "-T#" + format_duration_ns(-ns)
    if isinstance(v, float):
        return f"{v:.6g}"
    return str(v)
