"""What ``softplc check`` adds to the diagnostics of files: the most
frequent codes, and which other profiles would accept an error's
construct. (A folder or a project: its table is runtime/project/table.py.)"""

from __future__ import annotations

import collections

from .st.profile import PROFILES


def most_frequent(diagnostics: list) -> str:
    """'most frequent: E010 x2, W130 x1' (the eight most frequent codes), or ''."""
    codes = collections.Counter(d.code for d in diagnostics)
    return "most frequent: " + ", ".join(f"{c} x{n}" for c, n in codes.most_common(8)) if codes else ""


def note_other_profiles(files: list, profile: str, diagnostics: list, check) -> None:
    """Add to the hint of each error which other profiles accept the
    construct: checked with such a profile, the same place has no error and
    the files have no more errors than with this one (so the error did not
    just hide behind an earlier one). check(files, profile) -> diagnostics."""
    errors = [d for d in diagnostics if d.is_error]
    if not errors:
        return
    accepted: dict = {}
    for other in PROFILES:
        if other == profile:
            continue
        theirs = [d for d in check(files, other) if d.is_error]
        if len(theirs) > len(errors):
            continue
        places = {(d.pos.file, d.pos.line, d.pos.col) for d in theirs}
        for d in errors:
            if (d.pos.file, d.pos.line, d.pos.col) not in places:
                accepted.setdefault(id(d), []).append(other)
    for d in errors:
        others = accepted.get(id(d))
        if others and not all(o in (d.hint or "") for o in others):  # (unless the hint says so)
            who = f"the profiles {', '.join(others)} accept" if len(others) > 1 else f"the profile {others[0]} accepts"
            note = f"{who} this (--profile {others[0]})"
            d.hint = f"{d.hint}; {note}" if d.hint else note
