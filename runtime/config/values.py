"""Configuration values: the checks of single TOML values (durations,
identifiers, choices, files, integers in a range), each refusing a value
with a message in the configuration's own words, and the base model of
every table. Sections of the core and of the buses build on these."""

from __future__ import annotations

import difflib
import os
import re
from pathlib import Path
from typing import Annotated, Any, TypeGuard

from pydantic import BaseModel, ConfigDict, Field, PlainValidator, ValidationInfo
from pydantic_core import PydanticCustomError

from ..durations import EXAMPLES as DURATION_EXAMPLES
from ..durations import parse_duration_ns
from ..image import address as _address
from ..st.ast import LocatedAddress

U16_MAX = 0xFFFF


class Model(BaseModel):
    """A table of the file: unknown keys refused, no coercion of values."""

    model_config = ConfigDict(extra="forbid", strict=True)


def got(value) -> str:
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
    return f"a {type(value).__name__}"  # TOML dates and times


def fail(expected: str, value) -> PydanticCustomError:
    return PydanticCustomError("config", "expected {expected} (got {got})", {"expected": expected, "got": got(value)})


def duration_ns(value) -> int | None:
    try:
        return parse_duration_ns(value)
    except (OverflowError, ValueError):  # inf, nan
        return None


def positive_duration(value) -> int:
    """A duration > 0 in ns: '10ms', 'T#1s', '1s500ms', or a bare number of ms."""
    ns = duration_ns(value)
    if ns is None and isinstance(value, str) and negative(value):
        ns = -1
    if ns is None:
        raise fail(f"a duration such as {DURATION_EXAMPLES}", value)
    if ns <= 0:
        raise fail(f"a duration > 0 such as {DURATION_EXAMPLES}", value)
    return ns


def negative(text: str) -> bool:
    """'-5ms', 'T#-5ms': a duration but for its sign."""
    text = text.strip().lower()
    for prefix in ("time#", "t#"):
        if text.startswith(prefix):
            text = text[len(prefix) :]
            break
    return text.startswith("-") and duration_ns(text[1:]) is not None


def watchdog(value):
    """A duration > 0 in ns, or False (no watchdog)."""
    if value is False:
        return False
    ns = duration_ns(value)
    if ns is None or ns <= 0:
        raise fail(f"a duration > 0 such as {DURATION_EXAMPLES}, or false for no watchdog", value)
    return ns


def int_range(lo: int, hi: int | None = None):
    def check(value) -> int:
        if isinstance(value, int) and not isinstance(value, bool) and value >= lo and (hi is None or value <= hi):
            return value
        raise fail(f"an integer from {lo} to {hi}" if hi is not None else f"an integer >= {lo}", value)

    return PlainValidator(check)


IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*", re.A)


def is_ident(value: object) -> TypeGuard[str]:
    return isinstance(value, str) and IDENT.fullmatch(value) is not None


def identifier(what: str):
    def check(value) -> str:
        if is_ident(value):
            return value
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
    resolved = Path(os.path.normpath(_base_dir(info) / Path(text).expanduser()))
    if not resolved.exists():
        raise PydanticCustomError(
            "config",
            "no such file: {path} (relative paths start at the config file's directory)",
            {"path": str(resolved)},
        )
    if not resolved.is_file():
        raise PydanticCustomError("config", "not a file: {path}", {"path": str(resolved)})
    return resolved


def data_file(value, info: ValidationInfo) -> Path:
    # a NUL byte: no file has it in its name, and opening one raises ValueError
    if not isinstance(value, str) or not value.strip() or "\0" in value:
        raise fail('a file name such as "plant.retain"', value)
    resolved = Path(os.path.normpath(_base_dir(info) / Path(value).expanduser()))
    if resolved.is_dir():
        raise PydanticCustomError("config", "{path} is a directory; expected a file name", {"path": str(resolved)})
    return resolved


Duration = Annotated[int, PlainValidator(positive_duration)]
Watchdog = Annotated[Any, PlainValidator(watchdog)]
StFile = Annotated[Path, PlainValidator(st_file)]


UNIT_NS = {"ms": 1_000_000, "us": 1_000}


def duration_in(unit: str, *, off: str | None = None, most: tuple | None = None):
    """A duration as a whole number of unit ("ms" or "us"), rounded from the
    nanoseconds parse_duration_ns gives. off: what 0 / "0ms" / false means
    (None: they are refused); most: (largest value, why) where the bus
    carries the value in a field of fixed width."""
    per = UNIT_NS[unit]
    or_off = f", or false for {off}" if off else ""

    def check(value) -> int:
        if value is False and off:
            return 0
        ns = duration_ns(value)
        if ns is None or ns < 0 or (ns == 0 and not off):
            kind = "a duration" if off else "a duration > 0"
            raise fail(f"{kind} such as {DURATION_EXAMPLES}{or_off}", value)
        count = round(ns / per)
        if ns > 0 and count == 0:
            raise fail(f"a duration of at least 1{unit}{or_off}", value)
        if most is not None and count > most[0]:
            raise fail(f"a duration of at most {most[0]}{unit} ({most[1]}){or_off}", value)
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
        if isinstance(value, str) and value.strip():
            return value.strip()
        if isinstance(value, int) and not isinstance(value, bool):
            return str(value)
        raise fail(expected, value)

    return PlainValidator(check)


def nonempty(expected: str):
    def check(value) -> str:
        if isinstance(value, str) and value.strip():
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
