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

io_config/examples/ has one commented example per section.

Validation is two passes over the parsed TOML, and both run whatever the
other finds, so a file's errors are all reported at once, one per line:

  1. pydantic models (extra="forbid", strict): the shape of every table and
     the type and range of every value, each error at its key path;
  2. relations pydantic cannot see per value: interval vs freewheeling vs
     pause, unique task and instance names, safe outputs (the value type
     depends on the address), loopback addresses.

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
from .st.ast import LocatedAddress
from .st.profile import DEFAULT as _DEFAULT_PROFILE, PROFILES

__all__ = [
    "ConfigError", "ProgramInstance", "TaskConfig", "RetainConfig", "SafeOutput", "LoopbackLink",
    "PlcConfig", "load_config", "config_from_dict", "default_config_path", "default_watchdog_ns",
    "CanBusConfig", "PdoEntryConfig", "PdoConfig", "SdoWriteConfig", "CanopenNodeConfig", "CanopenConfig",
    "SimConfig",
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
    interface: str                   # any python-can interface name
    channel: str
    bitrate: int
    options: dict                    # passed to python-can
    key: str                         # "can[0]"


@dataclass
class PdoEntryConfig:
    index: int
    subindex: int
    address: LocatedAddress
    key: str                         # "canopen.node[0].tpdo[0].map[1]"


@dataclass
class PdoConfig:
    number: int
    transmission: int                # 0..240, 254, 255
    inhibit_us: int
    event_ms: int
    configure: bool                  # the master writes the mapping at boot
    entries: list[PdoEntryConfig]
    key: str


@dataclass
class SdoWriteConfig:
    index: int
    subindex: int
    value: int
    size: Optional[int]              # bytes; None: from the EDS
    key: str


@dataclass
class CanopenNodeConfig:
    name: str
    node_id: int
    eds: Path
    mandatory: bool
    heartbeat_ms: int                # the node's producer time (0 = none)
    heartbeat_timeout_ms: int        # the master's consumer timeout (0 = not watched)
    master_timeout_ms: int           # the node's consumer time for the master (0 = none)
    sdo: list[SdoWriteConfig]
    tpdo: list[PdoConfig]
    rpdo: list[PdoConfig]
    key: str


@dataclass
class CanopenConfig:
    bus: str
    node_id: int
    heartbeat_ms: int
    sync_us: int
    sdo_timeout_ms: int
    boot_timeout_ms: int
    retry_ms: int
    nodes: list[CanopenNodeConfig]
    key: str = "canopen"


@dataclass
class SimConfig:
    type: str
    name: str
    bus: str
    node_id: int
    registers: dict
    key: str


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
    resolved = Path(os.path.normpath(info.context["base_dir"] / Path(value).expanduser()))
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


def _duration_or_off(value) -> int:
    """A duration in ns, or 0 for "0ms" / false (switched off)."""
    if value is False:
        return 0
    ns = _duration_ns(value)
    if ns is None or ns < 0:
        raise _fail(f"a duration such as {DURATION_EXAMPLES}, or false", value)
    return ns


CAN_BITRATES = (10_000, 20_000, 50_000, 125_000, 250_000, 500_000, 800_000, 1_000_000)


def _bitrate(value) -> int:
    if isinstance(value, int) and not isinstance(value, bool) and value in CAN_BITRATES:
        return value
    raise _fail("a CANopen bitrate: " + ", ".join(str(b) for b in CAN_BITRATES), value)


def _text(what: str):
    def check(value) -> str:
        if isinstance(value, str) and value.strip():
            return value
        if isinstance(value, int) and not isinstance(value, bool):
            return str(value)
        raise _fail(what, value)
    return PlainValidator(check)


_OBJECT = re.compile(r"(?:0x)?([0-9A-Fa-f]{1,4}):(?:0x)?([0-9A-Fa-f]{1,2})")


def _object(value) -> tuple:
    """ "2004:06" (hex index : hex sub-index) -> (0x2004, 0x06)."""
    m = _OBJECT.fullmatch(value.strip()) if isinstance(value, str) else None
    if m is None:
        raise _fail('an object "index:subindex" in hex such as "2004:06"', value)
    return int(m.group(1), 16), int(m.group(2), 16)


def _transmission(value) -> int:
    if isinstance(value, int) and not isinstance(value, bool) and (0 <= value <= 240 or value in (254, 255)):
        return value
    raise _fail("a PDO transmission type: 0..240, 254 or 255", value)


def _eds_file(value, info: ValidationInfo) -> Path:
    """A shipped EDS by name ("ltmr", "fc280": io_config/eds/<name>.eds) or
    the path of an .eds file relative to the config file."""
    if not isinstance(value, str) or not value.strip():
        raise _fail('a shipped EDS name such as "ltmr" or the path of an .eds file', value)
    if re.fullmatch(r"[A-Za-z0-9_]+", value):
        shipped = resources.files("softplc.io_config") / "eds" / f"{value.lower()}.eds"
        if not shipped.is_file():
            names = sorted(p.name[:-4] for p in (resources.files("softplc.io_config") / "eds").iterdir()
                           if p.name.endswith(".eds"))
            raise PydanticCustomError("config", "no shipped EDS called {name} (there are: {names})",
                                      {"name": repr(value), "names": ", ".join(names)})
        return Path(str(shipped))
    resolved = Path(os.path.normpath(info.context["base_dir"] / Path(value).expanduser()))
    if not resolved.is_file():
        raise PydanticCustomError("config", "no such file: {path} (relative paths start at the "
                                  "config file's directory)", {"path": str(resolved)})
    return resolved


def _sdo_size(value) -> int:
    if value in (1, 2, 4) and not isinstance(value, bool):
        return value
    raise _fail("1, 2 or 4 (bytes)", value)


def _registers(value) -> dict:
    """{ "682" = 2 } -> {682: 2}: register numbers as keys, 16-bit values."""
    if not isinstance(value, dict):
        raise _fail('a table of register = value such as { "682" = 2 }', value)
    out = {}
    for key, v in value.items():
        if not (isinstance(key, str) and key.isdigit()):
            raise _fail('register numbers in decimal as keys, such as "682"', key)
        if not (isinstance(v, int) and not isinstance(v, bool) and 0 <= v <= 0xFFFF):
            raise _fail(f"a register value 0..65535 for register {key}", v)
        out[int(key)] = v
    return out


Duration = Annotated[int, PlainValidator(_duration)]
DurationOrOff = Annotated[int, PlainValidator(_duration_or_off)]
ObjectRef = Annotated[tuple, PlainValidator(_object)]
Watchdog = Annotated[Any, PlainValidator(_watchdog)]
StFile = Annotated[Path, PlainValidator(_st_file)]


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


class _Can(_Model):
    name: Annotated[str, _identifier("a bus name")] = Field("can0", description='a bus name such as "can0"')
    interface: Annotated[str, _text('a python-can interface such as "socketcan", "pcan" or "virtual"')] = \
        Field(description='a python-can interface such as "socketcan", "pcan" or "virtual"')
    channel: Annotated[str, _text('a channel such as "can0"')] = Field(description='a channel such as "can0"')
    bitrate: Annotated[int, PlainValidator(_bitrate)] = Field(250_000, description="a CANopen bitrate")
    options: dict[str, Any] = Field(default_factory=dict, description="a table of python-can options")


class _PdoEntry(_Model):
    object: ObjectRef = Field(description='an object "index:subindex" in hex such as "2004:06"')
    address: Any = Field(description='an image address such as "%IW100"')


class _Pdo(_Model):
    number: Annotated[int, _int_range(1, 512)] = Field(description="a PDO number 1..512")
    transmission: Annotated[int, PlainValidator(_transmission)] = Field(255, description="0..240, 254 or 255")
    inhibit: DurationOrOff = Field(0, description="a duration such as 5ms")
    event: DurationOrOff = Field(0, description="a duration such as 500ms")
    configure: bool = Field(True, description="true or false")
    map: list[_PdoEntry] = Field(min_length=1, max_length=8, description='an array of 1 to 8 '
                                 '{ object = "2004:06", address = "%IW100" } tables')


class _SdoWrite(_Model):
    object: ObjectRef = Field(description='an object "index:subindex" in hex such as "2007:21"')
    value: Annotated[int, _int_range(-(1 << 31), (1 << 32) - 1)] = Field(description="an integer")
    size: Optional[Annotated[int, PlainValidator(_sdo_size)]] = Field(None, description="1, 2 or 4")


class _Node(_Model):
    name: Annotated[str, _identifier("a node name")] = Field(description='a node name such as "motor"')
    id: Annotated[int, _int_range(1, 127)] = Field(description="a node id 1..127")
    eds: Annotated[Path, PlainValidator(_eds_file)] = Field(description='"ltmr", "fc280" or an .eds file')
    mandatory: bool = Field(True, description="true or false")
    heartbeat: DurationOrOff = Field(100_000_000, description="a duration such as 100ms, or false")
    heartbeat_timeout: Optional[DurationOrOff] = Field(None, description="a duration such as 300ms")
    master_timeout: Optional[DurationOrOff] = Field(None, description="a duration such as 500ms, or false")
    sdo: list[_SdoWrite] = Field(default_factory=list, description='an array of { object = "2007:21", '
                                                                   'value = 2 } tables')
    tpdo: list[_Pdo] = Field(default_factory=list, description="[[canopen.node.tpdo]] tables")
    rpdo: list[_Pdo] = Field(default_factory=list, description="[[canopen.node.rpdo]] tables")


class _Canopen(_Model):
    bus: Optional[Annotated[str, _identifier("a bus name")]] = Field(None, description='a [[can]] name')
    node_id: Annotated[int, _int_range(1, 127)] = Field(127, description="a node id 1..127")
    heartbeat: DurationOrOff = Field(100_000_000, description="a duration such as 100ms, or false")
    sync: DurationOrOff = Field(0, description="a duration such as 10ms, or false")
    sdo_timeout: Duration = Field(500_000_000, description="a duration such as 500ms")
    boot_timeout: Duration = Field(2_000_000_000, description="a duration such as 2s")
    retry: Duration = Field(1_000_000_000, description="a duration such as 1s")
    node: list[_Node] = Field(default_factory=list, description="[[canopen.node]] tables")


class _Sim(_Model):
    type: Annotated[str, _choice(("ltmr",))] = Field(description="'ltmr'")
    name: Optional[Annotated[str, _identifier("a simulator name")]] = Field(None, description="a name")
    bus: Optional[Annotated[str, _identifier("a bus name")]] = Field(None, description='a [[can]] name')
    node_id: Annotated[int, _int_range(1, 127)] = Field(description="a node id 1..127")
    registers: Annotated[dict, PlainValidator(_registers)] = Field(
        default_factory=dict, description='a table such as { "682" = 2 }')


class _Root(_Model):
    plc: _Plc = Field(description='a [plc] table with at least programs = ["file.st"]')
    retain: Optional[_Retain] = Field(None, description="a [retain] table")
    task: list[_Task] = Field(default_factory=list, description="[[task]] tables")
    outputs: Optional[_Outputs] = Field(None, description="an [outputs] table")
    loopback: list[_Loopback] = Field(default_factory=list, description="[[loopback]] tables")
    can: list[_Can] = Field(default_factory=list, description="[[can]] tables")
    canopen: Optional[_Canopen] = Field(None, description="a [canopen] table")
    sim: list[_Sim] = Field(default_factory=list, description="[[sim]] tables")


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
    index; stable, so the order within an entry is the schema's."""
    order = {name: i for i, name in enumerate(data)}

    def rank(item):
        loc = item[0]
        if not loc:
            return (-1, -1)
        first = order.get(loc[0], len(order))
        index = loc[1] if len(loc) > 1 and isinstance(loc[1], int) else -1
        return (first, index)
    return sorted(errors, key=rank)


# ====================================================================== relations


class _Relations:
    """The checks between values, on the raw data, tolerant of values that
    pass 1 refuses (it reports those). Also parses the safe outputs and the
    loopback links (addresses depend on the profile)."""

    def __init__(self, data: dict, base_dir: Path) -> None:
        self.errors: list = []
        self.safe_outputs: list = []
        self.loopback: list = []
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
        self.pdo_entries: dict = {}   # loc of a map entry -> LocatedAddress
        self.buses: dict = {}         # loc of a bus reference -> bus name
        self._can(data)

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


    # ---------------------------------------------------------------- CAN, CANopen, simulators

    def _can(self, data: dict) -> None:
        buses = data.get("can") if isinstance(data.get("can"), list) else []
        names: dict = {}
        for i, bus in enumerate(buses):
            name = bus.get("name", "can0") if isinstance(bus, dict) else None
            if _is_ident(name):
                first = names.setdefault(name, i)
                if first != i:
                    self.error(("can", i, "name"), f"duplicate bus name '{name}' (can[{first}] has it)")
        canopen = data.get("canopen")
        if isinstance(canopen, dict):
            self._bus_ref(("canopen",), canopen, names)
            self._canopen(canopen)
        sims = data.get("sim") if isinstance(data.get("sim"), list) else []
        taken: dict = {}
        for i, sim in enumerate(sims):
            if not isinstance(sim, dict):
                continue
            bus = self._bus_ref(("sim", i), sim, names)
            node = sim.get("node_id")
            if bus is not None and isinstance(node, int):
                first = taken.setdefault((bus, node), i)
                if first != i:
                    self.error(("sim", i, "node_id"), f"sim[{first}] already is node {node} on bus '{bus}'")

    def _bus_ref(self, here: tuple, table: dict, names: dict) -> Optional[str]:
        """The [[can]] bus a section uses: its bus key, or the only bus."""
        bus = table.get("bus")
        if bus is None:
            if len(names) == 1:
                bus = next(iter(names))
            else:
                self.error(here, "needs a [[can]] bus" if not names else
                           f"there are several [[can]] buses; say which: bus = \"{next(iter(names))}\"")
                return None
        elif isinstance(bus, str) and bus not in names:
            self.error(here + ("bus",), f"no [[can]] bus called '{bus}' (there are: {', '.join(names) or 'none'})")
            return None
        self.buses[here] = bus
        return bus

    def _canopen(self, canopen: dict) -> None:
        master = canopen.get("node_id", 127)
        master_hb = _duration_or_off_quiet(canopen.get("heartbeat", "100ms"))
        nodes = canopen.get("node") if isinstance(canopen.get("node"), list) else []
        ids: dict = {}
        names: dict = {}
        used: list = []   # (area, start, end, loc): image bytes the PDOs write or read
        for i, node in enumerate(nodes):
            if not isinstance(node, dict):
                continue
            here = ("canopen", "node", i)
            nid, name = node.get("id"), node.get("name")
            if isinstance(nid, int):
                if nid == master:
                    self.error(here + ("id",), f"{nid} is the master's own node_id")
                first = ids.setdefault(nid, i)
                if first != i:
                    self.error(here + ("id",), f"duplicate node id {nid} (canopen.node[{first}] has it)")
            if _is_ident(name):
                first = names.setdefault(name.upper(), i)
                if first != i:
                    self.error(here + ("name",), f"duplicate node name '{name}' (canopen.node[{first}] has it)")
            hb = _duration_or_off_quiet(node.get("heartbeat", "100ms"))
            timeout = node.get("heartbeat_timeout")
            if timeout is not None and hb is not None and hb > 0:
                t = _duration_or_off_quiet(timeout)
                if t is not None and 0 < t <= hb:
                    self.error(here + ("heartbeat_timeout",), "must be longer than the node's heartbeat")
            mt = node.get("master_timeout")
            if mt not in (None, False) and master_hb is not None:
                t = _duration_or_off_quiet(mt)
                if t and master_hb == 0:
                    self.error(here + ("master_timeout",), "the master produces no heartbeat "
                                                           "([canopen] heartbeat is off)")
                elif t and t <= master_hb:
                    self.error(here + ("master_timeout",), "must be longer than the master's heartbeat")
            for direction, area in (("tpdo", "I"), ("rpdo", "Q")):
                pdos = node.get(direction) if isinstance(node.get(direction), list) else []
                numbers: dict = {}
                for j, pdo in enumerate(pdos):
                    if not isinstance(pdo, dict):
                        continue
                    number = pdo.get("number")
                    if isinstance(number, int):
                        first = numbers.setdefault(number, j)
                        if first != j:
                            self.error(here + (direction, j, "number"),
                                       f"duplicate {direction.upper()} {number} ({direction}[{first}] has it)")
                    entries = pdo.get("map") if isinstance(pdo.get("map"), list) else []
                    for k, entry in enumerate(entries):
                        if isinstance(entry, dict) and "address" in entry:
                            self._pdo_address(here + (direction, j, "map", k), entry["address"], area, used)

    def _probe(self):
        if getattr(self, "_probe_image", None) is None:
            from .image.memory import ProcessImage
            self._probe_image = ProcessImage(self.addressing or "iec")
        return self._probe_image

    def _pdo_address(self, loc: tuple, text, area: str, used: list) -> None:
        addr = self._address(loc + ("address",), text, f"%{area}W100, %{area}X10.0")
        if addr is None:
            return
        kind = "a TPDO maps to %I inputs" if area == "I" else "an RPDO maps to %Q outputs"
        if addr.area != area:
            self.error(loc + ("address",), f"{kind} (got {_area_name(addr)})")
            return
        if addr.table is not None:
            self.error(loc + ("address",), f"expected a bit, byte, word, dword or lword address (got '{addr.text}')")
            return
        self.pdo_entries[loc] = addr
        if addr.bit is not None or addr.size in ("", "X"):
            return
        try:
            _a, start, n = self._probe().region(addr)
        except ValueError:
            return
        for other_area, o_start, o_end, other in used:
            if other_area == area and start < o_end and o_start < start + n:
                self.error(loc + ("address",), f"{addr.text} overlaps {_key(other)}")
                return
        used.append((area, start, start + n, loc + ("address",)))


def _duration_or_off_quiet(value) -> Optional[int]:
    try:
        return _duration_or_off(value)
    except PydanticCustomError:
        return None


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
    sims = [SimConfig(sim.type, sim.name or f"{sim.type}{sim.node_id}", rel.buses[("sim", i)], sim.node_id,
                      dict(sim.registers), f"sim[{i}]") for i, sim in enumerate(model.sim)]
    return PlcConfig(
        path=path, base_dir=base_dir, profile=model.plc.profile, programs=list(model.plc.programs),
        on_fault=model.plc.on_fault, start=model.plc.start, tasks=tasks, retain=retain,
        safe_outputs=rel.safe_outputs, loopback=rel.loopback, can=can, canopen=canopen, sims=sims, raw=data)


def _ms(ns: int) -> int:
    return round(ns / 1_000_000)


def _build_canopen(c: _Canopen, rel: _Relations) -> CanopenConfig:
    nodes = []
    for i, n in enumerate(c.node):
        key = f"canopen.node[{i}]"

        def pdos(direction: str, items: list) -> list:
            out = []
            for j, p in enumerate(items):
                here = ("canopen", "node", i, direction, j)
                entries = [PdoEntryConfig(e.object[0], e.object[1], rel.pdo_entries[here + ("map", k)],
                                          f"{key}.{direction}[{j}].map[{k}]")
                           for k, e in enumerate(p.map)]
                out.append(PdoConfig(p.number, p.transmission, round(p.inhibit / 1000), _ms(p.event),
                                     p.configure, entries, f"{key}.{direction}[{j}]"))
            return out
        heartbeat = _ms(n.heartbeat)
        timeout = _ms(n.heartbeat_timeout) if n.heartbeat_timeout is not None else 3 * heartbeat
        master_timeout = _ms(n.master_timeout) if n.master_timeout is not None else 5 * _ms(c.heartbeat)
        sdo = [SdoWriteConfig(w.object[0], w.object[1], w.value, w.size, f"{key}.sdo[{k}]")
               for k, w in enumerate(n.sdo)]
        nodes.append(CanopenNodeConfig(n.name, n.id, n.eds, n.mandatory, heartbeat, timeout, master_timeout,
                                       sdo, pdos("tpdo", n.tpdo), pdos("rpdo", n.rpdo), key))
    return CanopenConfig(rel.buses[("canopen",)], c.node_id, _ms(c.heartbeat), round(c.sync / 1000),
                         _ms(c.sdo_timeout), _ms(c.boot_timeout), _ms(c.retry), nodes)
