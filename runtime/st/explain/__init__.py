"""One page per diagnostic code, for ``softplc check --explain E030`` (as
``rustc --explain E0308``): what the code means, a minimal program that
draws it, how to fix it, and which profiles treat it differently.

The pages are the package's ``E030.md`` ... ``W180.md`` files (package data).
tests/st/test_explain.py keeps them honest: every code the compiler emits
has a page, no page is for a code nobody emits, and each page's example
still draws its code (its fix does not).
"""

from __future__ import annotations

import collections
import difflib
import re
from importlib import resources

_CODE = re.compile(r"([EW])(\d{3})")


def codes() -> list[str]:
    """Every code that has a page, sorted: ['E000', 'E001', ..., 'W180']."""
    return sorted(
        f.name[:-3]
        for f in resources.files(__name__).iterdir()
        if f.name.endswith(".md") and _CODE.fullmatch(f.name[:-3])
    )


def page(code: str) -> str | None:
    """The Markdown page of a code ('E030' or 'e030'), None if it has none."""
    key = code.strip().upper()
    if not _CODE.fullmatch(key):
        return None
    f = resources.files(__name__).joinpath(f"{key}.md")
    return f.read_text(encoding="utf-8") if f.is_file() else None


def near(code: str, n: int = 5) -> list[str]:
    """Codes with a page close to one that has none, nearest first: E032 ->
    E031, E030, E040 ...; by spelling for what is no code at all."""
    key = code.strip().upper()
    known = codes()
    m = re.fullmatch(r"([EW])(\d+)", key)
    if m is None:
        return difflib.get_close_matches(key, known, n=n, cutoff=0.3)
    letter, number = m.group(1), int(m.group(2))
    same = [c for c in known if c[0] == letter] or known
    return sorted(same, key=lambda c: (abs(int(c[1:]) - number), c))[:n]


def more_line(found: list[str]) -> str:
    """The last line of a check with diagnostics: how to read the page of
    the most frequent of the codes found (the first of them on a tie)."""
    top = collections.Counter(found).most_common(1)[0][0]
    return f"for more on a code: softplc check --explain {top}"
