"""The FC 280's status words, made from what the model knows: 16-03 /
2643h in the FC profile (Tabelle 4.10) and 6041h in DSP 402 (Tabellen 4.3,
4.6). Pure functions: Fc280Model (model.py) calls them.
"""

from __future__ import annotations

from fractions import Fraction

from .control import (
    DSP_AT_REFERENCE,
    DSP_REMOTE,
    DSP_RUNNING,
    DSP_SPEED_LIMIT,
    DSP_TARGET_REACHED,
    DSP_WARNING,
    STATE_BITS,
    DspState,
)
from .motor import Motion
from .profile import StatusWord
from .settings import Settings

# Warnings the FC status word shows in bits 13-15 (Tabelle 4.10; simulator choice of the bits):
VOLTAGE_WARNINGS = 0x00001000 | 0x00002000 | 0x08000000  # DC link low/high, voltage limit
TORQUE_WARNINGS = 0x00000040 | 0x02000000  # torque limit, current limit
TIMER_WARNINGS = 0x00000100 | 0x00000200  # motor ETR, inverter overload
# The status word bits as plain ints (IntFlag operators are slow on the tick's path)
_SW = {flag.name: int(flag) for flag in StatusWord}
_SW_LIMITS = {VOLTAGE_WARNINGS: "VOLTAGE_LIMIT", TORQUE_WARNINGS: "TORQUE_LIMIT", TIMER_WARNINGS: "THERMAL_TIMER"}
_SW_WARNING_BITS = tuple((bits, _SW[name]) for bits, name in _SW_LIMITS.items())


def fc_status_word(
    m: Motion, warnings: dict[str, int], s: Settings, out: Fraction, tripped: bool, trip_lock: bool
) -> int:
    """16-03, object 2643h (Tabelle 4.10): m the motion in force, warnings
    16-92/16-93, out the output frequency."""
    if tripped:
        sw = _SW["TRIP"] | (_SW["TRIP_LOCK"] if trip_lock else 0)
    else:
        sw = _SW["CONTROL_READY"] | _SW["DRIVE_READY"]
        if not m.coast:
            sw |= _SW["ENABLED"]
    if any(warnings.values()):
        sw |= _SW["WARNING"]
    if m.run and out == m.target:
        sw |= _SW["AT_REFERENCE"]
    if s.bus_control:
        sw |= _SW["BUS_CONTROL"]
    if abs(out) < s.f_max:
        sw |= _SW["IN_FREQUENCY_LIMIT"]
    if m.run or out != 0:
        sw |= _SW["RUNNING"]
    warning_word = warnings["16-92"]
    for bits, flag in _SW_WARNING_BITS:
        if warning_word & bits:
            sw |= flag
    return sw


def dsp_status_word(state: DspState, m: Motion, s: Settings, out: Fraction, warned: bool) -> int:
    """6041h out of the START state: the state's word of Tabelle 4.3 and the
    bits of Tabelle 4.6; warned: a warning is raised."""
    sw = STATE_BITS[state] | (DSP_REMOTE if s.bus_control else 0)
    if warned:
        sw |= DSP_WARNING
    if state == DspState.OPERATION_ENABLED and m.run and m.reference and out == m.target:
        sw |= DSP_AT_REFERENCE | DSP_TARGET_REACHED
    if out != 0 and abs(out) >= s.f_max:
        sw |= DSP_SPEED_LIMIT
    if m.run or out != 0:
        sw |= DSP_RUNNING
    return sw
