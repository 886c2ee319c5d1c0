"""What the simulated devices recorded, in the traces: the MPU2-S's breaker
closes (phase, voltage difference, slip, tripped), the EMCYs a simulated
CANopen device sent, each at its engine time (issue 33: a scenario's records
in --final-json and the trace).

A simulator that records says so by its events_since(t_ns): the events
after t_ns as (t_ns, text), in time order (sim/base.py). The trace files
carry them beside the watched values:

  CSV   a last column named EVENTS_COLUMN ("[[sim]]", as --final-json's key
        of the records: no ST name can be it), on the row of the first scan
        at or after each event: "gen 3.214500 s: breaker closed ..." (several
        joined by JOIN);
  VCD   a string variable per simulator under the top scope VCD_SCOPE
        ("sim", beside "softplc"): "3.214500 s: breaker closed ..." at the
        event's own time (or the last time stamp written, when the event
        came in between: real time);
  plots a mark per event (a dotted line through every panel, labelled).

read_csv and read_vcd give them back as the Trace's marks, and
`softplc plot TRACE` draws them.
"""

from __future__ import annotations

import re

EVENTS_COLUMN = "[[sim]]"
VCD_SCOPE = "sim"
JOIN = " | "
_TIMED = re.compile(r"^(?:(?P<name>\S+) )?(?P<t>\d+\.\d+) s: (?P<text>.*)$", re.S)


def records_events(sim) -> bool:
    """Whether a simulator records events (it overrides events_since)."""
    from ..sim.base import SimulatedDevice

    method = getattr(type(sim), "events_since", None)
    return method is not None and method is not SimulatedDevice.events_since


class SimEvents:
    """A cursor over the simulators' events: take() gives those since the
    last take(), as (t_ns, simulator name, text), in time order. One per
    trace writer."""

    def __init__(self, simulators: dict) -> None:
        self.sources = {name: sim for name, sim in simulators.items() if records_events(sim)}
        self._since = dict.fromkeys(self.sources, -1)

    def take(self, until_ns: int) -> list:
        """Those up to until_ns (the scan's time: a device's thread may have
        stamped one after it, which the next take() gives)."""
        found = []
        for name, sim in self.sources.items():
            new = [e for e in sim.events_since(self._since[name]) if e[0] <= until_ns]
            if new:
                self._since[name] = new[-1][0]
                found += [(t, name, text) for t, text in new]
        found.sort(key=lambda e: e[0])
        return found


def csv_column(simulators: dict) -> tuple | None:
    """The CSV trace's last column (engine/monitor.py TraceWriter's column):
    (EVENTS_COLUMN, the events up to a scan's time as text); None when no
    simulator records."""
    events = SimEvents(simulators)
    if not events.sources:
        return None
    return EVENTS_COLUMN, lambda now_ns: JOIN.join(timed(t, text, name) for t, name, text in events.take(now_ns))


def timed(t_ns: int, text: str, name: str | None = None) -> str:
    """An event as the trace files write it: "[name ]seconds s: text"."""
    return f"{name + ' ' if name else ''}{t_ns / 1e9:.6f} s: {text}"


def untimed(value: str, name: str | None = None) -> tuple[float, str] | None:
    """(seconds, "name: text") of a text timed() wrote; None for another text."""
    m = _TIMED.match(value)
    if m is None:
        return None
    who = m.group("name") or name
    return float(m.group("t")), f"{who}: {m.group('text')}" if who else m.group("text")


def marks_of(text: str, name: str | None = None) -> list:
    """The marks of one text of the trace files (events joined by JOIN)."""
    marks = (untimed(part, name) for part in text.split(JOIN)) if text else ()
    return [m for m in marks if m is not None]


def column_marks(texts: list) -> list:
    """The marks of a CSV trace's EVENTS_COLUMN (one text per row)."""
    return [mark for text in texts for mark in marks_of(text)]
