"""`softplc run`: its options, checked before anything starts, handed to
launch.run_plc (imported when the command runs, so the other commands do
not load the engine)."""

from __future__ import annotations

import re
import sys
from pathlib import Path

import click

from .cli_project import PARTIAL_OPTION, PROFILE_OPTION, compile_project, one_project
from .cli_report import echo_err, report, summary
from .durations import EXAMPLES, parse_duration_ns

#: --watch's commas, but those of an index ('grid[1, 3]')
_OUTSIDE_BRACKETS = re.compile(r",(?![^\[]*\])")


class Duration(click.ParamType):
    """A positive duration of engine time: 30s, 1m30s, 500ms, T#2s."""

    name = "duration"

    def convert(self, value, param, ctx) -> int:
        if isinstance(value, int):
            return value
        ns = parse_duration_ns(value)
        if ns is None or ns <= 0:
            self.fail(f"{value!r} is not a positive duration (examples: {EXAMPLES})", param, ctx)
        return ns


@click.command("run")
@click.argument("config", required=False, type=click.Path(), metavar="[CONFIG|PROJECT]")
@click.option(
    "--virtual-time", is_flag=True, help="Run on the virtual clock: jump from deadline to deadline (no waiting)."
)
@click.option(
    "--duration", type=Duration(), metavar="DURATION", help="Stop after this much engine time (30s, 1m, T#500ms)."
)
@click.option("--cycles", type=click.IntRange(min=1), metavar="N", help="Stop after N scans.")
@click.option(
    "--watch",
    "watch",
    multiple=True,
    metavar="VAR",
    help="Show VAR in the status line and the trace: Instance.var, a global, an element or a "
    "field (Line.parts[2].weight, grid[1, 2]), or an address such as %QW1. Repeat the option "
    "or separate names with commas.",
)
@click.option(
    "--set",
    "sets",
    multiple=True,
    metavar="VAR=VALUE",
    help="Write VALUE into VAR at the first scan, as an [init] entry (over it): Main.Setpoint=40, "
    "Motor.Auto=false, Main.t=T#2s. Repeat for several.",
)
@click.option(
    "--trace",
    "traces",
    multiple=True,
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Write the watched values over engine time; the ending says how: .csv (a row per scan), "
    ".vcd (GTKWave), .png/.svg/.pdf (a plot at the end); with what the simulated devices recorded "
    "(breaker closes, EMCYs) as events. Repeat for several.",
)
@click.option(
    "--bus-log",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Record what the PLC sends and receives on every bus, in engine time: in FILE, whose ending "
    'chooses the format, or beside it (docs/guide/simulation.md "Bus log" says which bus writes where).',
)
@click.option(
    "--unit",
    "units",
    multiple=True,
    metavar="VAR=UNIT",
    help="Label a watched number's plot axis with UNIT; numbers with the same unit share an axis.",
)
@click.option(
    "--final-json",
    type=click.Path(dir_okay=False, allow_dash=True),
    metavar="FILE",
    help="At the end, write every program's variables as JSON (as `exec` prints them; - for stdout).",
)
@click.option(
    "--cold", "start_mode", flag_value="cold", help="Cold start: every variable initialised, the retain file ignored."
)
@click.option(
    "--warm",
    "start_mode",
    flag_value="warm",
    help='Warm start: RETAIN and PERSISTENT variables restored (the default unless the config says start = "cold").',
)
@click.option(
    "--online-change/--no-online-change",
    default=None,
    help="Watch the ST files and swap a changed program in between two scans, keeping the values "
    "(SIGHUP: now) [default: on in real time, off with --virtual-time].",
)
@click.option(
    "--web",
    metavar="[HOST:]PORT",
    callback=lambda ctx, param, value: _listen(value),
    help="Serve the web monitor on PORT (0: any free one; 127.0.0.1 unless HOST says otherwise), "
    'with the [web] section\'s settings or, without one, its defaults (docs/guide/surfaces.md "Web monitor").',
)
@click.option(
    "--log-file",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Write the log (wall time, engine time, level, message) to FILE too, as a service does.",
)
@click.option(
    "--log-max-bytes",
    type=click.IntRange(min=0),
    default=10_000_000,
    show_default=True,
    metavar="N",
    help="Rotate the log file when it reaches N bytes: FILE becomes FILE.1 (0: never).",
)
@click.option(
    "--log-backups",
    type=click.IntRange(min=0),
    default=5,
    show_default=True,
    metavar="N",
    help="Keep N rotated log files (FILE.1 .. FILE.N), the oldest dropped.",
)
@PROFILE_OPTION
@PARTIAL_OPTION
def run_cmd(
    config: str | None,
    virtual_time: bool,
    duration: int | None,
    cycles: int | None,
    watch: tuple,
    sets: tuple,
    traces: tuple,
    bus_log: str | None,
    units: tuple,
    final_json: str | None,
    start_mode: str | None,
    online_change: bool | None,
    web: str | None,
    log_file: str | None,
    log_max_bytes: int,
    log_backups: int,
    profile: str | None,
    partial: bool,
) -> None:
    """Run the PLC: the tasks of CONFIG (a TOML file; without it the embedded
    default example) until Ctrl-C, SIGTERM, --duration or --cycles. A
    PROJECT instead (a TwinCAT .sln/.plcproj, a CODESYS export, a Beremiz
    folder, a folder) runs its programs with its own tasks (.TcTTO, its
    CONFIGURATION, else every PROGRAM every 10 ms), without buses.

    SIGUSR1 (or typing `restart` on a terminal) restarts tasks stopped by a
    runtime fault; SIGHUP compiles the ST files and swaps them in (online
    change: docs/guide/running.md "Online change"). Exit codes: 0 stopped cleanly, 1 compile errors, 2 bad
    configuration or option, 3 a runtime fault happened during the run (or the retained data
    could not be saved at the stop).
    """
    from .launch import run_plc

    if duration is not None and cycles is not None:
        raise click.UsageError("give --duration or --cycles, not both")
    prepared = None
    if config is not None and is_project(config):
        prepared = _project(config, profile, partial)
    elif profile is not None or partial:
        raise click.UsageError("--profile and --partial are for a project; a configuration's [plc] decides")
    paths = [p.strip() for item in watch for p in _OUTSIDE_BRACKETS.split(item) if p.strip()]
    sys.exit(
        run_plc(
            config,
            virtual_time=virtual_time,
            duration_ns=duration,
            cycles=cycles,
            watch=paths,
            sets=list(sets),
            traces=list(traces),
            units=list(units),
            final_json=final_json,
            start_mode=start_mode,
            report_compile_errors=lambda e: summary(*report(e.diagnostics, e.sources)),
            online_change=online_change,
            web=web,
            log_file=log_file,
            log_max_bytes=log_max_bytes,
            log_backups=log_backups,
            prepared=prepared,
            bus_log=bus_log,
        )
    )


def is_project(path: str) -> bool:
    """Whether run's argument is a project rather than a TOML configuration."""
    from .project.discover import is_project_file
    from .st.importers import is_source

    p = Path(path)
    return p.is_dir() or is_project_file(path) or (p.suffix.lower() != ".toml" and is_source(p.name))


def _project(path: str, profile: str | None, partial: bool) -> tuple:
    """(PlcConfig, Program) of a project, or exit: 1 for compile errors, 2
    when its tasks cannot run."""
    from .project.running import ProjectRunError, project_config

    if not Path(path).exists():
        raise click.BadParameter(f"{path} does not exist", param_hint="PROJECT")
    project = one_project([path], "run")
    program, analysis = compile_project(project, profile, partial)
    try:
        return project_config(analysis, program), program
    except ProjectRunError as e:
        echo_err(f"softplc: {e}")
        sys.exit(2)


def _listen(value: str | None) -> str | None:
    """--web's value, checked before anything starts."""
    from .config.servers import parse_listen

    if value is not None:
        try:
            parse_listen(value)
        except ValueError as e:
            raise click.BadParameter(str(e), param_hint="--web") from None
    return value
