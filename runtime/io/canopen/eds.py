"""EDS files (CiA 306 electronic data sheets): a generic writer.

Devices build their EDS from their own tables (devices/ltmr/eds.py from the
LTMR register map, devices/fc280/eds.py from digest 003) with the objects
here: VAR, ARRAY and RECORD objects with DataType, AccessType, DefaultValue
($NODEID+ allowed), PDOMapping and optional LowLimit/HighLimit, in the INI
layout that canopen.import_od reads, and the CiA 301 communication objects
every device has (PDO parameters, SDO server). The shipped EDS files are
generated, never edited by hand; a test regenerates each one and compares it
byte for byte (devices: `python -m softplc.runtime.devices` rewrites them).
"""

from __future__ import annotations

import importlib.resources
from dataclasses import dataclass, field

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

Default = int | str | None  # an int, "$NODEID+0x180", or the text of a string object


@dataclass(frozen=True)
class Entry:
    """One value: a VAR object, or one sub-index of an ARRAY/RECORD."""

    name: str
    data_type: int
    access: str = "ro"
    default: Default = 0
    pdo_mapping: bool = False
    low: int | None = None
    high: int | None = None

    def __post_init__(self):
        if self.access not in _ACCESS:
            raise ValueError(f"{self.name}: access {self.access!r} is not one of {_ACCESS}")


@dataclass(frozen=True)
class EdsObject:
    index: int
    name: str
    kind: str = "VAR"  # VAR, ARRAY or RECORD
    entry: Entry | None = None  # VAR only
    members: tuple = ()  # ARRAY/RECORD: ((subindex, Entry), ...)

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
    device_info: dict  # [DeviceInfo] keys in order (VendorName, VendorNumber ...)
    objects: tuple
    comments: tuple = ()
    file_info_extra: dict = field(default_factory=dict)


def var(index: int, name: str, data_type: int, access: str = "ro", default: Default = 0, **extra) -> EdsObject:
    return EdsObject(index, name, "VAR", entry=Entry(name, data_type, access, default, **extra))


def compound(index: int, name: str, members, kind: str = "RECORD", sub0: Entry | None = None) -> EdsObject:
    """An ARRAY or RECORD. Without an explicit `sub0`, sub-index 0 is the
    read-only UNSIGNED8 "highest sub-index supported"."""
    members = tuple(members)
    if sub0 is None:
        sub0 = Entry("Highest sub-index supported", UNSIGNED8, "ro", max(sub for sub, _ in members))
    return EdsObject(index, name, kind, members=((0, sub0), *members))


# ---------------------------------------------------------------------------
# Writer
# ---------------------------------------------------------------------------


def _value(default: int | str) -> str:
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
    lines = [
        f"ParameterName={entry.name}",
        f"ObjectType=0x{object_type:X}",
        f"DataType=0x{entry.data_type:04X}",
        f"AccessType={entry.access}",
    ]
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
    return _section(
        title, [f"SupportedObjects={len(indices)}"] + [f"{n}=0x{index:04X}" for n, index in enumerate(indices, 1)]
    )


def render(eds: EdsFile) -> str:
    """The EDS text. Deterministic: no dates from the clock, objects in index order."""
    for obj in eds.objects:
        for text in (obj.name, *(e.name for _, e in obj.members), obj.entry.name if obj.entry else ""):
            if not text.isascii() or ";" in text:
                raise ValueError(f"0x{obj.index:04X}: EDS names must be ASCII without ';': {text!r}")
    objects = sorted(eds.objects, key=lambda o: o.index)
    out = ["".join(f"; {line}\n" for line in eds.comments) + "\n" if eds.comments else ""]
    out.append(
        _section(
            "FileInfo",
            [
                f"FileName={eds.file_name}",
                "FileVersion=1",
                "FileRevision=0",
                "EDSVersion=4.0",
                f"Description={eds.description}",
                f"CreatedBy={eds.created_by}",
                *(f"{key}={value}" for key, value in eds.file_info_extra.items()),
            ],
        )
    )
    out.append(
        _section("DeviceInfo", [f"{key}={_device_info_value(key, value)}" for key, value in eds.device_info.items()])
    )
    out.append(_section("DummyUsage", [f"Dummy000{n}=0" for n in range(1, 8)]))
    if eds.comments:
        out.append(
            _section(
                "Comments",
                [f"Lines={len(eds.comments)}"] + [f"Line{n}={line}" for n, line in enumerate(eds.comments, 1)],
            )
        )
    mandatory = [o for o in objects if o.index in (0x1000, 0x1001, 0x1018)]
    optional = [o for o in objects if o not in mandatory and (0x1000 <= o.index < 0x2000 or o.index >= 0x6000)]
    manufacturer = [o for o in objects if 0x2000 <= o.index < 0x6000]
    out += [
        _object_list("MandatoryObjects", mandatory),
        _object_list("OptionalObjects", optional),
        _object_list("ManufacturerObjects", manufacturer),
    ]
    for obj in objects:
        if obj.kind == "VAR":
            out.append(_section(f"{obj.index:04X}", _entry_lines(obj.entry, _OBJECT_TYPES["VAR"])))
            continue
        out.append(
            _section(
                f"{obj.index:04X}",
                [
                    f"ParameterName={obj.name}",
                    f"ObjectType=0x{_OBJECT_TYPES[obj.kind]:X}",
                    f"SubNumber={len(obj.members)}",
                ],
            )
        )
        for sub, entry in obj.members:
            out.append(_section(f"{obj.index:04X}sub{sub:X}", _entry_lines(entry, _OBJECT_TYPES["VAR"])))
    return "".join(out)


# ---------------------------------------------------------------------------
# CiA 301 communication objects shared by both devices
# ---------------------------------------------------------------------------


def _nodeid(offset: int) -> str:
    return f"$NODEID+0x{offset:08X}"


def pdo_communication(
    index: int,
    cob_offset: int,
    transmit: bool,
    transmission_type: int = 0xFF,
    inhibit_time: int = 0,
    event_timer: int = 0,
) -> EdsObject:
    """0x1400+k (RPDO) or 0x1800+k (TPDO) communication parameters; the COB-ID is
    $NODEID+cob_offset (bit 31 set in the offset = PDO disabled)."""
    members = [
        (1, Entry("COB-ID", UNSIGNED32, "rw", _nodeid(cob_offset))),
        (2, Entry("Transmission type", UNSIGNED8, "rw", transmission_type)),
    ]
    if transmit:
        members += [
            (3, Entry("Inhibit time", UNSIGNED16, "rw", inhibit_time)),
            (4, Entry("Reserved", UNSIGNED8, "rw", 0)),
            (5, Entry("Event timer", UNSIGNED16, "rw", event_timer)),
        ]
    kind = "TPDO" if transmit else "RPDO"
    number = (index & 0xFF) + 1
    return compound(
        index,
        f"{kind}{number} communication parameter",
        members,
        sub0=Entry("Highest sub-index supported", UNSIGNED8, "ro", len(members)),
    )


def pdo_mapping(index: int, entries, slots: int = 4, kind: str = "ARRAY") -> EdsObject:
    """0x1600+k or 0x1A00+k: sub 0 = number of mapped entries (rw), subs 1..slots."""
    entries = tuple(entries)
    members = [
        (n, Entry(f"Mapping entry {n}", UNSIGNED32, "rw", entries[n - 1] if n <= len(entries) else 0))
        for n in range(1, slots + 1)
    ]
    pdo = ("RPDO" if index < 0x1A00 else "TPDO") + str((index & 0xFF) + 1)
    return compound(
        index,
        f"{pdo} mapping parameter",
        members,
        kind,
        sub0=Entry("Number of mapped objects", UNSIGNED8, "rw", len(entries)),
    )


def sdo_server() -> EdsObject:
    return compound(
        0x1200,
        "Server SDO parameter",
        [
            (1, Entry("COB-ID client to server", UNSIGNED32, "ro", "$NODEID+0x600")),
            (2, Entry("COB-ID server to client", UNSIGNED32, "ro", "$NODEID+0x580")),
        ],
        sub0=Entry("Number of entries", UNSIGNED8, "ro", 2),
    )


def shipped_eds(name: str):
    """A context manager giving the path of an EDS shipped in
    softplc.io_config/eds (a simulator builds its LocalNode from it)."""
    return importlib.resources.as_file(importlib.resources.files("softplc.io_config") / "eds" / name)
