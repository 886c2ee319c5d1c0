"""The table of a project's check: per file, and per POU in it, whether it
compiled, its errors, the references to missing libraries and the
warnings; then the totals.

    file / POU                          compiled  errors  libraries  warnings
    POUs/FB_Motor.TcPOU                      yes       0          0         0
    POUs/FB_Log.TcPOU                         no       0         14         0  needs Tc3_EventLogger
    plc.xml                                  3/4       1          0         0
      Counter                                yes       0          0         0
      Broken                                  no       1          0         0
    total: 3 files, 6 POUs, 4 compiled (67 %); 1 error, 14 from 1 missing library; 0 warnings

A file with one POU (a TwinCAT file) or none (a type, a variable list)
takes one line; a POU left out for a name it uses says which.
"""

from __future__ import annotations

import collections
from dataclasses import dataclass

from .analysis import Analysis
from .missing import NOT_FOUND

_HEAD = ("compiled", "errors", "libraries", "warnings")


@dataclass
class Row:
    label: str
    compiled: str  # yes, no, k/n, or - (nothing to compile)
    errors: int
    libraries: int
    warnings: int
    note: str = ""


@dataclass
class Totals:
    files: int
    pous: int
    compiled: int
    errors: int
    library_refs: int
    libraries: int
    warnings: int

    def line(self) -> str:
        share = f" ({round(100 * self.compiled / self.pous)} %)" if self.pous else ""
        libs = (
            f", {self.library_refs} from {self.libraries} missing librar{'y' if self.libraries == 1 else 'ies'}"
            if self.libraries
            else ""
        )
        return (
            f"total: {_n(self.files, 'file')}, {_n(self.pous, 'POU')}, {self.compiled} compiled{share}; "
            f"{_n(self.errors, 'error')}{libs}; {_n(self.warnings, 'warning')}"
        )


def _n(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")


def _tally(analysis: Analysis, groups: list, rest: list) -> tuple:
    """(per unit id: [errors, library references, warnings, libraries];
    per file: [errors, library references, warnings]): a unit counts what
    its own units hold."""
    units = analysis.units
    lib_of: dict = {}  # id of a replaced diagnostic -> its library
    for g in groups:
        for d in g.replaced:
            lib_of[id(d)] = g.name or "?"
    per_unit: dict = collections.defaultdict(lambda: [0, 0, 0, set()])  # errors, library refs, warnings, libraries
    per_file: dict = collections.defaultdict(lambda: [0, 0, 0])
    for d in [*rest, *(d for g in groups for d in g.replaced)]:
        if d.code in ("E223", "E224"):
            continue
        col = 1 if id(d) in lib_of else (0 if d.is_error else 2)
        per_file[d.pos.file][col] += 1
        u = units.hit(d.pos.file, d.pos.line, d.pos.col)
        while u is not None:
            per_unit[u.id][col] += 1
            if id(d) in lib_of:
                per_unit[u.id][3].add(lib_of[id(d)])
            u = units.all[u.parent] if u.parent is not None else None
    return per_unit, per_file


def notes(analysis: Analysis, groups: list, rest: list) -> dict:
    """unit id -> why the unit did not compile, for each unit that did not."""
    per_unit, _ = _tally(analysis, groups, rest)
    out = {}
    for u in analysis.units.all:
        note = _note(analysis, [u], per_unit)
        if note:
            out[u.id] = note
    return out


def rows(analysis: Analysis, groups: list, rest: list) -> tuple[list[Row], Totals]:
    """The rows and the totals of a project's table; groups and rest as
    missing.group gives them (rest: the diagnostics shown one by one)."""
    units = analysis.units
    per_unit, per_file = _tally(analysis, groups, rest)
    out: list[Row] = []
    pous = compiled = 0
    for path in analysis.project.files:
        label = analysis.project.label(path)
        file_units = units.by_file.get(path, [])
        items = [u for u in file_units if u.is_pou]
        lost = analysis.lost.get(path, [])
        e, lib, w = per_file[path]
        pous += len(items) + len(lost)
        done = [u for u in items if analysis.compiled(u)]
        compiled += len(done)
        if len(items) <= 1 and not lost:
            whole = items or [u for u in file_units if u.parent is None]
            ok = "-" if not whole else ("yes" if all(analysis.compiled(u) for u in whole) else "no")
            out.append(Row(label, ok, e, lib, w, _note(analysis, whole, per_unit)))
            continue
        out.append(Row(label, f"{len(done)}/{len(items) + len(lost)}", e, lib, w))
        rows_here = [(u.spans[0][0][0], u) for u in items] + [(line, name) for name, line in lost]
        for _line, item in sorted(rows_here, key=lambda r: r[0]):
            if isinstance(item, str):
                out.append(Row(f"  {item[:60]}", "no", _lost_errors(analysis, path, item), 0, 0, "not imported"))
                continue
            ue, ulib, uw, _libs = per_unit[item.id]
            ok = "yes" if analysis.compiled(item) else "no"
            out.append(Row(f"  {item.name}", ok, ue, ulib, uw, _note(analysis, [item], per_unit)))
    errors = sum(1 for d in rest if d.is_error and d.code not in ("E223", "E224"))
    warnings = sum(1 for d in rest if not d.is_error)
    refs = sum(len(g.replaced) for g in groups)  # errors (a place may hold two)
    named = len([g for g in groups if g.name != NOT_FOUND])
    totals = Totals(
        len(analysis.project.files), pous, compiled, errors, refs, named + (1 if len(groups) > named else 0), warnings
    )
    return out, totals


def _lost_errors(analysis: Analysis, path: str, name: str) -> int:
    """The errors outside every unit of path between the POU element of
    name and the next POU (what kept it from becoming ST)."""
    starts = sorted(
        [line for _n, line in analysis.lost.get(path, [])]
        + [u.spans[0][0][0] for u in analysis.units.by_file.get(path, []) if u.is_pou]
    )
    first = next(line for n, line in analysis.lost[path] if n == name)
    later = [line for line in starts if line > first]
    last = later[0] if later else 10**9
    units = analysis.units
    return sum(
        1
        for d in analysis.diagnostics
        if d.is_error
        and d.pos.file == path
        and first <= d.pos.line < last
        and units.hit(path, d.pos.line, d.pos.col) is None
    )


def _note(analysis: Analysis, units: list, per_unit: dict) -> str:
    """Why a unit that did not compile did not: the missing libraries it
    uses, or the name it uses of a unit left out."""
    if not units or all(analysis.compiled(u) for u in units):
        return ""
    libs = sorted({lib for u in units for lib in per_unit[u.id][3]})
    if libs:
        return "needs " + ", ".join("names not found" if lib == "?" else lib for lib in libs)
    because = [analysis.because[u.id] for u in units if u.id in analysis.because]
    if because and not any(per_unit[u.id][0] for u in units):
        return f"uses {because[0]}, which does not compile"
    return ""


def render(table: list[Row], totals: Totals, width: int = 60) -> str:
    """The table as text (labels longer than width cut from the left)."""
    labels = [r.label if len(r.label) <= width else "…" + r.label[-(width - 1) :] for r in table]
    w = max([len("file / POU"), *map(len, labels)])
    lines = [f"{'file / POU':<{w}}  " + "  ".join(_HEAD)]
    for label, r in zip(labels, table):
        cells = (r.compiled, r.errors, r.libraries, r.warnings)
        line = f"{label:<{w}}  " + "  ".join(f"{c!s:>{len(h)}}" for c, h in zip(cells, _HEAD))
        lines.append(f"{line}  {r.note}" if r.note else line)
    lines.append(totals.line())
    return "\n".join(lines)
