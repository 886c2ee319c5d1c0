"""CIA402_DRIVE (fblocks/comm/cia402.st), driven cycle by cycle in virtual
time, against the FC 280 manual's state machine table (manual 003 §4.3.2,
Tabelle 4.3) and against runtime/io/canopen/cia402.py, the same logic in
Python.

The test plays the drive: it sets the statusword (6041h) between cycles
and reads the controlword (6040h) the block would send."""

from __future__ import annotations

import itertools

import pytest

from softplc.runtime.io.canopen import cia402
from softplc.runtime.st.profile import PROFILES

from .st_bench import CYCLE_MS, Bench

DECLS = """
    axis : CIA402_DRIVE;
    enable : BOOL; quickStop : BOOL; reset : BOOL; sw : WORD;
"""
BODY = "axis(ENABLE := enable, QUICK_STOP := quickStop, FAULT_RESET := reset, STATUS_WORD := sw);"

# the statuswords of Tabelle 4.3 (hex)
SWITCH_ON_DISABLED = 0x0240
READY_TO_SWITCH_ON = 0x0231
SWITCHED_ON = 0x0233
OPERATION_ENABLED = 0x0237
QUICK_STOP_ACTIVE = 0x0207
FAULT_PRINTED = 0x023F  # transitions 13/14: "fault reaction active" and "fault" (A20)


def bench() -> Bench:
    return Bench(DECLS, BODY)


def cw(b: Bench) -> int:
    return b["axis.CONTROL_WORD"]


def test_tabelle_4_3_switch_on_sequence_0240_0231_0233_0237():
    b = bench().step(sw=0x0000)
    assert cw(b) == 0x0000 and b["axis.STATE"] == cia402.State.NOT_READY_TO_SWITCH_ON
    b.step(sw=SWITCH_ON_DISABLED)  # transitions 0, 1: the drive is up
    assert cw(b) == 0x0000 and b["axis.STATE"] == cia402.State.SWITCH_ON_DISABLED
    b.step(enable=True)
    assert cw(b) == 0x0006  # transition 2: shutdown
    b.step(sw=READY_TO_SWITCH_ON)
    assert cw(b) == 0x0007 and b["axis.READY"] and not b["axis.SWITCHED_ON"]  # transition 3: switch on
    b.step(sw=SWITCHED_ON)
    assert cw(b) == 0x000F and b["axis.SWITCHED_ON"] and not b["axis.ENABLED"]  # transition 4
    b.step(sw=OPERATION_ENABLED)
    assert cw(b) == 0x000F and b["axis.ENABLED"] and b["axis.STATE"] == cia402.State.OPERATION_ENABLED
    assert b["axis.REMOTE"]  # bit 9 in every word of the table


def test_disable_goes_back_through_0007_and_0006():
    b = bench().step(enable=False, sw=OPERATION_ENABLED)
    assert cw(b) == 0x0007  # transition 5: the motor ramps down
    b.step(sw=SWITCHED_ON)
    assert cw(b) == 0x0006  # transition 6
    b.step(sw=READY_TO_SWITCH_ON)
    assert cw(b) == 0x0006  # stays ready to switch on


def test_quick_stop_0002_to_0207_and_out_through_switch_on_disabled():
    b = bench().step(enable=True, sw=OPERATION_ENABLED)
    b.step(quickStop=True)
    assert cw(b) == 0x0002  # transition 11
    b.step(sw=QUICK_STOP_ACTIVE)
    assert cw(b) == 0x0002 and b["axis.QUICK_STOP_ACTIVE"] and b["axis.READY"]
    b.step(quickStop=False)
    assert cw(b) == 0x0000  # transition 12; 16 (back to enabled) is not supported
    b.step(sw=SWITCH_ON_DISABLED)
    assert cw(b) == 0x0006  # and up again


def test_fault_023f_reset_pulse_0080_to_0240():
    b = bench().step(enable=True, sw=OPERATION_ENABLED)
    assert cw(b) == 0x000F
    b.step(sw=FAULT_PRINTED)  # transition 13
    assert b["axis.FAULT"] and cw(b) == 0x0000
    assert b["axis.STATE"] == cia402.State.FAULT_REACTION_ACTIVE  # 023F by the masks (A20)
    b.step(reset=True)  # the last word was 0000: the reset bit at once
    assert cw(b) == 0x0080 and b["axis.RESETTING"]
    b.step(reset=False)  # the drive has not taken it yet: held
    assert cw(b) == 0x0080
    b.step(sw=SWITCH_ON_DISABLED)  # transition 15
    assert not b["axis.FAULT"] and not b["axis.RESETTING"]
    assert cw(b) == 0x0006  # and on toward enabled


def test_a_fault_seen_with_a_nonzero_word_gets_0000_before_0080():
    b = bench().step(enable=True, sw=OPERATION_ENABLED)
    b.step(sw=FAULT_PRINTED, reset=True)  # the edge in the very cycle the fault shows
    assert cw(b) == 0x0000  # 0000 first: transition 15's word (A21)
    b.step()
    assert cw(b) == 0x0080


def test_the_reset_bit_is_held_at_least_one_cycle():
    b = bench().step(sw=0x0238)  # the InterBus fault word: "fault" by the masks
    assert b["axis.STATE"] == cia402.State.FAULT and b["axis.FAULT"]
    b.step(reset=True)
    assert cw(b) == 0x0080
    b.step(sw=SWITCH_ON_DISABLED)  # the drive took it in the same cycle
    assert cw(b) == 0x0000  # 0080 was out for one cycle; not enabled: stays 0000


def test_a_fault_that_stays_gives_up_after_a_second_and_a_new_edge_retries():
    b = bench().step(sw=FAULT_PRINTED)
    b.step(reset=True)
    b.step(1000 // CYCLE_MS - 1)
    assert cw(b) == 0x0080
    b.step()
    assert cw(b) == 0x0000 and not b["axis.RESETTING"]
    b.step(reset=False)
    b.step(reset=True)
    assert cw(b) == 0x0080


def test_a_reset_edge_without_a_fault_is_ignored():
    b = bench().step(enable=True, sw=OPERATION_ENABLED, reset=True)
    assert cw(b) == 0x000F and not b["axis.RESETTING"]
    b.step(sw=FAULT_PRINTED)  # FAULT_RESET still TRUE: no edge
    assert cw(b) == 0x0000


# ---------------------------------------------------------------- agreement with cia402.py

# every combination of the bits the masks look at (0-3, 5, 6), with bit 4 and
# the upper bits of the Tabelle 4.3 words on and off
STATUS_WORDS = sorted({low | high for low in range(0x80) for high in (0x0000, 0x0600)})


def test_decode_agrees_with_cia402_for_every_mask_pattern():
    b = bench()
    for sw in STATUS_WORDS:
        b.step(sw=sw)
        assert b["axis.STATE"] == cia402.decode(sw), hex(sw)
        assert b["axis.FAULT"] == cia402.fault(sw), hex(sw)
        assert b["axis.ENABLED"] == (cia402.decode(sw) == cia402.State.OPERATION_ENABLED)


@pytest.mark.parametrize("state", list(cia402.State), ids=lambda s: s.name)
def test_next_command_agrees_with_cia402_for_every_state_and_input(state):
    b = bench()
    words = [sw for sw in STATUS_WORDS if cia402.decode(sw) == state]
    assert words
    for sw, enable, quick_stop in itertools.product(words, (False, True), (False, True)):
        b.step(sw=sw, enable=enable, quickStop=quick_stop)
        assert cw(b) == cia402.next_command(state, enable=enable, quick_stop=quick_stop), (hex(sw), enable)


def test_status_bits():
    b = bench().step(sw=0x0080 | 0x0400 | SWITCH_ON_DISABLED)
    assert b["axis.WARNING"] and b["axis.TARGET_REACHED"] and b["axis.REMOTE"]
    b.step(sw=0x0040)
    assert not (b["axis.WARNING"] or b["axis.TARGET_REACHED"] or b["axis.REMOTE"])


CONSTANTS = {
    **{f"CIA402_STATE_{s.name}": int(s) for s in cia402.State},
    **{
        f"CIA402_{name}": value
        for name, value in vars(cia402).items()
        if name.startswith(("SW_", "CW_", "VL_")) and isinstance(value, int)
    },
    **{
        f"CIA402_{name}": getattr(cia402, name)
        for name in (
            "DISABLE_VOLTAGE",
            "QUICK_STOP",
            "SHUTDOWN",
            "SWITCH_ON",
            "DISABLE_OPERATION",
            "ENABLE_OPERATION",
            "FAULT_RESET",
            "STATE_MACHINE_BITS",
        )
    },
}


def test_the_st_constants_are_cia402_py_numbers():
    decls = "".join(f"v{i} : DINT;\n" for i in range(len(CONSTANTS)))
    body = "".join(f"v{i} := {name};\n" for i, name in enumerate(CONSTANTS))
    b = Bench(decls, body).step()
    for i, (name, value) in enumerate(CONSTANTS.items()):
        assert b[f"v{i}"] == value, name


@pytest.mark.parametrize("profile", list(PROFILES))
def test_compiles_in_every_profile_without_warnings(profile):
    b = Bench(DECLS, BODY, profile).step(enable=True, sw=SWITCH_ON_DISABLED)
    assert b.runner.program.warnings == []
    assert cw(b) == 0x0006
