"""CiA 402 as a controller sees it (runtime/io/canopen/cia402.py): the
status words of the FC 280 manual's Tabelle 4.3 decode to their states with
the standard masks, and the next command walks a drive through the table's
transitions (manual 003 §4.3.2; digest 003 §3.2, M11)."""

from __future__ import annotations

import pytest

from softplc.runtime.io.canopen.cia402 import (
    DISABLE_OPERATION,
    DISABLE_VOLTAGE,
    ENABLE_OPERATION,
    QUICK_STOP,
    SHUTDOWN,
    SWITCH_ON,
    VL_RUN,
    State,
    decode,
    fault,
    next_command,
)


@pytest.mark.parametrize(
    "statusword, state",
    [
        (0x0200, State.NOT_READY_TO_SWITCH_ON),  # transition 0
        (0x0240, State.SWITCH_ON_DISABLED),  # 1, 7, 9, 10, 12, 15
        (0x0231, State.READY_TO_SWITCH_ON),  # 2, 6, 8
        (0x0233, State.SWITCHED_ON),  # 3, 5
        (0x0237, State.OPERATION_ENABLED),  # 4
        (0x0207, State.QUICK_STOP_ACTIVE),  # 11
        (0x023F, State.FAULT_REACTION_ACTIVE),  # 13, 14 as printed (A20)
        (0x0238, State.FAULT),  # 14 "per InterBus"
    ],
)
def test_the_status_words_of_tabelle_4_3(statusword, state):
    assert decode(statusword) == state


def test_a_fault_is_bit_3_whatever_the_mask_says():
    # the manual prints the fault state as 023F, which the masks read as
    # fault reaction active: both are faults to a controller (A20)
    assert fault(0x023F) and fault(0x0238) and not fault(0x0237) and not fault(0x0240)


def test_the_switch_on_sequence_of_tabelle_4_3():
    # transitions 2, 3, 4: CW 0006, 0007, 000F
    assert next_command(State.SWITCH_ON_DISABLED, enable=True) == SHUTDOWN == 0x0006
    assert next_command(State.READY_TO_SWITCH_ON, enable=True) == SWITCH_ON == 0x0007
    assert next_command(State.SWITCHED_ON, enable=True) == ENABLE_OPERATION == 0x000F
    assert next_command(State.OPERATION_ENABLED, enable=True) == ENABLE_OPERATION
    # a velocity-mode drive that runs gets the vl bits 4-6 on top (A22)
    assert ENABLE_OPERATION | VL_RUN == 0x007F


def test_disabling_ramps_down_first_then_shuts_down():
    assert next_command(State.OPERATION_ENABLED, enable=False) == DISABLE_OPERATION == 0x0007  # transition 5
    assert next_command(State.SWITCHED_ON, enable=False) == SHUTDOWN  # transition 6
    assert next_command(State.READY_TO_SWITCH_ON, enable=False) == SHUTDOWN
    assert next_command(State.SWITCH_ON_DISABLED, enable=False) == DISABLE_VOLTAGE


def test_quick_stop_and_the_way_out_of_it():
    assert next_command(State.OPERATION_ENABLED, enable=True, quick_stop=True) == QUICK_STOP == 0x0002  # 11
    assert next_command(State.QUICK_STOP_ACTIVE, enable=True, quick_stop=True) == QUICK_STOP
    # transition 16 (back to operation enabled) is not supported: out through 12
    assert next_command(State.QUICK_STOP_ACTIVE, enable=True) == DISABLE_VOLTAGE


def test_a_faulted_drive_gets_disable_voltage():
    for state in (State.FAULT, State.FAULT_REACTION_ACTIVE, State.NOT_READY_TO_SWITCH_ON):
        assert next_command(state, enable=True) == DISABLE_VOLTAGE
