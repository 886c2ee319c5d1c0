"""Watching a running engine: watched variables, the status line and the
CSV trace of `softplc run`."""

from __future__ import annotations

import csv
import json
import os
import shutil
import threading
from dataclasses import dataclass
from typing import TextIO

from ..image.address import default_type, parse_address
from ..st import types as T
from ..st.valuejson import encode_value
from .places import PathError, Resolver
from .snapshot import Snapshot, SnapshotHub


@dataclass(frozen=True)
class SignalInfo:
    """What a watched value is, for the traces: kind is "bool", "int",
    "real", "enum" (levels: the enumerators in declared order) or "text"
    (strings, arrays and structs as JSON); type_name is its ST type; bits
    and signed describe an "int"."""

    path: str
    kind: str
    type_name: str
    bits: int = 0
    signed: bool = False
    levels: tuple = ()


def signal_info(path: str, ty) -> SignalInfo:
    """The SignalInfo of a value of ST type ty."""
    t = T.resolve(ty)
    if isinstance(t, T.EnumType):
        names = [t.spelled[k] for k, _v in sorted(t.values.items(), key=lambda kv: kv[1])]
        return SignalInfo(path, "enum", t.name, levels=tuple(names))
    if isinstance(t, T.SubrangeType):
        return SignalInfo(path, "int", t.name, t.base.bits, t.base.category == T.SIGNED)
    if isinstance(t, T.ElementaryType):
        if t.is_bool:
            return SignalInfo(path, "bool", t.name, 1)
        if t.is_real:
            return SignalInfo(path, "real", t.name, t.bits)
        if t.is_intlike or t.is_time:
            return SignalInfo(path, "int", t.name, t.bits, t.category == T.SIGNED or t.category == T.DURATION)
    return SignalInfo(path, "text", getattr(t, "name", type(t).__name__))


class Watch:
    """Watched variables ('Main.speed', 'G_total', 'motor.run') and direct
    addresses ('%QW1'). Paths are resolved again after a restart or an
    online change, which replace program instances (Engine.generation)."""

    def __init__(self, engine, paths: list) -> None:
        self.engine = engine
        self.paths = list(paths)
        #: the paths as declared, once a SnapshotHub watches them (status_text)
        self.canonical: list = []
        self._resolved_at = None
        self._cells: list = []
        self._resolver: Resolver | None = None  # for elements and parts, made at the first one
        for path in self.paths:  # fail early, with the path in the message
            self._resolve(path)

    def _resolve(self, path: str):
        if path.startswith("%"):
            addr = parse_address(path, self.engine.image.addressing)  # AddressError for a bad one
            return ("image", addr)
        try:
            return self.engine.variable(path)
        except KeyError:
            pass
        try:  # an element or a part of one: 'Line.parts[2].weight', 'grid[1, 2]'
            self._resolver = self._resolver.fresh() if self._resolver is not None else Resolver(self.engine)
            return ("place", self._resolver.place(path))
        except PathError as exc:
            if "[" in path:  # the resolver's message says which index or name is wrong
                raise KeyError(str(exc)) from None
        names = ", ".join(name for name, _info, _obj in self.engine.instances.values())
        raise KeyError(
            f"no variable '{path}' (write Instance.variable for a program's variable "
            f"-- instances: {names} -- or the name of a global variable)"
        ) from None

    def _current(self) -> list:
        if self._resolved_at != self.engine.generation:
            self._cells = [self._resolve(p) for p in self.paths]
            self._resolved_at = self.engine.generation
        return self._cells

    def signals(self) -> list:
        """A SignalInfo per watched path, in order."""
        out = []
        for path, cell in zip(self.paths, self._current()):
            out.append(signal_info(path, _type(cell)))
        return out

    def raw(self) -> list:
        """Values for the trace: numbers where possible (BOOL 0/1, TIME in
        its integer unit), an enumeration's value by name, JSON text for
        arrays and structs."""
        out = []
        for cell in self._current():
            if cell[0] == "image":
                value = self.engine.image.read(cell[1])
                out.append(int(value) if isinstance(value, bool) else value)
                continue
            if cell[0] == "place":
                value, ty = cell[1].get(), cell[1].type
            else:
                holder, attr, ty = cell
                value = getattr(holder, attr)
            if isinstance(value, bool):
                out.append(int(value))
            elif isinstance(value, (float, str)):
                out.append(value)
            elif isinstance(value, int):
                enum = T.resolve(ty)
                out.append(encode_value(enum, value) if isinstance(enum, T.EnumType) else value)
            else:
                out.append(json.dumps(encode_value(ty, value), separators=(",", ":")))
        return out

    def shown(self, snap: Snapshot | None = None) -> list:
        """(path, text) pairs for the status line, values as `exec` writes
        them, from snap (default: a snapshot taken now); "?" for a path the
        snapshot could not read."""
        if snap is None:
            hub = SnapshotHub(self.engine, attach=False)
            self.canonical = hub.watch("status", self.paths)
            snap = hub.capture()
        out = []
        for path, canonical in zip(self.paths, self.canonical or self.paths):
            if canonical in snap.values:
                out.append((path, json.dumps(snap.json(canonical), separators=(",", ":"), ensure_ascii=False)))
            else:
                out.append((path, "?"))
        return out


def _type(cell) -> T.Type:
    """The ST type of a watched cell: a direct address's by its size, a place's, a variable's."""
    if cell[0] == "image":
        return default_type(cell[1])
    if cell[0] == "place":
        return cell[1].type
    return cell[2]


class TraceWriter:
    """One CSV row per scan: engine time in ms, the tick number, the watched
    values; with column = (name, text_at), a last column of that name holding
    text_at(the scan's engine time in ns) (the simulators' events:
    trace/events.py's csv_column)."""

    def __init__(self, stream: TextIO, watch: Watch, column: tuple | None = None) -> None:
        self.stream = stream
        self.watch = watch
        self.column = column
        self.writer = csv.writer(stream)
        self.writer.writerow(["time_ms", "cycle"] + watch.paths + ([column[0]] if column else []))

    def __call__(self, engine) -> None:
        now = engine.clock.now_ns()
        row = [now / 1e6, engine.cycle] + self.watch.raw()
        if self.column is not None:
            row.append(self.column[1](now))
        self.writer.writerow(row)


def _us(ns: float) -> str:
    return f"{ns / 1e3:.0f}us" if ns < 10_000_000 else f"{ns / 1e6:.1f}ms"


def status_line(engine, watch: Watch | None = None) -> str:
    """The status line of the engine as it is now (a stopped engine, a test)."""
    hub = SnapshotHub(engine, attach=False)
    if watch is not None and watch.paths:
        watch.canonical = hub.watch("status", watch.paths)
    return status_text(hub.capture(), watch)


def status_text(snap: Snapshot, watch: Watch | None = None) -> str:
    """One line: time, ticks, per task cycle times / jitter / overruns, faults,
    the drivers' status, watched values; from a snapshot (engine/snapshot.py)."""
    parts = [f"t={snap.time_ns / 1e9:.2f}s", f"cycles={snap.cycle}"]
    for s in snap.tasks:
        state = " FAULT" if s.fault is not None else ""
        parts.append(
            f"{s.name}{state}: {_us(s.last_ns)}/{_us(s.mean_ns)}/{_us(s.max_ns)} "
            f"jitter {_us(s.jitter_max_ns)} overruns {s.overruns}"
        )
    parts.append(f"faults={len(snap.faults)}" + (" outputs SAFE" if snap.outputs_safe else ""))
    for driver in snap.drivers:  # a bus driver's word on its bus: "canopen: 1/1 up"
        if driver.message:
            parts.append(driver.message if driver.ok else f"{driver.message} (!)")
    if watch is not None and watch.paths:
        parts.append(" ".join(f"{p}={v}" for p, v in watch.shown(snap)))
    return " | ".join(parts)


def fit(line: str, columns: int) -> str:
    """line cut to fit a terminal row of `columns` characters, ending in
    '…' when cut. One column stays free: a line that fills the row makes some
    terminals wrap, and a wrapped line cannot be rewritten in place."""
    width = max(columns - 1, 1)
    return line if len(line) <= width else line[: width - 1] + "…"


def terminal_columns(stream: TextIO) -> int:
    """The width of the terminal behind stream ($COLUMNS first, 80 when unknown)."""
    try:
        return int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        pass
    try:
        return os.get_terminal_size(stream.fileno()).columns
    except (AttributeError, ValueError, OSError):  # no fileno, or not a terminal
        return shutil.get_terminal_size().columns


class StatusReporter:
    """Shows the status line from a thread of its own, so the scan thread
    never waits on a terminal: on a terminal one line rewritten in place 4
    times a second, cut to the terminal's width (read again at each refresh,
    so resizing the window works); otherwise (a log) the whole line every
    `every_s` seconds. The last line, at the end of the run, is whole."""

    def __init__(
        self,
        engine,
        stream: TextIO,
        watch: Watch | None,
        tty: bool,
        every_s: float = 5.0,
        columns: int | None = None,
        hub: SnapshotHub | None = None,
    ) -> None:
        self.engine = engine
        self.stream = stream
        self.watch = watch
        self.tty = tty
        self.columns = columns  # None: ask the terminal
        self.period = 0.25 if tty else every_s
        self.hub = hub if hub is not None else SnapshotHub(engine, period_s=self.period)
        if watch is not None and watch.paths:
            watch.canonical = self.hub.watch("status", watch.paths)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, name="softplc-status", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def _loop(self) -> None:
        while not self._stop.wait(self.period):
            self.show()

    def show(self, final: bool = False) -> None:
        try:
            line = status_text(self.hub.current(), self.watch)
        except Exception as exc:  # no scan yet, a watched value changing shape: skip this refresh
            line = f"(status unavailable: {exc})"
        if self.tty and not final:
            self.stream.write("\r\x1b[K" + fit(line, self.columns or terminal_columns(self.stream)))
        else:
            self.stream.write(("\r\x1b[K" if self.tty else "") + line + "\n")
        self.stream.flush()

    def stop(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout=2)
        self.show(final=True)
