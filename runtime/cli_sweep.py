"""`softplc sweep CONFIG --matrix sweep.toml`: the scenarios of a sweep
file (runtime/sweep/matrix.py), each a deterministic virtual-time run of
CONFIG, on every core, or on a Dask cluster with --scheduler; one table of
the results and, with --plot, a figure.

Exit codes: 0 every scenario passed, 3 one or more failed (the table says
which and why), 1 CONFIG's programs do not compile, 2 a bad sweep file,
configuration or option."""

from __future__ import annotations

import sys
from pathlib import Path

import click


@click.command("sweep")
@click.argument("config", type=click.Path(dir_okay=False))
@click.option(
    "--matrix",
    "matrix_file",
    required=True,
    type=click.Path(dir_okay=False),
    metavar="SWEEP.toml",
    help="The scenarios ([matrix], [[scenario]] or [random]) and what each gives ([result]).",
)
@click.option(
    "-o",
    "--out",
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="The results table: .csv, or .parquet (pyarrow) [default: SWEEP.csv beside the sweep file].",
)
@click.option(
    "--plot", type=click.Path(dir_okay=False), metavar="FILE", help="Draw [result] plot into FILE (.png, .svg, .pdf)."
)
@click.option(
    "-j", "--workers", type=click.IntRange(min=1), metavar="N", help="Worker processes [default: one per core]."
)
@click.option(
    "--scheduler",
    metavar="ADDRESS",
    help="Run on a Dask distributed cluster (tcp://host:8786): its workers need softplc and CONFIG's files.",
)
def sweep_cmd(
    config: str, matrix_file: str, out: str | None, plot: str | None, workers: int | None, scheduler: str | None
) -> None:
    """Run every scenario of SWEEP.toml against CONFIG (a TOML file) in
    virtual time and write one row per scenario: its parameters, passed or
    not (a runtime fault, an expectation false), the values asked for and
    what the simulated devices recorded."""
    from .config.errors import ConfigError
    from .st.diagnostics import CompileError
    from .sweep import execute
    from .sweep.matrix import SweepError, load_sweep
    from .sweep.scenario import jobs as make_jobs
    from .sweep.table import TABLE_SUFFIXES, plot_results, write_table
    from .trace.plot import FORMATS, PlotUnavailable, require

    table = Path(out) if out else Path(matrix_file).with_suffix(".csv")
    if table.suffix.lower() not in TABLE_SUFFIXES:
        raise click.UsageError(f"-o {table}: the ending says the table's form: {', '.join(TABLE_SUFFIXES)}")
    if plot and Path(plot).suffix.lower() not in FORMATS:
        raise click.UsageError(f"--plot {plot}: the ending says the format: {', '.join(FORMATS)}")
    if workers and scheduler:
        raise click.UsageError("--workers and --scheduler: the cluster's workers are the scheduler's")
    try:
        if plot:
            require()
        sweep = load_sweep(matrix_file)
        if plot and not sweep.plot:
            raise click.UsageError(f"--plot {plot}: {matrix_file} has no [result] plot = {{ x = ..., y = ... }}")
        if not Path(config).is_file():
            raise click.UsageError(f"{config}: no such file")
        jobs = make_jobs(sweep, config)
        _compile_once(jobs[0])
    except (SweepError, ConfigError, PlotUnavailable) as e:
        click.echo(f"softplc: {e}", err=True)
        sys.exit(2)
    except CompileError as e:
        click.echo(f"softplc: {config}: the programs do not compile:\n{e}", err=True)
        sys.exit(1)
    where = f"on {scheduler}" if scheduler else f"on {workers or execute.default_workers()} worker(s)"
    click.echo(
        f"softplc: {len(jobs)} scenario(s) of {matrix_file}, {sweep.duration_ns / 1e9:g} s each, {where}", err=True
    )
    try:
        rows = execute.run(jobs, workers=workers, scheduler=scheduler, progress=_progress())
    except execute.SweepUnavailable as e:
        click.echo(f"softplc: {e}", err=True)
        sys.exit(2)
    try:
        write_table(rows, sweep, table)
        if plot:
            plot_results(rows, sweep, plot)
    except (OSError, RuntimeError) as e:
        click.echo(f"softplc: cannot write the results: {e}", err=True)
        sys.exit(2)
    failed = [r for r in rows if not r["passed"]]
    click.echo(f"softplc: {len(rows) - len(failed)} passed, {len(failed)} failed; wrote {table}", err=True)
    for row in failed[:10]:
        click.echo(f"  scenario {row['scenario']}: {row['failed']}", err=True)
    sys.exit(3 if failed else 0)


def _compile_once(job) -> None:
    """The first scenario built and stopped: a compile error (the same for
    all) or a bad device table is said once, before any worker starts."""
    from .sweep.scenario import build

    plc, _recorder = build(job)
    plc.stop()


def _progress():
    step = {"next": 0.1}

    def show(done: int, total: int) -> None:
        if done / total >= step["next"] or done == total:
            click.echo(f"softplc: {done}/{total} scenario(s) done", err=True)
            step["next"] = done / total + 0.1

    return show
