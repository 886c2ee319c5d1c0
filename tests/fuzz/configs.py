"""Configurations for the fuzz harness: the shipped ones (io_config/default.toml
and io_config/examples/*.toml), valid as they are, and mutated.

    shipped()              {name: (path, text, data)} of every shipped file
    mutated_documents()    (name, data): a parsed file with a few changes in
                           its tree: keys deleted, values of the wrong type,
                           huge, negative, long, odd; unknown keys; tables
                           of an array duplicated or emptied
    mutated_texts()        (name, text): a file's text with bytes, lines or
                           keys changed, for load_config to parse
"""

from __future__ import annotations

import datetime
import functools
import math
import tomllib
from pathlib import Path

from hypothesis import strategies as st

from ..st.fuzz_mutations import ST_ALPHABET

ROOT = Path(__file__).resolve().parents[2]
CONFIG_DIR = ROOT / "io_config"

# issue 16, "a 5,000-character value is echoed whole in the error" and "a
# path that is too long (ENAMETOOLONG)": generated strings up to 5,000
# characters (a message must still stay shorter than ECHO_LIMIT, test_config.py)
LONG = 5000


@functools.cache
def shipped() -> dict:
    files = [CONFIG_DIR / "default.toml", *sorted((CONFIG_DIR / "examples").glob("*.toml"))]
    out = {}
    for path in files:
        text = path.read_text("utf-8")
        out[path.relative_to(CONFIG_DIR).as_posix()] = (path, text, tomllib.loads(text))
    return out


def _copy(value):
    if isinstance(value, dict):
        return {k: _copy(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_copy(v) for v in value]
    return value


def _places(value, path=()):
    """Every (path, value) in a parsed document, tables and arrays included."""
    yield path, value
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _places(v, (*path, k))
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _places(v, (*path, i))


def _at(doc, path):
    for part in path:
        doc = doc[part]
    return doc


ODD_STRINGS = [
    "",
    " ",
    "x" * LONG,
    "\u00e9\u00e8\u202e\ufeff",
    "\0",
    "../../../../etc/passwd",
    "/" + "a" * LONG + "/b.st",
    "a/" * (LONG // 2),
    "%QW99999999",
    "%IX0.99",
    "%MD-1",
    "1e400s",
    "99999999999999999h",
    "-5ms",
    "0ms",
    "nan",
    "inf",
    "T#1d",
    "10 ms",
    "10mss",
    "0x7FF",
    "virtual",
    "socketcan",
    "rtu",
    "tcp",
    "sim",
    "codesys",
    "task",
    "plc",
    "cold",
    # issue 31: accepted or exit 4 before
    "1us",
    "1s1s1s1s",
    "%QL65535",
    "/dev/null",
    "a" * 1_000_000,
]
HUGE_NUMBERS = [
    -1,
    0,
    1,
    -(2**63),
    2**63 - 1,
    2**31,
    10**18,
    255,
    256,
    65535,
    65536,
    0x7FF,
    0x800,
    128,
    127,
    1e308,
    -1e308,
    math.inf,
    -math.inf,
    math.nan,
    0.5,
    -0.0,
    10,  # a duration without its unit (issue 31)
    10**1000,  # beyond 64 bits (5,000 digits go in as text: mutated_texts)
]


def _any_value():
    scalar = st.one_of(
        st.sampled_from(ODD_STRINGS),
        st.text(ST_ALPHABET, max_size=20),
        st.sampled_from(HUGE_NUMBERS),
        st.integers(),
        st.floats(),
        st.booleans(),
        st.just(datetime.date(2024, 2, 29)),
        st.just(datetime.time(12, 30)),
    )
    return st.recursive(
        scalar,
        lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.sampled_from(["a", "x"]), inner, max_size=2),
        max_leaves=4,
    )


def _mutate(draw, doc) -> None:
    places = list(_places(doc))
    path, value = draw(st.sampled_from(places))
    parent = _at(doc, path[:-1]) if path else None
    how = draw(st.sampled_from(["delete", "replace", "replace", "number", "string", "unknown", "duplicate", "empty"]))
    if how == "delete" and path:
        del parent[path[-1]]
    elif how == "replace" and path:
        parent[path[-1]] = draw(_any_value())
    elif how == "number" and path:
        parent[path[-1]] = draw(st.sampled_from(HUGE_NUMBERS) | st.integers())
    elif how == "string" and path:
        parent[path[-1]] = draw(st.sampled_from(ODD_STRINGS))
    elif how == "unknown" and isinstance(value, dict):
        value[draw(st.sampled_from(["bogus", "Name", "name ", "x" * 80, "", "programs", "id", "node"]))] = draw(
            _any_value()
        )
    elif how == "duplicate" and isinstance(value, list) and value:
        value.append(_copy(draw(st.sampled_from(value))))
    elif how == "empty" and isinstance(value, (list, dict)):
        value.clear()


@st.composite
def mutated_documents(draw):
    name = draw(st.sampled_from(sorted(shipped())))
    doc = _copy(shipped()[name][2])
    for _ in range(draw(st.integers(1, 3))):
        _mutate(draw, doc)
    return name, doc


@st.composite
def mutated_texts(draw):
    name = draw(st.sampled_from(sorted(shipped())))
    lines = shipped()[name][1].split("\n")
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(lines) - 1))
        how = draw(st.sampled_from(["bytes", "drop line", "duplicate line", "swap lines", "value", "deep"]))
        if how == "bytes":
            line = lines[i]
            j = draw(st.integers(0, len(line)))
            n = draw(st.integers(1, 3))
            if draw(st.booleans()):
                lines[i] = line[:j] + line[j + n :]
            else:
                lines[i] = line[:j] + draw(st.text(ST_ALPHABET, min_size=1, max_size=n)) + line[j:]
        elif how == "drop line":
            del lines[i]
        elif how == "duplicate line":
            lines.insert(i, lines[i])
        elif how == "swap lines":
            k = draw(st.integers(0, len(lines) - 1))
            lines[i], lines[k] = lines[k], lines[i]
        elif how == "deep":  # issue 31: the reader's RecursionError was exit 4
            n = draw(st.sampled_from([33, 1000, 5000]))
            lines.insert(i, draw(st.sampled_from([f"deep = {'[' * n}{']' * n}", f"deep = {'{a=' * n}1{'}' * n}"])))
            lines.insert(i, f"{'.'.join(['d'] * n)} = 1")
        elif "=" in lines[i] and not lines[i].lstrip().startswith("#"):
            key = lines[i].split("=", 1)[0]
            literal = draw(
                st.sampled_from(
                    ['""', "-1", "1e999", "inf", "nan", "99999999999999999999", "[]", "{}", "true", "[[]]", "9" * 5000]
                )
                | st.sampled_from(ODD_STRINGS).map(lambda s: '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"')
            )
            lines[i] = f"{key}= {literal}"
    return name, "\n".join(lines)


@st.composite
def huge_texts(draw, most: int):
    """A shipped file and up to `most` more tables, each with a bad value
    (issue 31: 10,000 bad tasks printed 2.1 MB of errors)."""
    name = draw(st.sampled_from(sorted(shipped())))
    n = draw(st.integers(60, most))
    bad = draw(st.sampled_from(['interval = "1us"', "interval = 10", f'name = "{"t" * 5000}"', 'priority = "x"']))
    table = f'[[task]]\nname = "T{{}}"\ninterval = "10ms"\nprograms = ["Main"]\n{bad}\n'
    return name, shipped()[name][1] + "\n" + "".join(table.format(i) for i in range(n))
