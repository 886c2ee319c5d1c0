"""Tc2_Standard's string functions with TwinCAT's parameter names
(Beckhoff Information System, Tc2_Standard > Functions > String
functions: CONCAT(STR1, STR2), LEN(STR), LEFT(STR, SIZE), MID(STR, LEN,
POS) ...): fblocks/libs/standard_strings.py."""

from __future__ import annotations

from softplc.fblocks.libs.standard_strings import standard_string_functions

FUNCTIONS = standard_string_functions()
