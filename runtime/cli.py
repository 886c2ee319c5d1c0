"""The ``softplc`` command.

    softplc check FILE...                    report diagnostics
    softplc check --explain CODE             the page of a diagnostic code (E030)
    softplc compile FILE... --emit-python    show the generated Python
    softplc exec FILE... --cycles N          run a PROGRAM (or FUNCTION) in virtual
                                             time and print its variables as JSON
    softplc run [CONFIG]                     run the PLC (see run --help)
    softplc plot TRACE [-o OUT.png]          plot a trace of run --trace
    softplc sweep CONFIG --matrix S.toml     run many scenarios of CONFIG (a table of results)

Exit codes (stable, scripts rely on them):
    0  success
    1  compile errors (or an input file that cannot be read)
    2  usage error: bad option, unknown entry, bad --cycle-time
    3  runtime fault in the ST program (message with ST file:line:col)
    4  internal error in softplc itself (a bug; set SOFTPLC_DEBUG=1 for the traceback)

Whatever the input, the user sees a message, never a Python traceback.
"""

from __future__ import annotations

import gc
import json
import os
import sys
import traceback
from pathlib import Path

import click

from . import cache
from .cli_log import log_cmd
from .cli_project import ALL_ERRORS_OPTION, PARTIAL_OPTION
from .cli_project import PROFILE_OPTION as PROJECT_PROFILE_OPTION
from .cli_report import echo_err as _echo_err
from .cli_report import report as _report
from .cli_report import summary as _summary
from .cli_run import Duration, run_cmd
from .cli_sweep import sweep_cmd
from .durations import EXAMPLES, parse_duration_ns
from .plugin.registry import PluginError
from .st.profile import DEFAULT, PROFILES

EXIT_OK = 0
EXIT_COMPILE = 1
EXIT_USAGE = 2
EXIT_FAULT = 3
EXIT_INTERNAL = 4

# ---------------------------------------------------------------- options


class CycleTime(click.ParamType):
    """A cycle time: '10ms', '1s', '1s500ms', 'T#10ms', or a bare number of
    milliseconds. The virtual clock ticks in whole milliseconds (TIME
    resolution), so a value must be a positive whole number of ms."""

    name = "duration"

    def convert(self, value, param, ctx) -> int:
        if isinstance(value, int):
            return value
        ns = parse_duration_ns(value)
        if ns is None:
            self.fail(f"{value!r} is not a duration (examples: {EXAMPLES})", param, ctx)
        if ns <= 0:
            self.fail(f"{value!r}: the cycle time must be positive", param, ctx)
        if ns % 1_000_000:
            self.fail(f"{value!r}: the cycle time must be a whole number of milliseconds", param, ctx)
        return ns // 1_000_000


PROFILE_OPTION = click.option(
    "--profile",
    type=click.Choice(list(PROFILES), case_sensitive=False),
    default=DEFAULT.name,
    show_default=True,
    help=(
        "Dialect: strict IEC 61131-3, MatIEC (OpenPLC, Beremiz), CODESYS, TwinCAT or Schneider Unity/Control Expert."
    ),
)


class LibraryArg(click.ParamType):
    """--library NAME|PATH: a library softplc ships (Tc2_System) or a folder
    of the user's (its name is its namespace)."""

    name = "library"

    def convert(self, value, param, ctx):
        from .program import Library
        from .program.shipped import is_shipped_name, shipped_named

        if isinstance(value, Library):
            return value
        if is_shipped_name(value):
            lib = shipped_named(value)
            assert lib is not None
            return lib
        path = Path(value)
        if not path.exists():
            self.fail(f"{value!r} is neither a library softplc ships nor a folder or file", param, ctx)
        return Library(path, path.stem if path.is_file() else path.name)


LIBRARY_OPTION = click.option(
    "--library",
    "libraries",
    type=LibraryArg(),
    multiple=True,
    metavar="NAME|PATH",
    help="A library to compile with: one softplc ships (Tc2_System) or a folder of yours. Repeatable.",
)

FILES_ARGUMENT = click.argument(
    "files", nargs=-1, required=True, type=click.Path(exists=True, dir_okay=False, readable=True)
)


# ---------------------------------------------------------------- helpers


def _compile(files, profile: str, libraries: tuple = ()):
    """Compile or exit 1 with the diagnostics. Warnings go to stderr either way."""
    from .program import compile_files
    from .st.diagnostics import CompileError

    try:
        prog = compile_files(list(files), profile=profile, libraries=libraries)
    except CompileError as e:
        errors, warnings = _report(e.diagnostics, e.sources)
        _summary(errors, warnings)
        sys.exit(EXIT_COMPILE)
    except OSError as e:  # a file vanished or became unreadable after the check
        _echo_err(f"softplc: cannot read {e.filename or 'input'}: {e.strerror or e}")
        sys.exit(EXIT_COMPILE)
    return prog


# ---------------------------------------------------------------- commands


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="softplc", prog_name="softplc")
@click.option(
    "--no-cache",
    is_flag=True,
    help="Neither read nor write softplc's cache (the parsed grammar and libraries; SOFTPLC_NO_CACHE=1 does the same).",
)
@click.pass_context
def cli(ctx: click.Context, no_cache: bool) -> None:
    """softplc: IEC 61131-3 Structured Text compiled to Python.

    Exit codes: 0 ok, 1 compile errors, 2 usage error, 3 runtime fault,
    4 internal error.
    """
    if no_cache:
        ctx.with_resource(cache.disabled())


@cli.command()
@click.argument("files", nargs=-1, type=click.Path(exists=True, readable=True))
@PROJECT_PROFILE_OPTION
@ALL_ERRORS_OPTION
@LIBRARY_OPTION
@click.option("--explain", "code", metavar="CODE", help="Print the page of a diagnostic code (e.g. E030); no FILES.")
def check(files, profile: str | None, all_errors: bool, libraries: tuple, code: str | None) -> None:
    """Check ST files, PLCopen XML and TwinCAT files, and projects: a
    TwinCAT .sln/.tsproj/.plcproj, a CODESYS export, a Beremiz folder, a
    folder. Diagnostics with file:line:column; for a project a table per
    file and POU (compiled, errors, warnings) and one line per missing
    library."""
    from .cli_project import check_projects

    if code is not None:
        _explain(code)
    if not files:
        raise click.UsageError("Missing argument 'FILES...'.")
    if _console:
        gc.disable()  # the process ends with the check (_leave): nothing to collect
    _leave(check_projects(list(files), profile, all_errors, _natives_for, libraries))


#: whether this process is the console script's, which main() runs and
#: ends (not a test's CliRunner nor an application calling the commands)
_console = False


def _leave(rc: int) -> None:
    """End the command with exit code rc. The console script's process
    leaves at once once its output is flushed: no collection of the checked
    trees and no teardown of every module, which cost `softplc check` about
    a tenth of its time (mypy leaves the same way). Only for a command that
    leaves nothing behind: no thread, no child, no atexit work, no file
    half written (the cache writes each entry with an atomic rename)."""
    if not _console:
        sys.exit(rc)
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (BrokenPipeError, OSError):  # `softplc check ... | head`: the reader left
            pass
    os._exit(rc)


def _natives_for(files: list) -> tuple:
    """A test file (test_*.st, softplc test) is checked with the assertions it calls."""
    return _test_natives() if any(Path(f).name.lower().startswith("test_") for f in files) else ()


def _explain(code: str) -> None:
    """Print code's page and exit 0; exit 2 naming the nearest codes if it has none."""
    from .st import explain

    text = explain.page(code)
    if text is None:
        near = explain.near(code)
        _echo_err(f"softplc: no diagnostic code {code!r}" + (f"; near: {', '.join(near)}" if near else ""))
        _echo_err("hint: a code is a letter and three digits, as check prints it: error E030, warning W130")
        sys.exit(EXIT_USAGE)
    click.echo(text, nl=False)
    sys.exit(EXIT_OK)


def _test_natives() -> tuple:
    from .testing.natives import NATIVES

    return NATIVES


@cli.command("compile")
@FILES_ARGUMENT
@click.option("--emit-python", is_flag=True, help="Print the generated Python module (or write it with -o).")
@click.option(
    "-o",
    "--output-dir",
    type=click.Path(file_okay=False),
    help="With --emit-python: write DIR/<stem of the first FILE>.py instead of printing.",
)
@PROFILE_OPTION
@LIBRARY_OPTION
def compile_cmd(files, emit_python: bool, output_dir: str | None, profile: str, libraries: tuple) -> None:
    """Compile ST files to Python; with --emit-python show the result."""
    if output_dir and not emit_python:
        raise click.UsageError("-o/--output-dir needs --emit-python")
    prog = _compile(files, profile, libraries)
    _report(prog.warnings, prog.sources)
    if not emit_python:
        _summary(0, len(prog.warnings))
        return
    if output_dir is None:
        click.echo(prog.python_source, nl=not prog.python_source.endswith("\n"))
        return
    target = Path(output_dir) / (Path(files[0]).stem + ".py")
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_text(prog.python_source, encoding="utf-8")
    except OSError as e:
        _echo_err(f"softplc: cannot write {target}: {e.strerror or e}")
        sys.exit(EXIT_COMPILE)
    _echo_err(f"wrote {target}")


@cli.command("new")
@click.argument("name")
@click.option("--dir", "where", type=click.Path(file_okay=False), default=".", help="Create it in DIR (default: here).")
def new_cmd(name: str, where: str) -> None:
    """Create a project folder NAME that runs at once on the simulated plant:
    plc.toml, src/main.st, a test in tests/, the plant's programs, a README."""
    from .scaffold import new_project

    try:
        root = new_project(name, Path(where))
    except FileExistsError:
        raise click.UsageError(f"{Path(where) / name} exists already") from None
    except ValueError as e:
        raise click.UsageError(str(e)) from None
    except OSError as e:
        _echo_err(f"softplc: cannot create {Path(where) / name}: {e.strerror or e}")
        sys.exit(EXIT_USAGE)
    _echo_err(
        f"created {root}\n  cd {root}\n  softplc run plc.toml --virtual-time --duration 10s --watch motorStarts\n"
        "  softplc test plc.toml tests/test_main.st"
    )


@cli.command("export-st")
@click.argument("sources", nargs=-1, required=True, type=click.Path(exists=True))
@click.option(
    "-o",
    "--output",
    type=click.Path(),
    help="Write the ST to OUT.st, or with DIR/ (an existing folder, or a name ending in /) one .st per source.",
)
@PROJECT_PROFILE_OPTION
@LIBRARY_OPTION
def export_st_cmd(sources: tuple, output: str | None, profile: str | None, libraries: tuple) -> None:
    """Write imported files and projects (PLCopen XML, TwinCAT, a folder) as
    plain ST, for review and porting: every POU that imports (one that does
    not compile is marked so); the rest are listed with their errors."""
    from .cli_project import export_projects

    sys.exit(export_projects(list(sources), output, profile, libraries))


@cli.command("exec")
@click.argument("files", nargs=-1, required=True, type=click.Path(exists=True, readable=True))
@click.option("--entry", metavar="NAME", help="PROGRAM or FUNCTION to run [default: the only PROGRAM in FILES].")
@click.option("--cycles", type=click.IntRange(min=0), default=1, show_default=True, help="Number of cycles to run.")
@click.option(
    "--cycle-time",
    type=CycleTime(),
    default="10ms",
    show_default=True,
    help="Virtual time per cycle, whole milliseconds: 10ms, 1s, T#250ms.",
)
@PROJECT_PROFILE_OPTION
@PARTIAL_OPTION
@LIBRARY_OPTION
def exec_cmd(
    files, entry: str | None, cycles: int, cycle_time: int, profile: str | None, partial: bool, libraries: tuple
) -> None:
    """Run a PROGRAM for N cycles in virtual time and print its variables as
    one JSON object; for a FUNCTION print {"return": value}. FILES may be a
    project (a TwinCAT .sln/.plcproj, a CODESYS export, a Beremiz folder, a
    folder); its task's PROGRAM is the default entry."""
    from .cli_project import compile_project, one_project, task_entry
    from .st.faults import STFault

    project = one_project(list(files), "exec")
    if project.kind == "files" and not partial:
        prog = _compile(project.files, profile or DEFAULT.name, libraries)
        _report(prog.warnings, prog.sources)
    else:
        prog, analysis = compile_project(project, profile, partial, libraries=libraries)
        entry = entry or task_entry(project, prog, analysis)
    entry = _pick_entry(prog.pous, entry)
    try:
        runner = prog.runner(entry, cycle_time_ms=cycle_time)
        runner.run(cycles)
    except KeyError as e:
        # The loader's message says more than the bare name (e.g. "is a FUNCTION_BLOCK").
        detail = e.args[0] if e.args and e.args[0] != entry else f"no PROGRAM or FUNCTION named {entry!r}"
        raise click.UsageError(str(detail)) from None
    except STFault as e:  # also raised by initialisation, before the first cycle
        _echo_err(str(e))
        sys.exit(EXIT_FAULT)
    text = json.dumps(_exec_result(runner), indent=2, ensure_ascii=False)
    # a WCHAR or WSTRING the program made from a surrogate code (WORD_TO_WCHAR(16#D800)):
    # printed as its JSON escape \ud800, which UTF-8 cannot hold as a character
    click.echo(text.encode("utf-8", "backslashreplace").decode("utf-8"))


def _exec_result(runner) -> dict:
    """What `exec` prints: a PROGRAM's variables (and the global variables,
    under the key VAR_GLOBAL, which no variable can be called), or a
    FUNCTION's return value."""
    from .st.valuejson import encode_instance, encode_value

    if runner.instance is None:
        if runner.result is None:  # --cycles 0: the function was never called
            return {"return": None}
        return {"return": encode_value(runner.result_type, runner.result)}
    result = encode_instance(runner.instance)
    globals_ = encode_instance(runner.globals, skip=runner.program.library_globals)
    if globals_:
        result["VAR_GLOBAL"] = globals_
    return result


def _pick_entry(pous: dict, entry: str | None) -> str:
    """The --entry name as declared, checked against the user's POUs."""
    if entry is None:
        programs = [name for name, kind in pous.items() if kind == "PROGRAM"]
        if len(programs) == 1:
            return programs[0]
        if not programs:
            raise click.UsageError("the files declare no PROGRAM; name a FUNCTION with --entry")
        raise click.UsageError(f"the files declare several PROGRAMs ({', '.join(programs)}); choose one with --entry")
    for name, kind in pous.items():
        if name.upper() == entry.upper():
            if kind == "FUNCTION_BLOCK":
                raise click.UsageError(
                    f"{name} is a FUNCTION_BLOCK; --entry takes a PROGRAM or a FUNCTION (call the block from a PROGRAM)"
                )
            return name
    # Not a user POU: let the runner decide (library FUNCTIONs may be runnable).
    return entry


@cli.command("plot")
@click.argument("trace", type=click.Path(exists=True, dir_okay=False))
@click.option(
    "-o", "--output", type=click.Path(dir_okay=False), help="The figure: .png, .svg or .pdf [default: TRACE.png]."
)
@click.option("--signals", metavar="A,B", help="Only these signals, in this order (default: all).")
@click.option(
    "--unit",
    "units",
    multiple=True,
    metavar="VAR=UNIT",
    help="Label a number's axis with UNIT; numbers with the same unit share an axis.",
)
@click.option(
    "--bus-log",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="The run's bus log (`softplc run --bus-log`): its frames --mark names are marked.",
)
@click.option(
    "--mark",
    "mark_texts",
    multiple=True,
    metavar="TEXT",
    help="Mark the frames whose line of `softplc log` holds TEXT ('EMCY', 'NMT start', 'unit 1: write').",
)
@click.option(
    "--config",
    type=click.Path(dir_okay=False),
    metavar="CONFIG",
    help="The run's TOML file, for the frames' words [default: the embedded example].",
)
def plot_cmd(
    trace: str,
    output: str | None,
    signals: str | None,
    units: tuple,
    bus_log: str | None,
    mark_texts: tuple,
    config: str | None,
) -> None:
    """Plot a trace of `softplc run --trace` (a .csv or .vcd file): BOOLs as
    stacked steps, enumerations by name, numbers as lines, over engine time;
    the simulated devices' events the trace holds (breaker closes, EMCYs)
    and, with --bus-log and --mark, the frames of the run's bus log, as
    dotted lines."""
    from .cli_log import marks
    from .trace.plot import FORMATS, PlotUnavailable, parse_units, plot
    from .trace.reading import read_trace
    from .trace.series import TraceFileError

    out = Path(output) if output else Path(trace).with_suffix(".png")
    if out.suffix.lower() not in FORMATS:
        raise click.UsageError(f"-o {out}: the ending says the format: {', '.join(FORMATS)}")
    if bool(bus_log) != bool(mark_texts):
        raise click.UsageError("--bus-log and --mark go together: the log, and which of its frames to mark")
    try:
        unit_of = parse_units(units)
        data = read_trace(trace)
        if signals:
            data = data.select([n.strip() for n in signals.split(",") if n.strip()])
        found = marks(bus_log, config, list(mark_texts)) if bus_log else []
        left_out = plot(data, out, unit_of, marks=sorted(data.marks + found))
    except (PlotUnavailable, TraceFileError, ValueError) as e:
        _echo_err(f"softplc: {e}")
        sys.exit(EXIT_USAGE)
    except KeyError as e:
        _echo_err(f"softplc: {e.args[0]}")
        sys.exit(EXIT_USAGE)
    except OSError as e:
        _echo_err(f"softplc: cannot write {out}: {e.strerror or e}")
        sys.exit(EXIT_USAGE)
    if left_out:
        _echo_err(f"not drawn (text): {', '.join(left_out)}")
    if bus_log:
        _echo_err(f"marked {len(found)} frame(s) of {bus_log}")
    _echo_err(f"wrote {out}")


@cli.command("test")
@click.argument("paths", nargs=-1, required=True, type=click.Path(), metavar="[CONFIG] FILE... | PROJECT")
@click.option(
    "--junit", type=click.Path(dir_okay=False), metavar="FILE.xml", help="Write the results as JUnit XML (for CI)."
)
@click.option(
    "-k", "pattern", metavar="PATTERN", help="Run only the tests whose name contains PATTERN (or matches a glob)."
)
@click.option(
    "--timeout",
    type=Duration(),
    default="60s",
    show_default=True,
    metavar="DURATION",
    help="Engine time a test may take before it fails (30s, 2m, T#500ms); a test's own "
    "{attribute 'timeout'} goes first.",
)
@click.option(
    "--default-plant",
    is_flag=True,
    help="Run the tests against the embedded default plant (what softplc run runs without a CONFIG).",
)
def test_cmd(paths: tuple, junit: str | None, pattern: str | None, timeout: int, default_plant: bool) -> None:
    """Run the tests written in ST in FILE... (FUNCTION_BLOCKs named TEST_...
    calling ASSERT_EQUAL, ASSERT_TRUE ...), each in a fresh PLC in virtual
    time, against the programs and simulated devices of CONFIG (a TOML file,
    or the default plant with --default-plant; without either the tests run
    alone); and TcUnit's test suites, of FILE... or
    of a PROJECT (a TwinCAT .sln/.tsproj/.plcproj, a folder) run with its
    own tasks until TcUnit reports every test finished.

    Exit codes: 0 every test passed, 1 a test failed, 2 bad configuration,
    ST files or option, or no test found.
    """
    from .collector import collector_off

    with collector_off():  # the imports of the engine and the compile side
        from .testing.command import run_tests

    label: str | None = None
    if default_plant:
        from .config import default_config_path

        if paths[0].lower().endswith(".toml"):
            raise click.UsageError(f"--default-plant or a CONFIG ({paths[0]}): not both")
        paths, label = (str(default_config_path()), *paths), "the default plant"
    elif len(paths) == 1 and is_test_project(paths[0]):
        from .cli_project import test_project

        sys.exit(test_project(paths[0], junit=junit, pattern=pattern, timeout_ns=timeout))
    sys.exit(
        run_tests(
            paths,
            junit=junit,
            pattern=pattern,
            timeout_ns=timeout,
            report_compile_errors=lambda e: _summary(*_report(e.diagnostics, e.sources)),
            config_label=label,
        )
    )


def is_test_project(path: str) -> bool:
    """Whether test's one argument is a project (a folder, a TwinCAT
    .sln/.tsproj/.plcproj) rather than a test file."""
    if Path(path).is_dir():
        return True
    if path.lower().endswith(".st"):
        return False  # the usual test file, told without loading the project readers
    from .project.discover import is_project_file

    return is_project_file(path)


# ---------------------------------------------------------------- entry point


cli.add_command(run_cmd)
cli.add_command(log_cmd)
cli.add_command(sweep_cmd)


def main(argv: list | None = None) -> None:
    """Console-script entry point: never lets a Python traceback reach the user."""
    global _console
    _console = True
    try:
        # standalone_mode=False: we map click's exceptions to our exit codes
        # ourselves (click would turn Ctrl-C into exit 1, our "compile error").
        rc = cli.main(args=argv, prog_name="softplc", standalone_mode=False)
    except click.ClickException as e:
        e.show()
        sys.exit(e.exit_code)  # UsageError and BadParameter: 2
    except (click.Abort, KeyboardInterrupt):
        _echo_err("softplc: interrupted")
        sys.exit(130)
    except PluginError as e:  # an installed bus or device package that cannot be used
        _echo_err(
            f"softplc: {e}\nThe package that declares it is broken or does not fit this softplc: "
            "upgrade it or uninstall it."
        )
        sys.exit(EXIT_USAGE)
    except BrokenPipeError:  # `softplc exec ... | head`: the reader left, nothing to say
        sys.stderr.close()
        sys.exit(EXIT_OK)
    except Exception as e:  # a bug in softplc, not in the user's program
        if os.environ.get("SOFTPLC_DEBUG"):
            traceback.print_exc()
        else:
            _echo_err(
                f"softplc: internal error: {type(e).__name__}: {e}\n"
                "This is a bug in softplc; run again with SOFTPLC_DEBUG=1 "
                "for the traceback and report it."
            )
        sys.exit(EXIT_INTERNAL)
    sys.exit(rc if isinstance(rc, int) else EXIT_OK)  # --help and --version return 0


if __name__ == "__main__":
    main()
