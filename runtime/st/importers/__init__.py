"""Source files other than plain ST, read as ST (issue 18): a PLCopen XML
export (plcopen.py), TwinCAT 3 files and projects (twincat.py), a CODESYS
2.3 export (codesys23.py: a .EXP, or a .TXT holding its markers).
``st_views`` gives the texts to parse for a file; the diagnostics'
positions are those of the original file (view.py). ``source_files``
replaces a project file (.plcproj) by the sources it lists."""

from __future__ import annotations

from importlib import import_module

from ..diagnostics import DiagnosticBag
from .view import StView

__all__ = ["StView", "is_imported", "is_source", "source_files", "st_export", "st_plain_lines", "st_views"]

# Each importer as (module, function), imported when a file of its kind is
# read: a program of plain ST (softplc test, the plc fixture) does not load
# them, nor the graphical languages (bodies.py loads those on first need).
_READERS = {
    ".xml": ("plcopen", "plcopen_views"),
    ".tcpou": ("twincat", "twincat_views"),
    ".tcdut": ("twincat", "twincat_views"),
    ".tcgvl": ("twincat", "twincat_views"),
    ".tcio": ("twincat", "twincat_views"),
    ".exp": ("codesys23", "codesys23_views"),
}
# Suffixes read by an importer only when the text is of its kind: (module, test, reader).
_SNIFFED = {".txt": ("codesys23", "is_codesys23", "codesys23_views")}
_PROJECTS = {".plcproj": ("twincat", "plcproj_files")}


def _function(module: str, name: str):
    return getattr(import_module(f"{__name__}.{module}"), name)


def source_files(paths: list, read, diags: DiagnosticBag) -> list:
    """paths with each project file replaced by the files it lists (read(path)
    gives a file's text, or None when it cannot be read: reported there)."""
    out = []
    for p in paths:
        lister = next((f for suffix, f in _PROJECTS.items() if str(p).lower().endswith(suffix)), None)
        if lister is None:
            out.append(p)
            continue
        text = read(p)
        if text is not None:
            out.extend(_function(*lister)(text, str(p), diags))
    return out


def is_imported(path: str) -> bool:
    """Whether path is read through an importer (by its suffix)."""
    return path.lower().endswith((*_READERS, *_PROJECTS))


def is_source(name: str) -> bool:
    """Whether a file of that name is a source softplc reads: ST, or a kind
    it imports (a project file included)."""
    return name.lower().endswith(".st") or is_imported(name)


def _reader(path: str, text: str):
    """The importer that reads path (by its suffix, or its text), or None
    for ST."""
    low = path.lower()
    for suffix, (module, reader) in _READERS.items():
        if low.endswith(suffix):
            return _function(module, reader)
    for suffix, (module, is_kind, reader) in _SNIFFED.items():
        if low.endswith(suffix) and _function(module, is_kind)(text):
            return _function(module, reader)
    return None


def st_views(path: str, text: str, diags: DiagnosticBag) -> list[StView]:
    """The ST texts of a source file: the text itself for ST, the views of
    an imported file (each parsed as a file of that name)."""
    reader = _reader(path, text)
    if reader is not None:
        return [v.view() for v in reader(text, path, diags)]
    return [StView(text)]


def st_plain_lines(path: str, text: str, diags: DiagnosticBag) -> list[list[tuple[int, str]]]:
    """Per view of a source file, (line of the file, plain ST) of each line
    that holds ST: what st_export writes, with the lines it comes from (a
    project's export writes a file's POUs one by one)."""
    reader = _reader(path, text)
    if reader is not None:
        return [v.plain_lines() for v in reader(text, path, diags)]
    return [[(n, line.rstrip()) for n, line in enumerate(text.splitlines(), 1)]]


def st_export(path: str, text: str, diags: DiagnosticBag) -> str:
    """An imported file as one plain ST text to read (softplc export-st),
    its IL bodies as the ST they are lowered to (st/syntax/il.py); an ST file as it
    is."""
    reader = _reader(path, text)
    if reader is not None:
        from ..syntax.il import lowered_for_reading
        from ..syntax.st_grammar import grammar

        views = reader(text, path, diags)
        for v in views:
            v.replace(lowered_for_reading(v.text(), grammar().lexer))
        return "\n".join(v.plain() for v in views)
    return text
