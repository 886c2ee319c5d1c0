"""`softplc log FILE [CONFIG]`: a bus log `softplc run --bus-log` wrote,
printed decoded in the configuration's words (its nodes, their objects
by the names of their EDS, its connections). The bus that wrote the file
reads it (Bus.read_log, through the registry): this module names none."""

from __future__ import annotations

import sys
from collections.abc import Iterator
from pathlib import Path

import click


@click.command("log")
@click.argument("file", type=click.Path(dir_okay=False))
@click.argument("config", required=False, type=click.Path(dir_okay=False))
def log_cmd(file: str, config: str | None) -> None:
    """Print the bus log FILE (of `softplc run --bus-log`) decoded, with the
    words of CONFIG (the TOML file of the run; without it the embedded
    default example). Exit code 2: a file no bus reads, or a bad CONFIG."""
    try:
        for line in decoded(file, config):
            click.echo(line)
    except ValueError as exc:  # a file or a line no bus reads: named, not a traceback
        click.echo(f"softplc: {exc}", err=True)
        sys.exit(2)


def decoded(file: str, config: str | None) -> Iterator[str]:
    """The lines of the bus log file decoded with config's words (None: the
    embedded default); ValueError naming file (or config) when no bus reads it."""
    from .config import ConfigError, default_config_path, load_config
    from .plugin.registry import registry

    path = Path(file)
    if not path.is_file():
        raise ValueError(f"{file}: no such file")
    try:
        cfg = load_config(config if config is not None else default_config_path())
    except ConfigError as exc:
        raise ValueError(str(exc)) from None
    for bus in registry().buses:
        lines = bus.read_log(path, cfg) if bus.read_log is not None else None
        if lines is not None:
            try:
                yield from lines
            except ValueError as exc:
                raise ValueError(f"{file}: {exc}") from None
            return
    raise ValueError(f"{file}: no bus reads such a log (the endings `softplc run --bus-log` writes)")


def marks(file: str, config: str | None, texts: list[str]) -> list[tuple[float, str]]:
    """(engine seconds, text) of every line of the decoded log that holds
    one of texts (the first it holds): what `softplc plot --mark` draws."""
    out = []
    for line in decoded(file, config):
        found = next((t for t in texts if t in line), None)
        if found is not None:
            out.append((float(line.split(maxsplit=1)[0]), found))
    return out
