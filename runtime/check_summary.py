"""What ``softplc check`` adds to the diagnostics: the sources a folder
holds, the table that sums up a check of many files (files, POUs, errors,
warnings, the most frequent codes), and which other profiles would accept
an error's construct."""

from __future__ import annotations

import collections
from pathlib import Path

from .st import ast as A
from .st.diagnostics import DiagnosticBag
from .st.importers import is_source, st_views
from .st.parser import parse_source
from .st.profile import PROFILES

# Folders a project has that hold no sources of its own.
_SKIPPED = {".git", "__pycache__", ".venv", "venv", "node_modules", "_Boot", "_CompileInfo", "_Libraries"}


def expand_sources(paths: list) -> list[str]:
    """paths with every folder replaced by the sources in it (sorted,
    sub-folders included): .st files and the kinds softplc imports (a
    .plcproj's files are read through the project: its members are left
    out when it is there)."""
    out: list[str] = []
    for p in map(Path, paths):
        if not p.is_dir():
            out.append(str(p))
            continue
        found = sorted(
            f
            for f in p.rglob("*")
            if f.is_file() and not _SKIPPED.intersection(f.relative_to(p).parts[:-1]) and is_source(f.name)
        )
        projects = [f for f in found if f.suffix.lower() == ".plcproj"]
        if projects:
            found = projects + [f for f in found if f.suffix.lower() in (".st",) and not _under(f, projects)]
        out.extend(str(f) for f in found)
    return out


def _under(f: Path, projects: list) -> bool:
    return any(f.is_relative_to(pr.parent) for pr in projects)


def pou_count(path: str, text: str) -> int:
    """How many POUs a source declares (as the parser reads it)."""
    diags = DiagnosticBag()
    return sum(
        1
        for view in st_views(path, text, diags)
        for d in parse_source(view.text, path, diags, lowered=view.lowered, origins=view.origins).decls
        if isinstance(d, (A.POU, A.Interface))
    )


def summary(files: dict, diagnostics: list) -> str:
    """The table of a check: per file (name -> text) its POUs, errors and
    warnings; then the totals and the codes by frequency."""
    errors: collections.Counter = collections.Counter()
    warnings: collections.Counter = collections.Counter()
    for d in diagnostics:
        (errors if d.is_error else warnings)[d.pos.file] += 1
    rows = [(name, pou_count(name, text), errors[name], warnings[name]) for name, text in files.items()]
    width = max([len("file"), *(len(r[0]) for r in rows)])
    lines = [f"{'file':<{width}}  {'POUs':>5}  {'errors':>6}  {'warnings':>8}"]
    lines += [f"{n:<{width}}  {p:>5}  {e:>6}  {w:>8}" for n, p, e, w in rows]
    total = (sum(r[1] for r in rows), sum(r[2] for r in rows), sum(r[3] for r in rows))
    lines.append(f"{f'{len(rows)} files':<{width}}  {total[0]:>5}  {total[1]:>6}  {total[2]:>8}")
    frequent = most_frequent(diagnostics)
    if frequent:
        lines.append(frequent)
    return "\n".join(lines)


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
