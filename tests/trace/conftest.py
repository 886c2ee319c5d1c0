"""Engines on the virtual clock (tests/engine/conftest.py) and a program
with a value of every kind a trace knows."""

from __future__ import annotations

from ..engine.conftest import MS, engines, task  # noqa: F401  (engines is a fixture)

SRC = """
TYPE Mode : (Off, Auto, Manual); END_TYPE
VAR_GLOBAL total : DINT; END_VAR
PROGRAM Main
VAR
    n : INT;
    on : BOOL;
    mode : Mode;
    x : REAL;
    t : TIME;
    w AT %QW1 : WORD;
    name : STRING;
END_VAR
n := n - 3; on := NOT on; x := x + 0.5; t := TIME();
IF n < -6 THEN mode := Manual; ELSE mode := Auto; END_IF
w := 16#FF00; total := total + 1; name := 'a b';
END_PROGRAM
"""

WATCHED = ["Main.n", "Main.on", "Main.mode", "Main.x", "Main.t", "total", "%QW1", "Main.name"]
