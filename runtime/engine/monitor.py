"""Watching a running engine: watched variables, the status line and the
CSV trace of `softplc run`."""

from __future__ import annotations

import csv
import json
import threading
from typing import TextIO

from ..image.address import parse_address
from ..st.valuejson import encode_value


class Watch:
    """Watched variables ('Main.speed', 'G_total', 'motor.run') and direct
    addresses ('%QW1'). Paths are resolved again after a restart, because a
    restart replaces the faulted tasks' program instances."""

    def __init__(self, engine, paths: list) -> None:
        self.engine = engine
        self.paths = list(paths)
        self._resolved_at = None
        self._cells: list = []
        for path in self.paths:  # fail early, with the path in the message
            self._resolve(path)

    def _resolve(self, path: str):
        if path.startswith("%"):
            addr = parse_address(path, self.engine.image.addressing)  # AddressError for a bad one
            return ("image", addr)
        try:
            return self.engine.variable(path)
        except KeyError:
            names = ", ".join(name for name, _info, _obj in self.engine.instances.values())
            raise KeyError(
                f"no variable '{path}' (write Instance.variable for a program's variable "
                f"-- instances: {names} -- or the name of a global variable)"
            ) from None

    def _current(self) -> list:
        if self._resolved_at != self.engine.restarts:
            self._cells = [self._resolve(p) for p in self.paths]
            self._resolved_at = self.engine.restarts
        return self._cells

    def raw(self) -> list:
        """Values for the trace: numbers where possible (BOOL 0/1, TIME in
        its integer unit), JSON text for arrays and structs."""
        out = []
        for cell in self._current():
            if cell[0] == "image":
                value = self.engine.image.read(cell[1])
                out.append(int(value) if isinstance(value, bool) else value)
                continue
            holder, attr, ty = cell
            value = getattr(holder, attr)
            if isinstance(value, bool):
                out.append(int(value))
            elif isinstance(value, (int, float, str)):
                out.append(value)
            else:
                out.append(json.dumps(encode_value(ty, value), separators=(",", ":")))
        return out

    def shown(self) -> list:
        """(path, text) pairs for the status line, values as `exec` writes them."""
        out = []
        for path, cell in zip(self.paths, self._current()):
            if cell[0] == "image":
                value = self.engine.image.read(cell[1])
            else:
                holder, attr, ty = cell
                value = encode_value(ty, getattr(holder, attr))
            out.append((path, json.dumps(value, separators=(",", ":"), ensure_ascii=False)))
        return out


class TraceWriter:
    """One CSV row per scan: engine time in ms, the tick number, the watched values."""

    def __init__(self, stream: TextIO, watch: Watch) -> None:
        self.stream = stream
        self.watch = watch
        self.writer = csv.writer(stream)
        self.writer.writerow(["time_ms", "cycle"] + watch.paths)

    def __call__(self, engine) -> None:
        self.writer.writerow([engine.clock.now_ns() / 1e6, engine.cycle] + self.watch.raw())


def _us(ns: float) -> str:
    return f"{ns / 1e3:.0f}us" if ns < 10_000_000 else f"{ns / 1e6:.1f}ms"


def status_line(engine, watch: Watch | None = None) -> str:
    """One line: time, ticks, per task cycle times / jitter / overruns, faults,
    the drivers' status, watched values."""
    parts = [f"t={engine.clock.now_ns() / 1e9:.2f}s", f"cycles={engine.cycle}"]
    for task in engine.tasks:
        s = task.stats
        state = " FAULT" if task.fault is not None else ""
        parts.append(
            f"{task.name}{state}: {_us(s.last_ns)}/{_us(s.mean_ns)}/{_us(s.max_ns)} "
            f"jitter {_us(s.jitter_max_ns)} overruns {s.overruns}"
        )
    parts.append(f"faults={len(engine.faults)}" + (" outputs SAFE" if engine.outputs_safe else ""))
    for driver in engine.drivers:  # a bus driver's word on its bus: "canopen: 1/1 up"
        status = driver.status()
        if status.message:
            parts.append(status.message if status.ok else f"{status.message} (!)")
    if watch is not None and watch.paths:
        parts.append(" ".join(f"{p}={v}" for p, v in watch.shown()))
    return " | ".join(parts)


class StatusReporter:
    """Shows the status line from a thread of its own, so the scan thread
    never waits on a terminal: rewritten in place 4 times a second on a
    terminal, a plain line every `every_s` seconds otherwise (logs)."""

    def __init__(self, engine, stream: TextIO, watch: Watch | None, tty: bool, every_s: float = 5.0) -> None:
        self.engine = engine
        self.stream = stream
        self.watch = watch
        self.tty = tty
        self.period = 0.25 if tty else every_s
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, name="softplc-status", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def _loop(self) -> None:
        while not self._stop.wait(self.period):
            self.show()

    def show(self, final: bool = False) -> None:
        try:
            line = status_line(self.engine, self.watch)
        except Exception as exc:  # a watched value changing shape mid-read: skip this refresh
            line = f"(status unavailable: {exc})"
        if self.tty and not final:
            self.stream.write("\r\x1b[K" + line)
        else:
            self.stream.write(("\r\x1b[K" if self.tty else "") + line + "\n")
        self.stream.flush()

    def stop(self) -> None:
        self._stop.set()
        if self._thread.is_alive():
            self._thread.join(timeout=2)
        self.show(final=True)
