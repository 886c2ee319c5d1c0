"""CANopen numbers: the manual's abort table (manual 001 §3.3), the CiA-301
NMT and COB-ID numbers the manual leaves out (digest 001 A22), and a check
that the real `canopen` stack puts the same numbers on a virtual bus."""

from __future__ import annotations

import itertools

import can
import canopen
import canopen.nmt
import pytest

from softplc.runtime.io.canopen import cia301
from softplc.runtime.io.canopen.cia301 import (
    ABORT_CODES,
    COB_NMT,
    COB_SYNC,
    MANUAL_ABORT_CODES,
    NMT_PRE_OPERATIONAL,
    NMT_RESET_COMMUNICATION,
    NMT_RESET_NODE,
    NMT_START,
    NMT_STOP,
    STATE_BOOTUP,
    STATE_NAMES,
    STATE_OPERATIONAL,
    STATE_PRE_OPERATIONAL,
    STATE_STOPPED,
    abort_text,
    cob_emcy,
    cob_heartbeat,
    cob_rpdo,
    cob_sdo_rx,
    cob_sdo_tx,
    cob_tpdo,
    heartbeat_consumer_entry,
    mapping_entry,
    split_mapping_entry,
)

# manual 001 L720-754, copied
MANUAL_ABORT_TABLE = {
    0x05030000: "Segmented transfer: the toggle bit has not been alternated",
    0x05040000: "The SDO protocol timed out",
    0x05040001: "The request code is not valid or is unknown",
    0x06010000: "An access trip has occurred during access to the parameter (for example, a write request on a "
    "read-only parameter)",
    0x06010001: "Tried to perform a read request on a parameter with write-only access rights",
    0x06010002: "Tried to perform a write request on a parameter with read-only access rights",
    0x06020000: "The index sent in the request refers to an object that does not exist in the object dictionary",
    0x06040041: "PDO object mapping: the parameter cannot be mapped to the PDO; this detected error occurs when "
    "writing to the 0x1600, 0x1A00, 0x1605, and 0x1A05 parameters (PDO mappings)",
    0x06040042: "PDO object mapping: the number or length of the parameters to be mapped would exceed the maximum "
    "PDO length.",
    0x06090011: "The sub-index sent in the request does not exist",
    0x06090030: "Value range of parameter exceeded (only for write access)",
    0x06090031: "Value of parameter written too high",
    0x06090032: "Value of parameter written too low",
    0x06090036: "The parameter maximum value is less than its minimum value",
    0x08000000: "A general detected error occurred",
}


def test_the_manual_abort_codes_with_their_texts():
    assert len(MANUAL_ABORT_TABLE) == 15
    for code, text in MANUAL_ABORT_TABLE.items():
        assert abort_text(code) == text
    assert set(MANUAL_ABORT_CODES) == set(MANUAL_ABORT_TABLE)


def test_named_abort_constants():
    assert (cia301.ABORT_TOGGLE, cia301.ABORT_TIMEOUT, cia301.ABORT_BAD_COMMAND) == (0x05030000, 0x05040000, 0x05040001)
    assert (cia301.ABORT_ACCESS, cia301.ABORT_WRITE_ONLY, cia301.ABORT_READ_ONLY) == (
        0x06010000,
        0x06010001,
        0x06010002,
    )
    assert (cia301.ABORT_NO_OBJECT, cia301.ABORT_NOT_MAPPABLE, cia301.ABORT_PDO_LENGTH) == (
        0x06020000,
        0x06040041,
        0x06040042,
    )
    assert (cia301.ABORT_LENGTH, cia301.ABORT_NO_SUBINDEX, cia301.ABORT_VALUE_RANGE) == (
        0x06070010,
        0x06090011,
        0x06090030,
    )
    assert (cia301.ABORT_VALUE_HIGH, cia301.ABORT_VALUE_LOW) == (0x06090031, 0x06090032)
    assert (cia301.ABORT_GENERAL, cia301.ABORT_DEVICE_STATE) == (0x08000000, 0x08000022)


def test_cia_codes_the_manual_leaves_out_have_texts():
    for code in (0x05040000, 0x06070010, 0x06060000, 0x08000022):
        assert code in ABORT_CODES and not abort_text(code).startswith("unknown")


def test_unknown_abort_code():
    assert abort_text(0x12345678) == "unknown abort code 0x12345678"
    assert abort_text(0) == "unknown abort code 0x00000000"


def test_cob_ids_for_node_40_and_node_1():
    # digest 001 §1.3, DERIVED for the node of the German ST examples (40 = 0x28) and node 1
    assert (cob_rpdo(1, 40), cob_tpdo(1, 40), cob_rpdo(4, 40), cob_tpdo(4, 40)) == (0x228, 0x1A8, 0x528, 0x4A8)
    assert (cob_sdo_rx(40), cob_sdo_tx(40), cob_emcy(40), cob_heartbeat(40)) == (0x628, 0x5A8, 0x0A8, 0x728)
    assert (cob_rpdo(1, 1), cob_tpdo(1, 1), cob_rpdo(4, 1), cob_tpdo(4, 1)) == (0x201, 0x181, 0x501, 0x481)
    assert (cob_sdo_rx(1), cob_sdo_tx(1), cob_emcy(1)) == (0x601, 0x581, 0x081)
    assert [cob_tpdo(k, 0) for k in (1, 2, 3, 4)] == [0x180, 0x280, 0x380, 0x480]
    assert [cob_rpdo(k, 0) for k in (1, 2, 3, 4)] == [0x200, 0x300, 0x400, 0x500]
    assert (COB_NMT, COB_SYNC) == (0x000, 0x080)  # SYNC: "Its factory setting is 0x080."


def test_mapping_entries_of_the_manual():
    # 0x1600:01 "Reg [704]" = 0x20080510 ; 0x1603:01 PKW request = 0x30000120 (manual L1199, L1304)
    assert mapping_entry(0x2008, 0x05, 16) == 0x20080510
    assert mapping_entry(0x3000, 0x01, 32) == 0x30000120
    assert split_mapping_entry(0x20040A10) == (0x2004, 0x0A, 16)
    assert split_mapping_entry(0x30000420) == (0x3000, 0x04, 32)


def test_heartbeat_consumer_entry():
    # digest 001 §1.5 DERIVED: producer 0x7F watched at 500 ms
    assert heartbeat_consumer_entry(0x7F, 500) == 0x007F01F4
    with pytest.raises(ValueError):
        heartbeat_consumer_entry(0, 500)
    with pytest.raises(ValueError):
        heartbeat_consumer_entry(40, 70_000)


def test_nmt_numbers_agree_with_the_canopen_stack():
    commands = canopen.nmt.NMT_COMMANDS
    assert (commands["OPERATIONAL"], commands["STOPPED"], commands["PRE-OPERATIONAL"]) == (
        NMT_START,
        NMT_STOP,
        NMT_PRE_OPERATIONAL,
    )
    assert (commands["RESET"], commands["RESET COMMUNICATION"]) == (NMT_RESET_NODE, NMT_RESET_COMMUNICATION)
    states = canopen.nmt.NMT_STATES
    assert (states[STATE_BOOTUP], states[STATE_STOPPED], states[STATE_OPERATIONAL], states[STATE_PRE_OPERATIONAL]) == (
        "INITIALISING",
        "STOPPED",
        "OPERATIONAL",
        "PRE-OPERATIONAL",
    )
    assert STATE_NAMES[STATE_PRE_OPERATIONAL] == "pre-operational"


_channels = itertools.count()


@pytest.fixture
def virtual_bus():
    """Two python-can endpoints on one in-process virtual channel: the stack's and a listener."""
    channel = f"devices-cia301-{next(_channels)}"
    stack_bus = can.Bus(interface="virtual", channel=channel)
    listener = can.Bus(interface="virtual", channel=channel)
    yield stack_bus, listener
    stack_bus.shutdown()
    listener.shutdown()


def _frames(listener) -> list:
    frames = []
    while (msg := listener.recv(timeout=0)) is not None:
        frames.append((msg.arbitration_id, bytes(msg.data)))
    return frames


def test_nmt_frames_the_canopen_master_sends(virtual_bus):
    # digest 001 §7.2: NMT start node 40 = 000 [01 28]; enter pre-operational = 000 [80 28]
    stack_bus, listener = virtual_bus
    network = canopen.Network(stack_bus)
    node = network.add_node(40, canopen.ObjectDictionary())
    node.nmt.state = "OPERATIONAL"
    node.nmt.state = "PRE-OPERATIONAL"
    assert _frames(listener) == [(COB_NMT, bytes([NMT_START, 40])), (COB_NMT, bytes([NMT_PRE_OPERATIONAL, 40]))]
    assert bytes([NMT_START, 40]) == bytes.fromhex("01 28")


def test_boot_up_frame_of_a_canopen_slave(virtual_bus):
    stack_bus, listener = virtual_bus
    network = canopen.Network(stack_bus)
    local = canopen.LocalNode(40, canopen.ObjectDictionary())
    network.add_node(local)
    local.nmt.send_command(NMT_RESET_NODE)
    assert _frames(listener) == [(cob_heartbeat(40), bytes([STATE_BOOTUP]))]
