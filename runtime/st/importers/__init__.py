"""Source files other than plain ST, read as ST (issue 18): a PLCopen XML
export (plcopen.py). ``st_views`` gives the texts to parse for a file; the
diagnostics' positions are those of the original file (view.py)."""

from __future__ import annotations

from ..diagnostics import DiagnosticBag
from .plcopen import plcopen_views

__all__ = ["is_imported", "st_export", "st_views"]

_READERS = {".xml": plcopen_views}


def is_imported(path: str) -> bool:
    """Whether path is read through an importer (by its suffix)."""
    return path.lower().endswith(tuple(_READERS))


def st_views(path: str, text: str, diags: DiagnosticBag) -> list[str]:
    """The ST texts of a source file: the text itself for ST, the views of
    an imported file (each parsed as a file of that name)."""
    for suffix, reader in _READERS.items():
        if path.lower().endswith(suffix):
            return [v.text() for v in reader(text, path, diags)]
    return [text]


def st_export(path: str, text: str, diags: DiagnosticBag) -> str:
    """An imported file as one plain ST text to read (softplc export-st);
    an ST file as it is."""
    for suffix, reader in _READERS.items():
        if path.lower().endswith(suffix):
            return "\n".join(v.plain() for v in reader(text, path, diags))
    return text
