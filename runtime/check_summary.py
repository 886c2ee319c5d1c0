"""``softplc check`` on folders: the sources a folder holds, and the table
that sums up a check of many files (files, POUs, errors, warnings, and the
most frequent codes)."""

from __future__ import annotations

import collections
from pathlib import Path

from .st import ast as A
from .st.diagnostics import DiagnosticBag
from .st.importers import is_imported, st_views
from .st.parser import parse_source

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
            if f.is_file()
            and not _SKIPPED.intersection(f.relative_to(p).parts[:-1])
            and (f.suffix.lower() == ".st" or is_imported(f.name))
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
        for d in parse_source(view, path, diags).decls
        if isinstance(d, (A.POU, A.Interface))
    )


def summary(files: dict, diagnostics: list) -> str:
    """The table of a check: per file (name -> text) its POUs, errors and
    warnings; then the totals and the codes by frequency."""
    errors: collections.Counter = collections.Counter()
    warnings: collections.Counter = collections.Counter()
    codes: collections.Counter = collections.Counter()
    for d in diagnostics:
        (errors if d.is_error else warnings)[d.pos.file] += 1
        codes[d.code] += 1
    rows = [(name, pou_count(name, text), errors[name], warnings[name]) for name, text in files.items()]
    width = max([len("file"), *(len(r[0]) for r in rows)])
    lines = [f"{'file':<{width}}  {'POUs':>5}  {'errors':>6}  {'warnings':>8}"]
    lines += [f"{n:<{width}}  {p:>5}  {e:>6}  {w:>8}" for n, p, e, w in rows]
    total = (sum(r[1] for r in rows), sum(r[2] for r in rows), sum(r[3] for r in rows))
    lines.append(f"{f'{len(rows)} files':<{width}}  {total[0]:>5}  {total[1]:>6}  {total[2]:>8}")
    if codes:
        lines.append("most frequent: " + ", ".join(f"{c} x{n}" for c, n in codes.most_common(8)))
    return "\n".join(lines)
