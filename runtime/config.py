"""The PLC configuration: a declarative TOML file (DESIGN.md, "Configuration
is declarative TOML in io_config/"), validated and turned into the plain
dataclasses the engine uses.

    cfg = load_config("io_config/plant.toml")     # PlcConfig, or ConfigError

The file::

    [plc]          profile, programs (ST files), on_fault, start
    [retain]       file, period                              (optional)
    [[task]]       name, interval | freewheeling (+ pause), priority,
                   watchdog, sensitivity, programs           (zero or more)
    [outputs]      safe = { "%QX0.0" = false, ... }          (optional)
    [[loopback]]   from, to, bytes                           (zero or more)
    [[can]]        name, interface, channel, bitrate, options (zero or more)
    [canopen]      bus, node_id, heartbeat, sync, sdo_timeout, boot_timeout,
                   retry                                     (optional)
    [[canopen.node]]  name, id, eds, mandatory, heartbeat,
                   heartbeat_timeout, master_timeout, sdo,
                   [[...tpdo]] / [[...rpdo]] (number, transmission, inhibit,
                   event, configure, map)                    (zero or more)
    [[modbus]]     name, transport (rtu | tcp), device, baud, parity,
                   stop_bits, data_bits, frame_gap, host, port, timeout,
                   retries, reconnect, reconnect_max          (zero or more)
    [[modbus.channel]]  name, unit, function, offset, count, write_offset,
                   write_count, read_to, write_from, trigger, period, edge
    [[sim]]        type, name, registers; CAN devices: bus, node_id;
                   Modbus devices: modbus, unit               (zero or more)

io_config/examples/ has one commented example per section (canopen.toml for
[[can]], [canopen] and [[sim]], modbus_rtu.toml and modbus_tcp.toml for
[[modbus]]). Durations are written as everywhere else
("100ms", "T#1s", false for none where that makes sense) and stored in the
unit their field names (heartbeat_ms, sync_us ...).

Validation is two passes over the parsed TOML, and both run whatever the
other finds, so a file's errors are all reported at once, one per line:

  1. pydantic models (extra="forbid", strict): the shape of every table and
     the type and range of every value, each error at its key path;
  2. relations pydantic cannot see per value: interval vs freewheeling vs
     pause, unique task and instance names, safe outputs (the value type
     depends on the address), loopback addresses; the CAN side: bus
     references, unique node ids and names, heartbeat times against each
     other, PDO addresses (they depend on the profile) and their overlaps,
     SDO values against their size; the Modbus side: the keys each
     transport takes, channel addresses and counts per function code,
     triggers, and simulated drives on a line that can reach them.

Every message names the file, the key path and what was expected::

    io_config/plant.toml: task[1].interval: expected a duration such as 10ms, 1s, T#250ms (got '10 parsecs')
"""
from __future__ import annotations

import difflib
import math
import os
import re
import tomllib
import typing
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from typing import Annotated, Any, Optional, Union

from pydantic import BaseModel, ConfigDict, Field, PlainValidator, ValidationError, ValidationInfo, \
    model_validator
from pydantic_core import PydanticCustomError

from .durations import EXAMPLES as DURATION_EXAMPLES, parse_duration_ns
from .image import address as _address
from .io.modbus_functions import FUNCTIONS as MODBUS_FUNCTION_KINDS, READ_LIMIT as MODBUS_READ_LIMIT, \
    WRITE_LIMIT as MODBUS_WRITE_LIMIT
from .st.ast import LocatedAddress
from .st.profile import DEFAULT as _DEFAULT_PROFILE, PROFILES

__all__ = [
    "ConfigError", "ProgramInstance", "TaskConfig", "RetainConfig", "SafeOutput", "LoopbackLink",
    "CanBusConfig", "PdoEntryConfig", "PdoConfig", "SdoWriteConfig", "CanopenNodeConfig", "CanopenConfig",
    "ModbusChannelConfig", "ModbusConnectionConfig", "SimConfig", "PlcConfig", "load_config", "config_from_dict", "default_config_path", "default_watchdog_ns",
]

DEFAULT_PAUSE_NS = 1_000_000
DEFAULT_RETAIN_PERIOD_NS = 1_000_000_000
PRIORITY_MAX = 31


# ====================================================================== result


class ConfigError(Exception):
    """Everything wrong with one configuration file.

    errors: (key path or "", message) pairs, in file order. position:
    (line, column) of a TOML syntax error, else None."""

    def __init__(self, file: str, errors: list, *, position: Optional[tuple] = None) -> None:
        self.file = str(file)
        self.errors = list(errors)
        self.position = position
        super().__init__(str(self))

    def lines(self) -> list:
        out = []
        for key, message in self.errors:
            if self.position is not None and not key:
                line, col = self.position
                out.append(f"{self.file}:{line}:{col}: {message}")
            elif key:
                out.append(f"{self.file}: {key}: {message}")
            else:
                out.append(f"{self.file}: {message}")
        return out

    def __str__(self) -> str:
        return "\n".join(self.lines())


@dataclass
class ProgramInstance:
    instance: str
    program: str
    key: str            # "task[0].programs[1]", for messages


@dataclass
class TaskConfig:
    name: str
    interval_ns: Optional[int]       # None: freewheeling
    pause_ns: int                    # freewheeling: the gap after a cycle
    priority: int                    # 0 (highest) .. 31
    watchdog_ns: Optional[int]       # None: no watchdog
    sensitivity: int                 # overruns in a row before the watchdog fires
    programs: list[ProgramInstance]
    key: str                         # "task[0]", for messages


@dataclass
class RetainConfig:
    file: Path
    period_ns: int


@dataclass
class SafeOutput:
    address: LocatedAddress
    value: Union[bool, int, float]   # bool for a bit address
    key: str                         # 'outputs.safe."%QX0.0"'


@dataclass
class LoopbackLink:
    source: LocatedAddress           # a %Q byte/word/dword/lword address
    target: LocatedAddress           # a %I byte/word/dword/lword address
    nbytes: int
    key: str                         # "loopback[0]"


@dataclass
class CanBusConfig:
    name: str
    interface: str                   # a python-can interface name: socketcan, pcan, virtual ...
    channel: str
    bitrate: int                     # bit/s
    options: dict                    # more keyword arguments for python-can
    key: str                         # "can[0]"


@dataclass
class PdoEntryConfig:
    index: int
    subindex: int
    address: LocatedAddress          # %I (TPDO) or %Q (RPDO): a bit, byte, word, dword or lword
    key: str                         # "canopen.node[0].tpdo[0].map[1]"


@dataclass
class PdoConfig:
    number: int                      # 1..512
    transmission: int                # 0..240 (SYNC), 254, 255 (event-driven)
    inhibit_us: int                  # 0: none
    event_ms: int                    # 0: none
    configure: bool                  # the master writes mapping and parameters at boot
    entries: list[PdoEntryConfig]
    key: str                         # "canopen.node[0].tpdo[0]"


@dataclass
class SdoWriteConfig:
    index: int
    subindex: int
    value: int
    size: Optional[int]              # bytes (1, 2, 4); None: the EDS says
    key: str                         # "canopen.node[0].sdo[0]"


@dataclass
class CanopenNodeConfig:
    name: str
    node_id: int
    eds: Path                        # absolute
    mandatory: bool
    heartbeat_ms: int                # the node's producer time, its 0x1017 (0: none)
    heartbeat_timeout_ms: int        # the master's consumer timeout for it (0: not watched)
    master_timeout_ms: int           # its 0x1016:01 consumer time for the master (0: none)
    sdo: list[SdoWriteConfig]        # boot-time writes, in order
    tpdo: list[PdoConfig]
    rpdo: list[PdoConfig]
    key: str                         # "canopen.node[0]"


@dataclass
class CanopenConfig:
    bus: str                         # the name of a CanBusConfig
    node_id: int                     # the master's own node id
    heartbeat_ms: int                # the master's producer period (0: none)
    sync_us: int                     # SYNC period (0: no SYNC)
    sdo_timeout_ms: int
    boot_timeout_ms: int
    retry_ms: int
    nodes: list[CanopenNodeConfig]
    key: str = "canopen"


@dataclass
class ModbusChannelConfig:
    name: str
    connection: str                  # the name of its ModbusConnectionConfig
    unit: int                        # the slave's unit id
    function: int                    # 1, 2, 3, 4, 5, 6, 15, 16, 23
    offset: int                      # PDU address: the read, or the write of a write-only function
    count: int                       # registers or bits read (or written by a write-only function)
    write_offset: int                # function 23: the write
    write_count: int                 # function 23
    read_to: Optional[LocatedAddress]        # %I / %M: where read data lands
    write_from: Optional[LocatedAddress]     # %Q / %M: what is written
    trigger: str                     # "cyclic" | "change" | "edge"
    period_ns: int                   # cyclic period; the wait after a failure for the others
    edge: Optional[LocatedAddress]   # trigger "edge": a BOOL address
    key: str                         # "modbus[0].channel[1]"


@dataclass
class ModbusConnectionConfig:
    name: str
    transport: str                   # "rtu" | "tcp"
    device: str                      # rtu: serial port, or "sim" (a NullModem to the [[sim]] drives)
    baud: int
    parity: str                      # "N" | "E" | "O"
    stop_bits: int
    data_bits: int
    frame_gap_us: Optional[int]      # None: 3.5 characters (modbus_link.frame_gap)
    host: str                        # tcp
    port: int                        # tcp; 0 with simulated slaves: any free port
    timeout_ms: int
    retries: int
    reconnect_ms: int
    reconnect_max_ms: int
    channels: list[ModbusChannelConfig]
    key: str                         # "modbus[0]"


@dataclass
class SimConfig:
    type: str                        # "ltmr", or an Eaton drive: "da1", "db1", "dc1", "de1", "de11"
    name: str
    bus: Optional[str]               # CAN devices: the name of a CanBusConfig
    node_id: Optional[int]           # CAN devices
    registers: dict[int, int]        # initial register values
    key: str                         # "sim[0]"
    modbus: Optional[str] = None     # Modbus devices: the name of a ModbusConnectionConfig
    unit: Optional[int] = None       # Modbus devices: unit id


@dataclass
class PlcConfig:
    path: Optional[Path]             # the file as given; None when built from a dict alone
    base_dir: Path                   # relative paths in the file resolve against it
    profile: str
    programs: list[Path]             # the ST files, absolute
    on_fault: str                    # "task" | "plc"
    start: str                       # "warm" | "cold"
    tasks: list[TaskConfig] = field(default_factory=list)
    retain: Optional[RetainConfig] = None
    safe_outputs: list[SafeOutput] = field(default_factory=list)
    loopback: list[LoopbackLink] = field(default_factory=list)
    can: list[CanBusConfig] = field(default_factory=list)
    canopen: Optional[CanopenConfig] = None
    sims: list[SimConfig] = field(default_factory=list)
    modbus: list[ModbusConnectionConfig] = field(default_factory=list)
    raw: dict = field(default_factory=dict)   # the parsed TOML, for sections added later


def default_watchdog_ns(interval_ns: Optional[int]) -> int:
    """Watchdog time when a task gives none: ten intervals but at least
    100 ms for a cyclic task; 1 s for a freewheeling one."""
    if interval_ns is None:
        return 1_000_000_000
    return max(10 * interval_ns, 100_000_000)


def default_config_path() -> Path:
    """The embedded default configuration (io_config/default.toml, installed
    as package data of softplc.io_config)."""
    return Path(os.fspath(resources.files("softplc.io_config").joinpath("default.toml")))


def _shipped_eds() -> dict:
    """name -> absolute path of the EDS files installed with the package
    (io_config/eds/<name>.eds): what a node's eds = "ltmr" names."""
    folder = Path(os.fspath(resources.files("softplc.io_config").joinpath("eds")))
    return {p.stem.lower(): p for p in sorted(folder.glob("*.eds"))}


# ====================================================================== loading


def load_config(path) -> PlcConfig:
    """Read, parse and validate a configuration file. Raises ConfigError."""
    label = str(path)
    path = Path(path)
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        raise ConfigError(label, [("", "no such configuration file")]) from None
    except IsADirectoryError:
        raise ConfigError(label, [("", "is a directory, not a configuration file")]) from None
    except OSError as exc:
        raise ConfigError(label, [("", f"cannot read the configuration file: {exc.strerror or exc}")]) \
            from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigError(label, [("", f"not UTF-8 text (byte {exc.start}); a TOML file is UTF-8")]) \
            from None
    try:
        parsed = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message, position = _toml_error(str(exc), text)
        raise ConfigError(label, [("", f"invalid TOML: {message}")], position=position) from None
    return config_from_dict(parsed, path)


_TOML_AT = re.compile(r"\s*\(at line (\d+), column (\d+)\)$")
_TOML_AT_END = re.compile(r"\s*\(at end of document\)$")


def _toml_error(message: str, text: str) -> tuple:
    """tomllib's message without its position suffix, and (line, column)."""
    m = _TOML_AT.search(message)
    if m:
        return message[:m.start()], (int(m.group(1)), int(m.group(2)))
    m = _TOML_AT_END.search(message)
    if m:
        lines = text.split("\n")
        return message[:m.start()] + " at the end of the file", (len(lines), len(lines[-1]) + 1)
    return message, None


def config_from_dict(data: dict, path=None, *, base_dir=None) -> PlcConfig:
    """Validate already-parsed configuration data (tests; the command line
    without a config file). path names the file in messages and, unless
    base_dir is given, its directory is where relative paths resolve (the
    current directory without a path). Raises ConfigError."""
    label = str(path) if path is not None else "<configuration>"
    if base_dir is None:
        base_dir = Path(path).parent if path is not None else Path.cwd()
    base_dir = Path(os.path.abspath(base_dir))
    if not isinstance(data, dict):
        raise ConfigError(label, [("", f"expected a TOML document (got {_got(data)})")])

    errors: list = []
    model = None
    try:
        model = _Root.model_validate(data, context={"base_dir": base_dir})
    except ValidationError as exc:
        errors.extend(_translate(err) for err in exc.errors())
    rel = _Relations(data, base_dir)
    errors.extend(rel.errors)
    if errors:
        errors = _in_file_order(errors, data)
        raise ConfigError(label, [(_key(loc), message) for loc, message in errors])
    return _build(model, rel, data, Path(path) if path is not None else None, base_dir)


# ====================================================================== values
#
# Scalars are checked by plain validators rather than pydantic's own types,
# so that each message says what was expected in the config's own words.


def _got(value) -> str:
    """A value as the user wrote it, for '(got ...)'."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "an empty array" if not value else "an array"
    if isinstance(value, (int, float)):
        return repr(value)
    return f"a {type(value).__name__}"   # TOML dates and times


def _fail(expected: str, value) -> PydanticCustomError:
    return PydanticCustomError("config", "expected {expected} (got {got})",
                               {"expected": expected, "got": _got(value)})


def _duration_ns(value) -> Optional[int]:
    try:
        return parse_duration_ns(value)
    except (OverflowError, ValueError):   # inf, nan
        return None


def _duration(value) -> int:
    """A duration > 0 in ns: '10ms', 'T#1s', '1s500ms', or a bare number of ms."""
    ns = _duration_ns(value)
    if ns is None and isinstance(value, str) and _negative(value):
        ns = -1
    if ns is None:
        raise _fail(f"a duration such as {DURATION_EXAMPLES}", value)
    if ns <= 0:
        raise _fail(f"a duration > 0 such as {DURATION_EXAMPLES}", value)
    return ns


def _negative(text: str) -> bool:
    """'-5ms', 'T#-5ms': a duration but for its sign."""
    text = text.strip().lower()
    for prefix in ("time#", "t#"):
        if text.startswith(prefix):
            text = text[len(prefix):]
            break
    return text.startswith("-") and _duration_ns(text[1:]) is not None


def _watchdog(value):
    """A duration > 0 in ns, or False (no watchdog)."""
    if value is False:
        return False
    ns = _duration_ns(value)
    if ns is None or ns <= 0:
        raise _fail(f"a duration > 0 such as {DURATION_EXAMPLES}, or false for no watchdog", value)
    return ns


def _int_range(lo: int, hi: Optional[int] = None):
    def check(value) -> int:
        if isinstance(value, int) and not isinstance(value, bool) and value >= lo \
                and (hi is None or value <= hi):
            return value
        raise _fail(f"an integer from {lo} to {hi}" if hi is not None else f"an integer >= {lo}", value)
    return PlainValidator(check)


_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*", re.A)


def _is_ident(value) -> bool:
    return isinstance(value, str) and _IDENT.fullmatch(value) is not None


def _identifier(what: str):
    def check(value) -> str:
        if _is_ident(value):
            return value
        raise _fail(f"{what}: an IEC identifier (letters, digits, _; not starting with a digit)", value)
    return PlainValidator(check)


def _choice(options):
    """One of options, case-insensitive; returned in lower case."""
    options = tuple(options)
    listed = ", ".join(f"'{o}'" for o in options)

    def check(value) -> str:
        if isinstance(value, str) and value.lower() in options:
            return value.lower()
        hint = ""
        if isinstance(value, str):
            close = difflib.get_close_matches(value.lower(), options, n=1)
            if close:
                hint = f"; did you mean '{close[0]}'?"
        raise PydanticCustomError("config", "expected one of {listed} (got {got}{hint})",
                                  {"listed": listed, "got": _got(value), "hint": hint})
    return PlainValidator(check)


def _st_file(value, info: ValidationInfo) -> Path:
    """An existing ST file, relative to the config file's directory."""
    if not isinstance(value, str) or not value.strip():
        raise _fail('the path of an ST file such as "../st_programs/conveyor.st"', value)
    return _existing_file(value, info)


def _existing_file(text: str, info: ValidationInfo) -> Path:
    """text as an existing file, relative to the config file's directory."""
    resolved = Path(os.path.normpath(info.context["base_dir"] / Path(text).expanduser()))
    if not resolved.exists():
        raise PydanticCustomError("config", "no such file: {path} (relative paths start at the "
                                  "config file's directory)", {"path": str(resolved)})
    if not resolved.is_file():
        raise PydanticCustomError("config", "not a file: {path}", {"path": str(resolved)})
    return resolved


def _data_file(value, info: ValidationInfo) -> Path:
    if not isinstance(value, str) or not value.strip():
        raise _fail('a file name such as "plant.retain"', value)
    resolved = Path(os.path.normpath(info.context["base_dir"] / Path(value).expanduser()))
    if resolved.is_dir():
        raise PydanticCustomError("config", "{path} is a directory; expected a file name",
                                  {"path": str(resolved)})
    return resolved


Duration = Annotated[int, PlainValidator(_duration)]
Watchdog = Annotated[Any, PlainValidator(_watchdog)]
StFile = Annotated[Path, PlainValidator(_st_file)]


# ---------------------------------------------------------------- CAN and CANopen values

# manual 001 L183-205 (Network Port Baud Rate Setting): the CANopen rates.
CAN_BITRATES = (10_000, 20_000, 50_000, 125_000, 250_000, 500_000, 800_000, 1_000_000)
DEFAULT_BITRATE = 250_000            # manual 001 L206: the LTMR's factory setting
NODE_ID_MAX = 127                    # manual 001 L163: "an address from 1 to 127"
U16_MAX = 0xFFFF
PDO_ENTRIES_MAX = 8                  # manual 001 L117: a PDO carries 8 bytes
PDO_BITS_MAX = 64
CAN_SIM_TYPES = ("ltmr",)
MODBUS_SIM_TYPES = ("da1", "db1", "dc1", "de1", "de11")     # manual 002: the Eaton PowerXL families
SIM_TYPES = CAN_SIM_TYPES + MODBUS_SIM_TYPES
MODBUS_FUNCTIONS = tuple(MODBUS_FUNCTION_KINDS)
MODBUS_SIM_DEVICE = "sim"
MODBUS_UNIT_MAX = 247                # Modbus over serial line 2.2: 1..247 (0 = broadcast)
DEFAULT_HEARTBEAT_MS = 100           # the master's and a node's, unless the file says

_UNIT_NS = {"ms": 1_000_000, "us": 1_000}


def _duration_in(unit: str, *, off: Optional[str] = None, most: Optional[tuple] = None):
    """A duration as a whole number of unit ("ms" or "us"), rounded from the
    nanoseconds parse_duration_ns gives. off: what 0 / "0ms" / false means
    (None: they are refused); most: (largest value, why) where the bus
    carries the value in a field of fixed width."""
    per = _UNIT_NS[unit]
    or_off = f", or false for {off}" if off else ""

    def check(value) -> int:
        if value is False and off:
            return 0
        ns = _duration_ns(value)
        if ns is None or ns < 0 or (ns == 0 and not off):
            kind = "a duration" if off else "a duration > 0"
            raise _fail(f"{kind} such as {DURATION_EXAMPLES}{or_off}", value)
        count = round(ns / per)
        if ns > 0 and count == 0:
            raise _fail(f"a duration of at least 1{unit}{or_off}", value)
        if most is not None and count > most[0]:
            raise _fail(f"a duration of at most {most[0]}{unit} ({most[1]}){or_off}", value)
        return count
    return check


# The checks are kept as functions too: _Relations compares the values.
_master_heartbeat = _duration_in("ms", off="no heartbeat")
_sync_period = _duration_in("us", off="no SYNC", most=(0xFFFF_FFFF, "0x1006 holds microseconds in 32 bits"))
_timeout_ms = _duration_in("ms")
# manual 001 L964: 0x1017 Producer Heartbeat Time, Unsigned 16, unit 1 ms.
_node_heartbeat = _duration_in("ms", off="no heartbeat", most=(U16_MAX, "0x1017 holds ms in 16 bits"))
_heartbeat_timeout = _duration_in("ms", off="not watching it")
# manual 001 L957: 0x1016:01 bits 0-15 = heartbeat time, unit 1 ms.
_master_timeout = _duration_in("ms", off="the node not watching the master",
                               most=(U16_MAX, "0x1016:01 holds ms in 16 bits"))
# manual 001 L1365: TPDO inhibit time, Unsigned 16, unit 0.1 ms.
_inhibit = _duration_in("us", off="none", most=(U16_MAX * 100, "the inhibit time is 16 bits of 100us"))
# Event timer: Unsigned 16 in ms, as CiA 301 says; manual 001 L1379 says
# 0.1 ms, which digest 001 A7 resolves for CiA (ms).
_event = _duration_in("ms", off="none", most=(U16_MAX, "the event timer is 16 bits of ms"))


def _duration_field(check):
    return Annotated[int, PlainValidator(check)]


def _quiet(check, value):
    """check(value), or None when pass 1 refuses the value (it reports it)."""
    try:
        return check(value)
    except PydanticCustomError:
        return None


def _bitrate(value) -> int:
    if isinstance(value, int) and not isinstance(value, bool) and value in CAN_BITRATES:
        return value
    raise _fail("one of the CANopen bitrates " + ", ".join(str(b) for b in CAN_BITRATES), value)


def _text(expected: str):
    """A non-empty string; an integer is taken as its decimal text (channel = 0)."""
    def check(value) -> str:
        if isinstance(value, str) and value.strip():
            return value.strip()
        if isinstance(value, int) and not isinstance(value, bool):
            return str(value)
        raise _fail(expected, value)
    return PlainValidator(check)


def _nonempty(expected: str):
    def check(value) -> str:
        if isinstance(value, str) and value.strip():
            return value.strip()
        raise _fail(expected, value)
    return PlainValidator(check)


_OBJECT = re.compile(r"(?:0x)?([0-9A-F]{1,4}):(?:0x)?([0-9A-F]{1,2})", re.A | re.I)


def _object(value) -> tuple:
    """'2004:06' or '0x2004:06' (hex index : hex sub-index) -> (0x2004, 0x06)."""
    m = _OBJECT.fullmatch(value.strip()) if isinstance(value, str) else None
    if m is None:
        raise _fail('an object "index:subindex" in hex, such as "2004:06"', value)
    return int(m.group(1), 16), int(m.group(2), 16)


def _transmission(value) -> int:
    # manual 001 L1114: asynchronous (255), synchronously cyclic (1-240),
    # synchronously acyclic (0); CiA 301 adds 254 (event-driven, manufacturer).
    if isinstance(value, int) and not isinstance(value, bool) and (0 <= value <= 240 or value in (254, 255)):
        return value
    raise _fail("a transmission type 0..240, 254 or 255", value)


def _integer(value) -> int:
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    raise _fail("an integer", value)


def _sdo_size(value) -> int:
    if isinstance(value, int) and not isinstance(value, bool) and value in (1, 2, 4):
        return value
    raise _fail("a size in bytes: 1, 2 or 4", value)


def _eds_file(value, info: ValidationInfo) -> Path:
    """A shipped EDS by name ("ltmr": io_config/eds/ltmr.eds, installed with
    the package) or the path of an EDS file relative to the config file."""
    shipped = _shipped_eds()
    names = ", ".join(f"'{n}'" for n in shipped)
    if not isinstance(value, str) or not value.strip():
        raise _fail(f"a shipped EDS name ({names}) or the path of an .eds file", value)
    text = value.strip()
    if re.fullmatch(r"[A-Za-z0-9_-]+", text):      # a name, not a path
        if text.lower() in shipped:
            return shipped[text.lower()]
        close = difflib.get_close_matches(text.lower(), list(shipped), n=1)
        hint = f"; did you mean '{close[0]}'?" if close else ""
        raise PydanticCustomError("config", "expected a shipped EDS name ({names}) or the path of an .eds "
                                  "file (got {got}{hint})",
                                  {"names": names, "got": _got(value), "hint": hint})
    return _existing_file(text, info)


def _choice_int(options):
    def check(value) -> int:
        if isinstance(value, int) and not isinstance(value, bool) and value in options:
            return value
        raise _fail("one of " + ", ".join(map(str, options)), value)
    return PlainValidator(check)


def _choice_upper(options):
    def check(value) -> str:
        if isinstance(value, str) and value.upper() in options:
            return value.upper()
        raise _fail("one of " + ", ".join(f"'{o}'" for o in options), value)
    return PlainValidator(check)


MODBUS_BAUDS = (1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200)
_frame_gap = _duration_in("us", most=(1_000_000, "at most 1s"))

NodeId = Annotated[int, _int_range(1, NODE_ID_MAX)]
BusName = Annotated[str, _identifier("a bus name")]


# ====================================================================== schema


class _Model(BaseModel):
    model_config = ConfigDict(extra="forbid", strict=True)


class _Plc(_Model):
    profile: Annotated[str, _choice(PROFILES)] = Field(
        _DEFAULT_PROFILE.name, description=f"one of {', '.join(PROFILES)}")
    programs: list[StFile] = Field(
        min_length=1, description='an array of ST files such as ["../st_programs/conveyor.st"]')
    on_fault: Annotated[str, _choice(("task", "plc"))] = Field("task", description="'task' or 'plc'")
    start: Annotated[str, _choice(("warm", "cold"))] = Field("warm", description="'warm' or 'cold'")


class _Retain(_Model):
    file: Annotated[Path, PlainValidator(_data_file)] = Field(
        description='a file name such as "plant.retain"')
    period: Duration = Field(DEFAULT_RETAIN_PERIOD_NS, description=f"a duration such as {DURATION_EXAMPLES}")


class _ProgramEntry(_Model):
    instance: Annotated[str, _identifier("an instance name")] = Field(
        description='an instance name such as "Line2"')
    program: Annotated[str, _identifier("a PROGRAM name")] = Field(
        description='a PROGRAM name such as "Conveyor"')

    @model_validator(mode="before")
    @classmethod
    def _short_form(cls, value):
        if isinstance(value, str):
            if not _is_ident(value):
                raise _fail("a PROGRAM name (an IEC identifier)", value)
            return {"instance": value, "program": value}
        if not isinstance(value, dict):
            raise _fail('a PROGRAM name such as "Conveyor" or a table '
                        '{ instance = "Line2", program = "Conveyor" }', value)
        return value


class _Task(_Model):
    name: Annotated[str, _identifier("a task name")] = Field(description='a task name such as "Fast"')
    interval: Optional[Duration] = Field(None, description=f"a duration such as {DURATION_EXAMPLES}")
    freewheeling: bool = Field(False, description="true or false")
    pause: Optional[Duration] = Field(None, description=f"a duration such as {DURATION_EXAMPLES}")
    priority: Annotated[int, _int_range(0, PRIORITY_MAX)] = Field(
        1, description=f"an integer from 0 to {PRIORITY_MAX}")
    watchdog: Optional[Watchdog] = Field(None, description="a duration, or false")
    sensitivity: Annotated[int, _int_range(1)] = Field(1, description="an integer >= 1")
    programs: list[_ProgramEntry] = Field(
        min_length=1, description='an array of PROGRAM names or { instance = "...", program = "..." } '
                                  'tables, such as ["Conveyor"]')


class _Outputs(_Model):
    safe: dict[str, Any] = Field(
        default_factory=dict, description='a table of %Q address = value, such as { "%QX0.0" = false }')


class _Loopback(_Model):
    source: Any = Field(alias="from", description='a %Q byte/word/dword/lword address such as "%QB0"')
    target: Any = Field(alias="to", description='a %I byte/word/dword/lword address such as "%IB0"')
    nbytes: Annotated[int, _int_range(1)] = Field(alias="bytes", description="an integer >= 1")


_INTERFACE = 'a python-can interface such as "socketcan", "pcan" or "virtual"'


class _Can(_Model):
    name: BusName = Field("can0", description='a bus name such as "can0"')
    interface: Annotated[str, _nonempty(_INTERFACE)] = Field(description=_INTERFACE)
    channel: Annotated[str, _text('a channel such as "can0" or "PCAN_USBBUS1"')] = Field(
        description='a channel such as "can0" or "PCAN_USBBUS1"')
    bitrate: Annotated[int, PlainValidator(_bitrate)] = Field(DEFAULT_BITRATE,
                                                              description="a CANopen bitrate")
    options: dict[str, Any] = Field(
        default_factory=dict, description="a table of python-can options, such as { fd = false }")


class _PdoEntry(_Model):
    object: Annotated[tuple, PlainValidator(_object)] = Field(
        description='an object "index:subindex" in hex, such as "2004:06"')
    address: Any = Field(description='an image address such as "%IW0" for a TPDO, "%QW0" for an RPDO')


class _Pdo(_Model):
    number: Annotated[int, _int_range(1, 512)] = Field(description="a PDO number from 1 to 512")
    transmission: Annotated[int, PlainValidator(_transmission)] = Field(255, description="0..240, 254 or 255")
    inhibit: _duration_field(_inhibit) = Field(0, description="a duration such as 10ms")
    event: _duration_field(_event) = Field(0, description="a duration such as 500ms")
    configure: bool = Field(True, description="true or false")
    map: list[_PdoEntry] = Field(
        min_length=1, max_length=PDO_ENTRIES_MAX,
        description=f'an array of 1 to {PDO_ENTRIES_MAX} {{ object = "2004:06", address = "%IW0" }} tables; '
                    "a PDO carries 8 bytes")


class _SdoWrite(_Model):
    object: Annotated[tuple, PlainValidator(_object)] = Field(
        description='an object "index:subindex" in hex, such as "2007:21"')
    value: Annotated[int, PlainValidator(_integer)] = Field(description="an integer")
    size: Optional[Annotated[int, PlainValidator(_sdo_size)]] = Field(None, description="1, 2 or 4")


class _Node(_Model):
    name: Annotated[str, _identifier("a node name")] = Field(description='a node name such as "motor1"')
    id: NodeId = Field(description=f"a node id from 1 to {NODE_ID_MAX}")
    eds: Annotated[Path, PlainValidator(_eds_file)] = Field(
        description='a shipped EDS name such as "ltmr" or the path of an .eds file')
    mandatory: bool = Field(True, description="true or false")
    heartbeat: _duration_field(_node_heartbeat) = Field(DEFAULT_HEARTBEAT_MS,
                                                        description="a duration such as 100ms, or false")
    heartbeat_timeout: Optional[_duration_field(_heartbeat_timeout)] = Field(
        None, description="a duration such as 300ms, or false")
    master_timeout: Optional[_duration_field(_master_timeout)] = Field(
        None, description="a duration such as 500ms, or false")
    sdo: list[_SdoWrite] = Field(default_factory=list,
                                 description='an array of { object = "2007:21", value = 2 } tables')
    tpdo: list[_Pdo] = Field(default_factory=list, description="[[canopen.node.tpdo]] tables")
    rpdo: list[_Pdo] = Field(default_factory=list, description="[[canopen.node.rpdo]] tables")


class _Canopen(_Model):
    bus: Optional[BusName] = Field(None, description="the name of a [[can]] bus")
    node_id: NodeId = Field(NODE_ID_MAX, description=f"a node id from 1 to {NODE_ID_MAX}")
    heartbeat: _duration_field(_master_heartbeat) = Field(DEFAULT_HEARTBEAT_MS,
                                                          description="a duration such as 100ms, or false")
    sync: _duration_field(_sync_period) = Field(0, description="a duration such as 10ms, or false")
    sdo_timeout: _duration_field(_timeout_ms) = Field(500, description="a duration such as 500ms")
    boot_timeout: _duration_field(_timeout_ms) = Field(2000, description="a duration such as 2s")
    retry: _duration_field(_timeout_ms) = Field(1000, description="a duration such as 1s")
    node: list[_Node] = Field(default_factory=list, description="[[canopen.node]] tables")


_DEVICE = 'a serial port such as "/dev/ttyUSB0", or "sim" for the simulated drives of [[sim]]'


class _ModbusChannel(_Model):
    name: Optional[Annotated[str, _identifier("a channel name")]] = Field(
        None, description='a channel name such as "drive_status"')
    unit: Annotated[int, _int_range(0, MODBUS_UNIT_MAX)] = Field(
        description=f"a unit id from 1 to {MODBUS_UNIT_MAX} (0: broadcast write)")
    function: Annotated[int, _choice_int(MODBUS_FUNCTIONS)] = Field(
        description="a function code: " + ", ".join(map(str, MODBUS_FUNCTIONS)))
    offset: Annotated[int, _int_range(0, U16_MAX)] = Field(
        description="a PDU address from 0 to 65535 (Eaton ID n is offset n-1)")
    count: Annotated[int, _int_range(1, 2000)] = Field(1, description="an integer from 1 to 2000")
    write_offset: Optional[Annotated[int, _int_range(0, U16_MAX)]] = Field(
        None, description="a PDU address from 0 to 65535")
    write_count: Optional[Annotated[int, _int_range(1, 121)]] = Field(
        None, description="an integer from 1 to 121")
    read_to: Any = Field(None, description='an %I or %M address such as "%IW100"')
    write_from: Any = Field(None, description='a %Q or %M address such as "%QW100"')
    trigger: Annotated[str, _choice(("cyclic", "change", "edge"))] = Field(
        "cyclic", description="'cyclic', 'change' or 'edge'")
    period: _duration_field(_timeout_ms) = Field(100, description="a duration such as 100ms")
    edge: Any = Field(None, description='a BOOL address such as "%QX10.0"')


class _Modbus(_Model):
    name: Annotated[str, _identifier("a connection name")] = Field(
        "modbus0", description='a connection name such as "drives"')
    transport: Annotated[str, _choice(("rtu", "tcp"))] = Field(description="'rtu' or 'tcp'")
    device: Optional[Annotated[str, _nonempty(_DEVICE)]] = Field(None, description=_DEVICE)
    baud: Annotated[int, _choice_int(MODBUS_BAUDS)] = Field(
        19200, description="a baud rate: " + ", ".join(map(str, MODBUS_BAUDS)))
    parity: Annotated[str, _choice_upper(("N", "E", "O"))] = Field("N", description="'N', 'E' or 'O'")
    stop_bits: Annotated[int, _choice_int((1, 2))] = Field(1, description="1 or 2")
    data_bits: Annotated[int, _choice_int((7, 8))] = Field(8, description="7 or 8")
    frame_gap: Optional[_duration_field(_frame_gap)] = Field(
        None, description="a duration such as 2ms (default: 3.5 characters)")
    host: Optional[Annotated[str, _nonempty('a host such as "192.168.0.20"')]] = Field(
        None, description='a host such as "192.168.0.20"')
    port: Optional[Annotated[int, _int_range(0, U16_MAX)]] = Field(None, description="a TCP port such as 502")
    timeout: _duration_field(_timeout_ms) = Field(200, description="a duration such as 200ms")
    retries: Annotated[int, _int_range(0, 10)] = Field(1, description="an integer from 0 to 10")
    reconnect: _duration_field(_timeout_ms) = Field(1000, description="a duration such as 1s")
    reconnect_max: _duration_field(_timeout_ms) = Field(10_000, description="a duration such as 10s")
    channel: list[_ModbusChannel] = Field(default_factory=list, description="[[modbus.channel]] tables")


class _Sim(_Model):
    type: Annotated[str, _choice(SIM_TYPES)] = Field(
        description=", ".join(f"'{t}'" for t in SIM_TYPES[:-1]) + f" or '{SIM_TYPES[-1]}'")
    name: Optional[Annotated[str, _identifier("a simulator name")]] = Field(
        None, description='a simulator name such as "ltmr40"')
    bus: Optional[BusName] = Field(None, description="the name of a [[can]] bus")
    node_id: Optional[NodeId] = Field(None, description=f"a node id from 1 to {NODE_ID_MAX}")
    modbus: Optional[Annotated[str, _identifier("a connection name")]] = Field(
        None, description="the name of a [[modbus]] connection")
    unit: Optional[Annotated[int, _int_range(1, MODBUS_UNIT_MAX)]] = Field(
        None, description=f"a unit id from 1 to {MODBUS_UNIT_MAX}")
    registers: dict[str, Annotated[int, _int_range(0, U16_MAX)]] = Field(
        default_factory=dict, description='a table of register = value, such as { "682" = 2 }')


class _Root(_Model):
    plc: _Plc = Field(description='a [plc] table with at least programs = ["file.st"]')
    retain: Optional[_Retain] = Field(None, description="a [retain] table")
    task: list[_Task] = Field(default_factory=list, description="[[task]] tables")
    outputs: Optional[_Outputs] = Field(None, description="an [outputs] table")
    loopback: list[_Loopback] = Field(default_factory=list, description="[[loopback]] tables")
    can: list[_Can] = Field(default_factory=list, description="[[can]] tables")
    canopen: Optional[_Canopen] = Field(None, description="a [canopen] table")
    sim: list[_Sim] = Field(default_factory=list, description="[[sim]] tables")
    modbus: list[_Modbus] = Field(default_factory=list, description="[[modbus]] tables")


# ====================================================================== pydantic errors -> messages


def _keys(model: type) -> dict:
    """TOML key -> FieldInfo of a model."""
    return {(f.alias or name): f for name, f in model.model_fields.items()}


def _model_in(annotation) -> Optional[type]:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in typing.get_args(annotation):
        found = _model_in(arg)
        if found is not None:
            return found
    return None


def _model_at(loc: tuple) -> Optional[type]:
    """The model of the table at loc (() is the document)."""
    model = _Root
    for part in loc:
        if isinstance(part, int):
            continue   # an array entry: the model of the array's items
        info = _keys(model).get(part) if model is not None else None
        if info is None:
            return None
        model = _model_in(info.annotation)
    return model


def _field_at(loc: tuple):
    """The FieldInfo of the key at loc, or None (array entries, unknown keys)."""
    if not loc or isinstance(loc[-1], int):
        return None
    owner = _model_at(loc[:-1])
    return _keys(owner).get(loc[-1]) if owner is not None else None


def _translate(err: dict) -> tuple:
    """A pydantic error as (loc, message in the config's words)."""
    loc = tuple(err["loc"])
    kind = err["type"]
    value = err.get("input")
    if kind == "config":
        return loc, err["msg"]
    if kind == "extra_forbidden":
        owner = _model_at(loc[:-1])
        valid = list(_keys(owner)) if owner is not None else []
        name = str(loc[-1])
        lower = {v.lower(): v for v in valid}
        close = difflib.get_close_matches(name.lower(), list(lower), n=1, cutoff=0.6)
        hint = f"did you mean '{lower[close[0]]}'?" if close else f"expected one of {', '.join(valid)}"
        return loc, f"unknown key ({hint})"
    info = _field_at(loc)
    described = info.description if info is not None else None
    if kind == "missing":
        return loc, f"required key missing (expected {described})" if described else "required key missing"
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return loc, f"expected {described or 'a table'} (got {_got(value)})"
    if kind == "list_type":
        return loc, f"expected {described or 'an array'} (got {_got(value)})"
    if kind == "too_short":
        return loc, f"expected {described or 'at least one entry'} (got an empty array)"
    if kind == "too_long":
        return loc, f"expected {described or 'fewer entries'} (got {len(value)} entries)"
    if kind == "bool_type":
        return loc, f"expected true or false (got {_got(value)})"
    return loc, f"{err['msg']} (got {_got(value)})"


def _key(loc: tuple) -> str:
    """('task', 1, 'interval') -> 'task[1].interval'; odd keys quoted."""
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
            continue
        part = str(part)
        text = part if re.fullmatch(r"[A-Za-z0-9_-]+", part) else '"' + part.replace('"', '\\"') + '"'
        out += ("." if out else "") + text
    return out


def _in_file_order(errors: list, data: dict) -> list:
    """Sort errors by section (as they appear in the file), then by array
    entry, down to nested arrays such as canopen.node[0].tpdo[1].map[2];
    stable, so the order within one table is the schema's."""
    def rank(item) -> tuple:
        loc = item[0]
        out: list = []
        here: Any = data
        for i, part in enumerate(loc):
            if isinstance(part, int):
                out.append(part)
                here = here[part] if isinstance(here, list) and part < len(here) else None
                continue
            table = here if isinstance(here, dict) else {}
            if i == 0 or (i + 1 < len(loc) and isinstance(loc[i + 1], int)):
                # a section or an array: where the file has it
                out.append(list(table).index(part) if part in table else len(table))
            here = table.get(part)
        return tuple(out)
    return sorted(errors, key=rank)


# ====================================================================== relations


class _ModbusRelations:
    """The [[modbus]] checks of _Relations (mixed in)."""

    def _modbus_side(self, data: dict) -> None:
        conns = data.get("modbus")
        if not isinstance(conns, list):
            return
        for i, conn in enumerate(conns):
            if not isinstance(conn, dict):
                continue
            here = ("modbus", i)
            name = conn.get("name", "modbus0")
            if _is_ident(name):
                first = self.modbus_names.get(name.upper())
                if first is None:
                    self.modbus_names[name.upper()] = (i, conn)
                else:
                    self.error(here + (("name",) if "name" in conn else ()),
                               f"duplicate connection name '{name}' (modbus[{first[0]}] has it; names are "
                               "case-insensitive)" + ("" if "name" in conn else ": give each [[modbus]] a name"))
            transport = conn.get("transport")
            transport = transport.lower() if isinstance(transport, str) else None
            if transport == "rtu":
                if "device" not in conn:
                    self.error(here, f"required key missing: device ({_DEVICE})")
                for key in ("host", "port"):
                    if key in conn:
                        self.error(here + (key,), "only for transport = 'tcp' (this connection is 'rtu')")
            elif transport == "tcp":
                for key in ("device", "baud", "parity", "stop_bits", "data_bits", "frame_gap"):
                    if key in conn:
                        self.error(here + (key,), "only for transport = 'rtu' (this connection is 'tcp')")
            channels = conn.get("channel")
            if isinstance(channels, list):
                self._modbus_channels(here, channels)

    def _modbus_channels(self, here: tuple, channels: list) -> None:
        names: dict = {}
        for j, ch in enumerate(channels):
            if not isinstance(ch, dict):
                continue
            at = here + ("channel", j)
            name = ch.get("name")
            if _is_ident(name):
                first = names.setdefault(name.upper(), j)
                if first != j:
                    self.error(at + ("name",), f"duplicate channel name '{name}' (channel[{first}] has it; "
                                               "names are case-insensitive)")
            fc = ch.get("function")
            if fc not in MODBUS_FUNCTIONS or isinstance(fc, bool):
                continue   # pass 1 reports it
            reads, writes, bits = MODBUS_FUNCTION_KINDS[fc]
            count = ch.get("count", 1)
            limit = MODBUS_READ_LIMIT[fc] if reads else MODBUS_WRITE_LIMIT[fc]
            if _in_range(count, 1, 2000) and count > limit:    # above 2000: pass 1 reports it
                what = ("bit" if bits else "register") + ("s" if limit > 1 else "")
                self.error(at + ("count",), f"function {fc} carries at most {limit} {what} (got {count})")
            if fc == 23:
                for key in ("write_offset", "write_count"):
                    if key not in ch:
                        self.error(at, f"required key missing: {key} (function 23 writes and reads)")
            else:
                for key in ("write_offset", "write_count"):
                    if key in ch:
                        self.error(at + (key,), "only for function 23 (offset and count give the block)")
            wc = ch.get("write_count", count) if fc == 23 else count
            self._channel_address(at, ch, "read_to", reads, ("I", "M"), count if reads else 0, bits)
            self._channel_address(at, ch, "write_from", writes, ("Q", "M"), wc if writes else 0, bits)
            trigger = ch.get("trigger", "cyclic")
            trigger = trigger.lower() if isinstance(trigger, str) else None
            if trigger == "change" and not writes:
                self.error(at + ("trigger",), f"'change' watches the data to write; function {fc} only reads "
                                              "(use 'cyclic' or 'edge')")
            if trigger == "edge":
                if "edge" not in ch:
                    self.error(at, 'required key missing: edge (the BOOL whose rising edge triggers, such '
                                   'as "%QX10.0")')
                else:
                    addr = self._address(at + ("edge",), ch["edge"], "%QX10.0, %MX2.0")
                    if addr is not None and addr.bit is None and addr.size not in ("", "X"):
                        self.error(at + ("edge",), f"expected a BOOL (bit) address such as %QX10.0 "
                                                   f"(got '{addr.text}')")
                    elif addr is not None:
                        self.modbus_addresses[at + ("edge",)] = addr
            elif "edge" in ch:
                self.error(at + ("edge",), "only for trigger = 'edge'")
            if ch.get("unit") == 0 and reads:
                self.error(at + ("unit",), "unit 0 is the broadcast address: nobody answers, so only "
                                           "writes can go to it")

    def _channel_address(self, at: tuple, ch: dict, key: str, needed: bool, areas: tuple, count: int,
                         bits: bool) -> None:
        what = "reads into" if key == "read_to" else "writes from"
        if not needed:
            if key in ch:
                self.error(at + (key,), f"function {ch.get('function')} does not use {key}")
            return
        if key not in ch:
            self.error(at, f"required key missing: {key} (the image address the channel {what})")
            return
        examples = f"%{areas[0]}W100, %MW20"
        addr = self._address(at + (key,), ch[key], examples)
        if addr is None:
            return
        if addr.area not in areas:
            self.error(at + (key,), f"expected an address in {' or '.join('%' + a for a in areas)} "
                                    f"(got {_area_name(addr)})")
            return
        try:
            _area, offset, _n = self._probe().region(addr)
        except ValueError as exc:
            self.error(at + (key,), str(exc))
            return
        nbytes = (count + 7) // 8 if bits else 2 * count
        if offset + nbytes > self._probe().size:
            self.error(at + (key,), f"{count} {'bits' if bits else 'registers'} from {addr.text} run past the "
                                    f"end of the %{addr.area} area")
            return
        self.modbus_addresses[at + (key,)] = addr

    def _modbus_sim(self, here: tuple, sim: dict, units: dict) -> None:
        """An Eaton drive on a [[modbus]] connection: RTU with device = "sim"
        or TCP on 127.0.0.1; one drive per unit id."""
        for key in ("bus", "node_id"):
            if key in sim:
                self.error(here + (key,), "only for a CAN device; a Modbus device has modbus and unit")
        if "unit" not in sim:
            self.error(here, "required key missing: unit (the drive's Modbus address)")
        conn = sim.get("modbus")
        if conn is None:
            if len(self.modbus_names) == 1:
                conn = next(iter(self.modbus_names.values()))[1].get("name", "modbus0")
            else:
                self.error(here, "required key missing: modbus (the [[modbus]] connection the drive is on)"
                           if self.modbus_names else "a simulated drive needs a [[modbus]] connection "
                           "(the file has none)")
                return
        elif not _is_ident(conn):
            return
        entry = self.modbus_names.get(conn.upper())
        if entry is None:
            self.error(here + ("modbus",), f"expected one of {', '.join(repr(t.get('name', 'modbus0')) for _i, t in self.modbus_names.values())}, "
                                           f"the [[modbus]] connections (got '{conn}')")
            return
        index, table = entry
        self.sim_connection[here] = table.get("name", "modbus0")
        transport = str(table.get("transport", "")).lower()
        if transport == "rtu" and table.get("device") != MODBUS_SIM_DEVICE:
            self.error(here + ("modbus",), f"modbus[{index}] is a serial line to real devices; a simulated "
                                           f'drive needs device = "{MODBUS_SIM_DEVICE}" there')
        if transport == "tcp" and table.get("host", "127.0.0.1") not in ("127.0.0.1", "localhost"):
            self.error(here + ("modbus",), f"modbus[{index}] goes to {table.get('host')}; a simulated drive "
                                           "listens on 127.0.0.1 only")
        unit = sim.get("unit")
        if _in_range(unit, 1, None):
            first = units.setdefault((index, unit), here)
            if first != here:
                self.error(here + ("unit",), f"duplicate unit {unit} on modbus[{index}] ({_key(first)} has it)")


class _Relations(_ModbusRelations):
    """The checks between values, on the raw data, tolerant of values that
    pass 1 refuses (it reports those). Also parses the safe outputs and the
    loopback links and the PDO addresses (addresses depend on the profile),
    and resolves the bus each CANopen master and simulator is on."""

    def __init__(self, data: dict, base_dir: Path) -> None:
        self.errors: list = []
        self.safe_outputs: list = []
        self.loopback: list = []
        self.pdo_addresses: dict = {}   # loc of a PDO map entry -> LocatedAddress
        self.bus_of: dict = {}          # ("canopen",) or ("sim", i) -> the [[can]] name it uses
        self.sim_connection: dict = {}  # ("sim", i) -> the [[modbus]] name a simulated drive is on
        plc = data.get("plc") if isinstance(data.get("plc"), dict) else {}
        profile = plc.get("profile", _DEFAULT_PROFILE.name)
        profile = PROFILES.get(profile.lower()) if isinstance(profile, str) else None
        self.addressing = profile.addressing if profile is not None else None
        tasks = data.get("task")
        if isinstance(tasks, list):
            self._tasks(tasks)
        outputs = data.get("outputs")
        if isinstance(outputs, dict) and isinstance(outputs.get("safe"), dict):
            self._safe(outputs["safe"])
        links = data.get("loopback")
        if isinstance(links, list):
            self._loopback(links)
        self.modbus_addresses: dict = {}   # loc of a channel address key -> LocatedAddress
        self.modbus_names: dict = {}       # NAME (upper) -> the [[modbus]] table, of valid names
        self._modbus_side(data)
        self._can_side(data)

    def error(self, loc: tuple, message: str) -> None:
        self.errors.append((loc, message))

    # ---------------------------------------------------------------- tasks

    def _tasks(self, tasks: list) -> None:
        names: dict = {}
        instances: dict = {}
        for i, task in enumerate(tasks):
            if not isinstance(task, dict):
                continue
            here = ("task", i)
            self._timing(here, task)
            name = task.get("name")
            if _is_ident(name):
                first = names.setdefault(name.upper(), i)
                if first != i:
                    self.error(here + ("name",), f"duplicate task name '{name}' (task[{first}] has it; "
                                                 "names are case-insensitive)")
            programs = task.get("programs")
            if not isinstance(programs, list):
                continue
            for j, entry in enumerate(programs):
                if isinstance(entry, str):
                    instance, loc = entry, here + ("programs", j)
                elif isinstance(entry, dict):
                    instance, loc = entry.get("instance"), here + ("programs", j, "instance")
                else:
                    continue
                if not _is_ident(instance):
                    continue
                first = instances.setdefault(instance.upper(), loc)
                if first != loc:
                    hint = ("; give one its own instance name: "
                            f'{{ instance = "{instance}2", program = "{entry}" }}' if isinstance(entry, str)
                            else "")
                    self.error(loc, f"duplicate program instance '{instance}' (also at {_key(first)}; "
                                    f"instance names are unique across tasks, case-insensitive){hint}")

    def _timing(self, here: tuple, task: dict) -> None:
        if not isinstance(task.get("freewheeling", False), bool):
            return   # pass 1 reports it; whether the task is cyclic is unknown
        has_interval = "interval" in task
        freewheeling = task.get("freewheeling") is True
        if has_interval and freewheeling:
            self.error(here + ("freewheeling",), "a task has either an interval or freewheeling = true, "
                                                 "not both")
        elif not has_interval and not freewheeling:
            self.error(here, 'expected interval = "10ms" (a cyclic task) or freewheeling = true '
                             "(got neither)")
        if "pause" in task and has_interval and not freewheeling:
            self.error(here + ("pause",), "only for a freewheeling task (this one has an interval)")
        if "sensitivity" in task and task.get("watchdog") is False:
            self.error(here + ("sensitivity",), "only meaningful with a watchdog (this task has "
                                                "watchdog = false)")

    # ---------------------------------------------------------------- addresses

    def _address(self, loc: tuple, text, examples: str) -> Optional[LocatedAddress]:
        if not isinstance(text, str):
            self.error(loc, f"expected a direct address such as {examples} (got {_got(text)})")
            return None
        try:
            return _address.parse_address(text, self.addressing)
        except ValueError as exc:   # AddressError, and LiteralError should one slip through
            message = str(exc)
            if "is not a direct address" in message:
                message = f"expected a direct address such as {examples} (got {_got(text)})"
            else:   # drop the address the key already names
                prefix = text.strip().upper() + ": "
                message = message[len(prefix):] if message.startswith(prefix) else message
            self.error(loc, message)
            return None

    def _safe(self, safe: dict) -> None:
        seen: dict = {}
        for text, value in safe.items():
            loc = ("outputs", "safe", text)
            addr = self._address(loc, text, "%QX0.0, %QW2")
            if addr is None:
                continue
            if addr.area != "Q":
                self.error(loc, f"expected a %Q output address (got {_area_name(addr)})")
                continue
            if addr.table is not None:
                self.error(loc, "expected a single bit, byte, word, dword or lword (got a word table); "
                                "list the words one by one")
                continue
            ident = (addr.size if addr.size != "" else "X", addr.indices, addr.bit)
            if ident in seen:
                self.error(loc, f"the same address as {_key(seen[ident])}")
                continue
            seen[ident] = loc
            checked = self._safe_value(loc, addr, value)
            if checked is not None:
                self.safe_outputs.append(SafeOutput(addr, checked[0], _key(loc)))

    def _safe_value(self, loc: tuple, addr: LocatedAddress, value) -> Optional[tuple]:
        if addr.bit is not None or addr.size in ("", "X"):
            if isinstance(value, bool):
                return (value,)
            if isinstance(value, int) and value in (0, 1):
                return (bool(value),)
            self.error(loc, f"expected true or false (or 0 / 1) for a bit address (got {_got(value)})")
            return None
        bits = _address.SIZE_BITS[addr.size]
        what = {8: "a byte", 16: "a word", 32: "a dword", 64: "an lword"}[bits]
        lo, hi = -(1 << (bits - 1)), (1 << bits) - 1
        if isinstance(value, int) and not isinstance(value, bool):
            if lo <= value <= hi:
                return (value,)
            self.error(loc, f"expected an integer from {lo} to {hi} for {what} address (got {value})")
            return None
        if isinstance(value, float) and bits >= 32:
            if bits == 32 and math.isfinite(value) and abs(value) > 3.4028234663852886e38:
                self.error(loc, f"expected a REAL (at most 3.4e38) for a dword address (got {value!r})")
                return None
            return (value,)
        if isinstance(value, float):
            self.error(loc, f"expected an integer for {what} address (got {value!r}; a REAL needs a "
                            "%QD address, an LREAL a %QL address)")
            return None
        kind = "an integer or a float" if bits >= 32 else "an integer"
        self.error(loc, f"expected {kind} for {what} address (got {_got(value)})")
        return None

    def _loopback(self, links: list) -> None:
        for i, link in enumerate(links):
            if not isinstance(link, dict):
                continue
            here = ("loopback", i)
            ends = {}
            for key, area in (("from", "Q"), ("to", "I")):
                if key not in link:
                    continue   # pass 1 reports it missing
                addr = self._address(here + (key,), link[key], f"%{area}B0, %{area}W2")
                if addr is None:
                    continue
                kind = "%Q output" if area == "Q" else "%I input"
                if addr.area != area:
                    self.error(here + (key,), f"expected a {kind} address (got {_area_name(addr)})")
                elif addr.bit is not None or addr.table is not None or addr.size not in _address.SIZE_BITS:
                    self.error(here + (key,), f"expected a {kind} byte, word, dword or lword address "
                                              f"such as %{area}B0 (got '{addr.text}'); the link copies "
                                              "whole bytes")
                else:
                    ends[key] = addr
            nbytes = link.get("bytes")
            if len(ends) == 2 and isinstance(nbytes, int) and not isinstance(nbytes, bool) and nbytes >= 1:
                self.loopback.append(LoopbackLink(ends["from"], ends["to"], nbytes, _key(here)))


    # ---------------------------------------------------------------- CAN buses, CANopen, simulators

    def _can_side(self, data: dict) -> None:
        buses = data.get("can") if isinstance(data.get("can"), list) else []
        names = self._bus_names(buses)
        canopen = data.get("canopen")
        master = None
        if isinstance(canopen, dict):
            bus = self._bus_of(("canopen",), canopen, names, len(buses), "the CANopen master")
            node_id = canopen.get("node_id", NODE_ID_MAX)
            master = (bus, node_id if _in_range(node_id, 1, NODE_ID_MAX) else None)
            self._canopen(canopen, master[1])
        sims = data.get("sim")
        if isinstance(sims, list):
            self._sims(sims, names, len(buses), master)

    def _bus_names(self, buses: list) -> dict:
        """NAME (upper case) -> the name as written, of the buses with a valid name."""
        names: dict = {}
        for i, bus in enumerate(buses):
            if not isinstance(bus, dict):
                continue
            name = bus.get("name", "can0")
            if not _is_ident(name):
                continue   # pass 1 reports it
            first = names.get(name.upper())
            if first is None:
                names[name.upper()] = (name, i)
            elif "name" in bus:
                self.error(("can", i, "name"), f"duplicate bus name '{name}' (can[{first[1]}] has it; "
                                               "names are case-insensitive)")
            else:
                self.error(("can", i), f"duplicate bus name '{name}' (the default; can[{first[1]}] has it): "
                                       "give each [[can]] its own name")
        return {upper: name for upper, (name, _i) in names.items()}

    def _bus_of(self, here: tuple, table: dict, names: dict, count: int, what: str) -> Optional[str]:
        """The [[can]] bus a [canopen] or [[sim]] table uses: its bus key, or
        the only bus. None (and perhaps an error) when there is none."""
        bus = table.get("bus")
        listed = ", ".join(f"'{n}'" for n in names.values())
        if count == 0:
            self.error(here, f"{what} needs a [[can]] bus (the file has none): add a [[can]] table with "
                             "interface and channel")
            return None
        if bus is None:
            if count == 1 and len(names) == 1:
                bus = next(iter(names.values()))
            elif count > 1:
                self.error(here + ("bus",), f"required key missing: the file has several [[can]] buses "
                                            f"(expected one of {listed})")
                return None
            else:
                return None   # the only bus has a bad name: pass 1 reports it
        elif not _is_ident(bus):
            return None       # pass 1 reports it
        elif bus.upper() in names:
            bus = names[bus.upper()]
        else:
            if len(names) == count:   # every bus has a valid name, so this one is unknown
                self.error(here + ("bus",), f"expected one of {listed}, the [[can]] buses (got '{bus}')")
            return None
        self.bus_of[here] = bus
        return bus

    def _canopen(self, canopen: dict, master_id: Optional[int]) -> None:
        nodes = canopen.get("node")
        if not isinstance(nodes, list):
            return
        master_heartbeat = _quiet(_master_heartbeat, canopen.get("heartbeat", DEFAULT_HEARTBEAT_MS))
        ids: dict = {}
        names: dict = {}
        claimed = self._loopback_targets()
        for i, node in enumerate(nodes):
            if not isinstance(node, dict):
                continue
            here = ("canopen", "node", i)
            node_id, name = node.get("id"), node.get("name")
            if _in_range(node_id, 1, NODE_ID_MAX):
                if node_id == master_id:
                    self.error(here + ("id",), f"{node_id} is the master's own node id (canopen.node_id)")
                elif node_id in ids:
                    self.error(here + ("id",), f"duplicate node id {node_id} ({_key(ids[node_id])} has it)")
                else:
                    ids[node_id] = here
            if _is_ident(name):
                first = names.setdefault(name.upper(), here)
                if first != here:
                    self.error(here + ("name",), f"duplicate node name '{name}' ({_key(first)} has it; "
                                                 "names are case-insensitive)")
            self._heartbeats(here, node, canopen, master_heartbeat)
            for direction in ("tpdo", "rpdo"):
                if isinstance(node.get(direction), list):
                    self._pdos(here, direction, node[direction], claimed)
            if isinstance(node.get("sdo"), list):
                self._sdo_values(here, node["sdo"])

    def _heartbeats(self, here: tuple, node: dict, canopen: dict, master_heartbeat: Optional[int]) -> None:
        """The node's heartbeat against the master's timeout for it, and the
        master's heartbeat against the node's timeout for the master."""
        heartbeat = _quiet(_node_heartbeat, node.get("heartbeat", DEFAULT_HEARTBEAT_MS))
        timeout = _quiet(_heartbeat_timeout, node.get("heartbeat_timeout"))
        if heartbeat is not None and timeout:   # given and not off
            if heartbeat == 0:
                self.error(here + ("heartbeat_timeout",), "only meaningful with a heartbeat (this node has "
                                                          f"heartbeat = {_got(node['heartbeat'])})")
            elif timeout <= heartbeat:
                self.error(here + ("heartbeat_timeout",),
                           f"expected a duration longer than the node's heartbeat ({heartbeat}ms), or false "
                           f"for not watching it (got {_got(node['heartbeat_timeout'])})")
        if master_heartbeat is None:
            return
        if "master_timeout" in node:
            timeout = _quiet(_master_timeout, node["master_timeout"])
            if not timeout:
                return        # off, or refused by pass 1
            if master_heartbeat == 0:
                self.error(here + ("master_timeout",), "only meaningful when the master sends a heartbeat "
                                                       f"(canopen.heartbeat = {_got(canopen['heartbeat'])})")
            elif timeout <= master_heartbeat:
                self.error(here + ("master_timeout",),
                           f"expected a duration longer than canopen.heartbeat ({master_heartbeat}ms), or "
                           f"false for the node not watching the master (got {_got(node['master_timeout'])})")
        elif master_heartbeat and _default_master_timeout(master_heartbeat) <= master_heartbeat:
            self.error(here, f"the default master_timeout, 5 x canopen.heartbeat at most {U16_MAX}ms, is not "
                             f"longer than canopen.heartbeat ({master_heartbeat}ms): give master_timeout, or "
                             "false")

    def _pdos(self, here: tuple, direction: str, pdos: list, claimed: list) -> None:
        """PDO numbers unique per direction, and the image addresses of the
        entries: %I for a TPDO, %Q for an RPDO, no two overlapping."""
        numbers: dict = {}
        area = "I" if direction == "tpdo" else "Q"
        for j, pdo in enumerate(pdos):
            if not isinstance(pdo, dict):
                continue
            at = here + (direction, j)
            number = pdo.get("number")
            if _in_range(number, 1, 512):
                first = numbers.setdefault(number, at)
                if first != at:
                    self.error(at + ("number",), f"duplicate {direction.upper()} number {number} "
                                                 f"({_key(first)} has it)")
            entries = pdo.get("map")
            if not isinstance(entries, list):
                continue
            bits = 0
            for k, entry in enumerate(entries):
                if isinstance(entry, dict) and "address" in entry:
                    addr = self._pdo_address(at + ("map", k, "address"), entry["address"], area, claimed)
                    if addr is not None:
                        self.pdo_addresses[at + ("map", k)] = addr
                        bits += _bit_count(addr)
            if bits > PDO_BITS_MAX and len(entries) <= PDO_ENTRIES_MAX:   # else pass 1 says too many
                self.error(at + ("map",), f"the addresses hold {bits} bits; a PDO carries at most "
                                          f"{PDO_BITS_MAX} (8 bytes)")

    def _pdo_address(self, loc: tuple, text, area: str, claimed: list) -> Optional[LocatedAddress]:
        addr = self._address(loc, text, f"%{area}W0, %{area}X0.0")
        if addr is None:
            return None
        kind = "a TPDO's entries go to %I inputs" if area == "I" else "an RPDO's entries come from %Q outputs"
        if addr.area != area:
            self.error(loc, f"expected a %{area} address: {kind} (got {_area_name(addr)})")
            return None
        if addr.table is not None:
            self.error(loc, f"expected a bit, byte, word, dword or lword address (got '{addr.text}', a word "
                            "table): map one object per address")
            return None
        span = self._image_bits(loc, addr)
        if span is None:
            return None
        first, last = span
        for other_area, other_first, other_last, other_loc, other_text in claimed:
            if other_area == area and first <= other_last and other_first <= last:
                self.error(loc, f"'{addr.text}' overlaps {_key(other_loc)} ({other_text})")
                return addr
        claimed.append((area, first, last, loc, f"'{addr.text}'"))
        return addr

    def _probe(self):
        """A process image laid out as the profile's, for where addresses fall."""
        if getattr(self, "_probe_image", None) is None:
            from .image.memory import ProcessImage
            self._probe_image = ProcessImage(self.addressing or "iec")
        return self._probe_image

    def _image_bits(self, loc: tuple, addr: LocatedAddress) -> Optional[tuple]:
        """(first, last) bit of its area that addr covers, or None (and an
        error) outside the image. The layout is memory.py's: bytes for the
        IEC model, words for Schneider; bit n of byte b is bit 8b + n."""
        image = self._probe()
        if addr.bit is not None or addr.size in ("", "X"):
            if addr.bit is not None:     # %IW3:X2 (Schneider): a bit of a word
                word = image.byte_offset(LocatedAddress(addr.area, "W", addr.indices, None, None, addr.text))
                bit = 8 * word + addr.bit
            elif len(addr.indices) >= 2:
                bit = 8 * addr.indices[-2] + addr.indices[-1]
            else:
                bit = addr.indices[0]
            if bit >= 8 * image.size:
                self.error(loc, f"'{addr.text}' is outside the {image.size}-byte %{addr.area} area")
                return None
            return bit, bit
        try:
            _area, offset, nbytes = image.region(addr)
        except ValueError as exc:
            self.error(loc, str(exc))
            return None
        return 8 * offset, 8 * (offset + nbytes) - 1

    def _loopback_targets(self) -> list:
        """The %I bytes the loopback links write, which no TPDO may write too."""
        claimed = []
        for i, link in enumerate(self.loopback):
            try:
                _area, offset, _n = self._probe().region(link.target)
            except ValueError:
                continue
            claimed.append(("I", 8 * offset, 8 * (offset + link.nbytes) - 1, ("loopback", i, "to"),
                            f"'{link.target.text}', {link.nbytes} byte{'s' if link.nbytes > 1 else ''}"))
        return claimed

    def _sdo_values(self, here: tuple, writes: list) -> None:
        for k, write in enumerate(writes):
            if not isinstance(write, dict):
                continue
            value, size = write.get("value"), write.get("size")
            if _in_range(value, None, None) and size in (1, 2, 4) and not isinstance(size, bool):
                lo, hi = -(1 << (8 * size - 1)), (1 << (8 * size)) - 1
                if not lo <= value <= hi:
                    self.error(here + ("sdo", k, "value"), f"expected an integer from {lo} to {hi} for "
                                                           f"size = {size} (got {value})")

    def _sims(self, sims: list, names: dict, count: int, master: Optional[tuple]) -> None:
        """Simulators: on a bus, not two on one node id of a bus, not on the
        master's node id; unique names. A simulator may share a node id with
        a [[canopen.node]]: it is that node."""
        at_node: dict = {}
        sim_names: dict = {}
        units: dict = {}
        for i, sim in enumerate(sims):
            if not isinstance(sim, dict):
                continue
            here = ("sim", i)
            kind = sim.get("type")
            if isinstance(kind, str) and kind.lower() in MODBUS_SIM_TYPES:
                self._modbus_sim(here, sim, units)
                self._sim_name(here, sim, sim_names)
                self._sim_registers(here, sim)
                continue
            for key in ("modbus", "unit"):
                if key in sim:
                    self.error(here + (key,), f"only for a Modbus device ({', '.join(MODBUS_SIM_TYPES)}); "
                                              "a CAN device has bus and node_id")
            if "node_id" not in sim:
                self.error(here, "required key missing: node_id (a CAN device's node id)")
            bus = self._bus_of(here, sim, names, count, "a simulated device")
            node_id = sim.get("node_id")
            if bus is not None and _in_range(node_id, 1, NODE_ID_MAX):
                if master is not None and master == (bus, node_id):
                    self.error(here + ("node_id",), f"{node_id} is the CANopen master's own node id on bus "
                                                    f"'{bus}' (canopen.node_id)")
                elif (bus, node_id) in at_node:
                    self.error(here + ("node_id",), f"duplicate node id {node_id} on bus '{bus}' "
                                                    f"({_key(at_node[bus, node_id])} has it)")
                else:
                    at_node[bus, node_id] = here
            self._sim_name(here, sim, sim_names)
            self._sim_registers(here, sim)

    def _sim_registers(self, here: tuple, sim: dict) -> None:
        registers = sim.get("registers")
        if isinstance(registers, dict):
            for number in registers:
                if not _register_number(number):
                    self.error(here + ("registers", number), f"expected a register number from 0 to "
                               f'{U16_MAX} in decimal, such as "682" (got {_got(number)})')

    def _sim_name(self, here: tuple, sim: dict, names: dict) -> None:
        if "name" in sim:
            name = sim["name"]
            if not _is_ident(name):
                return        # pass 1 reports it
            first = names.setdefault(name.upper(), here)
            if first != here:
                self.error(here + ("name",), f"duplicate simulator name '{name}' ({_key(first)} has it; "
                                             "names are case-insensitive)")
            return
        kind, node_id = sim.get("type"), sim.get("node_id")
        if isinstance(kind, str) and kind.lower() in MODBUS_SIM_TYPES and _in_range(sim.get("unit"), 1, None):
            name = f"{kind.lower()}_{sim['unit']}"
            first = names.setdefault(name.upper(), here)
            if first != here:
                self.error(here, f"duplicate simulator name '{name}', the default <type>_<unit> "
                                 f"({_key(first)} has it): give one a name")
        elif isinstance(kind, str) and kind.lower() in SIM_TYPES and _in_range(node_id, 1, NODE_ID_MAX):
            name = f"{kind.lower()}{node_id}"
            first = names.setdefault(name.upper(), here)
            if first != here:
                self.error(here, f"duplicate simulator name '{name}', the default <type><node_id> "
                                 f"({_key(first)} has it): give one a name")


def _in_range(value, lo: Optional[int], hi: Optional[int]) -> bool:
    """An integer (not a bool) within lo..hi (None: unbounded)."""
    return isinstance(value, int) and not isinstance(value, bool) and (lo is None or value >= lo) \
        and (hi is None or value <= hi)


def _register_number(key) -> bool:
    return isinstance(key, str) and key.isascii() and key.isdigit() and int(key) <= U16_MAX


def _bit_count(addr: LocatedAddress) -> int:
    if addr.bit is not None or addr.size in ("", "X"):
        return 1
    return _address.SIZE_BITS[addr.size]


def _default_master_timeout(master_heartbeat_ms: int) -> int:
    """5 heartbeats of the master, within what 0x1016:01 holds."""
    return min(5 * master_heartbeat_ms, U16_MAX)


def _area_name(addr: LocatedAddress) -> str:
    return f"'{addr.text}', " + {"I": "an input", "Q": "an output", "M": "a memory address"}[addr.area]


# ====================================================================== build


def _build(model: _Root, rel: _Relations, data: dict, path: Optional[Path], base_dir: Path) -> PlcConfig:
    tasks = []
    for i, t in enumerate(model.task):
        key = f"task[{i}]"
        interval = t.interval
        if t.watchdog is None:
            watchdog = default_watchdog_ns(interval)
        else:
            watchdog = None if t.watchdog is False else t.watchdog
        programs = [ProgramInstance(p.instance, p.program, f"{key}.programs[{j}]")
                    for j, p in enumerate(t.programs)]
        tasks.append(TaskConfig(
            name=t.name, interval_ns=interval,
            pause_ns=t.pause if t.pause is not None else DEFAULT_PAUSE_NS,
            priority=t.priority, watchdog_ns=watchdog, sensitivity=t.sensitivity,
            programs=programs, key=key))
    retain = RetainConfig(model.retain.file, model.retain.period) if model.retain is not None else None
    can = [CanBusConfig(b.name, b.interface, b.channel, b.bitrate, dict(b.options), f"can[{i}]")
           for i, b in enumerate(model.can)]
    canopen = _build_canopen(model.canopen, rel) if model.canopen is not None else None
    sims = []
    for i, sim in enumerate(model.sim):
        modbus_device = sim.type in MODBUS_SIM_TYPES
        default_name = f"{sim.type}_{sim.unit}" if modbus_device else f"{sim.type}{sim.node_id}"
        sims.append(SimConfig(type=sim.type, name=sim.name or default_name, bus=rel.bus_of.get(("sim", i)),
                              node_id=sim.node_id, registers={int(r): v for r, v in sim.registers.items()},
                              key=f"sim[{i}]", modbus=rel.sim_connection.get(("sim", i)), unit=sim.unit))
    modbus = [_build_modbus(i, m, rel) for i, m in enumerate(model.modbus)]
    return PlcConfig(
        path=path, base_dir=base_dir, profile=model.plc.profile, programs=list(model.plc.programs),
        on_fault=model.plc.on_fault, start=model.plc.start, tasks=tasks, retain=retain,
        safe_outputs=rel.safe_outputs, loopback=rel.loopback, can=can, canopen=canopen, sims=sims,
        modbus=modbus, raw=data)


def _build_canopen(c: _Canopen, rel: _Relations) -> CanopenConfig:
    nodes = []
    for i, n in enumerate(c.node):
        key = f"canopen.node[{i}]"
        if n.heartbeat_timeout is not None:
            heartbeat_timeout = n.heartbeat_timeout
        else:
            heartbeat_timeout = 3 * n.heartbeat          # 0 when the node sends none
        if n.master_timeout is not None:
            master_timeout = n.master_timeout
        else:
            master_timeout = _default_master_timeout(c.heartbeat) if c.heartbeat else 0
        nodes.append(CanopenNodeConfig(
            name=n.name, node_id=n.id, eds=n.eds, mandatory=n.mandatory, heartbeat_ms=n.heartbeat,
            heartbeat_timeout_ms=heartbeat_timeout, master_timeout_ms=master_timeout,
            sdo=[SdoWriteConfig(w.object[0], w.object[1], w.value, w.size, f"{key}.sdo[{k}]")
                 for k, w in enumerate(n.sdo)],
            tpdo=_build_pdos(n.tpdo, ("canopen", "node", i, "tpdo"), rel),
            rpdo=_build_pdos(n.rpdo, ("canopen", "node", i, "rpdo"), rel),
            key=key))
    return CanopenConfig(bus=rel.bus_of["canopen",], node_id=c.node_id, heartbeat_ms=c.heartbeat,
                         sync_us=c.sync, sdo_timeout_ms=c.sdo_timeout, boot_timeout_ms=c.boot_timeout,
                         retry_ms=c.retry, nodes=nodes)


def _build_modbus(i: int, m: _Modbus, rel: _Relations) -> ModbusConnectionConfig:
    key = f"modbus[{i}]"
    channels = []
    for j, c in enumerate(m.channel):
        at = ("modbus", i, "channel", j)
        channels.append(ModbusChannelConfig(
            name=c.name or f"{m.name}_{j}", connection=m.name, unit=c.unit, function=c.function,
            offset=c.offset, count=c.count, write_offset=c.write_offset or 0,
            write_count=c.write_count or 0, read_to=rel.modbus_addresses.get(at + ("read_to",)),
            write_from=rel.modbus_addresses.get(at + ("write_from",)), trigger=c.trigger,
            period_ns=c.period * 1_000_000, edge=rel.modbus_addresses.get(at + ("edge",)), key=_key(at)))
    return ModbusConnectionConfig(
        name=m.name, transport=m.transport, device=m.device or "", baud=m.baud, parity=m.parity,
        stop_bits=m.stop_bits, data_bits=m.data_bits, frame_gap_us=m.frame_gap,
        host=m.host or "127.0.0.1", port=m.port if m.port is not None else 502, timeout_ms=m.timeout,
        retries=m.retries, reconnect_ms=m.reconnect, reconnect_max_ms=m.reconnect_max,
        channels=channels, key=key)


def _build_pdos(pdos: list, here: tuple, rel: _Relations) -> list:
    out = []
    for j, p in enumerate(pdos):
        at = here + (j,)
        entries = [PdoEntryConfig(e.object[0], e.object[1], rel.pdo_addresses[at + ("map", k)],
                                  _key(at + ("map", k)))
                   for k, e in enumerate(p.map)]
        out.append(PdoConfig(number=p.number, transmission=p.transmission, inhibit_us=p.inhibit,
                             event_ms=p.event, configure=p.configure, entries=entries, key=_key(at)))
    return out
