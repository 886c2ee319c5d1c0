"""[[sim]] faults = [...]: faults a simulated device gets at given times of
the run, so that a plant misbehaves on schedule, the same way every run.

    [[sim]]
    type = "fc280"
    node_id = 20
    faults = [
        { at = "20s", fault = "over_current" },          # a trip
        { at = "40s", fault = "unplug", for = "2s" },     # the cable out for 2 s
        { at = "60s", fault = "warning", value = 0x40, for = "5s" },
    ]

`at` is engine time (the status line's t=, from the start of the run);
`for` undoes a lasting fault that long after; `value` is the fault's
argument where it takes one. Which faults there are, and which take a
value or last, is the device's to say (Device.sim_faults); the engine fires
them (engine/sim_schedule.py) through the simulator's inject().
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import Field, PlainValidator

from ..plugin.seams import Device
from .relations import Relations
from .values import DURATION_EXAMPLES, Duration, Model, at_most_a_day, duration_ns, fail, identifier


@dataclass(frozen=True)
class FaultEvent:
    at_ns: int  # engine time
    fault: str  # one of the device's SimFault names, lower case
    value: int | float | None = None
    for_ns: int | None = None  # a lasting fault: undone after this long


def _instant(value) -> int:
    """A duration >= 0 in ns."""
    ns = duration_ns(value)
    if ns is None or ns < 0:
        raise fail(f"a time of the run such as {DURATION_EXAMPLES}", value)
    return at_most_a_day(ns, value)


def _value(value):
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return value
    raise fail("a number", value)


class FaultEntry(Model):
    at: Annotated[int, PlainValidator(_instant)] = Field(description="engine time, such as 20s")
    fault: Annotated[str, identifier("a fault name")] = Field(description="a fault of the device")
    value: Annotated[Any, PlainValidator(_value)] = Field(None, description="the fault's argument, a number")
    for_: Duration | None = Field(None, alias="for", description="a lasting fault: how long, such as 2s")


Faults = list[FaultEntry]


def check_faults(here: tuple, sim: dict, device: Device, ctx: Relations) -> None:
    """Pass 2: each entry names a fault of the device, with a value where it
    takes one and `for` only where it lasts."""
    entries = sim.get("faults")
    if not isinstance(entries, list):
        return
    offered = {f.name: f for f in device.sim_faults}
    names = ", ".join(offered) or "none"
    for i, entry in enumerate(entries):
        if not isinstance(entry, dict) or not isinstance(entry.get("fault"), str):
            continue  # pass 1 reports it
        at = here + ("faults", i)
        fault = offered.get(entry["fault"].lower())
        if fault is None:
            ctx.error(at + ("fault",), f"{sim['type']} has no fault {entry['fault']!r}; it has {names}")
            continue
        if fault.value and "value" not in entry:
            ctx.error(at, f"fault {fault.name} needs a value: {fault.value}")
        if not fault.value and "value" in entry:
            ctx.error(at + ("value",), f"fault {fault.name} takes no value")
        if not fault.lasting and "for" in entry:
            ctx.error(at + ("for",), f"fault {fault.name} does not last: it takes no 'for'")


def fault_events(entries: Faults | None) -> tuple[FaultEvent, ...]:
    return tuple(FaultEvent(e.at, e.fault.lower(), e.value, e.for_) for e in sorted(entries or (), key=lambda e: e.at))
