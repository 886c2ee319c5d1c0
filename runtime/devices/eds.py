"""EDS files (CiA 306 electronic data sheets) written from device knowledge.

    python -m softplc.runtime.devices.eds      # rewrites io_config/eds/ltmr.eds and fc280.eds

The shipped EDS files are generated, never edited by hand: the LTMR file from
runtime/devices/ltmr.py (the register map of manual 001) and its
communication profile (manual 001 §4), the FC 280 file from digest 003. A
test regenerates both and compares them byte for byte, so the EDS cannot
drift from the Python tables. The writer itself is generic: VAR, ARRAY and
RECORD objects with DataType, AccessType, DefaultValue ($NODEID+ allowed),
PDOMapping and optional LowLimit/HighLimit, in the INI layout that
canopen.import_od reads.
"""
from __future__ import annotations

import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Optional, Union

from . import ltmr

# CiA 301 data type codes
BOOLEAN = 0x0001
INTEGER8 = 0x0002
INTEGER16 = 0x0003
INTEGER32 = 0x0004
UNSIGNED8 = 0x0005
UNSIGNED16 = 0x0006
UNSIGNED32 = 0x0007
VISIBLE_STRING = 0x0009

_OBJECT_TYPES = {"VAR": 0x7, "ARRAY": 0x8, "RECORD": 0x9}
_ACCESS = ("ro", "rw", "wo", "const")

Default = Union[int, str, None]   # an int, "$NODEID+0x180", or the text of a string object

EDS_DIR = Path(__file__).resolve().parents[2] / "io_config" / "eds"


@dataclass(frozen=True)
class Entry:
    """One value: a VAR object, or one sub-index of an ARRAY/RECORD."""
    name: str
    data_type: int
    access: str = "ro"
    default: Default = 0
    pdo_mapping: bool = False
    low: Optional[int] = None
    high: Optional[int] = None

    def __post_init__(self):
        if self.access not in _ACCESS:
            raise ValueError(f"{self.name}: access {self.access!r} is not one of {_ACCESS}")


@dataclass(frozen=True)
class EdsObject:
    index: int
    name: str
    kind: str = "VAR"                 # VAR, ARRAY or RECORD
    entry: Optional[Entry] = None     # VAR only
    members: tuple = ()               # ARRAY/RECORD: ((subindex, Entry), ...)

    def __post_init__(self):
        if self.kind not in _OBJECT_TYPES:
            raise ValueError(f"0x{self.index:04X}: object kind {self.kind!r} is not one of {tuple(_OBJECT_TYPES)}")
        if (self.kind == "VAR") != (self.entry is not None):
            raise ValueError(f"0x{self.index:04X}: a VAR has one entry, an ARRAY/RECORD has members")


@dataclass(frozen=True)
class EdsFile:
    file_name: str
    description: str
    created_by: str
    device_info: dict                 # [DeviceInfo] keys in order (VendorName, VendorNumber ...)
    objects: tuple
    comments: tuple = ()
    file_info_extra: dict = field(default_factory=dict)


def var(index: int, name: str, data_type: int, access: str = "ro", default: Default = 0, **extra) -> EdsObject:
    return EdsObject(index, name, "VAR", entry=Entry(name, data_type, access, default, **extra))


def compound(index: int, name: str, members, kind: str = "RECORD", sub0: Optional[Entry] = None) -> EdsObject:
    """An ARRAY or RECORD. Without an explicit `sub0`, sub-index 0 is the
    read-only UNSIGNED8 "highest sub-index supported"."""
    members = tuple(members)
    if sub0 is None:
        sub0 = Entry("Highest sub-index supported", UNSIGNED8, "ro", max(sub for sub, _ in members))
    return EdsObject(index, name, kind, members=((0, sub0), *members))


# ---------------------------------------------------------------------------
# Writer
# ---------------------------------------------------------------------------

def _value(default: Default) -> str:
    if isinstance(default, bool):
        return str(int(default))
    if isinstance(default, int):
        return f"0x{default:X}" if default >= 0 else str(default)
    return default


def _device_info_value(key: str, value) -> str:
    if key in ("VendorNumber", "ProductNumber", "RevisionNumber"):
        return f"0x{value:08X}"
    return str(int(value)) if isinstance(value, (bool, int)) else str(value)


def _entry_lines(entry: Entry, object_type: int) -> list:
    lines = [f"ParameterName={entry.name}",
             f"ObjectType=0x{object_type:X}",
             f"DataType=0x{entry.data_type:04X}",
             f"AccessType={entry.access}"]
    if entry.low is not None:
        lines.append(f"LowLimit={_value(entry.low)}")
    if entry.high is not None:
        lines.append(f"HighLimit={_value(entry.high)}")
    if entry.default is not None:
        lines.append(f"DefaultValue={_value(entry.default)}")
    lines.append(f"PDOMapping={int(entry.pdo_mapping)}")
    return lines


def _section(title: str, lines) -> str:
    return f"[{title}]\n" + "".join(f"{line}\n" for line in lines) + "\n"


def _object_list(title: str, objects) -> str:
    indices = [obj.index for obj in objects]
    return _section(title, [f"SupportedObjects={len(indices)}"]
                    + [f"{n}=0x{index:04X}" for n, index in enumerate(indices, 1)])


def render(eds: EdsFile) -> str:
    """The EDS text. Deterministic: no dates from the clock, objects in index order."""
    for obj in eds.objects:
        for text in (obj.name, *(e.name for _, e in obj.members), obj.entry.name if obj.entry else ""):
            if not text.isascii() or ";" in text:
                raise ValueError(f"0x{obj.index:04X}: EDS names must be ASCII without ';': {text!r}")
    objects = sorted(eds.objects, key=lambda o: o.index)
    out = ["".join(f"; {line}\n" for line in eds.comments) + "\n" if eds.comments else ""]
    out.append(_section("FileInfo", [
        f"FileName={eds.file_name}", "FileVersion=1", "FileRevision=0", "EDSVersion=4.0",
        f"Description={eds.description}", f"CreatedBy={eds.created_by}",
        *(f"{key}={value}" for key, value in eds.file_info_extra.items())]))
    out.append(_section("DeviceInfo", [f"{key}={_device_info_value(key, value)}"
                                       for key, value in eds.device_info.items()]))
    out.append(_section("DummyUsage", [f"Dummy000{n}=0" for n in range(1, 8)]))
    if eds.comments:
        out.append(_section("Comments", [f"Lines={len(eds.comments)}"]
                            + [f"Line{n}={line}" for n, line in enumerate(eds.comments, 1)]))
    mandatory = [o for o in objects if o.index in (0x1000, 0x1001, 0x1018)]
    optional = [o for o in objects if o not in mandatory and (0x1000 <= o.index < 0x2000 or o.index >= 0x6000)]
    manufacturer = [o for o in objects if 0x2000 <= o.index < 0x6000]
    out += [_object_list("MandatoryObjects", mandatory), _object_list("OptionalObjects", optional),
            _object_list("ManufacturerObjects", manufacturer)]
    for obj in objects:
        if obj.kind == "VAR":
            out.append(_section(f"{obj.index:04X}", _entry_lines(obj.entry, _OBJECT_TYPES["VAR"])))
            continue
        out.append(_section(f"{obj.index:04X}", [f"ParameterName={obj.name}",
                                                  f"ObjectType=0x{_OBJECT_TYPES[obj.kind]:X}",
                                                  f"SubNumber={len(obj.members)}"]))
        for sub, entry in obj.members:
            out.append(_section(f"{obj.index:04X}sub{sub:X}", _entry_lines(entry, _OBJECT_TYPES["VAR"])))
    return "".join(out)


# ---------------------------------------------------------------------------
# CiA 301 communication objects shared by both devices
# ---------------------------------------------------------------------------

def _nodeid(offset: int) -> str:
    return f"$NODEID+0x{offset:08X}"


def pdo_communication(index: int, cob_offset: int, transmit: bool, transmission_type: int = 0xFF,
                      inhibit_time: int = 0, event_timer: int = 0) -> EdsObject:
    """0x1400+k (RPDO) or 0x1800+k (TPDO) communication parameters; the COB-ID is
    $NODEID+cob_offset (bit 31 set in the offset = PDO disabled)."""
    members = [(1, Entry("COB-ID", UNSIGNED32, "rw", _nodeid(cob_offset))),
               (2, Entry("Transmission type", UNSIGNED8, "rw", transmission_type))]
    if transmit:
        members += [(3, Entry("Inhibit time", UNSIGNED16, "rw", inhibit_time)),
                    (4, Entry("Reserved", UNSIGNED8, "rw", 0)),
                    (5, Entry("Event timer", UNSIGNED16, "rw", event_timer))]
    kind = "TPDO" if transmit else "RPDO"
    number = (index & 0xFF) + 1
    return compound(index, f"{kind}{number} communication parameter", members,
                    sub0=Entry("Highest sub-index supported", UNSIGNED8, "ro", len(members)))


def pdo_mapping(index: int, entries, slots: int = 4, kind: str = "ARRAY") -> EdsObject:
    """0x1600+k or 0x1A00+k: sub 0 = number of mapped entries (rw), subs 1..slots."""
    entries = tuple(entries)
    members = [(n, Entry(f"Mapping entry {n}", UNSIGNED32, "rw", entries[n - 1] if n <= len(entries) else 0))
               for n in range(1, slots + 1)]
    pdo = ("RPDO" if index < 0x1A00 else "TPDO") + str((index & 0xFF) + 1)
    return compound(index, f"{pdo} mapping parameter", members, kind,
                    sub0=Entry("Number of mapped objects", UNSIGNED8, "rw", len(entries)))


def sdo_server() -> EdsObject:
    return compound(0x1200, "Server SDO parameter", [
        (1, Entry("COB-ID client to server", UNSIGNED32, "ro", "$NODEID+0x600")),
        (2, Entry("COB-ID server to client", UNSIGNED32, "ro", "$NODEID+0x580"))],
        sub0=Entry("Number of entries", UNSIGNED8, "ro", 2))


# ---------------------------------------------------------------------------
# TeSys T LTMR (manual 001 §4 and the register map of ltmr.py)
# ---------------------------------------------------------------------------

_LTMR_GROUPS = {0x2000: "Identification variables", 0x2001: "Statistics variables",
                0x2002: "Trip history variables", 0x2003: "Trip history extension variables",
                0x2004: "Monitoring variables", 0x2005: "Configuration variables",
                0x2006: "Configuration variables 2", 0x2007: "Setting variables",
                0x2008: "Command variables", 0x200D: "Custom logic variables"}

# Enumerations whose range the manual prints (DT_OutputFallbackStrategy L2171, DT_CANopenExtBaudRate L2003)
_LTMR_HIGH_LIMITS = {ltmr.REG_HMI_FALLBACK: 5, ltmr.REG_NETWORK_FALLBACK: 5, ltmr.REG_BAUD_RATE: 9}


def _register_entry(reg: int, mappable: bool) -> Entry:
    register = ltmr.REGISTERS[reg]
    high = _LTMR_HIGH_LIMITS.get(reg)
    low = None
    if register.kind == "reserved" and register.access == "rw":
        low = high = 0    # "Reserved, in Read/Write tables, means that you must write 0" (L1717)
    return Entry(ltmr.register_label(reg), INTEGER16 if register.type == "Int" else UNSIGNED16,
                 register.access, ltmr.FACTORY_SETTINGS.get(reg, 0), mappable, low, high)


def ltmr_register_objects() -> list:
    """0x2000-0x2008 and 0x200D: one sub-entry per register, Forbidden registers
    left out (a request for them is answered "sub-index does not exist", A21)."""
    objects = []
    for first, last, index in ltmr.REGISTER_BLOCKS:
        mappable = index in ltmr.TPDO_MAPPABLE_INDICES + ltmr.RPDO_MAPPABLE_INDICES
        members = [(reg - first + 1, _register_entry(reg, mappable))
                   for reg in range(first, last + 1) if not ltmr.is_forbidden(reg)]
        objects.append(compound(index, _LTMR_GROUPS[index], members))
    return objects


def ltmr_communication_objects(product_code: int = ltmr.PRODUCT_CODE_REMOTE) -> list:
    """The communication profile objects 0x1000-0x1A03 with the manual's factory values (L757-1653)."""
    u32 = UNSIGNED32
    objects = [
        var(0x1000, "Device type", u32, "ro", 0x00000000),
        var(0x1001, "Error register", UNSIGNED8, "ro", 0x00),
        compound(0x1003, "Pre-defined error field",
                 [(n, Entry(f"Standard error field {n}", u32, "ro", 0)) for n in range(1, 6)], "ARRAY",
                 sub0=Entry("Number of errors", UNSIGNED8, "rw", 0)),   # only 0 can be written
        # 0x1004 and 0x1020 sub 0 are UNSIGNED32 as printed; the second 0x1004 "sub 0x01" is sub 2 (A17)
        compound(0x1004, "Number of PDOs supported", [
            (1, Entry("Number of synchronous PDOs", u32, "ro", 0)),
            (2, Entry("Number of asynchronous PDOs", u32, "ro", 0))], "ARRAY",
            sub0=Entry("Number of PDOs supported", u32, "ro", 0x00040004)),
        var(0x1005, "COB-ID SYNC message", u32, "rw", 0x80),
        var(0x1006, "Communication cycle period", u32, "rw", 0),
        var(0x1007, "Synchronous window length", u32, "rw", 0),
        var(0x1008, "Manufacturer device name", VISIBLE_STRING, "const", ltmr.DEVICE_NAME),
        var(0x1009, "Manufacturer hardware version", VISIBLE_STRING, "const", ltmr.HARDWARE_VERSION),
        var(0x100A, "Manufacturer software version", VISIBLE_STRING, "const", ltmr.SOFTWARE_VERSION),
        var(0x100C, "Guard time", UNSIGNED16, "rw", 0),
        var(0x100D, "Life time factor", UNSIGNED8, "rw", 0),
        var(0x1014, "COB-ID EMCY", u32, "rw", "$NODEID+0x80"),
        compound(0x1016, "Consumer heartbeat time", [(1, Entry("Consumer heartbeat time 1", u32, "rw", 0))],
                 "ARRAY", sub0=Entry("Number of entries", UNSIGNED8, "ro", 1)),
        var(0x1017, "Producer heartbeat time", UNSIGNED16, "rw", 0),
        compound(0x1018, "Identity object", [
            (1, Entry("Vendor ID", u32, "ro", ltmr.VENDOR_ID)),
            (2, Entry("Product code", u32, "ro", product_code)),
            (3, Entry("Revision number", u32, "ro", ltmr.PRODUCT_REVISION)),
            (4, Entry("Serial number", u32, "ro", 0))],
            sub0=Entry("Number of entries", UNSIGNED8, "ro", 4)),
        compound(0x1020, "Verify configuration", [
            (1, Entry("Configuration date", u32, "rw", 0)),
            (2, Entry("Configuration time", u32, "rw", 0))], "ARRAY",
            sub0=Entry("Number of entries", u32, "ro", 2)),
        compound(0x1029, "Error behavior", [(1, Entry("Communication error", UNSIGNED8, "rw", 0))], "ARRAY",
                 sub0=Entry("Number of error classes", UNSIGNED8, "ro", 1)),
        sdo_server(),
    ]
    # PDO1 and PDO4 valid, PDO2/3 disabled (bit 31); every transmission type 0xFF (A4)
    cob_offsets = {1: 0x000, 2: 0x80000000, 3: 0x80000000, 4: 0x000}
    mappings = {1: (ltmr.RPDO1_DEFAULT, ltmr.TPDO1_DEFAULT), 2: ((), ()), 3: ((), ()),
                4: (ltmr.RPDO4_DEFAULT, ltmr.TPDO4_DEFAULT)}
    for k in range(1, 5):
        rx_map, tx_map = mappings[k]
        objects += [pdo_communication(0x1400 + k - 1, cob_offsets[k] + 0x200 + 0x100 * (k - 1), transmit=False),
                    pdo_mapping(0x1600 + k - 1, rx_map),
                    pdo_communication(0x1800 + k - 1, cob_offsets[k] + 0x180 + 0x100 * (k - 1), transmit=True),
                    pdo_mapping(0x1A00 + k - 1, tx_map)]
    return objects


def ltmr_pkw_object() -> EdsObject:
    """0x3000:01..04, the PKW words as four UNSIGNED32 (manual L337-360)."""
    return compound(ltmr.PKW_INDEX, "PKW", [
        (1, Entry("PKW request words 1-2", UNSIGNED32, "rw", 0, pdo_mapping=True)),
        (2, Entry("PKW request words 3-4", UNSIGNED32, "rw", 0, pdo_mapping=True)),
        (3, Entry("PKW response words 1-2", UNSIGNED32, "ro", 0, pdo_mapping=True)),
        (4, Entry("PKW response words 3-4", UNSIGNED32, "ro", 0, pdo_mapping=True))])


def ltmr_eds(product_code: int = ltmr.PRODUCT_CODE_REMOTE) -> EdsFile:
    return EdsFile(
        file_name="ltmr.eds",
        description="TeSys T LTMR motor management controller, CANopen",
        created_by="softplc runtime/devices/eds.py",
        device_info={"VendorName": "Schneider Electric", "VendorNumber": ltmr.VENDOR_ID,
                     "ProductName": "TeSys T LTMR", "ProductNumber": product_code,
                     "RevisionNumber": ltmr.PRODUCT_REVISION,
                     **{f"BaudRate_{rate}": 1 for rate in (10, 20, 50, 125, 250, 500, 800, 1000)},
                     "SimpleBootUpMaster": 0, "SimpleBootUpSlave": 1, "Granularity": 8,
                     "DynamicChannelsSupported": 0, "GroupMessaging": 0,
                     "NrOfRXPDO": 4, "NrOfTXPDO": 4, "LSS_Supported": 0},
        objects=(*ltmr_communication_objects(product_code), *ltmr_register_objects(), ltmr_pkw_object()),
        comments=(
            "Written from the manual DOCA0132EN (TeSys T LTMR, Using the CANopen Communication Network,",
            "chapter object dictionary and register tables), not Schneider Electric's EDS file.",
            "Generated by python -m softplc.runtime.devices.eds from runtime/devices/ltmr.py. Do not edit.",
            "Register n is sub-entry [n] of 0x2000-0x2008 / 0x200D. Forbidden registers are left out.",
        ))


# ---------------------------------------------------------------------------
# Danfoss FC 280 skeleton (digest 003; [M] manual, [P] placeholder)
# ---------------------------------------------------------------------------

FC280_VENDOR_ID = 200008          # [M] 0x1018:01 "200008 dec" (digest 003 §6)
FC280_DEVICE_TYPE = 0x00010192    # [M] frequency converter (1), profile 402 (digest 003 §6)


def _fc_param(group: int, number: int) -> int:
    """Drive parameter g-nn is object 0x2000 + g*100 + nn (digest 003 §5.1)."""
    return 0x2000 + group * 100 + number


def fc280_objects() -> list:
    u8, u16, u32 = UNSIGNED8, UNSIGNED16, UNSIGNED32
    delta = [(1, Entry("Delta speed", u32, "rw", 0)), (2, Entry("Delta time", u16, "rw", 0))]
    objects = [
        var(0x1000, "Device type", u32, "ro", FC280_DEVICE_TYPE),                 # [M]
        var(0x1001, "Error register", u8, "ro", 0),                              # [M] bit 0 generic only
        var(0x1005, "COB-ID SYNC", u32, "rw", 0x80),          # [M] object; 0x80 [P] (manual prints 125)
        var(0x1008, "Manufacturer device name", VISIBLE_STRING, "ro", "FC 280"),       # [P] par. 15-40
        var(0x100A, "Manufacturer software version", VISIBLE_STRING, "ro", "1.1"),   # [P] par. 15-49
        var(0x100C, "Guard time", u16, "rw", 0),                                 # [M] ms
        var(0x100D, "Life time factor", u8, "rw", 0),                            # [M]
        compound(0x1010, "Store parameters",                                     # [M] signature "save"
                 [(n, Entry(f"Store parameters {n}", u32, "rw", 0)) for n in range(1, 5)], "ARRAY"),
        compound(0x1011, "Restore default parameters",                           # [M] signature "load"
                 [(n, Entry(f"Restore parameters {n}", u32, "rw", 0)) for n in range(1, 5)], "ARRAY"),
        var(0x1014, "COB-ID EMCY", u32, "ro", "$NODEID+0x80"),                   # [M] read-only here
        var(0x1017, "Producer heartbeat time", u16, "rw", 0),                    # [M] 0 = not used
        compound(0x1018, "Identity object", [
            (1, Entry("Vendor ID", u32, "ro", FC280_VENDOR_ID)),                 # [M]
            (2, Entry("Product code", u32, "ro", 0)),                            # [P]
            (3, Entry("Revision number", u32, "ro", 0)),                         # [P]
            (4, Entry("Serial number", u32, "ro", 0))],                          # [P]
            sub0=Entry("Number of entries", u8, "ro", 4)),
        sdo_server(),
        # DSP 402 objects the manual names (digest 003 §3.1); types from CiA 402 [P]
        var(0x603F, "Error code", u16, "ro", 0),
        var(0x6040, "Controlword", u16, "rw", 0, pdo_mapping=True),
        var(0x6041, "Statusword", u16, "ro", 0, pdo_mapping=True),
        var(0x6042, "vl target velocity", INTEGER16, "rw", 0, pdo_mapping=True),   # RPM by default [M]
        var(0x6043, "vl velocity demand", INTEGER16, "ro", 0, pdo_mapping=True),
        var(0x6044, "vl control effort", INTEGER16, "ro", 0, pdo_mapping=True),
        compound(0x6046, "vl velocity min max amount", [
            (1, Entry("vl velocity min amount", u32, "rw", 0)),
            (2, Entry("vl velocity max amount", u32, "rw", 0))], "ARRAY"),
        compound(0x6048, "vl velocity acceleration", delta),
        compound(0x6049, "vl velocity deceleration", delta),
        compound(0x604A, "vl velocity quick stop", delta),
        compound(0x604C, "vl dimension factor", [
            (1, Entry("vl dimension factor numerator", INTEGER32, "rw", 1)),
            (2, Entry("vl dimension factor denominator", INTEGER32, "rw", 1))], "ARRAY"),
        var(0x6502, "Supported drive modes", u32, "ro", 0),
        # FC profile process data (digest 003 §4.1): 16-80 control word, 16-82 reference, 16-03 status word [M];
        # 16-05 main actual value by the index rule [P]
        var(_fc_param(16, 80), "Fieldbus CTW 1 (16-80)", u16, "rw", 0, pdo_mapping=True),
        var(_fc_param(16, 82), "Fieldbus REF 1 (16-82)", INTEGER16, "rw", 0, pdo_mapping=True),
        var(_fc_param(16, 3), "Status word (16-03)", u16, "ro", 0, pdo_mapping=True),
        var(_fc_param(16, 5), "Main actual value (16-05)", INTEGER16, "ro", 0, pdo_mapping=True),
    ]
    # Drive parameters of manual table 6.1 with their factory settings [M] (digest 003 §5.5)
    parameters = [((8, 1), "Control site", u8, 0), ((8, 2), "Control source", u8, 3),
                  ((8, 3), "Control word timeout time", u16, 10),      # 1 s, conversion index -1
                  ((8, 4), "Control word timeout function", u8, 0), ((8, 7), "Diagnosis trigger", u8, 0),
                  ((8, 10), "Control word profile", u8, 0), ((8, 14), "Configurable control word CTW", u8, 1),
                  *(((8, n), f"Selection 8-{n}", u8, 3) for n in range(50, 57)),
                  ((8, 90), "Bus jog 1 speed", u16, 6000),            # 100 RPM, conversion index 67 (A34)
                  ((8, 91), "Bus jog 2 speed", u16, 12000),           # 200 RPM
                  ((10, 1), "Baud rate select", u8, 20), ((10, 2), "Node ID", u8, 127),
                  ((10, 5), "Transmit error counter", u8, 0), ((10, 6), "Receive error counter", u8, 0),
                  ((10, 31), "Store data values", u8, 0), ((10, 33), "Store always", u8, 0),
                  ((16, 84), "Fieldbus comm. status", u16, 0), ((16, 90), "Alarm word", u32, 0),
                  ((16, 91), "Alarm word 2", u32, 0), ((16, 92), "Warning word", u32, 0),
                  ((16, 93), "Warning word 2", u32, 0), ((16, 97), "Alarm word 3", u32, 0)]
    # counters and status words are readouts [P]
    read_only = {(10, 5), (10, 6), (16, 84), (16, 90), (16, 91), (16, 92), (16, 93), (16, 97)}
    for (group, number), name, data_type, default in parameters:
        access = "ro" if (group, number) in read_only else "rw"
        objects.append(var(_fc_param(group, number), f"{name} ({group}-{number:02d})", data_type, access, default))
    # Three RPDOs and three TPDOs (digest 003 §2.1) [M]; TPDO inhibit time 300 = 30 ms [M].
    # The default mappings are only in a picture of the manual (digest 003 §2.7): the ones here are [P]:
    # PDO1 the FC profile words, PDO2 (disabled) the DSP 402 words, PDO3 empty and disabled.
    rx = {1: (0x26900010, 0x26920010), 2: (0x60400010, 0x60420010), 3: ()}
    tx = {1: (0x26430010, 0x26450010), 2: (0x60410010, 0x60440010), 3: ()}
    disabled = {1: 0, 2: 0x80000000, 3: 0x80000000}
    for k in (1, 2, 3):
        objects += [pdo_communication(0x1400 + k - 1, disabled[k] + 0x200 + 0x100 * (k - 1), transmit=False),
                    pdo_mapping(0x1600 + k - 1, rx[k], slots=8),
                    pdo_communication(0x1800 + k - 1, disabled[k] + 0x180 + 0x100 * (k - 1), transmit=True,
                                      inhibit_time=300),
                    pdo_mapping(0x1A00 + k - 1, tx[k], slots=8)]
    return objects


def fc280_eds() -> EdsFile:
    return EdsFile(
        file_name="fc280.eds",
        description="Danfoss VLT Midi Drive FC 280, CANopen (skeleton)",
        created_by="softplc runtime/devices/eds.py",
        device_info={"VendorName": "Danfoss", "VendorNumber": FC280_VENDOR_ID, "ProductName": "VLT FC 280",
                     "ProductNumber": 0, "RevisionNumber": 0,
                     **{f"BaudRate_{rate}": int(rate != 100) for rate in (10, 20, 50, 125, 250, 500, 800, 1000)},
                     "SimpleBootUpMaster": 0, "SimpleBootUpSlave": 1, "Granularity": 8,
                     "DynamicChannelsSupported": 0, "GroupMessaging": 0,
                     "NrOfRXPDO": 3, "NrOfTXPDO": 3, "LSS_Supported": 0},
        objects=tuple(fc280_objects()),
        comments=(
            "A skeleton written from the Danfoss FC 280 CANopen programming guide (digest 003),",
            "not Danfoss's EDS file. Values the manual gives: device type, vendor ID 200008, the DSP 402",
            "and FC profile objects, the parameter factory settings, TPDO inhibit time 300 (30 ms).",
            "Placeholders: product code, revision, device name and software version strings, the SYNC",
            "COB-ID 0x80 (manual prints 125), data types of the 0x6000 objects (CiA 402) and every",
            "default PDO mapping (the manual shows them only in a picture).",
            "Generated by python -m softplc.runtime.devices.eds. Do not edit.",
        ))


SHIPPED = {"ltmr.eds": ltmr_eds, "fc280.eds": fc280_eds}


def main(argv=None) -> int:
    target = Path(argv[0]) if argv else EDS_DIR
    target.mkdir(parents=True, exist_ok=True)
    for name, build in SHIPPED.items():
        path = target / name
        path.write_text(render(build()), encoding="ascii", newline="\n")
        print(f"wrote {path}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
