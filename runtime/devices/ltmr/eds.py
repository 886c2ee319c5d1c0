"""The LTMR's EDS (io_config/eds/ltmr.eds), written from the register map
of manual 001 (registers.py, bits.py) and its communication profile (profile.py)."""

from __future__ import annotations

from ...io.canopen.eds import (
    INTEGER16,
    UNSIGNED8,
    UNSIGNED16,
    UNSIGNED32,
    VISIBLE_STRING,
    EdsFile,
    EdsObject,
    Entry,
    compound,
    pdo_communication,
    pdo_mapping,
    sdo_server,
    var,
)
from . import bits as ltmr_bits
from . import profile as ltmr_profile
from . import registers as ltmr

# ---------------------------------------------------------------------------
# TeSys T LTMR (manual 001 §4 and the register map of registers.py)
# ---------------------------------------------------------------------------

_LTMR_GROUPS = {
    0x2000: "Identification variables",
    0x2001: "Statistics variables",
    0x2002: "Trip history variables",
    0x2003: "Trip history extension variables",
    0x2004: "Monitoring variables",
    0x2005: "Configuration variables",
    0x2006: "Configuration variables 2",
    0x2007: "Setting variables",
    0x2008: "Command variables",
    0x200D: "Custom logic variables",
}

# Enumerations whose range the manual prints (DT_OutputFallbackStrategy L2171, DT_CANopenExtBaudRate L2003)
_LTMR_HIGH_LIMITS = {ltmr.REG_HMI_FALLBACK: 5, ltmr.REG_NETWORK_FALLBACK: 5, ltmr.REG_BAUD_RATE: 9}


def _register_entry(reg: int, mappable: bool) -> Entry:
    register = ltmr.REGISTERS[reg]
    high = _LTMR_HIGH_LIMITS.get(reg)
    low = None
    if register.kind == "reserved" and register.access == "rw":
        low = high = 0  # "Reserved, in Read/Write tables, means that you must write 0" (L1717)
    return Entry(
        ltmr.register_label(reg),
        INTEGER16 if register.type == "Int" else UNSIGNED16,
        register.access,
        ltmr_bits.FACTORY_SETTINGS.get(reg, 0),
        mappable,
        low,
        high,
    )


def ltmr_register_objects() -> list:
    """0x2000-0x2008 and 0x200D: one sub-entry per register, Forbidden registers
    left out (a request for them is answered "sub-index does not exist", A21)."""
    objects = []
    for first, last, index in ltmr.REGISTER_BLOCKS:
        mappable = index in ltmr_profile.TPDO_MAPPABLE_INDICES + ltmr_profile.RPDO_MAPPABLE_INDICES
        members = [
            (reg - first + 1, _register_entry(reg, mappable))
            for reg in range(first, last + 1)
            if not ltmr.is_forbidden(reg)
        ]
        objects.append(compound(index, _LTMR_GROUPS[index], members))
    return objects


def ltmr_communication_objects(product_code: int = ltmr_profile.PRODUCT_CODE_REMOTE) -> list:
    """The communication profile objects 0x1000-0x1A03 with the manual's factory values (L757-1653)."""
    u32 = UNSIGNED32
    objects = [
        var(0x1000, "Device type", u32, "ro", 0x00000000),
        var(0x1001, "Error register", UNSIGNED8, "ro", 0x00),
        compound(
            0x1003,
            "Pre-defined error field",
            [(n, Entry(f"Standard error field {n}", u32, "ro", 0)) for n in range(1, 6)],
            "ARRAY",
            sub0=Entry("Number of errors", UNSIGNED8, "rw", 0),
        ),  # only 0 can be written
        # 0x1004 and 0x1020 sub 0 are UNSIGNED32 as printed; the second 0x1004 "sub 0x01" is sub 2 (A17)
        compound(
            0x1004,
            "Number of PDOs supported",
            [
                (1, Entry("Number of synchronous PDOs", u32, "ro", 0)),
                (2, Entry("Number of asynchronous PDOs", u32, "ro", 0)),
            ],
            "ARRAY",
            sub0=Entry("Number of PDOs supported", u32, "ro", 0x00040004),
        ),
        var(0x1005, "COB-ID SYNC message", u32, "rw", 0x80),
        var(0x1006, "Communication cycle period", u32, "rw", 0),
        var(0x1007, "Synchronous window length", u32, "rw", 0),
        var(0x1008, "Manufacturer device name", VISIBLE_STRING, "const", ltmr_profile.DEVICE_NAME),
        var(0x1009, "Manufacturer hardware version", VISIBLE_STRING, "const", ltmr_profile.HARDWARE_VERSION),
        var(0x100A, "Manufacturer software version", VISIBLE_STRING, "const", ltmr_profile.SOFTWARE_VERSION),
        var(0x100C, "Guard time", UNSIGNED16, "rw", 0),
        var(0x100D, "Life time factor", UNSIGNED8, "rw", 0),
        var(0x1014, "COB-ID EMCY", u32, "rw", "$NODEID+0x80"),
        compound(
            0x1016,
            "Consumer heartbeat time",
            [(1, Entry("Consumer heartbeat time 1", u32, "rw", 0))],
            "ARRAY",
            sub0=Entry("Number of entries", UNSIGNED8, "ro", 1),
        ),
        var(0x1017, "Producer heartbeat time", UNSIGNED16, "rw", 0),
        compound(
            0x1018,
            "Identity object",
            [
                (1, Entry("Vendor ID", u32, "ro", ltmr_profile.VENDOR_ID)),
                (2, Entry("Product code", u32, "ro", product_code)),
                (3, Entry("Revision number", u32, "ro", ltmr_profile.PRODUCT_REVISION)),
                (4, Entry("Serial number", u32, "ro", 0)),
            ],
            sub0=Entry("Number of entries", UNSIGNED8, "ro", 4),
        ),
        compound(
            0x1020,
            "Verify configuration",
            [(1, Entry("Configuration date", u32, "rw", 0)), (2, Entry("Configuration time", u32, "rw", 0))],
            "ARRAY",
            sub0=Entry("Number of entries", u32, "ro", 2),
        ),
        compound(
            0x1029,
            "Error behavior",
            [(1, Entry("Communication error", UNSIGNED8, "rw", 0))],
            "ARRAY",
            sub0=Entry("Number of error classes", UNSIGNED8, "ro", 1),
        ),
        sdo_server(),
    ]
    # PDO1 and PDO4 valid, PDO2/3 disabled (bit 31); every transmission type 0xFF (A4)
    cob_offsets = {1: 0x000, 2: 0x80000000, 3: 0x80000000, 4: 0x000}
    mappings = {
        1: (ltmr_profile.RPDO1_DEFAULT, ltmr_profile.TPDO1_DEFAULT),
        2: ((), ()),
        3: ((), ()),
        4: (ltmr_profile.RPDO4_DEFAULT, ltmr_profile.TPDO4_DEFAULT),
    }
    for k in range(1, 5):
        rx_map, tx_map = mappings[k]
        objects += [
            pdo_communication(0x1400 + k - 1, cob_offsets[k] + 0x200 + 0x100 * (k - 1), transmit=False),
            pdo_mapping(0x1600 + k - 1, rx_map),
            pdo_communication(0x1800 + k - 1, cob_offsets[k] + 0x180 + 0x100 * (k - 1), transmit=True),
            pdo_mapping(0x1A00 + k - 1, tx_map),
        ]
    return objects


def ltmr_pkw_object() -> EdsObject:
    """0x3000:01..04, the PKW words as four UNSIGNED32 (manual L337-360)."""
    return compound(
        ltmr_profile.PKW_INDEX,
        "PKW",
        [
            (1, Entry("PKW request words 1-2", UNSIGNED32, "rw", 0, pdo_mapping=True)),
            (2, Entry("PKW request words 3-4", UNSIGNED32, "rw", 0, pdo_mapping=True)),
            (3, Entry("PKW response words 1-2", UNSIGNED32, "ro", 0, pdo_mapping=True)),
            (4, Entry("PKW response words 3-4", UNSIGNED32, "ro", 0, pdo_mapping=True)),
        ],
    )


def ltmr_eds(product_code: int = ltmr_profile.PRODUCT_CODE_REMOTE) -> EdsFile:
    return EdsFile(
        file_name="ltmr.eds",
        description="TeSys T LTMR motor management controller, CANopen",
        created_by="softplc runtime/devices/ltmr/eds.py",
        device_info={
            "VendorName": "Schneider Electric",
            "VendorNumber": ltmr_profile.VENDOR_ID,
            "ProductName": "TeSys T LTMR",
            "ProductNumber": product_code,
            "RevisionNumber": ltmr_profile.PRODUCT_REVISION,
            **{f"BaudRate_{rate}": 1 for rate in (10, 20, 50, 125, 250, 500, 800, 1000)},
            "SimpleBootUpMaster": 0,
            "SimpleBootUpSlave": 1,
            "Granularity": 8,
            "DynamicChannelsSupported": 0,
            "GroupMessaging": 0,
            "NrOfRXPDO": 4,
            "NrOfTXPDO": 4,
            "LSS_Supported": 0,
        },
        objects=(*ltmr_communication_objects(product_code), *ltmr_register_objects(), ltmr_pkw_object()),
        comments=(
            "Written from the manual DOCA0132EN (TeSys T LTMR, Using the CANopen Communication Network,",
            "chapter object dictionary and register tables), not Schneider Electric's EDS file.",
            "Generated by python -m softplc.runtime.devices from runtime/devices/ltmr/registers.py, bits.py "
            "and profile.py. Do not edit.",
            "Register n is sub-entry [n] of 0x2000-0x2008 / 0x200D. Forbidden registers are left out.",
        ),
    )
