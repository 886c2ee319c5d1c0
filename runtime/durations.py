"""Durations as people write them in a command line or a config file:
'10ms', '1s500ms', '2.5s', 'T#250ms', 'TIME#1h' (each unit once, the
largest first, as in IEC 61131-3), or a bare number of milliseconds. One
parser serves the CLI and the TOML configuration, so both accept the same
spellings, but for the bare number: the configuration wants its unit
(config/values.py)."""

from __future__ import annotations

import re

# IEC duration units, largest first, in nanoseconds.
UNITS_NS = {
    "d": 86_400_000_000_000,
    "h": 3_600_000_000_000,
    "m": 60_000_000_000,
    "s": 1_000_000_000,
    "ms": 1_000_000,
    "us": 1_000,
    "ns": 1,
}
_PART = re.compile(r"(\d+(?:\.\d+)?)(ms|us|ns|d|h|m|s)")

EXAMPLES = "10ms, 1s, T#250ms"  # what error messages suggest


def parse_duration_ns(value) -> int | None:
    """The duration in nanoseconds, or None if value is not a duration.
    A bare number (int or digit string) means milliseconds."""
    if isinstance(value, bool):
        return None
    if isinstance(value, int):
        return value * 1_000_000
    if isinstance(value, float):
        return round(value * 1_000_000)
    if not isinstance(value, str):
        return None
    text = "".join(value.split()).lower().replace("_", "")
    for prefix in ("time#", "t#"):
        if text.startswith(prefix):
            text = text[len(prefix) :]
            break
    if text.isdigit():
        return int(text) * 1_000_000
    pos, total = 0, 0.0
    last = None  # the unit before: each unit once, the largest first (IEC: T#1h30m, not T#30m1h or T#1s1s)
    while pos < len(text):
        m = _PART.match(text, pos)
        if m is None:
            return None
        unit = UNITS_NS[m.group(2)]
        if last is not None and unit >= last:
            return None
        last = unit
        total += float(m.group(1)) * unit
        pos = m.end()
    return round(total) if text else None


def format_duration_ns(ns: int) -> str:
    """A short human form: 10ms, 1.5s, 250us."""
    if ns % 1_000_000_000 == 0:
        return f"{ns // 1_000_000_000}s"
    if ns >= 1_000_000_000:
        return f"{ns / 1e9:g}s"
    if ns % 1_000_000 == 0 or ns >= 1_000_000:
        return f"{ns / 1e6:g}ms"
    return f"{ns / 1e3:g}us"
