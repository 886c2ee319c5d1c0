"""What `softplc check`, `exec` and `export-st` do with a project (a
TwinCAT .sln/.tsproj/.plcproj, a CODESYS export, a Beremiz folder, a
folder): check it as a whole, print the diagnostics with the errors of a
missing library as one line per library, the table per file and POU, and
the counts; compile the part that compiles for `--partial`; write what
imports as ST."""

from __future__ import annotations

import sys
from pathlib import Path

import click

from .cli_report import echo_err, plural, report
from .st.profile import PROFILES

KIND_NAMES = {
    "twincat": "TwinCAT PLC project",
    "codesys": "CODESYS export",
    "beremiz": "Beremiz project",
    "plcopen": "PLCopen XML file",
    "folder": "folder",
    "files": "files",
}

PROFILE_OPTION = click.option(
    "--profile",
    type=click.Choice(list(PROFILES), case_sensitive=False),
    default=None,
    help=(
        "Dialect: strict IEC 61131-3, MatIEC (OpenPLC, Beremiz), CODESYS, TwinCAT or Schneider Unity/Control "
        "Expert [default: the project's (twincat for TwinCAT, codesys for a CODESYS export, matiec for Beremiz), "
        "else codesys]."
    ),
)
ALL_ERRORS_OPTION = click.option(
    "--all-errors",
    is_flag=True,
    help="Show every error a missing library causes, instead of one line per library.",
)
PARTIAL_OPTION = click.option(
    "--partial",
    is_flag=True,
    help="Compile and run the part of the project that compiles (the rest is listed), not nothing.",
)


def open_or_exit(paths: list) -> list:
    from .project import open_projects

    projects = open_projects(paths)
    if not any(p.files or p.diags.items for p in projects):
        echo_err("softplc: no ST sources in " + ", ".join(map(str, paths)))
        sys.exit(2)
    return projects


def _grouped(analysis, all_errors: bool) -> tuple:
    """(missing-library groups, the diagnostics shown one by one)."""
    from .project.missing import group_analysis

    if all_errors:
        return [], list(analysis.diagnostics)
    return group_analysis(analysis, frozenset(lib.namespace for lib in analysis.libraries))


def print_diagnostics(analysis, groups: list, rest: list) -> tuple[int, int, int]:
    """Every diagnostic, then one line per missing library; (errors,
    references to missing libraries, warnings)."""
    errors, warnings = report(rest, analysis.sources)
    report([g.diagnostic() for g in groups], analysis.sources)
    return errors, sum(len(g.replaced) for g in groups), warnings


def counts_line(errors: int, library_refs: int, libraries: int, warnings: int) -> str:
    """'2 errors, 1 warning', or '12 errors, 214 more from 3 missing
    libraries, 14 warnings'."""
    if not library_refs:
        return f"{plural(errors, 'error')}, {plural(warnings, 'warning')}"
    libs = f"{libraries} missing librar{'y' if libraries == 1 else 'ies'}"
    return f"{plural(errors, 'error')}, {library_refs} more from {libs}, {plural(warnings, 'warning')}"


def check_projects(paths: list, profile: str | None, all_errors: bool, natives_for, libraries: tuple = ()) -> int:
    """`softplc check` of files, folders and projects: the exit code."""
    from .check_summary import most_frequent, note_other_profiles
    from .program import check_files
    from .project.analysis import analyse
    from .project.table import render, rows
    from .st import dialects, explain
    from .st.profile import DEFAULT

    failed = False
    for project in open_or_exit(paths):
        natives = natives_for(project.files)
        plain = project.kind in ("files", "folder", "plcopen")
        if project.kind != "files":
            echo_err(f"{KIND_NAMES[project.kind]} {project.name}: {plural(len(project.files), 'source file')}")
        analysis = analyse(
            project, profile, natives=natives, libraries=libraries, subset=project.kind != "files", check_only=True
        )
        prof = analysis.profile.name
        if plain:
            note_other_profiles(project.files, prof, analysis.diagnostics, _checker(check_files, natives))
        groups, rest = _grouped(analysis, all_errors)
        errors, refs, warnings = print_diagnostics(analysis, groups, rest)
        if project.kind != "files":
            table, totals = rows(analysis, groups, rest)
            echo_err(render(table, totals))
        if len({d.code for d in rest}) > 1:
            echo_err(most_frequent(rest))
        if project.extensions:
            ext = ", ".join(f"{name} ({kind})" for name, kind in project.extensions)
            echo_err(f"extensions softplc does not run: {ext}")
        source = "--profile" if profile else ("the project's" if project.profile else "default")
        echo_err(f"profile: {prof}" + ("" if source == "--profile" or prof == DEFAULT.name else f" ({source})"))
        if plain and (errors or warnings) and profile is None:
            _dialect_hint(project.files, prof, errors, warnings, natives, check_files, dialects)
        named = len({g.name for g in groups})
        echo_err(counts_line(errors, refs, named, warnings))
        shown = [d.code for d in rest] + [g.diagnostic().code for g in groups]
        if shown:
            echo_err(explain.more_line(shown))
        failed = failed or bool(errors or refs)
    return 1 if failed else 0


def _checker(check_files, natives: tuple):
    return lambda files, profile: check_files(files, profile, natives=natives)[0]


def _dialect_hint(files, profile, errors, warnings, natives, check_files, dialects) -> None:
    """When the files read like another dialect that checks them better, say so."""
    texts = []
    for f in files:
        try:
            texts.append(Path(f).read_text(encoding="utf-8", errors="replace"))
        except OSError:
            return
    for other, whats in dialects.candidates(texts, profile):
        diagnostics, _sources = check_files(list(files), profile=other, natives=natives)
        e = sum(1 for d in diagnostics if d.is_error)
        if e < errors or (e == errors == 0 and len(diagnostics) < warnings):
            echo_err(dialects.hint(other, whats))
            return


def one_project(paths: list, what: str):
    """The one project a command runs; a usage error for several."""
    projects = open_or_exit(paths)
    if len(projects) > 1:
        names = ", ".join(f"{p.name} ({p.path})" for p in projects)
        raise click.UsageError(f"{what} runs one project; these are {len(projects)}: {names}; name one")
    return projects[0]


def compile_project(project, profile: str | None, partial: bool, all_errors: bool = False, libraries: tuple = ()):
    """(the Program of the project, or of the part that compiles with
    partial, the analysis); exits 1 with the diagnostics when there is
    none to run."""
    from .project.analysis import analyse

    analysis = analyse(project, profile, libraries=libraries, subset=partial)
    groups, rest = _grouped(analysis, all_errors)
    if analysis.errors and not partial:
        errors, refs, warnings = print_diagnostics(analysis, groups, rest)
        echo_err(counts_line(errors, refs, len(groups), warnings))
        echo_err("hint: --partial runs the part of the project that compiles")
        sys.exit(1)
    if analysis.program is None:
        print_diagnostics(analysis, groups, rest)
        echo_err("softplc: no part of the project compiles")
        sys.exit(1)
    report([d for d in rest if not d.is_error], analysis.sources)
    left = [u.name for u in analysis.units.all if u.is_pou and not analysis.compiled(u)]
    if left:
        shown = ", ".join(left[:12]) + (f" … {len(left)} in all" if len(left) > 12 else "")
        echo_err(f"left out, they do not compile (softplc check lists why): {shown}")
    return analysis.program, analysis


def test_project(path: str, *, junit: str | None, pattern: str | None, timeout_ns: int) -> int:
    """`softplc test PROJECT`: the project's TcUnit suites (the library
    is offered whether the project references it or not), run with the
    project's tasks; its errors are reported as `check` does (exit 2)."""
    from .project.analysis import analyse
    from .project.running import ProjectRunError, project_config
    from .testing.command import run_project_tests
    from .testing.tcunit import tcunit_library

    project = one_project([path], "test")
    analysis = analyse(project, None, libraries=(tcunit_library(),), subset=False)
    groups, rest = _grouped(analysis, False)
    if analysis.errors or analysis.program is None:
        errors, refs, warnings = print_diagnostics(analysis, groups, rest)
        echo_err(counts_line(errors, refs, len(groups), warnings))
        return 2
    report([d for d in rest if not d.is_error], analysis.sources)
    try:
        config = project_config(analysis, analysis.program)
    except ProjectRunError as e:
        echo_err(f"softplc test: {e}")
        return 2
    label = f"{KIND_NAMES[project.kind]} {project.name}"
    return run_project_tests(analysis.program, config, label, junit=junit, pattern=pattern, timeout_ns=timeout_ns)


def task_entry(project, program, analysis=None) -> str | None:
    """The PROGRAM the project's tasks call, when they call exactly one.
    A usage error when the project has PROGRAMs and none compiled."""
    if analysis is not None and not any(k == "PROGRAM" for k in program.pous.values()):
        programs = [u.name for u in analysis.units.all if u.kind == "PROGRAM"]
        if programs:
            raise click.UsageError(
                f"no PROGRAM of the project compiles ({', '.join(programs[:5])}: softplc check says why)"
            )
    called = {name.upper(): name for t in project.tasks for name, _pos in t.programs}
    known = {n.upper(): n for n, k in program.pous.items() if k == "PROGRAM"}
    found = [known[k] for k in called if k in known]
    return found[0] if len(found) == 1 else None


def export_projects(paths: list, output: str | None, profile: str | None, libraries: tuple = ()) -> int:
    """`softplc export-st`: every POU that imports as ST, to stdout, one
    file (-o OUT.st) or one .st per source (-o DIR/); the rest listed with
    their errors. The exit code: 1 when something did not import."""
    from .project.analysis import analyse
    from .project.export import comment, configuration, export
    from .project.table import notes

    projects = open_or_exit(paths)
    to_dir = output is not None and (output.endswith(("/", "\\")) or Path(output).is_dir())
    pieces: list[tuple[str, str]] = []  # (name of the .st to write, ST)
    written = skipped = 0
    lists: list[str] = []  # global variable lists named by their files
    for project in projects:
        analysis = analyse(project, profile, libraries=libraries, subset=True)
        groups, rest = _grouped(analysis, False)
        files = export(analysis, notes(analysis, groups, rest))
        own = [d for d in analysis.diagnostics if d.pos.file not in project.files]  # the project files'
        skipped += sum(1 for d in own if d.is_error)
        report(own, analysis.sources)
        lists += [project.label(f.path) for f in files if f.global_list]
        names: set = set()
        prefix = f"{project.name}/" if to_dir and len(projects) > 1 else ""
        for f in files:
            names.update(n.upper() for n in f.written)
            written += len(f.written)
            for what, diags in f.skipped:
                skipped += 1
                echo_err(f"not exported from {f.label}: {what}")
                report(diags, analysis.sources)
            if f.text:
                rel = Path(f.label)
                if rel.is_absolute() or ".." in rel.parts:  # (a file from outside the project's folder)
                    rel = Path(rel.name)
                head = "" if to_dir or len(files) == 1 and len(projects) == 1 else comment(f"from {f.label}") + "\n"
                pieces.append((prefix + str(rel.with_suffix(".st")), head + f.text))
        conf = configuration(analysis, names)
        if conf:
            pieces.append((prefix + f"{Path(project.name).name or 'project'}_tasks.st", conf))
    if not pieces:
        echo_err("softplc: nothing imports; nothing written")
        return 1
    if output is None:
        click.echo("\n".join(text for _name, text in pieces), nl=False)
    else:
        _write(output, to_dir, pieces)
    if lists and output is not None and not to_dir or lists and output is None and len(pieces) > 1:
        echo_err(
            f"note: the global variable lists of {', '.join(lists[:3])}{' …' if len(lists) > 3 else ''} are named "
            "by their files; code that names a list (GVL.x) needs it in a file of its own: export with -o DIR/"
        )
    echo_err(f"exported {plural(written, 'declaration')}" + (f"; {skipped} not (listed above)" if skipped else ""))
    return 1 if skipped else 0


def _write(output: str, to_dir: bool, pieces: list) -> None:
    try:
        if not to_dir:
            Path(output).write_text("\n".join(text for _name, text in pieces), encoding="utf-8")
        else:
            for name, text in pieces:
                target = Path(output) / name
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(text, encoding="utf-8")
    except OSError as e:
        echo_err(f"softplc: cannot write {e.filename or output}: {e.strerror or e}")
        sys.exit(1)
    echo_err(f"wrote {output}" if not to_dir else f"wrote {len(pieces)} files to {output}")
