"""VCD traces (Value Change Dump, IEEE 1364), for GTKWave and other wave
viewers, written with pyvcd.

Each watched value is a variable under the scope `softplc`, nested by the
dots of its path (Main.motor.run is `run` in softplc.Main.motor; globals and
direct addresses such as %QW1 sit in softplc itself). Times are engine time
in nanoseconds (`$timescale 1 ns`), the same clock as the status line's t=
and the CSV's time_ms. The variables, by ST type:

  BOOL                          wire, 1 bit
  SINT .. LINT, TIME, LTIME     integer of the type's width (signed; TIME in
                                ms, LTIME in ns, as the CSV writes them)
  USINT .. ULINT, BYTE .. LWORD reg of the type's width (unsigned)
  REAL, LREAL                   real
  enumerations                  string: the enumerator's name (GTKWave shows
                                the text), or the number when a value names none
  STRING, arrays, structs       string (arrays and structs as compact JSON)
"""

from __future__ import annotations

import datetime as _dt
import re
from pathlib import Path
from typing import TextIO

from vcd import VCDWriter
from vcd.reader import TokenKind, tokenize

from .events import JOIN, VCD_SCOPE, marks_of, timed
from .series import Series, Trace, TraceFileError

SCOPE = "softplc"


def _vcd_var(info) -> tuple:
    """(var_type, size, to_value, initial value) for a SignalInfo."""
    if info.kind == "bool":
        return "wire", 1, int, 0
    if info.kind == "int":
        return ("integer" if info.signed else "reg"), info.bits or 64, int, 0
    if info.kind == "real":
        return "real", 64, float, 0.0
    return "string", 1, str, ""


class VcdTraceWriter:
    """An after_tick callback writing the watched values' changes as VCD;
    close() at the end of the run writes the final time stamp."""

    def __init__(self, stream: TextIO, watch, events=None) -> None:
        self.watch = watch
        self.writer = VCDWriter(
            stream,
            timescale="1 ns",
            date=_dt.datetime.now().astimezone().isoformat(timespec="seconds"),
            version="softplc run",
        )
        self.vars: list = []
        for info in watch.signals():
            scope, _, name = ("", "", info.path) if info.path.startswith("%") else info.path.rpartition(".")
            var_type, size, convert, init = _vcd_var(info)
            var = self.writer.register_var(f"{SCOPE}.{scope}" if scope else SCOPE, name, var_type, size=size, init=init)
            self.vars.append((var, convert))
        self.events = events if events is not None and events.sources else None
        self.event_vars = {
            name: self.writer.register_var(VCD_SCOPE, name, "string", size=1, init="")
            for name in (self.events.sources if self.events else ())
        }
        self._last_ns = 0

    def __call__(self, engine) -> None:
        now = engine.clock.now_ns()
        change = self.writer.change
        if self.events is not None:
            self._write_events(self.events.take(now))
        self._last_ns = now
        for (var, convert), value in zip(self.vars, self.watch.raw()):
            change(var, now, convert(value))

    def _write_events(self, events: list) -> None:
        """Each at its own time, or at the last time stamp written when it
        came in between (real time: a device's thread); the events of one
        simulator at one time stamp joined."""
        texts: dict = {}
        for t, name, text in events:
            at = max(t, self._last_ns)
            texts.setdefault((at, name), []).append(timed(t, text))
        for (at, name), parts in texts.items():  # in time order, as take() gave them
            self.writer.change(self.event_vars[name], at, JOIN.join(parts))
            self._last_ns = at

    def close(self, end_ns: int | None = None) -> None:
        self.writer.close(max(end_ns or 0, self._last_ns))


_PER_SECOND = {"s": 1, "ms": 1e3, "us": 1e6, "ns": 1e9, "ps": 1e12, "fs": 1e15}


def read_vcd(path: str | Path) -> Trace:
    """The variables of a VCD file as a Trace: a 1-bit wire or reg is a
    BOOL, an integer a signed number, any other vector an unsigned one, a
    real a REAL, a string an enumeration (levels in order of appearance).
    Names are the dotted scope path, without the top scope `softplc`. The
    series are stepped: a VCD has a value only where it changed. The
    strings under the top scope `sim` are the simulators' events: the
    Trace's marks (trace/events.py)."""
    path = Path(path)
    magnitude, per_second = 1, 1e9
    scopes: list = []
    by_id: dict = {}  # id code -> (Series, var type, size)
    series: list = []
    events: dict = {}  # id code -> simulator name (under VCD_SCOPE)
    marks: list = []
    t = 0.0
    try:
        with path.open("rb") as f:
            for token in tokenize(f):
                kind = token.kind
                if kind is TokenKind.TIMESCALE:
                    magnitude = int(token.timescale.magnitude)
                    per_second = _PER_SECOND[token.timescale.unit.value]
                elif kind is TokenKind.SCOPE:
                    scopes.append(token.scope.ident)
                elif kind is TokenKind.UPSCOPE:
                    scopes.pop()
                elif kind is TokenKind.VAR:
                    var = token.var
                    if var.id_code in by_id:  # the same signal under a second name
                        continue
                    if scopes == [VCD_SCOPE]:  # a simulator's events: marks
                        events[var.id_code] = var.reference
                        continue
                    parts = scopes[1:] if scopes[:1] == [SCOPE] else scopes
                    s = _var_series(".".join([*parts, var.reference]), var.type_.value, var.size)
                    by_id[var.id_code] = (s, var.type_.value, var.size)
                    series.append(s)
                elif kind is TokenKind.CHANGE_TIME:
                    t = token.time_change * magnitude / per_second
                else:
                    change = _change(token)
                    if change is not None and change[0] in events:
                        marks += marks_of(_unescaped(str(change[1])), events[change[0]])
                        continue
                    entry = by_id.get(change[0]) if change is not None else None
                    if change is not None and entry is not None:
                        entry[0].add(t, _value(entry, change[1]))
    except OSError as e:
        raise TraceFileError(f"{path}: cannot read: {e.strerror or e}") from None
    except Exception as e:  # pyvcd's VCDParseError and malformed values
        raise TraceFileError(f"{path}: not a VCD file softplc can read: {e}") from None
    for s in series:  # a VCD holds a value until it changes: to the last time stamp
        if s.values and s.times[-1] < t:
            s.add(t, s.values[-1])
        s.stepped = True
        if s.kind == "enum":
            s.levels = tuple(dict.fromkeys(s.values))
        s.finish()
    return Trace(series, str(path), marks)


def _unescaped(text: str) -> str:
    """A VCD string as written: pyvcd writes a blank (and other bytes a VCD
    value cannot hold) as \\xHH."""
    return re.sub(r"\\x([0-9a-fA-F]{2})", lambda m: chr(int(m.group(1), 16)), text)


def _change(token) -> tuple | None:
    """(id code, value) of a value change token, else None."""
    kind = token.kind
    if kind is TokenKind.CHANGE_SCALAR:
        return token.scalar_change.id_code, token.scalar_change.value
    if kind is TokenKind.CHANGE_VECTOR:
        return token.vector_change.id_code, token.vector_change.value
    if kind is TokenKind.CHANGE_REAL:
        return token.real_change.id_code, token.real_change.value
    if kind is TokenKind.CHANGE_STRING:
        return token.string_change.id_code, token.string_change.value
    return None


def _var_series(name: str, var_type: str, size: int) -> Series:
    if var_type == "real":
        return Series(name, "real", "REAL")
    if var_type == "string":
        return Series(name, "enum")
    if size == 1:
        return Series(name, "bool", "BOOL")
    return Series(name, "int")


def _value(entry: tuple, value):
    series, var_type, size = entry
    if series.kind == "bool":
        return 1 if value in ("1", 1) else 0
    if series.kind == "int":
        if isinstance(value, str):  # x or z bits: no number to draw
            return float("nan")
        if var_type == "integer" and value >= 1 << (size - 1):
            value -= 1 << size
        return value
    return value
