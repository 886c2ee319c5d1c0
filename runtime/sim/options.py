"""[[sim]] keys many simulated devices share: ``registers = { "682" = 2 }``,
initial values of the device's registers (decimal register numbers)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Annotated

from pydantic import Field

from ..config.relations import Relations
from ..config.section import SimOptions
from ..config.values import U16_MAX, got, int_range


@dataclass
class Registers:
    """Initial register values of a simulated device: number -> value."""

    registers: dict[int, int] = field(default_factory=dict)


def _register_number(key) -> bool:
    return isinstance(key, str) and key.isascii() and key.isdigit() and int(key) <= U16_MAX


class RegisterPresets(SimOptions):
    registers: dict[str, Annotated[int, int_range(0, U16_MAX)]] = Field(
        default_factory=dict, description='a table of register = value, such as { "682" = 2 }'
    )

    @classmethod
    def check(cls, here: tuple, sim: dict, ctx: Relations) -> None:
        registers = sim.get("registers")
        if isinstance(registers, dict):
            for number in registers:
                if not _register_number(number):
                    ctx.error(
                        here + ("registers", number),
                        f'expected a register number from 0 to {U16_MAX} in decimal, such as "682" (got {got(number)})',
                    )

    def build(self) -> Registers:
        return Registers({int(number): value for number, value in self.registers.items()})
