"""The string functions of CODESYS's Standard library under their formal
parameter names (CODESYS online help, Standard library, String functions:
``CONCAT(STR1, STR2)``, ``LEFT(STR, SIZE)``, ``MID(STR, LEN, POS)`` ...),
so that a call with named arguments compiles. They are softplc's IEC
string functions (fblocks/iec/functions.py) under other names; a program
that chooses the library gets these in their place."""

from __future__ import annotations

from dataclasses import replace

from softplc.fblocks.iec.functions import STANDARD_FUNCTIONS, StdFunc

#: function -> its parameters' names, in order
_NAMES = {
    "CONCAT": ("STR1", "STR2"),
    "DELETE": ("STR", "LEN", "POS"),
    "FIND": ("STR1", "STR2"),
    "INSERT": ("STR1", "STR2", "POS"),
    "LEFT": ("STR", "SIZE"),
    "LEN": ("STR",),
    "MID": ("STR", "LEN", "POS"),
    "REPLACE": ("STR1", "STR2", "L", "P"),
    "RIGHT": ("STR", "SIZE"),
}


def _renamed(name: str, names: tuple) -> StdFunc:
    iec = STANDARD_FUNCTIONS[name]
    params = tuple((new, spec) for new, (_old, spec) in zip(names, iec.params))
    return replace(iec, params=params, extensible=False)


FUNCTIONS: dict[str, StdFunc] = {name: _renamed(name, names) for name, names in _NAMES.items()}
