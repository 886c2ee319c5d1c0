"""`softplc log FILE [CONFIG]`: a bus log `softplc run --bus-log` wrote,
printed decoded in the configuration's words (its nodes, their objects
by the names of their EDS, its connections). The bus that wrote the file
reads it (Bus.read_log, through the registry): this module names none."""

from __future__ import annotations

import sys
from pathlib import Path

import click


@click.command("log")
@click.argument("file", type=click.Path(dir_okay=False))
@click.argument("config", required=False, type=click.Path(dir_okay=False))
def log_cmd(file: str, config: str | None) -> None:
    """Print the bus log FILE (of `softplc run --bus-log`) decoded, with the
    words of CONFIG (the TOML file of the run; without it the embedded
    default example). Exit code 2: a file no bus reads, or a bad CONFIG."""
    from .config import ConfigError, default_config_path, load_config
    from .plugin.registry import registry

    path = Path(file)
    if not path.is_file():
        raise click.BadParameter(f"{file}: no such file", param_hint="FILE")
    try:
        cfg = load_config(config if config is not None else default_config_path())
    except ConfigError as exc:
        click.echo(f"softplc: {exc}", err=True)
        sys.exit(2)
    for bus in registry().buses:
        if bus.read_log is None:
            continue
        lines = bus.read_log(path, cfg)
        if lines is None:
            continue
        try:
            for line in lines:
                click.echo(line)
        except ValueError as exc:  # a line the bus cannot read: named, not a traceback
            click.echo(f"softplc: {file}: {exc}", err=True)
            sys.exit(2)
        return
    click.echo(f"softplc: {file}: no bus reads such a log (the endings `softplc run --bus-log` writes)", err=True)
    sys.exit(2)
