"""The FC 280's EDS (io_config/eds/fc280.eds), written from manual 003 and
digest 003 ([M] manual, [S] CiA 301/402, [P] placeholder): the communication
objects of Tabelle 7.1, every parameter of parameters.PARAMETERS as object
2000h + g*100 + nn (§5.1) with its type, access, factory setting, the
limits where store.py narrows the type's, and PDO mapping flag, and the CiA 402 velocity mode objects the
manual names (§4.3.1).

Array parameters (3-10, 5-40) have element [i] at sub-index i + 1 and the
number of elements at sub-index 0, as every CiA 301 ARRAY and as
parameters.sdo_object has it (the manual only says "the correct subindex",
digest 003 A35).
"""

from __future__ import annotations

from ...io.canopen.eds import (
    INTEGER16,
    INTEGER32,
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
from .parameters import PARAMETERS, Parameter
from .store import PDO_MAPPABLE, RANGES, READ_ONLY, TEXTS, limits

FC280_VENDOR_ID = 200008  # [M] 0x1018:01 "200008 Dez." (Tabelle 7.7)
FC280_DEVICE_TYPE = 0x00010192  # [M] frequency converter (1), profile 402 (Tabelle 7.2)
TPDO_INHIBIT_100US = 300  # [M] 30 ms (§4.1.4)
STORAGE_ON_COMMAND = 0x00000001  # [S] 1010h/1011h read: saves/restores on command (CiA 301)
SUPPORTED_DRIVE_MODES = 0x00000002  # [S] 6502h bit 1: velocity mode (vl), the one the manual describes

# CiA 402 vl settings: [P] values that match the parameters' factory settings
# (1500 RPM = 50 Hz, 4-14 65 Hz = 1950 RPM, ramps 3-41/3-42 3 s, 3-81 1 s);
# the drive keeps them, it ramps and limits by the parameters (simulator choice).
VL_MAX_RPM = 1950
VL_DELTA_RPM = 1500
VL_RAMP_S = 3
VL_QUICK_STOP_S = 1

_TYPES = {
    "UInt8": UNSIGNED8,
    "UInt16": UNSIGNED16,
    "UInt32": UNSIGNED32,
    "Int16": INTEGER16,
    "Int32": INTEGER32,
    "VisStr": VISIBLE_STRING,
}

# The parameters' names in English (the manual's are German: parameters.py)
ENGLISH = {
    "0-01": "Language",
    "0-10": "Active set-up",
    "0-11": "Programming set-up",
    "1-00": "Configuration mode",
    "1-01": "Motor control principle",
    "1-23": "Motor nominal frequency",
    "1-25": "Motor nominal speed",
    "2-01": "DC brake current",
    "2-02": "DC braking time",
    "3-00": "Reference range",
    "3-02": "Minimum reference",
    "3-03": "Maximum reference",
    "3-10": "Preset reference",
    "3-19": "Jog speed RPM",
    "3-41": "Ramp 1 ramp-up time",
    "3-42": "Ramp 1 ramp-down time",
    "3-51": "Ramp 2 ramp-up time",
    "3-52": "Ramp 2 ramp-down time",
    "3-81": "Quick stop ramp time",
    "4-14": "Motor speed high limit Hz",
    "5-40": "Function relay",
    "8-01": "Control site",
    "8-02": "Control source",
    "8-03": "Control word timeout time",
    "8-04": "Control word timeout function",
    "8-07": "Diagnosis trigger",
    "8-10": "Control word profile",
    "8-14": "Configurable control word CTW",
    "8-50": "Coasting select",
    "8-51": "Quick stop select",
    "8-52": "DC brake select",
    "8-53": "Start select",
    "8-54": "Reversing select",
    "8-55": "Set-up select",
    "8-56": "Preset reference select",
    "8-90": "Bus jog 1 speed",
    "8-91": "Bus jog 2 speed",
    "10-01": "Baud rate select",
    "10-02": "Node ID",
    "10-05": "Transmit error counter",
    "10-06": "Receive error counter",
    "10-31": "Store data values",
    "10-33": "Store always",
    "15-40": "FC type",
    "15-49": "SW ID control card",
    "16-03": "Status word",
    "16-05": "Main actual value",
    "16-80": "Fieldbus CTW 1",
    "16-82": "Fieldbus REF 1",
    "16-84": "Fieldbus comm. status",
    "16-90": "Alarm word",
    "16-91": "Alarm word 2",
    "16-92": "Warning word",
    "16-93": "Warning word 2",
    "16-97": "Alarm word 3",
}


def parameter_entry(p: Parameter, name: str) -> Entry:
    """One value of a parameter: [M] for the rows of Tabelle 6.1, the
    simulator's choice (parameters.py) for the others."""
    access = "ro" if p.number in READ_ONLY else "rw"
    if p.type == "VisStr":
        return Entry(name, VISIBLE_STRING, access, TEXTS.get(p.number, ""))
    low, high = limits(p) if p.number in RANGES else (None, None)  # only where narrower than the type
    return Entry(name, _TYPES[p.type], access, p.default, pdo_mapping=p.number in PDO_MAPPABLE, low=low, high=high)


def parameter_objects() -> list:
    objects = []
    for p in PARAMETERS.values():
        name = f"{ENGLISH[p.number]} ({p.number})"
        if p.elements:
            members = [(i + 1, parameter_entry(p, f"{name}[{i}]")) for i in range(p.elements)]
            objects.append(compound(p.index, name, members, "ARRAY"))
        else:
            objects.append(EdsObject(p.index, name, "VAR", entry=parameter_entry(p, name)))
    return objects


def _delta(rpm: int, seconds: int) -> list:
    return [(1, Entry("Delta speed", UNSIGNED32, "rw", rpm)), (2, Entry("Delta time", UNSIGNED16, "rw", seconds))]


def _ratio(name: str, data_type: int) -> list:
    return [
        (1, Entry(f"{name} numerator", data_type, "rw", 1)),
        (2, Entry(f"{name} denominator", data_type, "rw", 1)),
    ]


def profile_objects() -> list:
    """The DSP 402 objects of §4.3.1 (603Fh: §7.1.3), types and access of CiA 402 [S]."""
    i16, u16, u32 = INTEGER16, UNSIGNED16, UNSIGNED32
    return [
        var(0x603F, "Error code", u16, "ro", 0),
        var(0x6040, "Controlword", u16, "rw", 0, pdo_mapping=True),
        var(0x6041, "Statusword", u16, "ro", 0, pdo_mapping=True),
        var(0x6042, "vl target velocity", i16, "rw", 0, pdo_mapping=True),  # RPM by default [M] §4.3.5
        var(0x6043, "vl velocity demand", i16, "ro", 0, pdo_mapping=True),
        var(0x6044, "vl control effort", i16, "ro", 0, pdo_mapping=True),  # [M] "VI Regelungsaufwand"
        var(0x6045, "vl manipulated velocity", i16, "ro", 0, pdo_mapping=True),  # [S] not in the manual's list
        compound(
            0x6046,
            "vl velocity min max amount",
            [
                (1, Entry("vl velocity min amount", u32, "rw", 0)),
                (2, Entry("vl velocity max amount", u32, "rw", VL_MAX_RPM)),
            ],
            "ARRAY",
        ),
        compound(0x6048, "vl velocity acceleration", _delta(VL_DELTA_RPM, VL_RAMP_S)),
        compound(0x6049, "vl velocity deceleration", _delta(VL_DELTA_RPM, VL_RAMP_S)),
        compound(0x604A, "vl velocity quick stop", _delta(VL_DELTA_RPM, VL_QUICK_STOP_S)),
        compound(0x604B, "vl set-point factor", _ratio("vl set-point factor", i16), "ARRAY"),  # [S] not listed
        compound(0x604C, "vl dimension factor", _ratio("vl dimension factor", INTEGER32), "ARRAY"),
        var(0x6502, "Supported drive modes", u32, "ro", SUPPORTED_DRIVE_MODES),
    ]


def communication_objects() -> list:
    """1000h-1A02h (Tabelle 7.1)."""
    u8, u16, u32 = UNSIGNED8, UNSIGNED16, UNSIGNED32

    def storage(index: int, name: str, what: str) -> object:
        members = [(n, Entry(f"{what} {n}", u32, "rw", STORAGE_ON_COMMAND if n != 3 else 0)) for n in range(1, 5)]
        return compound(index, name, members, "ARRAY")  # [M] subs 1, 2, 4; 3 reserved (Tabellen 7.5, 7.6)

    objects = [
        var(0x1000, "Device type", u32, "ro", FC280_DEVICE_TYPE),  # [M]
        var(0x1001, "Error register", u8, "ro", 0),  # [M] bit 0 generic only (Tabelle 7.3)
        var(0x1005, "COB-ID SYNC", u32, "rw", 0x80),  # [M] object; 0x80 [S] (the manual prints 125, A1)
        var(0x1008, "Manufacturer device name", VISIBLE_STRING, "ro", TEXTS["15-40"]),  # [P] as 15-40
        var(0x100A, "Manufacturer software version", VISIBLE_STRING, "ro", TEXTS["15-49"]),  # [P] as 15-49
        var(0x100C, "Guard time", u16, "rw", 0),  # [M] ms
        var(0x100D, "Life time factor", u8, "rw", 0),  # [M]
        storage(0x1010, "Store parameters", "Store parameters"),  # [M] signature "save"
        storage(0x1011, "Restore default parameters", "Restore parameters"),  # [M] signature "load"
        var(0x1014, "COB-ID EMCY", u32, "ro", "$NODEID+0x80"),  # [M] read-only
        var(0x1017, "Producer heartbeat time", u16, "rw", 0),  # [M] 0 = not used
        compound(
            0x1018,
            "Identity object",
            [
                (1, Entry("Vendor ID", u32, "ro", FC280_VENDOR_ID)),  # [M]
                (2, Entry("Product code", u32, "ro", 0)),  # [P]
                (3, Entry("Revision number", u32, "ro", 0)),  # [P]
                (4, Entry("Serial number", u32, "ro", 0)),  # [P]
            ],
            sub0=Entry("Number of entries", u8, "ro", 4),
        ),
        sdo_server(),
    ]
    # Three RPDOs and three TPDOs (§4.1, Tabelle 7.1) [M]; TPDO inhibit time 300 = 30 ms [M] (§4.1.4).
    # The default mappings are only in a picture of the manual (digest 003 §2.7): the ones here are [P]:
    # PDO1 the FC profile words, PDO2 (disabled) the DSP 402 words, PDO3 empty and disabled.
    rx = {1: (0x26900010, 0x26920010), 2: (0x60400010, 0x60420010), 3: ()}
    tx = {1: (0x26430010, 0x26450010), 2: (0x60410010, 0x60440010), 3: ()}
    disabled = {1: 0, 2: 0x80000000, 3: 0x80000000}
    for k in (1, 2, 3):
        objects += [
            pdo_communication(0x1400 + k - 1, disabled[k] + 0x200 + 0x100 * (k - 1), transmit=False),
            pdo_mapping(0x1600 + k - 1, rx[k], slots=8),
            pdo_communication(
                0x1800 + k - 1, disabled[k] + 0x180 + 0x100 * (k - 1), transmit=True, inhibit_time=TPDO_INHIBIT_100US
            ),
            pdo_mapping(0x1A00 + k - 1, tx[k], slots=8),
        ]
    return objects


def fc280_objects() -> list:
    return communication_objects() + parameter_objects() + profile_objects()


def fc280_eds() -> EdsFile:
    return EdsFile(
        file_name="fc280.eds",
        description="Danfoss VLT Midi Drive FC 280, CANopen",
        created_by="softplc runtime/devices/fc280/eds.py",
        device_info={
            "VendorName": "Danfoss",
            "VendorNumber": FC280_VENDOR_ID,
            "ProductName": "VLT FC 280",
            "ProductNumber": 0,
            "RevisionNumber": 0,
            **{f"BaudRate_{rate}": int(rate != 100) for rate in (10, 20, 50, 125, 250, 500, 800, 1000)},
            "SimpleBootUpMaster": 0,
            "SimpleBootUpSlave": 1,
            "Granularity": 8,
            "DynamicChannelsSupported": 0,
            "GroupMessaging": 0,
            "NrOfRXPDO": 3,
            "NrOfTXPDO": 3,
            "LSS_Supported": 0,
        },
        objects=tuple(fc280_objects()),
        comments=(
            "Written from the Danfoss FC 280 CANopen programming guide (digest 003), not Danfoss's EDS file.",
            "Values the manual gives: device type, vendor ID 200008, the communication objects of Tabelle 7.1,",
            "the DSP 402 and FC profile objects, the factory settings of Tabelle 6.1, TPDO inhibit time 300",
            "(30 ms). Every parameter the softplc FC 280 support uses is object 2000h + parameter number;",
            "array parameters have element [i] at sub-index i+1. Placeholders: product code, revision, device name",
            "and software version strings, the SYNC COB-ID 0x80 (manual prints 125), the factory settings of",
            "the parameters the manual only names, the 0x6000 objects' types and values (CiA 402) and every",
            "default PDO mapping (the manual shows them only in a picture).",
            "Generated by python -m softplc.runtime.devices. Do not edit.",
        ),
    )
