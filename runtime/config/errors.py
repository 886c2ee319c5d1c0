"""Configuration errors: ConfigError (every error of one file, each with
its key path), and pydantic's errors told in the configuration's words:
the key path as the file writes it (task[1].interval), what was expected
(from the field's description) and what was given, in file order."""

from __future__ import annotations

import difflib
import re
import typing
from typing import Any

from pydantic import BaseModel
from pydantic.fields import FieldInfo
from pydantic_core import ErrorDetails

from ..st.diagnostics import SHOWN
from .values import KEEP, LONG, cut, got


class ConfigError(Exception):
    """Everything wrong with one configuration file.

    errors: (key path or "", message) pairs, in file order, every long
    value in them cut (values.cut). position: (line, column) of a TOML
    syntax error, else None."""

    def __init__(self, file: str, errors: list, *, position: tuple | None = None) -> None:
        self.file = cut(str(file))
        self.errors = [(cut(key), cut(message)) for key, message in errors]
        self.position = position
        super().__init__(str(self))

    def lines(self) -> list:
        """One line per error, at most SHOWN of them and then how many more."""
        out = []
        for key, message in self.errors[:SHOWN]:
            if self.position is not None and not key:
                line, col = self.position
                out.append(f"{self.file}:{line}:{col}: {message}")
            elif key:
                out.append(f"{self.file}: {key}: {message}")
            else:
                out.append(f"{self.file}: {message}")
        if len(self.errors) > SHOWN:
            more = len(self.errors) - SHOWN
            out.append(f"{self.file}: ... {more} more error{'s' if more > 1 else ''}")
        return out

    def __str__(self) -> str:
        return "\n".join(self.lines())


def _keys(model: type[BaseModel]) -> dict[str, FieldInfo]:
    """TOML key -> FieldInfo of a model."""
    return {(f.alias or name): f for name, f in model.model_fields.items()}


def _model_in(annotation: Any) -> type[BaseModel] | None:
    if isinstance(annotation, type) and issubclass(annotation, BaseModel):
        return annotation
    for arg in typing.get_args(annotation):
        found = _model_in(arg)
        if found is not None:
            return found
    return None


def _model_at(root: type[BaseModel], loc: tuple) -> type[BaseModel] | None:
    """The model of the table at loc (() is the document)."""
    model: type[BaseModel] | None = root
    for part in loc:
        if isinstance(part, int):
            continue  # an array entry: the model of the array's items
        info = _keys(model).get(part) if model is not None else None
        if info is None:
            return None
        model = _model_in(info.annotation)
    return model


def _field_at(root: type[BaseModel], loc: tuple) -> FieldInfo | None:
    """The FieldInfo of the key at loc, or None (array entries, unknown keys)."""
    if not loc or isinstance(loc[-1], int):
        return None
    owner = _model_at(root, loc[:-1])
    return _keys(owner).get(loc[-1]) if owner is not None else None


def translate(root: type[BaseModel], err: ErrorDetails) -> tuple:
    """A pydantic error of the document model root as (loc, message in the
    config's words)."""
    loc = tuple(err["loc"])
    kind = err["type"]
    value = err["input"]
    if kind == "config":
        return loc, err["msg"]
    if kind == "extra_forbidden":
        owner = _model_at(root, loc[:-1])
        valid = list(_keys(owner)) if owner is not None else []
        name = str(loc[-1])
        lower = {v.lower(): v for v in valid}
        close = difflib.get_close_matches(name.lower(), list(lower), n=1, cutoff=0.6)
        hint = f"did you mean '{lower[close[0]]}'?" if close else f"expected one of {', '.join(valid)}"
        return loc, f"unknown key ({hint})"
    info = _field_at(root, loc)
    described = info.description if info is not None else None
    if kind == "missing":
        return loc, f"required key missing (expected {described})" if described else "required key missing"
    if kind in ("model_type", "model_attributes_type", "dict_type"):
        return loc, f"expected {described or 'a table'} (got {got(value)})"
    if kind == "list_type":
        return loc, f"expected {described or 'an array'} (got {got(value)})"
    if kind == "too_short":
        return loc, f"expected {described or 'at least one entry'} (got an empty array)"
    if kind == "too_long":
        return loc, f"expected {described or 'fewer entries'} (got {len(value)} entries)"
    if kind == "bool_type":
        return loc, f"expected true or false (got {got(value)})"
    return loc, f"{err['msg']} (got {got(value)})"


def not_finite(root: type[BaseModel], loc: tuple, value: float | int, default: str = "a finite number") -> str:
    """The message for a value no key takes at loc (an inf or nan, an
    integer of hundreds of digits): what the key takes, when the schema
    says, else default."""
    info = _field_at(root, loc)
    described = info.description if info is not None and info.description else default
    return f"expected {described} (got {got(value)})"


def key_text(loc: tuple) -> str:
    """('task', 1, 'interval') -> 'task[1].interval'; odd keys quoted."""
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
            continue
        part = str(part)
        text = part if re.fullmatch(r"[A-Za-z0-9_-]+", part) else '"' + part.replace('"', '\\"') + '"'
        if len(part) > LONG:  # a long unknown key: its start and length
            text = '"' + part[:KEEP].replace('"', '\\"') + f'…" ({len(part)} characters)'
        out += ("." if out else "") + text
    return out


def in_file_order(errors: list, data: dict) -> list:
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
