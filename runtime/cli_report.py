"""How the softplc command prints diagnostics: every one to stderr, then
the counts (`2 errors, 1 warning`)."""

from __future__ import annotations

import click

from .st.diagnostics import SHOWN


def echo_err(text: str) -> None:
    click.echo(text, err=True)


def report(diagnostics, sources) -> tuple[int, int]:
    """Print the diagnostics (errors and warnings) to stderr, at most
    SHOWN a file as for a configuration's errors (50,000 duplicate CASE
    labels printed 7.9 MB), then how many more; return the counts."""
    errors = warnings = 0
    shown: dict = {}  # file -> diagnostics printed
    hidden: dict = {}  # file -> [errors, warnings] not printed
    for d in diagnostics:
        if d.is_error:
            errors += 1
        else:
            warnings += 1
        n = shown.get(d.pos.file, 0)
        if n < SHOWN:
            shown[d.pos.file] = n + 1
            echo_err(d.format(sources))
        else:
            hidden.setdefault(d.pos.file, [0, 0])[0 if d.is_error else 1] += 1
    for file, (e, w) in hidden.items():
        more = " and ".join(x for x in (e and plural(e, "more error"), w and plural(w, "more warning")) if x)
        echo_err(f"{file}: ... {more}")
    return errors, warnings


def plural(n: int, word: str) -> str:
    return f"{n} {word}" if n == 1 else f"{n} {word}s"


def summary(errors: int, warnings: int) -> None:
    echo_err(f"{plural(errors, 'error')}, {plural(warnings, 'warning')}")
