"""A project written as plain ST (`softplc export-st`): every POU, type
and variable list that imports (no import or syntax error in it), file by
file, each one that does not compile marked by a comment saying why; the
ones that do not import are listed with their errors instead. A TwinCAT
project's tasks (.TcTTO) become a CONFIGURATION.

Only checked text goes into the ST besides the lines of the sources: names
the parser read (identifiers), numbers, and the file names and library
names of the comments with every character that could end a comment
removed.
"""

from __future__ import annotations

import bisect
import re
from dataclasses import dataclass, field

from ..st.diagnostics import DiagnosticBag
from ..st.importers import st_plain_lines
from ..st.syntax.build_decls import identifier_from_path
from .analysis import Analysis

_UNSAFE = re.compile(r"[^A-Za-z0-9_ .,/\\#@+-]")


def _safe(text: str, limit: int = 120) -> str:
    """text for an ST comment: no character that could end it or a line."""
    return _UNSAFE.sub("_", text)[:limit]


@dataclass
class ExportedFile:
    path: str  # the source
    label: str  # its name in the project
    text: str  # the ST written ("" when nothing imports)
    written: list = field(default_factory=list)  # names of the units written
    global_list: bool = False  # it holds a global variable list (named by the file)
    #: (what, its errors) of what does not import: a unit's name, or the
    #: diagnostic's own message for what no unit holds
    skipped: list = field(default_factory=list)


def export(analysis: Analysis, notes: dict | None = None) -> list[ExportedFile]:
    """The project's files as ST. notes: unit id -> why it does not
    compile (the table's note), for the comment before it."""
    notes = notes or {}
    units = analysis.units
    broken = _not_imported(analysis)
    out = []
    for path in analysis.project.files:
        text = analysis.texts.get(path)
        label = analysis.project.label(path)
        if text is None:
            errors = [d for d in analysis.diagnostics if d.pos.file == path and d.is_error]
            out.append(ExportedFile(path, label, "", skipped=[(label, errors)]))
            continue
        try:
            if path in analysis.project.generated:  # ST already, laid on the lines of its file
                views = [[(n, line.strip()) for n, line in enumerate(text.splitlines(), 1) if line.strip()]]
            else:
                views = st_plain_lines(path, text, DiagnosticBag())
        except Exception:  # an importer's own failure: E009 of the analysis says so
            views = []
        top = [u for u in units.by_file.get(path, []) if u.parent is None]
        owned = _owners(views, top)
        result = ExportedFile(path, label, "")
        parts = []
        for u in top:
            if u.id in broken:
                result.skipped.append((u.name, broken[u.id]))
                continue
            lines = [line for view, owners in zip(views, owned) for (n, line), o in zip(view, owners) if o is u]
            if not lines:
                continue
            if not analysis.compiled(u) and u.kind != "ACTION":
                why = notes.get(u.id) or "it has errors (softplc check lists them)"
                parts.append(f"(* not compiled by softplc: {_safe(why)} *)")
            parts.extend(lines)
            result.written.append(u.name)
            result.global_list = result.global_list or u.kind == "VAR_BLOCK"
        for d in analysis.diagnostics:
            here = d.pos.file == path and d.is_error and is_import_error(d.code)
            if here and units.hit(path, d.pos.line, d.pos.col) is None:
                result.skipped.append((d.message, [d]))
        result.text = "\n".join(parts) + "\n" if parts else ""
        out.append(result)
    return out


def is_import_error(code: str) -> bool:
    """Whether an error means the source did not become ST: it cannot be
    read (E000), its syntax (E001-E005, E007-E009), the importers'
    (E180-E219)."""
    number = int(code[1:]) if code[:1] == "E" and code[1:].isdigit() else -1
    return 0 <= number <= 9 and number != 6 or 180 <= number <= 219


def _not_imported(analysis: Analysis) -> dict:
    """unit id -> the import and syntax errors in it."""
    out: dict = {}
    for d in analysis.diagnostics:
        if not d.is_error or not is_import_error(d.code):
            continue
        u = analysis.units.hit(d.pos.file, d.pos.line, d.pos.col)
        while u is not None and u.parent is not None:
            u = analysis.units.all[u.parent]
        if u is not None:
            out.setdefault(u.id, []).append(d)
    return out


def _owners(views: list, top: list) -> list:
    """Per view, the unit each line belongs to: the one whose lines hold
    it; a line between two (a pragma, a comment, TYPE) goes to the next,
    unless it closes (END_TYPE, END_VAR ...): then to the one before."""
    ranges = sorted((min(s[0][0] for s in u.spans), max(s[1][0] for s in u.spans), u.id, u) for u in top)
    starts = [r[0] for r in ranges]
    out = []
    for view in views:
        owners: list = []
        for n, line in view:
            i = bisect.bisect_right(starts, n) - 1  # the last unit starting at or before n
            if i >= 0 and ranges[i][1] >= n:
                owners.append(ranges[i][3])
                continue
            before = ranges[i][3] if i >= 0 else None
            after = ranges[i + 1][3] if i + 1 < len(ranges) else None
            closing = line.lstrip().upper().startswith("END_")
            owners.append(before if closing or after is None else after)
        out.append(owners)
    return out


def configuration(analysis: Analysis, written: set) -> str:
    """A TwinCAT project's tasks as an ST CONFIGURATION (the PROGRAMs
    written only), or ''."""
    tasks = []
    for t in analysis.project.tasks:
        calls = [name for name, _pos in t.programs if name.upper() in written]
        if calls:
            tasks.append((t, calls))
    if not tasks:
        return ""
    name = identifier_from_path(analysis.project.name or "Project")
    lines = [f"CONFIGURATION {name}", "    RESOURCE PLC ON PLC"]
    for t, _calls in tasks:
        ns = t.interval_ns
        interval = f"T#{ns // 1_000_000}ms" if ns % 1_000_000 == 0 else f"T#{ns // 1000}us"
        lines.append(f"        TASK {t.name} (INTERVAL := {interval}, PRIORITY := {int(t.priority)});")
    for t, calls in tasks:
        lines.extend(f"        PROGRAM {p} WITH {t.name} : {p};" for p in calls)
    lines += ["    END_RESOURCE", "END_CONFIGURATION", ""]
    return "\n".join(lines)


def comment(text: str) -> str:
    """A one-line ST comment of text (made safe)."""
    return f"(* {_safe(text, 200)} *)"
