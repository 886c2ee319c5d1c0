"""The simulated LTMR's own [[sim]] keys: the registers every register
device takes (sim/options.py), and the motor's load.

    [[sim]]
    type = "ltmr"
    node_id = 40
    load = 115.0              # % of FLC while running (default 80): a thermal trip in a minute or so
    registers = { "682" = 2 }

The load is the motor current the model draws while running, in percent of
the full-load current (FLC, registers 652/653); during the start the
inrush (600 %) or the load, whichever is higher. The `load` fault of
[[sim]] faults changes it for a while; this is the value a run starts with.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated

from pydantic import Field

from ...config.values import real_range
from ...sim.options import RegisterPresets, Registers
from .defaults import DEFAULT_LOAD_PERCENT

MAX_LOAD_PERCENT = 1000.0  # a locked rotor draws some 600 % FLC; beyond 1000 % is no motor


@dataclass
class LtmrPresets(Registers):
    load_percent: float = DEFAULT_LOAD_PERCENT


class LtmrSimOptions(RegisterPresets):
    load: Annotated[float, real_range(0.0, MAX_LOAD_PERCENT, "a load in % of FLC")] = Field(
        DEFAULT_LOAD_PERCENT, description="the motor's current while running, in % of FLC, such as 80.0"
    )

    def build(self) -> LtmrPresets:
        return LtmrPresets(super().build().registers, load_percent=float(self.load))
