"""Reading a configuration file: TOML, then the two passes over the
sections of the core and of every registered bus, then the PlcConfig the
engine is built from.

    cfg = load_config("io_config/plant.toml")     # PlcConfig, or ConfigError
    cfg.tasks, cfg.sims, cfg.can, cfg.modbus ...  # a bus's section by its key
    cfg.sections["web"]                            # a server's ServerConfig, or None

Pass 1 validates the whole document against one pydantic model composed of
the sections' models; pass 2 runs each section's relations on the raw data
(config/relations.py). Both run whatever the other finds, so a file's
errors are all reported at once, in file order.
"""

from __future__ import annotations

import math
import os
import re
import tomllib
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from types import GenericAlias
from typing import Any

from pydantic import Field, ValidationError, create_model

from ..plugin.registry import Registry, loaded, plugin_sections, registry
from ..program.libraries import Library
from ..program.shipped import shipped_named
from ..st.syntax.build_decls import identifier_from_path
from .errors import ConfigError, in_file_order, key_text, not_finite, translate
from .plc import CORE_SECTIONS, DEFAULT_SPIN_NS, RetainConfig, SafeOutput, TaskConfig, with_safe_defaults
from .relations import Relations
from .scenario import SCENARIO_SECTIONS, ScenarioWrite
from .section import Section
from .servers import SERVER_SECTIONS
from .sims import SimConfig, SimSection
from .values import Model, got


@dataclass
class PlcConfig:
    path: Path | None  # the file as given; None when built from a dict alone
    base_dir: Path  # relative paths in the file resolve against it
    profile: str
    programs: list[Path]  # the ST files, absolute
    on_fault: str  # "task" | "plc"
    start: str  # "warm" | "cold"
    #: the user's libraries ([plc] libraries), compiled in as far as the programs use them
    libraries: list[Library] = field(default_factory=list)
    #: the real clock busy-waits this long before each release ([plc] spin)
    spin_ns: int = DEFAULT_SPIN_NS
    #: the scan thread's SCHED_FIFO priority on the real clock, 0: the normal scheduler ([plc] realtime_priority)
    realtime_priority: int = 0
    tasks: list[TaskConfig] = field(default_factory=list)
    retain: RetainConfig | None = None
    safe_outputs: list[SafeOutput] = field(default_factory=list)
    sims: list[SimConfig] = field(default_factory=list)
    #: a scenario's writes: [init] (and --set) at the first scan, [[schedule]] at their times
    init: list[ScenarioWrite] = field(default_factory=list)
    schedule: list[ScenarioWrite] = field(default_factory=list)
    #: the buses' sections by TOML key (cfg.can is cfg.sections["can"])
    sections: dict[str, Any] = field(default_factory=dict)
    raw: dict = field(default_factory=dict)  # the parsed TOML
    #: what may be wrong but need not be, each "file: key: message" (logged by the launcher)
    warnings: list[str] = field(default_factory=list)

    def __getattr__(self, name: str) -> Any:
        sections = self.__dict__.get("sections")
        if sections is not None and name in sections:
            return sections[name]
        raise AttributeError(f"{type(self).__name__} has no attribute or section {name!r}")


def default_config_path() -> Path:
    """The embedded default configuration (io_config/default.toml, installed
    as package data of softplc.io_config)."""
    return Path(str(resources.files("softplc.io_config").joinpath("default.toml")))


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
        raise ConfigError(label, [("", f"cannot read the configuration file: {exc.strerror or exc}")]) from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigError(label, [("", f"not UTF-8 text (byte {exc.start}); a TOML file is UTF-8")]) from None
    deep = _too_deep_at(text)
    if deep is not None:  # before tomllib, which recurses per level (and a collector's callback with it)
        raise ConfigError(label, [("", TOO_DEEP)], position=deep)
    try:
        parsed = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        message, position = _toml_error(str(exc), text)
        raise ConfigError(label, [("", f"invalid TOML: {message}")], position=position) from None
    except RecursionError:  # the reader recurses into arrays and inline tables
        raise ConfigError(label, [("", TOO_DEEP)]) from None
    except ValueError:  # a decimal integer of more digits than Python converts (4300)
        position, digits = _long_number(text)
        raise ConfigError(
            label, [("", f"an integer of {digits} digits: no key takes a number that large")], position=position
        ) from None
    return config_from_dict(parsed, path)


#: tables and arrays nested in one another, at most (the shipped examples nest 8 deep)
MAX_DEPTH = 32
TOO_DEEP = f"tables, arrays or dotted keys nested more than {MAX_DEPTH} deep: no key takes that"
#: an integer of more bits than this is no key's value (an LWORD, the largest, has 64)
MAX_INT_BITS = 64


#: what counts in the nesting of a TOML text: a comment, a string (skipped
#: whole), a bracket or brace; a quote that opens no whole string stops the
#: scan (tomllib reports the file)
_NESTING_TOKEN = re.compile(
    r"""#[^\n]*|'''.*?'''|\"\"\"(?:\\.|[^\\])*?\"\"\"|"(?:[^"\\\n]|\\.)*"|'[^'\n]*'|([\[{])|[\]}]|(["'])""",
    re.DOTALL,
)


def _too_deep_at(text: str) -> tuple | None:
    """(line, column) of the first bracket or brace nested more than
    MAX_DEPTH deep, or None. tomllib reads an array or inline table by
    recursion: 5000 levels are a RecursionError inside it, and any gc
    callback run that deep fails too ("Exception ignored in
    sys.unraisablehook"). A value nested this deep has a key path longer
    than MAX_DEPTH, which _unusable refuses anyway."""
    depth = 0
    for m in _NESTING_TOKEN.finditer(text):
        if m.group(2):
            return None
        if m.group(1):
            depth += 1
            if depth > MAX_DEPTH:
                return _line_column(text, m.start())
        elif m.group().startswith(("]", "}")):
            depth = max(0, depth - 1)
    return None


def _long_number(text: str) -> tuple:
    """((line, column), digits) of the longest run of digits in text."""
    best = max(re.finditer(r"[0-9][0-9_]*", text), key=lambda m: len(m.group()), default=None)
    if best is None:
        return None, 0
    return _line_column(text, best.start()), len(best.group().replace("_", ""))


def _line_column(text: str, offset: int) -> tuple:
    """(line, column) of offset in text, both from 1."""
    return text.count("\n", 0, offset) + 1, offset - (text.rfind("\n", 0, offset) + 1) + 1


_TOML_AT = re.compile(r"\s*\(at line (\d+), column (\d+)\)$")
_TOML_AT_END = re.compile(r"\s*\(at end of document\)$")


def _toml_error(message: str, text: str) -> tuple:
    """tomllib's message without its position suffix, and (line, column)."""
    m = _TOML_AT.search(message)
    if m:
        return message[: m.start()], (int(m.group(1)), int(m.group(2)))
    m = _TOML_AT_END.search(message)
    if m:
        lines = text.split("\n")
        return message[: m.start()] + " at the end of the file", (len(lines), len(lines[-1]) + 1)
    return message, None


def _unusable(root, data: Any) -> list:
    """(loc, message) of every value no key takes, found without recursion
    (nothing recursive may see the data before this has cut it): tables and
    arrays nested more than MAX_DEPTH deep, inf and nan (TOML writes them,
    no key takes them: a duration, a count, a parameter's value), integers
    of more than MAX_INT_BITS bits."""
    found = []
    stack: list = [((), data)]
    while stack:
        here, node = stack.pop()
        if isinstance(node, (dict, list)):
            if len(here) >= MAX_DEPTH:
                found.append((here, TOO_DEEP))
                continue
            items = node.items() if isinstance(node, dict) else enumerate(node)
            stack.extend((here + (key,), value) for key, value in reversed(list(items)))
        elif isinstance(node, float) and not math.isfinite(node):
            found.append((here, not_finite(root, here, node)))
        elif isinstance(node, int) and not isinstance(node, bool) and node.bit_length() > MAX_INT_BITS:
            found.append((here, not_finite(root, here, node, "an integer of at most 64 bits")))
    return found


def _replaced(data: dict, locs: list) -> dict:
    """data with None at each of locs: the tables and arrays on the way to
    them copied, the rest shared (the caller's data stays as it is)."""
    out = dict(data)
    copied: set = {()}
    for loc in locs:
        node: Any = out
        for i, part in enumerate(loc[:-1]):
            here = loc[: i + 1]
            if here not in copied:
                node[part] = dict(node[part]) if isinstance(node[part], dict) else list(node[part])
                copied.add(here)
            node = node[part]
        node[loc[-1]] = None
    return out


class _Document:
    """The sections of a configuration and the pass-1 model of the whole
    document, for one state of the registry. Without one (reg None), for a
    document of the core's and the servers' keys alone: its model has the
    keys given (keys) and [plc], the other core and server sections are
    checked and built as absent, and the buses' sections, known by their
    keys only (the registry's index: plugin_sections), take their value for
    a file without them."""

    def __init__(self, reg: Registry | None, keys: frozenset = frozenset()) -> None:
        self.version = reg.version if reg is not None else None
        #: the value of each section the document cannot have, by key
        self.absent: dict[str, Any] = {}
        if reg is not None:
            sims: list[Section] = [SimSection(reg)]
            bus_sections = [s for bus in reg.buses for s in bus.sections]
            for section in bus_sections:
                section.bind(reg)
        else:
            sims, bus_sections = [], []
            self.absent = {"sim": [], **{key: [] if many else None for key, many in plugin_sections()}}
        # the document's keys in this order ("expected one of plc, retain ..."); the
        # simulated devices are checked last, when the buses they sit on are known
        core = [*CORE_SECTIONS, *SCENARIO_SECTIONS, *SERVER_SECTIONS]
        self.sections: list[Section] = [*core, *sims, *bus_sections]
        self.check_order: list[Section] = [*core, *bus_sections, *sims]
        if reg is None:
            self.sections = [s for s in self.sections if s.key in keys or s.key == "plc"]
        fields: dict[str, Any] = {}
        for section in self.sections:
            # list[model], built as a call: mypy takes no runtime value as a type argument
            annotation: Any = GenericAlias(list, section.model) if section.many else section.model | None
            if section.key == "plc":
                fields[section.key] = (section.model, Field(description=section.description))
            elif section.many:
                fields[section.key] = (annotation, Field(default_factory=list, description=section.description))
            else:
                fields[section.key] = (annotation, Field(None, description=section.description))
        self.root = create_model("Document", __base__=Model, **fields)

    def value(self, model: Any, section: Section) -> Any:
        """The section's value in the validated model: its default where
        the model has no such key (a section absent from a core document)."""
        return getattr(model, section.key) if section.key in self.root.model_fields else section.default


_document: _Document | None = None
#: the documents of core and server keys, by the keys they have
_core_documents: dict[frozenset, _Document] = {}
#: the keys of a document checked without the registry: the core's and the servers'
_CORE_KEYS = frozenset(s.key for s in (*CORE_SECTIONS, *SCENARIO_SECTIONS, *SERVER_SECTIONS))


def _current_document(data: dict | None = None) -> _Document:
    """The document for data (None: for any data): without loading the
    buses and devices while the registry is not loaded and data has only
    the core's and the servers' keys (no bus section, no [[sim]] table)."""
    global _document
    if data is not None and not loaded() and data.keys() <= _CORE_KEYS:
        keys = frozenset(data)
        doc = _core_documents.get(keys)
        if doc is None:
            doc = _core_documents[keys] = _Document(None, keys)
        return doc
    reg = registry()
    if _document is None or _document.version != reg.version:
        _document = _Document(reg)
    return _document


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
        raise ConfigError(label, [("", f"expected a TOML document (got {got(data)})")])
    doc = _current_document(data)
    raw = data
    errors = _unusable(doc.root, data)
    if errors:  # the passes see none of them: None in their place, reported here
        data = _replaced(data, [loc for loc, _message in errors])
    refused = {loc for loc, _message in errors}
    model = None
    try:
        model = doc.root.model_validate(data, context={"base_dir": base_dir})
    except ValidationError as exc:
        errors.extend(e for e in (translate(doc.root, err) for err in exc.errors()) if e[0] not in refused)
    ctx = Relations(data, base_dir)
    for section in doc.check_order:
        section.check(data.get(section.key), ctx)
    errors.extend(e for e in ctx.errors if e[0] not in refused)
    if errors:
        errors = in_file_order(errors, data)
        raise ConfigError(label, [(key_text(loc), message) for loc, message in errors])
    assert model is not None
    built = {s.key: s.build(doc.value(model, s), ctx) for s in doc.check_order}
    built.update(doc.absent)  # (after the servers' sections, in registry order: as a full document's)
    plc = built.pop("plc")
    core = {
        "retain": built.pop("retain"),
        "tasks": built.pop("task"),
        "safe_outputs": with_safe_defaults(built.pop("outputs"), ctx),
        "sims": built.pop("sim"),
        "init": built.pop("init"),
        "schedule": built.pop("schedule"),
    }
    return PlcConfig(
        path=Path(path) if path is not None else None,
        base_dir=base_dir,
        profile=plc.profile,
        programs=list(plc.programs),
        libraries=[
            _shipped(lib.shipped)
            if lib.shipped is not None
            else Library(lib.path, lib.namespace or identifier_from_path(str(lib.path)), lib.profile)
            for lib in plc.libraries
        ],
        on_fault=plc.on_fault,
        start=plc.start,
        spin_ns=plc.spin,
        realtime_priority=plc.realtime_priority,
        sections=built,
        raw=raw,
        warnings=[f"{label}: {key_text(loc)}: {message}" for loc, message in in_file_order(ctx.warnings, data)],
        **core,
    )


def _shipped(name: str) -> Library:
    lib = shipped_named(name)
    assert lib is not None  # (the section's check: config/values.shipped_library)
    return lib
