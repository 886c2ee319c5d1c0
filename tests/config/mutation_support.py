"""Hostile values for every key of a configuration: what the mutation tests
share. A mutation replaces one value (or adds one key the schema knows) by
a value of the wrong type, a negative, huge, non-finite, empty or too long
one; the configuration must then load, or be refused with a ConfigError
(or, from the build, a TaskSetupError or DriverError) whose every line
names the file and which names the key, and never echoes a long value whole.
"""

from __future__ import annotations

import copy
import datetime
import tomllib
from collections.abc import Iterator
from pathlib import Path

from softplc.runtime.config import ConfigError, config_from_dict
from softplc.runtime.config.errors import _keys, _model_at, key_text
from softplc.runtime.config.load import _current_document

LONG = "x" * 5000
#: a path longer than the system allows (ENAMETOOLONG), in components of 250 characters
LONG_PATH = "/".join(["a" * 250] * 30)

HOSTILE = {
    # wrong types
    "a string": "bogus",
    "an integer": 17,
    "a float": 1.5,
    "a boolean": True,
    "a table": {"a": 1},
    "an array": [1, "a"],
    "a date": datetime.date(2024, 1, 2),
    # negative
    "-1": -1,
    "-1.5": -1.5,
    "a negative duration": "-5ms",
    # huge
    "the largest TOML integer": 2**63 - 1,
    "a huge float": 1.7e308,
    "a huge duration": "9" * 30 + "d",
    "a duration beyond a float": "1" * 400 + "d",
    "inf": float("inf"),
    "nan": float("nan"),
    "65535": 65535,
    "65536": 65536,
    # empty
    "an empty string": "",
    "an empty array": [],
    "an empty table": {},
    # too long
    "5000 characters": LONG,
    "a path too long": LONG_PATH,
    "a file name too long": "a" * 300 + ".st",
}


#: one value of each kind, for the larger files
SAMPLE = (
    "a string",
    "a table",
    "-1",
    "the largest TOML integer",
    "a huge duration",
    "inf",
    "an empty array",
    "5000 characters",
    "a path too long",
)


def key_paths(data: dict) -> Iterator[tuple]:
    """Every key and array entry of data, tables and arrays included, as
    loc tuples ("loopback", 0, "bytes")."""

    def walk(node, here: tuple):
        if isinstance(node, dict):
            for key, value in node.items():
                yield here + (key,)
                yield from walk(value, here + (key,))
        elif isinstance(node, list):
            for i, value in enumerate(node):
                yield here + (i,)
                yield from walk(value, here + (i,))

    yield from walk(data, ())


def absent_keys(data: dict) -> Iterator[tuple]:
    """The keys the schema knows that a table of data does not give."""
    root = _current_document().root
    for loc in [(), *key_paths(data)]:
        node = at(data, loc)
        model = _model_at(root, loc) if isinstance(node, dict) else None
        if model is not None:
            yield from (loc + (key,) for key in _keys(model) if key not in node)


def at(data, loc: tuple):
    for part in loc:
        data = data[part]
    return data


def mutated(data: dict, loc: tuple, value) -> dict:
    out = copy.deepcopy(data)
    at(out, loc[:-1])[loc[-1]] = value
    return out


def mutations(path: Path, *, absent: bool = True, values=tuple(HOSTILE)) -> Iterator[tuple]:
    """(loc, name of the hostile value, the mutated tables) for every key of
    the file (and every key its tables could have, with absent) and each
    of the hostile values named."""
    data = tomllib.loads(path.read_text(encoding="utf-8"))
    locs = list(key_paths(data)) + (list(absent_keys(data)) if absent else [])
    for loc in locs:
        for name in values:
            yield loc, name, mutated(data, loc, HOSTILE[name])


def names_the_key(errors: list, loc: tuple) -> bool:
    """One of errors ((key path, message) pairs) is at loc's key or a key
    inside it, or, for a relation reported at the other key, names loc's
    table and key in its message ("loopback[0] (to = '%IB0', bytes = 17)")."""
    key = key_text(loc)
    table, last = key_text(loc[:-1]), loc[-1]
    return any(
        k == key or k.startswith((key + ".", key + "[")) or (table and table in m and f"{last} = " in m)
        for k, m in errors
    )


def check_message(text: str, path: Path) -> None:
    """Every line names the file; no long value is echoed whole."""
    for line in text.splitlines():
        assert line.startswith(f"{path}:"), line[:200]
        assert len(line) < 400, f"{len(line)} characters: {line[:200]}…"
    assert LONG[:100] not in text and "a" * 300 not in text


def load_mutation(path: Path, tables: dict) -> ConfigError | None:
    """The ConfigError of the mutated tables (checked: each line names the
    file, no long value whole), or None when they load."""
    try:
        config_from_dict(tables, path)
    except ConfigError as err:
        check_message(str(err), path)
        return err
    return None
