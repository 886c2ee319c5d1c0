"""How much of real projects softplc takes: per project (a folder or a
project file; the kind is found as `softplc check` finds it), its files
and POUs, the share of POUs that compile (in the largest part of the
project that compiles), how many PROGRAMs of that part run N cycles in
virtual time without a runtime fault, the errors by code with the share a
missing library causes apart, and the time the check took.

    python benchmarks/real_projects.py /work/projects/pcdshub+lcls-twincat-general
    python benchmarks/real_projects.py FOLDER... --cycles 100 --codes 8

Real projects are not part of the repository (their licences do not allow
it): give their folders. Nothing is asserted; the test suite only checks
that the script starts and reads its own small projects.
"""

from __future__ import annotations

import argparse
import collections
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

from host import timeit_factor

from softplc.runtime.project import open_projects
from softplc.runtime.project.analysis import analyse
from softplc.runtime.project.missing import group_analysis
from softplc.runtime.st.faults import STFault


@dataclass
class Row:
    name: str
    kind: str
    files: int
    pous: int
    compiled: int
    programs: int = 0
    ran: int = 0
    errors: int = 0
    library_errors: int = 0
    by_code: collections.Counter = field(default_factory=collections.Counter)
    libraries: list = field(default_factory=list)  # (name, references)
    faults: list = field(default_factory=list)  # (program, fault)
    seconds: float = 0.0


def measure(project, cycles: int) -> Row:
    t0 = time.perf_counter()
    analysis = analyse(project)
    groups, rest = group_analysis(analysis)
    pous = [u for u in analysis.units.all if u.is_pou]
    lost = sum(len(names) for names in analysis.lost.values())  # POUs that did not become ST
    row = Row(project.name, project.kind, len(project.files), len(pous) + lost, sum(analysis.compiled(u) for u in pous))
    row.errors = sum(1 for d in analysis.diagnostics if d.is_error)
    row.library_errors = sum(len(g.replaced) for g in groups)
    row.by_code = collections.Counter(d.code for d in rest if d.is_error)
    row.libraries = [(g.name or "names not found", g.count) for g in groups]
    program = analysis.program
    if program is not None:
        for name, kind in program.pous.items():
            if kind != "PROGRAM":
                continue
            row.programs += 1
            try:
                program.runner(name, cycle_time_ms=10).run(cycles)
                row.ran += 1
            except STFault as e:
                row.faults.append((name, str(e).splitlines()[0]))
    row.seconds = time.perf_counter() - t0
    return row


def _share(part: int, whole: int) -> str:
    return f"{round(100 * part / whole)} %" if whole else "-"


def render(rows: list, cycles: int, codes: int) -> str:
    head = ("project", "kind", "files", "POUs", "compiled", f"runs ({cycles} cycles)", "errors", "missing libs", "time")
    table = [
        (
            r.name,
            r.kind,
            str(r.files),
            str(r.pous),
            f"{r.compiled} ({_share(r.compiled, r.pous)})",
            f"{r.ran}/{r.programs}",
            str(r.errors),
            f"{r.library_errors} ({_share(r.library_errors, r.errors)})",
            f"{r.seconds:.1f} s",
        )
        for r in rows
    ]
    widths = [max(len(h), *(len(t[i]) for t in table)) for i, h in enumerate(head)]
    lines = ["  ".join(h.ljust(w) if i < 2 else h.rjust(w) for i, (h, w) in enumerate(zip(head, widths)))]
    for r, t in zip(rows, table):
        lines.append("  ".join(c.ljust(w) if i < 2 else c.rjust(w) for i, (c, w) in enumerate(zip(t, widths))))
        if r.by_code:
            lines.append("    errors by code: " + ", ".join(f"{c} {n}" for c, n in r.by_code.most_common(codes)))
        if r.libraries:
            shown = ", ".join(f"{name} {n}" for name, n in r.libraries[:codes])
            lines.append(f"    missing libraries (references): {shown}")
        for program, fault in r.faults:
            lines.append(f"    fault in {program}: {fault}")
    return "\n".join(lines)


def main(argv: list | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("paths", nargs="+", metavar="FOLDER", help="a project folder or file (several: one row each)")
    parser.add_argument("--cycles", type=int, default=100, help="cycles each PROGRAM runs (default 100)")
    parser.add_argument("--codes", type=int, default=8, help="error codes and libraries shown per project (default 8)")
    args = parser.parse_args(argv)
    host = timeit_factor()
    print(host.line())
    rows = [measure(project, args.cycles) for path in args.paths for project in open_projects([path])]
    print(render(rows, args.cycles, args.codes))
    total = sum(r.seconds for r in rows)
    pous, compiled = sum(r.pous for r in rows), sum(r.compiled for r in rows)
    errors, library = sum(r.errors for r in rows), sum(r.library_errors for r in rows)
    print(
        f"all: {len(rows)} projects, {pous} POUs, {compiled} compiled ({_share(compiled, pous)}), "
        f"{sum(r.ran for r in rows)}/{sum(r.programs for r in rows)} PROGRAMs ran, {errors} errors "
        f"({_share(library, errors)} from missing libraries), {total:.1f} s "
        f"({host.scaled(total):.1f} s on the reference host)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
