"""The native function SysTime reads the date through: SOFTPLC_UTC_MS()
is the date of the task clock in milliseconds since 1970-01-01 00:00 UTC,
served by the runtime's clock (runtime/program/context.py): the wall
clock's date in real time, the epoch plus the virtual clock in virtual
time. Constant within a cycle, as TIME() is."""

from __future__ import annotations

from softplc.runtime.st.native import CLOCK, NativeFunction, NoClock

NATIVES = (NativeFunction("SOFTPLC_UTC_MS", (), CLOCK, NoClock(), "SOFTPLC_UTC_MS()", result="ULINT"),)
