"""CiA 402 (drives and motion control): the device control state machine as a
controller sees it through the controlword (6040h) and the statusword
(6041h), for any DSP 402 drive. Pure: no bus.

    state = decode(0x0237)                  # State.OPERATION_ENABLED
    next_command(state, enable=True)        # 0x000F: stay enabled
    next_command(State.SWITCH_ON_DISABLED, enable=True)   # 0x0006: shutdown first

The masks and commands are CiA 402's (digest 003 §3.2 [S]); the FC 280
manual prints the same transitions (manual 003 §4.3.2, Tabelle 4.3), with
three contradictions this module decides (docs/contradictions.md "Danfoss FC 280 — digest 003"):

- The fault state is printed as 0x023F, which the standard masks read as
  "fault reaction active" (only 0x0238 reads as "fault"; digest 003 A20):
  fault() is bit 3, and both states are faults to a controller.
- Transition 15 (fault -> switch on disabled) lists controlword 0x0000, but
  bit 7 is "reset" (Tabelle 4.4) and CiA 402 resets on its 0 -> 1 edge: a
  fault reset is 0x0080 held for one cycle after 0x0000 (digest 003 A21).
- Transition 4 lists 0x000F (enable operation), but in velocity mode bits
  4-6 (ramp function generator enable, unlock, use reference) must also be
  1 for the motor to follow the reference (digest 003 A22): 0x000F reaches
  "operation enabled"; the mode bits are the caller's (VL_* below), and a
  running vl drive gets 0x007F.
"""

from __future__ import annotations

import enum


class State(enum.IntEnum):
    """The device control states (CiA 402), numbered as the ST constants."""

    NOT_READY_TO_SWITCH_ON = 0
    SWITCH_ON_DISABLED = 1
    READY_TO_SWITCH_ON = 2
    SWITCHED_ON = 3
    OPERATION_ENABLED = 4
    QUICK_STOP_ACTIVE = 5
    FAULT_REACTION_ACTIVE = 6
    FAULT = 7


# (mask, value) -> state, in the order CiA 402 tests them
_DECODE = (
    (0x004F, 0x0000, State.NOT_READY_TO_SWITCH_ON),
    (0x004F, 0x0040, State.SWITCH_ON_DISABLED),
    (0x006F, 0x0021, State.READY_TO_SWITCH_ON),
    (0x006F, 0x0023, State.SWITCHED_ON),
    (0x006F, 0x0027, State.OPERATION_ENABLED),
    (0x006F, 0x0007, State.QUICK_STOP_ACTIVE),
    (0x004F, 0x000F, State.FAULT_REACTION_ACTIVE),
    (0x004F, 0x0008, State.FAULT),
)

# statusword bits (Tabelle 4.6)
SW_READY_TO_SWITCH_ON = 0x0001
SW_SWITCHED_ON = 0x0002
SW_OPERATION_ENABLED = 0x0004
SW_FAULT = 0x0008
SW_VOLTAGE_ENABLED = 0x0010
SW_QUICK_STOP = 0x0020  # 0: a quick stop is active
SW_SWITCH_ON_DISABLED = 0x0040
SW_WARNING = 0x0080
SW_REMOTE = 0x0200
SW_TARGET_REACHED = 0x0400
SW_LIMIT = 0x0800

# controlword bits (Tabelle 4.4)
CW_SWITCH_ON = 0x0001
CW_ENABLE_VOLTAGE = 0x0002
CW_QUICK_STOP = 0x0004  # 0: quick stop
CW_ENABLE_OPERATION = 0x0008
CW_FAULT_RESET = 0x0080
# velocity mode (vl) bits 4-6: ramp function generator enable, unlock, use reference
VL_RFG_ENABLE = 0x0010
VL_RFG_UNLOCK = 0x0020
VL_RFG_USE_REFERENCE = 0x0040
VL_RUN = VL_RFG_ENABLE | VL_RFG_UNLOCK | VL_RFG_USE_REFERENCE
CW_HALT = 0x0100

# device control commands (CiA 402; the values of Tabelle 4.3)
DISABLE_VOLTAGE = 0x0000
QUICK_STOP = 0x0002
SHUTDOWN = 0x0006
SWITCH_ON = 0x0007
DISABLE_OPERATION = 0x0007
ENABLE_OPERATION = 0x000F
FAULT_RESET = CW_FAULT_RESET

#: the bits the state machine owns; the others belong to the operation mode
STATE_MACHINE_BITS = CW_SWITCH_ON | CW_ENABLE_VOLTAGE | CW_QUICK_STOP | CW_ENABLE_OPERATION | CW_FAULT_RESET


def decode(statusword: int) -> State:
    """The state a statusword shows (the standard masks)."""
    for mask, value, state in _DECODE:
        if statusword & mask == value:
            return state
    return State.NOT_READY_TO_SWITCH_ON  # bit patterns no state has


def fault(statusword: int) -> bool:
    """A fault is present: bit 3 (the FC 280 prints its fault state as
    0x023F, which the masks read as fault reaction active)."""
    return bool(statusword & SW_FAULT)


def next_command(state: State, *, enable: bool, quick_stop: bool = False) -> int:
    """The controlword (state machine bits only) that moves a drive one step
    toward what the caller wants: operation enabled when enable; when not,
    disable operation first (transition 5: the motor ramps down), then ready
    to switch on; quick stop active while quick_stop (from operation
    enabled). A faulted drive gets disable voltage (0x0000); resetting it is
    the caller's 0x0080 pulse."""
    if state in (State.FAULT, State.FAULT_REACTION_ACTIVE, State.NOT_READY_TO_SWITCH_ON):
        return DISABLE_VOLTAGE
    if state == State.QUICK_STOP_ACTIVE:
        # transition 16 (back to operation enabled) is not supported by every
        # drive (the FC 280 does not): leave through switch on disabled
        return QUICK_STOP if quick_stop else DISABLE_VOLTAGE
    if quick_stop and state == State.OPERATION_ENABLED:
        return QUICK_STOP
    if not enable:
        if state == State.OPERATION_ENABLED:
            return DISABLE_OPERATION
        return SHUTDOWN if state != State.SWITCH_ON_DISABLED else DISABLE_VOLTAGE
    return {
        State.SWITCH_ON_DISABLED: SHUTDOWN,
        State.READY_TO_SWITCH_ON: SWITCH_ON,
        State.SWITCHED_ON: ENABLE_OPERATION,
        State.OPERATION_ENABLED: ENABLE_OPERATION,
    }[state]
