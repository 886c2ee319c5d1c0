"""How the softplc command prints diagnostics: every one to stderr, then
the counts (`2 errors, 1 warning`)."""

from __future__ import annotations

import click


def echo_err(text: str) -> None:
    click.echo(text, err=True)


def report(diagnostics, sources) -> tuple[int, int]:
    """Print every diagnostic (errors and warnings) to stderr; return the counts."""
    errors = warnings = 0
    for d in diagnostics:
        echo_err(d.format(sources))
        if d.is_error:
            errors += 1
        else:
            warnings += 1
    return errors, warnings


def plural(n: int, word: str) -> str:
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


def summary(errors: int, warnings: int) -> None:
    echo_err(f"{plural(errors, 'error')}, {plural(warnings, 'warning')}")
