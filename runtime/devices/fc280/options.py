"""The FC 280 simulator's own [[sim]] key: the drive's saved parameter values
when it is first switched on, by parameter number as the manual writes it,
in the parameter's unit (the conversion index of Tabelle 6.2 applies):

    [[sim]]
    type = "fc280"
    node_id = 5
    parameters = { "8-03" = 1.0, "8-04" = 5, "10-01" = 21, "3-10" = [25.0, 50.0] }

Options ([n]) are their numbers; an array parameter takes an array, from
element 0. Pass 2 checks each value against what the drive takes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Annotated

from pydantic import Field, PlainValidator

from ...config.relations import Relations
from ...config.section import SimOptions
from ...config.values import fail, got
from .parameters import Parameter, parameter, to_raw
from .store import READ_ONLY, Refused, check

Number = int | float


def _number(value: object) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _value(value):
    if _number(value) or (isinstance(value, list) and value and all(_number(v) for v in value)):
        return value
    raise fail("a number in the parameter's unit, or an array of numbers for an array parameter", value)


@dataclass
class Fc280Presets:
    """Raw values by parameter number (arrays as lists), for Fc280Simulator."""

    parameters: dict[str, int | list[int]] = field(default_factory=dict)


def raw_presets(number: str, value) -> tuple[Parameter, int | list[int]]:
    """The parameter and raw value(s) of one entry; ValueError with the reason."""
    try:
        p = parameter(number)
    except ValueError:
        raise ValueError(f'expected an FC 280 parameter number such as "8-03" (got {got(number)})') from None
    except KeyError:
        raise ValueError(f"parameter {number} is not one the FC 280 simulator knows") from None
    if p.number in READ_ONLY or p.type == "VisStr":
        raise ValueError(f"{p.number} {p.name} is a readout of the drive, not a setting")
    values = value if isinstance(value, list) else [value]
    if isinstance(value, list) != bool(p.elements):
        shape = f"an array of up to {p.elements} values" if p.elements else "one value, not an array"
        raise ValueError(f"{p.number} {p.name} takes {shape}")
    if len(values) > max(p.elements, 1):
        raise ValueError(f"{p.number} {p.name} has {p.elements} elements, not {len(values)}")
    raws = []
    for item in values:
        if not math.isfinite(item):
            raise ValueError(f"{p.number} {p.name} takes a finite number (got {got(item)})")
        if p.conversion is None and item != int(item):
            raise ValueError(f"{p.number} {p.name} takes an option number such as 1 (got {got(item)})")
        raw = to_raw(p, item)
        try:
            check(p, raw)
        except Refused as exc:
            unit = f" {p.unit}" if p.unit else ""
            raise ValueError(f"{p.number} {p.name}: {got(item)}{unit} is {exc.reason.value} ({exc})") from None
        raws.append(raw)
    return p, (raws if p.elements else raws[0])


class Fc280Options(SimOptions):
    parameters: dict[str, Annotated[Number | list[Number], PlainValidator(_value)]] = Field(
        default_factory=dict,
        description='a table of parameter = value in its unit, such as { "8-03" = 1.0, "10-01" = 21 }',
    )

    @classmethod
    def check(cls, here: tuple, sim: dict, ctx: Relations) -> None:
        parameters = sim.get("parameters")
        if not isinstance(parameters, dict):
            return  # pass 1 reports it
        for number, value in parameters.items():
            if not (_number(value) or isinstance(value, list)):
                continue  # pass 1 reports it
            try:
                raw_presets(number, value)
            except ValueError as exc:
                ctx.error(here + ("parameters", number), str(exc))

    def build(self) -> Fc280Presets:
        presets: dict[str, int | list[int]] = {}
        for number, value in self.parameters.items():
            p, raw = raw_presets(number, value)
            presets[p.number] = raw
        return Fc280Presets(presets)
