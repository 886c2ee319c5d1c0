"""CANopen (CiA 301) numbers the LTMR manual uses or leaves out: SDO abort
codes, NMT commands and states, the pre-defined COB-IDs, PDO mapping
entries. The manual's own abort table is manual 001 §3.3 (L720-754); the
NMT, heartbeat and COB-ID numbers are CiA 301's (digest 001, A22)."""

from __future__ import annotations

ABORT_TOGGLE = 0x05030000
ABORT_TIMEOUT = 0x05040000
ABORT_BAD_COMMAND = 0x05040001
ABORT_ACCESS = 0x06010000
ABORT_WRITE_ONLY = 0x06010001
ABORT_READ_ONLY = 0x06010002
ABORT_NO_OBJECT = 0x06020000
ABORT_NOT_MAPPABLE = 0x06040041
ABORT_PDO_LENGTH = 0x06040042
ABORT_HARDWARE = 0x06060000
ABORT_LENGTH = 0x06070010
ABORT_NO_SUBINDEX = 0x06090011
ABORT_VALUE_RANGE = 0x06090030
ABORT_VALUE_HIGH = 0x06090031
ABORT_VALUE_LOW = 0x06090032
ABORT_MAX_BELOW_MIN = 0x06090036
ABORT_GENERAL = 0x08000000
ABORT_DEVICE_STATE = 0x08000022

ABORT_CODES = {
    # manual 001 §3.3 (L720-754), texts as printed
    ABORT_TOGGLE: "Segmented transfer: the toggle bit has not been alternated",
    ABORT_TIMEOUT: "The SDO protocol timed out",
    ABORT_BAD_COMMAND: "The request code is not valid or is unknown",
    ABORT_ACCESS: "An access trip has occurred during access to the parameter (for example, a write request on "
    "a read-only parameter)",
    ABORT_WRITE_ONLY: "Tried to perform a read request on a parameter with write-only access rights",
    ABORT_READ_ONLY: "Tried to perform a write request on a parameter with read-only access rights",
    ABORT_NO_OBJECT: "The index sent in the request refers to an object that does not exist in the object dictionary",
    ABORT_NOT_MAPPABLE: "PDO object mapping: the parameter cannot be mapped to the PDO; this detected error occurs "
    "when writing to the 0x1600, 0x1A00, 0x1605, and 0x1A05 parameters (PDO mappings)",
    ABORT_PDO_LENGTH: "PDO object mapping: the number or length of the parameters to be mapped would exceed "
    "the maximum PDO length.",
    ABORT_NO_SUBINDEX: "The sub-index sent in the request does not exist",
    ABORT_VALUE_RANGE: "Value range of parameter exceeded (only for write access)",
    ABORT_VALUE_HIGH: "Value of parameter written too high",
    ABORT_VALUE_LOW: "Value of parameter written too low",
    ABORT_MAX_BELOW_MIN: "The parameter maximum value is less than its minimum value",
    ABORT_GENERAL: "A general detected error occurred",
    # CiA 301, not in the manual
    ABORT_HARDWARE: "Access failed because of a hardware error",
    ABORT_LENGTH: "Data type does not match, length of service parameter does not match",
    ABORT_DEVICE_STATE: "Data cannot be transferred or stored because of the present device state",
    0x05040005: "Out of memory",
    0x06040043: "General parameter incompatibility",
    0x06040047: "General internal incompatibility in the device",
    0x06070012: "Data type does not match, length of service parameter too high",
    0x06070013: "Data type does not match, length of service parameter too low",
    0x060A0023: "Resource not available: SDO connection",
    0x08000020: "Data cannot be transferred or stored to the application",
    0x08000021: "Data cannot be transferred or stored to the application because of local control",
}

# The 15 codes the LTMR manual lists (manual 001 L720-754); PKW errors use the same codes
MANUAL_ABORT_CODES = (
    ABORT_TOGGLE,
    ABORT_TIMEOUT,
    ABORT_BAD_COMMAND,
    ABORT_ACCESS,
    ABORT_WRITE_ONLY,
    ABORT_READ_ONLY,
    ABORT_NO_OBJECT,
    ABORT_NOT_MAPPABLE,
    ABORT_PDO_LENGTH,
    ABORT_NO_SUBINDEX,
    ABORT_VALUE_RANGE,
    ABORT_VALUE_HIGH,
    ABORT_VALUE_LOW,
    ABORT_MAX_BELOW_MIN,
    ABORT_GENERAL,
)


def abort_text(code: int) -> str:
    return ABORT_CODES.get(code, f"unknown abort code 0x{code:08X}")


# NMT command specifiers (CiA 301; the manual names the services only, manual 001 L75-90)
NMT_START = 0x01
NMT_STOP = 0x02
NMT_PRE_OPERATIONAL = 0x80
NMT_RESET_NODE = 0x81
NMT_RESET_COMMUNICATION = 0x82

# NMT states as a heartbeat / boot-up frame carries them (CiA 301)
STATE_BOOTUP = 0x00
STATE_STOPPED = 0x04
STATE_OPERATIONAL = 0x05
STATE_PRE_OPERATIONAL = 0x7F
STATE_NAMES = {
    STATE_BOOTUP: "boot-up",
    STATE_STOPPED: "stopped",
    STATE_OPERATIONAL: "operational",
    STATE_PRE_OPERATIONAL: "pre-operational",
}

# The pre-defined connection set (manual 001 §1.3 gives the factory values of the LTMR's OD)
COB_NMT = 0x000
COB_SYNC = 0x080
COB_ID_INVALID = 1 << 31  # bit 31 of a PDO / EMCY COB-ID: does not exist / not valid

# Error control objects (CiA 301)
GUARD_TIME = 0x100C  # Unsigned 16, ms between two guarding requests of the master
LIFE_TIME_FACTOR = 0x100D  # Unsigned 8: guard time x factor is the node's life time
CONSUMER_HEARTBEAT = 0x1016  # sub n: (producer node << 16) | time in ms
PRODUCER_HEARTBEAT = 0x1017  # Unsigned 16, ms (0: none)

# PDO k's communication and mapping parameters are at these indices + k - 1
RPDO_COMM, RPDO_MAP = 0x1400, 0x1600
TPDO_COMM, TPDO_MAP = 0x1800, 0x1A00


# CAN-IDs no PDO may use (CiA 301, restricted CAN-IDs): NMT and reserved ones,
# the default SDO channels, the NMT error control (heartbeat, boot-up) ones
RESTRICTED_COB_IDS = ((0x000, 0x07F), (0x101, 0x180), (0x581, 0x5FF), (0x601, 0x67F), (0x6E0, 0x6FF), (0x701, 0x7FF))


def restricted_cob_id(cob_id: int) -> bool:
    return any(lo <= cob_id <= hi for lo, hi in RESTRICTED_COB_IDS)


def cob_emcy(node: int) -> int:
    return 0x080 + node


def cob_tpdo(k: int, node: int) -> int:
    return 0x180 + 0x100 * (k - 1) + node


def cob_rpdo(k: int, node: int) -> int:
    return 0x200 + 0x100 * (k - 1) + node


def cob_sdo_tx(node: int) -> int:
    return 0x580 + node


def cob_sdo_rx(node: int) -> int:
    return 0x600 + node


def cob_heartbeat(node: int) -> int:
    return 0x700 + node


def mapping_entry(index: int, subindex: int, bits: int) -> int:
    """A PDO mapping entry (0x16xx/0x1Axx sub n): index, sub-index, length in bits."""
    return (index << 16) | (subindex << 8) | bits


def split_mapping_entry(value: int) -> tuple:
    return (value >> 16) & 0xFFFF, (value >> 8) & 0xFF, value & 0xFF


def heartbeat_consumer_entry(producer_node: int, time_ms: int) -> int:
    """A 0x1016 sub-entry: bits 16-23 producer node-ID, bits 0-15 time in ms (manual 001 L957)."""
    if not (1 <= producer_node <= 127 and 0 <= time_ms <= 0xFFFF):
        raise ValueError(f"heartbeat consumer entry: node {producer_node} (1-127), time {time_ms} ms (0-65535)")
    return (producer_node << 16) | time_ms
