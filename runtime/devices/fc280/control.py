"""What the FC 280 makes of its control words: the FC profile's bits through
the bus/terminal selections 8-01 and 8-50 ... 8-56 (manual 003 §4.4.2,
Tabelle 4.7, chapter 6), and the DSP 402 state machine with its velocity
mode bits (§4.3.2-4.3.4, Tabellen 4.3, 4.4, 4.6). Pure: the model asks.

    fc = fc_commands(0x047C, selections)       # start, no stop function
    state = dsp_next(DspState.SWITCH_ON_DISABLED, 0x0006)   # READY_TO_SWITCH_ON
    dsp_status(state)                          # 0x0231 (without the dynamic bits)

No digital inputs are simulated: a terminal never asks for anything, so
"[0] Klemme" leaves a function off, "[2] Bus UND Klemme" too, and "[1]" and
"[3] Bus ODER Klemme" follow the bus (simulator choice).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from .profile import ControlWord as Cw

# 8-01 Führungshoheit (chapter 6)
SITE_TERMINAL_AND_WORD, SITE_TERMINAL_ONLY, SITE_WORD_ONLY = 0, 1, 2
# 8-50 ... 8-56 (chapter 6)
SELECT_TERMINAL, SELECT_BUS, SELECT_BUS_AND_TERMINAL, SELECT_BUS_OR_TERMINAL = range(4)
SETUP_EXTERNAL = 9  # 0-10 [9] Externe Anwahl: set-up from the control word (§4.4.2 bits 13/14)
RELAY_CTW_BIT_11, RELAY_CTW_BIT_12 = 36, 37  # 5-40 "Steuerwort Bit 11/12" (simulator choice of the numbers)

# DSP 402 control word bits beyond the state machine's (Tabelle 4.4)
DSP_RAMP = 0x0010  # bit 4: 0 = quick stop ramp ("Schnellstopp/Rampe")
DSP_UNFREEZE = 0x0020  # bit 5: 0 = hold the output frequency
DSP_START = 0x0040  # bit 6: 0 = ramp stop
DSP_RESET = 0x0080  # bit 7: a 0 -> 1 edge acknowledges a fault (A21)
DSP_JOG_1 = 0x0800  # bit 11: 8-90, only with bit 4 = 0 and bits 0-3 = 1
DSP_REVERSE = 0x8000  # bit 15


def gated(selection: int, site: int, bus: bool, terminal: bool = False) -> bool:
    """A function the bus asks for (bus) as 8-01 and its 8-5x selection let it through."""
    if site == SITE_WORD_ONLY:
        return bus
    if site == SITE_TERMINAL_ONLY:
        return terminal
    return {
        SELECT_TERMINAL: terminal,
        SELECT_BUS: bus,
        SELECT_BUS_AND_TERMINAL: bus and terminal,
        SELECT_BUS_OR_TERMINAL: bus or terminal,
    }.get(selection, bus or terminal)


@dataclass(frozen=True)
class Selections:
    """8-01 and 8-50 ... 8-56 as the drive has them."""

    site: int = SITE_TERMINAL_AND_WORD
    coast: int = SELECT_BUS_OR_TERMINAL  # 8-50
    quick_stop: int = SELECT_BUS_OR_TERMINAL  # 8-51
    dc_brake: int = SELECT_BUS_OR_TERMINAL  # 8-52
    start: int = SELECT_BUS_OR_TERMINAL  # 8-53
    reverse: int = SELECT_BUS_OR_TERMINAL  # 8-54 (A25: the parameter list's [3])
    setup: int = SELECT_BUS_OR_TERMINAL  # 8-55
    preset: int = SELECT_BUS_OR_TERMINAL  # 8-56


@dataclass(frozen=True)
class FcCommands:
    """The FC profile control word (Tabelle 4.7) after the gating."""

    coast: bool = True  # no control word yet: the motor is released
    dc_brake: bool = False
    quick_stop: bool = False
    hold: bool = False
    start: bool = False
    jog: bool = False
    ramp_2: bool = False
    reverse: bool = False
    preset: int = 0  # 3-10 element 0..3
    setup: int = 1  # 1..4 from bits 13/14 (Tabelle 4.9); 1 when the selection keeps the bus out


def fc_commands(word: int | None, sel: Selections) -> FcCommands:
    """word: the last valid control word (bit 10 set), None before the first.
    Bits 2-5 are active low (0 asks for DC brake, coast, quick stop, hold)."""
    if word is None:
        return FcCommands()
    site = sel.site

    def asked(selection: int, bus: bool) -> bool:
        return gated(selection, site, bus)

    preset_bits = word & (Cw.PRESET_LSB | Cw.PRESET_MSB)
    setup_bits = (word >> 13) & 0x3
    return FcCommands(
        coast=asked(sel.coast, not word & Cw.NO_COAST),
        dc_brake=asked(sel.dc_brake, not word & Cw.RAMP),
        quick_stop=asked(sel.quick_stop, not word & Cw.NO_QUICK_STOP),
        hold=not word & Cw.USE_RAMP,  # no selection parameter gates it (§4.4.2)
        start=asked(sel.start, bool(word & Cw.START)),
        jog=bool(word & Cw.JOG),
        ramp_2=bool(word & Cw.RAMP_2),
        reverse=asked(sel.reverse, bool(word & Cw.REVERSE)),
        preset=preset_bits if asked(sel.preset, bool(preset_bits)) else 0,
        setup=(setup_bits if asked(sel.setup, True) else 0) + 1,
    )


# ---------------------------------------------------------------------------- DSP 402


class DspState(enum.IntEnum):
    START = 0  # 6041h before the profile runs (Tabelle 4.3 "Startzustand")
    NOT_READY_TO_SWITCH_ON = 1
    SWITCH_ON_DISABLED = 2
    READY_TO_SWITCH_ON = 3
    SWITCHED_ON = 4
    OPERATION_ENABLED = 5
    QUICK_STOP_ACTIVE = 6
    FAULT = 7


# Tabelle 4.3 status words without bit 9 (remote), bit 7 (warning) and the
# dynamic bits 8, 10, 11, 14, which the model adds. The fault state is
# printed 023F (fault reaction active by the CiA 402 masks; InterBus 0238):
# 023F as printed (A20).
STATE_BITS = {
    DspState.START: 0x0000,
    DspState.NOT_READY_TO_SWITCH_ON: 0x0000,
    DspState.SWITCH_ON_DISABLED: 0x0040,
    DspState.READY_TO_SWITCH_ON: 0x0031,
    DspState.SWITCHED_ON: 0x0033,
    DspState.OPERATION_ENABLED: 0x0037,
    DspState.QUICK_STOP_ACTIVE: 0x0007,
    DspState.FAULT: 0x003F,
}
DSP_WARNING = 0x0080  # bit 7
DSP_AT_REFERENCE = 0x0100  # bit 8: speed = reference
DSP_REMOTE = 0x0200  # bit 9
DSP_TARGET_REACHED = 0x0400  # bit 10
DSP_SPEED_LIMIT = 0x0800  # bit 11: the table's "Drehzahlgrenze aktiv" (A19): at the 4-14 limit
DSP_RUNNING = 0x4000  # bit 14 (the text; Tabelle 4.6 marks 12-15 reserved, A19)


def _step(state: DspState, word: int) -> DspState:
    """One transition of Tabelle 4.3 for a control word (CiA 402 command masks)."""
    disable_voltage = not word & 0x0002  # xxxx xx0x
    quick_stop = word & 0x0006 == 0x0002  # xxxx x01x
    shutdown = word & 0x0007 == 0x0006  # xxxx x110
    switch_on = word & 0x0007 == 0x0007  # xxxx x111
    enable = word & 0x000F == 0x000F  # xxxx 1111
    s = DspState
    if state == s.SWITCH_ON_DISABLED:
        return s.READY_TO_SWITCH_ON if shutdown else state  # 2
    if state == s.READY_TO_SWITCH_ON:
        if disable_voltage or quick_stop:
            return s.SWITCH_ON_DISABLED  # 7
        return s.SWITCHED_ON if switch_on else state  # 3
    if state == s.SWITCHED_ON:
        if disable_voltage or quick_stop:
            return s.SWITCH_ON_DISABLED  # 10
        if shutdown:
            return s.READY_TO_SWITCH_ON  # 6
        return s.OPERATION_ENABLED if enable else state  # 4
    if state == s.OPERATION_ENABLED:
        if disable_voltage:
            return s.SWITCH_ON_DISABLED  # 9
        if quick_stop:
            return s.QUICK_STOP_ACTIVE  # 11
        if shutdown:
            return s.READY_TO_SWITCH_ON  # 8
        return state if enable else s.SWITCHED_ON  # 5
    if state == s.QUICK_STOP_ACTIVE:
        return s.SWITCH_ON_DISABLED if disable_voltage else state  # 12; 16 is not supported
    return state  # START, FAULT: only the model moves them (8-10, 13, 15)


def dsp_next(state: DspState, word: int) -> DspState:
    """The state a control word leads to. Transition 1 (not ready -> switch on
    disabled) is taken on the first control word, as Tabelle 4.3 lists it
    with 0000/0001 (CiA 402 makes it automatic: simulator choice), and the
    word then acts from there; a word may take several steps (0x000F from
    ready to switch on: 3 and 4), as CiA 402 allows."""
    if state == DspState.NOT_READY_TO_SWITCH_ON:
        state = DspState.SWITCH_ON_DISABLED  # 1
    for _ in range(4):
        new = _step(state, word)
        if new == state:
            break
        state = new
    return state


@dataclass(frozen=True)
class VlCommands:
    """The velocity mode bits of Tabelle 4.4 in operation enabled (A22: 000F
    enables operation, 007F makes the motor follow the reference). The model
    takes them in this order: jog, quick stop, hold, ramp stop, follow."""

    jog: bool = False  # bit 11, "nur möglich, wenn Bit 04=0 und Bit 00-03=1": 8-90
    quick_stop: bool = False  # bit 4 = 0: "Übergang 7 oder 11 oder Schnellstopp"
    hold: bool = False  # bit 5 = 0: the output frequency is kept
    start: bool = False  # bit 6 = 1; 0: ramp stop
    reverse: bool = False  # bit 15 (8-54 gates it)
    setup: int = 1  # bits 13/14 (Tabelle 4.5), 8-55 gates them


def vl_commands(word: int | None, sel: Selections) -> VlCommands:
    if word is None:
        return VlCommands(quick_stop=True)
    return VlCommands(
        jog=bool(word & DSP_JOG_1) and not word & DSP_RAMP,
        quick_stop=not word & DSP_RAMP,
        hold=not word & DSP_UNFREEZE,
        start=bool(word & DSP_START),
        reverse=gated(sel.reverse, sel.site, bool(word & DSP_REVERSE)),
        setup=(((word >> 13) & 0x3) if gated(sel.setup, sel.site, True) else 0) + 1,
    )
