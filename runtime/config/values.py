"""Configuration values: the checks of single TOML values (durations,
identifiers, choices, files, integers in a range), each refusing a value
with a message in the configuration's own words, and the base model of
every table. Sections of the core and of the buses build on these."""

from __future__ import annotations

import difflib
import ipaddress
import os
import re
import stat
from pathlib import Path
from typing import Annotated, Any, TypeGuard

from pydantic import BaseModel, ConfigDict, Field, PlainValidator, ValidationInfo
from pydantic_core import PydanticCustomError

from ..durations import EXAMPLES as DURATION_EXAMPLES
from ..durations import parse_duration_ns
from ..image import address as _address
from ..st.ast import LocatedAddress

U16_MAX = 0xFFFF
#: every duration of a configuration is at most this (a day): beyond, clocks,
#: timers and serial timeouts overflow, and no plant waits that long
MAX_DURATION_NS = 86_400_000_000_000
MAX_DURATION_TEXT = "1d"
#: a value longer than LONG characters is shown as its first KEEP and its
#: length; so is a run of text longer than LONG_RUN (no path is, in practice)
LONG, LONG_RUN, KEEP = 100, 255, 60


class Model(BaseModel):
    """A table of the file: unknown keys refused, no coercion of values."""

    model_config = ConfigDict(extra="forbid", strict=True)


def got(value) -> str:
    """A value as the user wrote it, for '(got ...)'; a long string cut:
    'xxxx…' (5000 characters)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        if len(value) > LONG:
            head = repr(value[:KEEP])
            return f"{head[:-1]}…{head[-1]} ({len(value)} characters)"
        return repr(value)
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "an empty array" if not value else "an array"
    if isinstance(value, int) and value.bit_length() > 128:  # repr refuses beyond 4300 digits
        return f"an integer of about {int(value.bit_length() * 0.30103) + 1} digits"
    if isinstance(value, (int, float)):
        return repr(value)
    return f"a {type(value).__name__}"  # TOML dates and times


# a run of text with no space, quote, bracket or separator: a value, a path
_RUN = re.compile(r"[^\s'\"(),:;\[\]{}]{" + str(LONG_RUN + 1) + ",}")
#: a message longer than this is cut at its end
MESSAGE_MAX = 1000


def cut(text: str) -> str:
    """A message with every long run of text in it (a value, a path: no
    space, quote, bracket or separator in LONG_RUN characters) cut to its first KEEP
    characters and its length, and the whole to at most MESSAGE_MAX
    characters: what a configuration error echoes stays readable."""
    text = _RUN.sub(lambda m: f"{m.group()[:KEEP]}… ({len(m.group())} characters)", text)
    return text if len(text) <= MESSAGE_MAX else text[: MESSAGE_MAX - 1] + "…"


def fail(expected: str, value) -> PydanticCustomError:
    return PydanticCustomError("config", "expected {expected} (got {got})", {"expected": expected, "got": got(value)})


_BARE = re.compile(r"\s*\d+(\.\d*)?\s*")


def duration_ns(value) -> int | None:
    """A duration of the configuration in ns, None when value is none; a
    number without its unit (10, "10", 2.5: ms or s?) is refused with the
    hint, unless it is 0 (zero in any unit)."""
    bare = (isinstance(value, (int, float)) and not isinstance(value, bool)) or (
        isinstance(value, str) and _BARE.fullmatch(value) is not None
    )
    try:
        ns = parse_duration_ns(value)
    except (OverflowError, ValueError):  # inf, nan
        return None
    if bare and ns and ns > 0:
        number = value.strip() if isinstance(value, str) else value
        number = number if len(str(number)) <= 12 else 10
        raise PydanticCustomError(
            "config",
            "expected a duration with its unit, such as {number}ms or {number}s (got {got}: a number alone has none)",
            {"number": str(number), "got": got(value)},
        )
    return ns


def positive_duration(value) -> int:
    """A duration > 0 in ns, at most a day: '10ms', 'T#1s', '1s500ms', or a bare number of ms."""
    ns = duration_ns(value)
    if ns is None and isinstance(value, str) and negative(value):
        ns = -1
    if ns is None:
        raise fail(f"a duration such as {DURATION_EXAMPLES}", value)
    if ns <= 0:
        raise fail(f"a duration > 0 such as {DURATION_EXAMPLES}", value)
    return at_most_a_day(ns, value)


def at_most_a_day(ns: int, value, or_off: str = "") -> int:
    """ns, or the error of a duration beyond MAX_DURATION_NS."""
    if ns > MAX_DURATION_NS:
        raise fail(f"a duration of at most {MAX_DURATION_TEXT}{or_off}", value)
    return ns


def negative(text: str) -> bool:
    """'-5ms', 'T#-5ms': a duration but for its sign."""
    text = text.strip().lower()
    for prefix in ("time#", "t#"):
        if text.startswith(prefix):
            text = text[len(prefix) :]
            break
    return text.startswith("-") and parse_duration_ns(text[1:]) is not None


def watchdog(value):
    """A duration > 0 in ns, or False (no watchdog)."""
    if value is False:
        return False
    ns = duration_ns(value)
    if ns is None or ns <= 0:
        raise fail(f"a duration > 0 such as {DURATION_EXAMPLES}, or false for no watchdog", value)
    return at_most_a_day(ns, value, ", or false for no watchdog")


SPIN_MAX_NS = 10_000_000
SPIN_EXPECTED = "a duration from 0 to 10ms such as 200us, 0.5ms or 0"


def spin_duration(value) -> int:
    """The real clock's busy wait before a release, in ns: 0 .. 10 ms."""
    ns = duration_ns(value)
    if ns is None or not 0 <= ns <= SPIN_MAX_NS:
        raise fail(SPIN_EXPECTED, value)
    return ns


def int_range(lo: int, hi: int | None = None):
    def check(value) -> int:
        if isinstance(value, int) and not isinstance(value, bool) and value >= lo and (hi is None or value <= hi):
            return value
        raise fail(f"an integer from {lo} to {hi}" if hi is not None else f"an integer >= {lo}", value)

    return PlainValidator(check)


def real_range(lo: float, hi: float, what: str = "a number"):
    """A number (an integer is taken too) from lo to hi, as a float; what says which, in the message."""

    def check(value) -> float:
        if isinstance(value, int | float) and not isinstance(value, bool) and lo <= value <= hi:
            return float(value)
        raise fail(f"{what} from {lo} to {hi}", value)

    return PlainValidator(check)


IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*", re.A)


def is_ident(value: object) -> TypeGuard[str]:
    return isinstance(value, str) and IDENT.fullmatch(value) is not None


#: a name of the configuration (a task, a bus, a node ...) has at most this many
#: characters, so that no log line or message ever has to cut one
MAX_NAME = LONG
#: a text value (a CAN channel, a serial port, a host) at most this many
MAX_TEXT = LONG_RUN


def identifier(what: str):
    def check(value) -> str:
        if is_ident(value) and len(value) <= MAX_NAME:
            return value
        if is_ident(value):
            raise fail(f"{what}: an IEC identifier of at most {MAX_NAME} characters", value)
        raise fail(f"{what}: an IEC identifier (letters, digits, _; not starting with a digit)", value)

    return PlainValidator(check)


def choice(options):
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
        raise PydanticCustomError(
            "config", "expected one of {listed} (got {got}{hint})", {"listed": listed, "got": got(value), "hint": hint}
        )

    return PlainValidator(check)


def st_file(value, info: ValidationInfo) -> Path:
    """An existing ST file, relative to the config file's directory."""
    if not isinstance(value, str) or not value.strip():
        raise fail('the path of an ST file such as "../st_programs/conveyor.st"', value)
    return existing_file(value, info)


def _base_dir(info: ValidationInfo) -> Path:
    """The config file's directory: config_from_dict validates with it as context."""
    context = info.context
    assert context is not None, "a configuration is validated with its base_dir as context"
    return context["base_dir"]


def existing_file(text: str, info: ValidationInfo) -> Path:
    """text as an existing file, relative to the config file's directory."""
    resolved = _resolved(text, info)
    found = _stat(resolved)
    if found is None:
        raise PydanticCustomError(
            "config",
            "no such file: {path} (relative paths start at the config file's directory)",
            {"path": str(resolved)},
        )
    if not stat.S_ISREG(found.st_mode):
        raise PydanticCustomError("config", "not a file: {path}", {"path": str(resolved)})
    return resolved


def library_path(value, info: ValidationInfo) -> Path:
    """An existing folder (or file) of library sources, relative to the
    config file's directory."""
    if not isinstance(value, str) or not value.strip() or "\0" in value:
        raise fail('the path of a library folder such as "../libs/oscat"', value)
    resolved = _resolved(value, info)
    if _stat(resolved) is None:
        raise PydanticCustomError(
            "config",
            "no such folder: {path} (relative paths start at the config file's directory)",
            {"path": str(resolved)},
        )
    return resolved


def data_file(value, info: ValidationInfo) -> Path:
    # a NUL byte: no file has it in its name, and opening one raises ValueError
    if not isinstance(value, str) or not value.strip() or "\0" in value:
        raise fail('a file name such as "plant.retain"', value)
    resolved = _resolved(value, info)
    found = _stat(resolved)
    if found is not None and stat.S_ISDIR(found.st_mode):
        raise PydanticCustomError("config", "{path} is a directory; expected a file name", {"path": str(resolved)})
    other = not_regular(resolved)
    if other is not None:  # /dev/null: renamed to /dev/null.corrupt when softplc ran as root
        raise PydanticCustomError(
            "config",
            "{path} is {other}; expected a regular file or a name not yet taken (softplc writes the file "
            "and renames it into place)",
            {"path": str(resolved), "other": other},
        )
    folder = _stat(resolved.parent)
    if folder is None or not stat.S_ISDIR(folder.st_mode):
        raise PydanticCustomError(
            "config",
            "no such directory: {path} (the file is written there; relative paths start at the config file's "
            "directory)",
            {"path": str(resolved.parent)},
        )
    return resolved


def not_regular(path: Path) -> str | None:
    """What path is when it exists and is no regular file ("a character
    device" ...), else None; a symbolic link is not followed (a rename
    would replace the link, not what it points to)."""
    try:
        mode = os.lstat(path).st_mode
    except (OSError, ValueError):
        return None  # no such file (or _stat reported why)
    if stat.S_ISREG(mode):
        return None
    kinds = (
        (stat.S_ISDIR, "a directory"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISSOCK, "a socket"),
        (stat.S_ISLNK, "a symbolic link"),
    )
    return next((what for test, what in kinds if test(mode)), "no regular file")


def _resolved(text: str, info: ValidationInfo) -> Path:
    return Path(os.path.normpath(_base_dir(info) / Path(text).expanduser()))


def _stat(path: Path) -> os.stat_result | None:
    """The file's status, None when there is no such file; a path the
    system refuses (too long, a NUL character, a loop of links) is the
    key's error."""
    try:
        return path.stat()
    except (FileNotFoundError, NotADirectoryError):
        return None
    except (OSError, ValueError) as exc:
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise PydanticCustomError(
            "config", "{why}: {path}", {"path": str(path), "why": why[:1].lower() + why[1:]}
        ) from None


Duration = Annotated[int, PlainValidator(positive_duration)]
Watchdog = Annotated[Any, PlainValidator(watchdog)]
StFile = Annotated[Path, PlainValidator(st_file)]
LibraryPath = Annotated[Path, PlainValidator(library_path)]


def shipped_library(value, _info: ValidationInfo | None = None) -> str:
    """The name of a library softplc ships, as the library spells it."""
    from ..program.shipped import shipped

    spec = shipped().get(value.strip().upper()) if isinstance(value, str) else None
    if spec is None:
        names = ", ".join(sorted(s.name for s in set(shipped().values()))) or "none yet"
        raise PydanticCustomError(
            "config",
            "no library softplc ships is named {value} (it ships: {names})",
            {"value": str(value)[:60], "names": names},
        )
    return spec.name


UNIT_NS = {"ms": 1_000_000, "us": 1_000}


def duration_in(unit: str, *, off: str | None = None, most: tuple | None = None, least: tuple | None = None):
    """A duration as a whole number of unit ("ms" or "us"), rounded from the
    nanoseconds parse_duration_ns gives. off: what 0 / "0ms" / false means
    (None: they are refused); most: (largest value, why) where the bus
    carries the value in a field of fixed width; least: (the least in ns,
    as text, why) where a shorter one only costs; never more than a day
    (MAX_DURATION_NS)."""
    per = UNIT_NS[unit]
    or_off = f", or false for {off}" if off else ""

    def check(value) -> int:
        if value is False and off:
            return 0
        ns = duration_ns(value)
        if ns is None or ns < 0 or (ns == 0 and not off):
            kind = "a duration" if off else "a duration > 0"
            raise fail(f"{kind} such as {DURATION_EXAMPLES}{or_off}", value)
        if least is not None and 0 < ns < least[0]:
            raise fail(f"a duration of at least {least[1]} ({least[2]}){or_off}", value)
        count = round(ns / per)
        if ns > 0 and count == 0:
            raise fail(f"a duration of at least 1{unit}{or_off}", value)
        if most is not None and count > most[0]:
            raise fail(f"a duration of at most {most[0]}{unit} ({most[1]}){or_off}", value)
        at_most_a_day(ns, value, or_off)
        return count

    return check


def quiet(check, value):
    """check(value), or None when pass 1 refuses the value (it reports it)."""
    try:
        return check(value)
    except PydanticCustomError:
        return None


def text_value(expected: str):
    """A non-empty string; an integer is taken as its decimal text (channel = 0)."""

    def check(value) -> str:
        if isinstance(value, str) and value.strip() and len(value.strip()) <= MAX_TEXT:
            return value.strip()
        if isinstance(value, int) and not isinstance(value, bool):
            return str(value)
        raise fail(_at_most(expected, value), value)

    return PlainValidator(check)


def nonempty(expected: str):
    def check(value) -> str:
        if isinstance(value, str) and value.strip() and len(value.strip()) <= MAX_TEXT:
            return value.strip()
        raise fail(_at_most(expected, value), value)

    return PlainValidator(check)


def _at_most(expected: str, value) -> str:
    """What a text value of the right type but too long was expected to be."""
    return f"{expected}, of at most {MAX_TEXT} characters" if isinstance(value, str) and value.strip() else expected


_LABEL = re.compile(r"(?!-)[A-Za-z0-9_-]{1,63}(?<!-)", re.A)


def is_host(text: str) -> bool:
    """An IP address (v4, v6), or a host name: at most 253 characters, its
    labels 1 to 63 letters, digits, - or _ (RFC 1123; the name service
    refuses more, the IDNA codec with an exception of its own)."""
    try:
        ipaddress.ip_address(text[1:-1] if text.startswith("[") and text.endswith("]") else text)
        return True
    except ValueError:
        pass
    name = text[:-1] if text.endswith(".") else text
    return 0 < len(name) <= 253 and all(_LABEL.fullmatch(label) for label in name.split("."))


def host_value(expected: str):
    """A host to listen on or to connect to, as is_host takes it."""

    def check(value) -> str:
        if isinstance(value, str) and is_host(value.strip()):
            return value.strip()
        raise fail(expected, value)

    return PlainValidator(check)


def integer(value) -> int:
    if isinstance(value, int) and not isinstance(value, bool):
        return value
    raise fail("an integer", value)


def choice_int(options):
    def check(value) -> int:
        if isinstance(value, int) and not isinstance(value, bool) and value in options:
            return value
        raise fail("one of " + ", ".join(map(str, options)), value)

    return PlainValidator(check)


def choice_upper(options):
    def check(value) -> str:
        if isinstance(value, str) and value.upper() in options:
            return value.upper()
        raise fail("one of " + ", ".join(f"'{o}'" for o in options), value)

    return PlainValidator(check)


def in_range(value: object, lo: int | None, hi: int | None) -> TypeGuard[int]:
    """An integer (not a bool) within lo..hi (None: unbounded)."""
    return (
        isinstance(value, int)
        and not isinstance(value, bool)
        and (lo is None or value >= lo)
        and (hi is None or value <= hi)
    )


def bit_count(addr: LocatedAddress) -> int:
    if addr.bit is not None or addr.size in ("", "X"):
        return 1
    return _address.SIZE_BITS[addr.size]


def area_name(addr: LocatedAddress) -> str:
    return f"'{addr.text}', " + {"I": "an input", "Q": "an output", "M": "a memory address"}[addr.area]


def optional_field(info: Any) -> tuple:
    """A model's field (a pydantic FieldInfo) as an optional field of another
    model: its type with its validators (the Annotated metadata pydantic keeps
    apart from the annotation), None when missing, its description. For the
    sections whose tables take the keys of several devices ([[sim]] ...)."""
    annotation: Any = info.annotation
    if info.metadata:
        annotation = Annotated[(annotation, *info.metadata)]
    return annotation | None, Field(None, description=info.description)
