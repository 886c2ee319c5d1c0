"""Runtime library, variable-length arrays: what an ``ARRAY[*]`` parameter
holds (IEC 61131-3 ed.3 6.5.4; CODESYS "Array with variable length").

The caller passes its array by reference with the bounds it was declared
with, so the callee indexes it with the caller's indices and
LOWER_BOUND/UPPER_BOUND read them. Whole-array assignment and copies go
through ``_assign``/``_copy`` as for any aggregate (values.py).
"""

from __future__ import annotations

from ..faults import out_of_bounds
from ..values import assign_into, copy_value


class VarArray:
    """An array passed to an ARRAY[*] parameter: its storage (nested lists,
    row-major) and the bounds of each dimension."""

    __slots__ = ("data", "bounds")

    def __init__(self, data: list, bounds: tuple) -> None:
        self.data = data
        self.bounds = bounds

    def __iter__(self):
        return iter(self.data)

    def __len__(self) -> int:
        return len(self.data)

    def __getitem__(self, i: int):
        return self.data[i]

    def __setitem__(self, i: int, value) -> None:  # passed on to a VAR_IN_OUT of fixed bounds
        self.data[i] = value

    def _assign(self, src) -> None:
        assign_into(self.data, src.data if isinstance(src, VarArray) else src)

    def _copy(self) -> list:
        return copy_value(self.data)


def position(i: int, bounds: tuple) -> int:
    """The list position of index i in a dimension of bounds (lo, hi); out
    of the bounds: the array-bounds fault of a fixed array."""
    lo, hi = bounds
    if lo <= i <= hi:
        return i - lo
    return out_of_bounds(i, lo, hi)


def passed(value, bounds: tuple) -> VarArray:
    """What an ARRAY[*] parameter receives: a fixed array with its declared
    bounds, or the VarArray an ARRAY[*] parameter of the caller holds."""
    if isinstance(value, VarArray):
        return value
    return VarArray(value, bounds)
