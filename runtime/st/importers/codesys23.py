"""CODESYS 2.3 text exports read as ST: a ``.EXP`` file (Project > Export,
one POU or a whole project) and the same text under another name (OSCAT
BASIC 3.33 ships as ``OSCAT_BASIC_333.TXT``, told by its content).

An export is ST already. Each object (a POU, a data type, a global variable
list) follows a few marker comments, ``(* @NESTEDCOMMENTS := 'Yes' *)``,
``(* @PATH := '\\/Folder' *)`` ...; a POU's declaration and body are split
by ``(* @END_DECLARATION := '0' *)``, a list ends with ``(* @OBJECT_END :=
'name' *)``. Markers are comments, so every object stays at its own lines
and columns: diagnostics point into the export. What is not ST, or ST as
CODESYS 2.3 alone took it:

- a ``LIBRARY`` ... ``END_LIBRARY`` section (the libraries the project
  uses, ``Standard.lib 4.10.05 11:14:46``, and their POU counts) is left
  out: what the program calls from a library softplc lacks is E043 there;
- ``FUNCTIONBLOCK`` opening a POU is read as ``FUNCTION_BLOCK``;
- an array's initial values without brackets (``SX : ARRAY[1..7] OF BYTE
  := 1,3,7,15;``) are read in brackets, as IEC 61131-3 and CODESYS V3 write
  them.

The two rewrites keep the positions of the tokens after them (the view's
origins). An IL body stays as it is (the parser reads IL where ST fails);
graphical bodies of a 2.3 export (``_FBD_BODY``, ``_LD_BODY``, ``_SFC``)
are not read: E182 names the POU, and the rest is imported.
"""

from __future__ import annotations

import re

from ..ast import Pos
from ..diagnostics import DiagnosticBag
from ..syntax.lexer import strip_comments
from .view import LineView

# Markers that only a CODESYS 2.3 export writes (a .TXT is read as one when
# its text holds them).
_MARKER = re.compile(r"^\(\* @(?:NESTEDCOMMENTS|END_DECLARATION|PATH|OBJECTFLAGS) := ", re.M)
_LIBRARY = re.compile(r"^LIBRARY[ \t]*\r?$", re.M)
_END_LIBRARY = re.compile(r"^END_LIBRARY\b", re.M)
_FUNCTIONBLOCK = re.compile(r"^([ \t]*)FUNCTIONBLOCK\b", re.M)
_GRAPHICAL = re.compile(r"^[ \t]*_(FBD_BODY|LD_BODY|SFC|CFC)\b", re.M)
_POU_START = re.compile(r"^[ \t]*(?:FUNCTION_BLOCK|FUNCTIONBLOCK|FUNCTION|PROGRAM)[ \t]+([A-Za-z_][A-Za-z0-9_]*)", re.M)
_POU_END = re.compile(r"^[ \t]*END_(?:FUNCTION_BLOCK|FUNCTION|PROGRAM)\b", re.M)
# name(s) : ARRAY[...] OF type := (the initial values follow)
_ARRAY_INIT = re.compile(
    r"\b[A-Za-z_]\w*(?:\s*,\s*[A-Za-z_]\w*)*\s*:\s*ARRAY\s*\[[^\]]*\](?:\s*OF\s+ARRAY\s*\[[^\]]*\])*\s*OF\s+[^;:=]+?:=",
    re.I,
)
_VALUE_TOKEN = re.compile(r"'(?:\$.|[^'$\n])*'|\"(?:\$.|[^\"$\n])*\"|[\[\](),;]|[^\s\[\](),;'\"]+")


def is_codesys23(text: str) -> bool:
    """Whether a text (a .TXT) is a CODESYS 2.3 export: it has its markers."""
    return _MARKER.search(text, 0, 4096) is not None


def codesys23_views(text: str, path: str, diags: DiagnosticBag) -> list[LineView]:
    """The ST view of a CODESYS 2.3 export, on the export's own lines."""
    blank, _ = strip_comments(text, lambda *a: None, nested=True)  # for finding things outside comments
    starts = _line_starts(text)
    skipped = _library_lines(blank, starts) | _graphical_pous(blank, starts, path, diags)
    edits: dict[int, list[tuple[int, int, str]]] = {}  # line -> (col, length replaced, new text)
    for m in _FUNCTIONBLOCK.finditer(blank):
        line, col = _line_col(starts, m.start(1) + len(m.group(1)))
        edits.setdefault(line, []).append((col, len("FUNCTIONBLOCK"), "FUNCTION_BLOCK"))
    for first, last in _bare_array_values(blank):
        for at, new in ((first, "["), (last, "]")):
            line, col = _line_col(starts, at)
            edits.setdefault(line, []).append((col, 0, new))
    lines = text.split("\n")
    view = LineView(len(lines))
    for n, raw in enumerate(lines, 1):
        if n in skipped:
            continue
        _put_line(view, n, raw.rstrip("\r"), sorted(edits.get(n, ())))
    return [view]


def _put_line(view: LineView, n: int, text: str, edits: list) -> None:
    """text on line n with edits (col, replaced length, new text) made; what
    follows an edit keeps the column it has in the export (an origin). A
    blank where pieces meet stays one in plain() (export-st)."""
    done = 0  # characters of text written
    for col, length, new in edits:
        if col - 1 > done:
            _put(view, n, text, done, col - 1)
        view.put(n, col, new, sep=" " if col > 1 and text[col - 2].isspace() else "", origin=(n, col))
        done = col - 1 + length
    if done < len(text) or not edits:
        _put(view, n, text, done, len(text))


def _put(view: LineView, n: int, text: str, start: int, end: int) -> None:
    """text[start:end] on line n: where it stands, or (after an edit) from
    its column on (an origin)."""
    piece = text[start:end]
    if not start:
        view.put(n, 1, piece, sep="")
        return
    sep = " " if piece[:1].isspace() else ""
    view.put(n, start + 1, piece, sep=sep, origin=(n, start + 1))


def _line_starts(text: str) -> list[int]:
    return [0] + [i + 1 for i, ch in enumerate(text) if ch == "\n"]


def _line_col(starts: list[int], offset: int) -> tuple[int, int]:
    lo, hi = 0, len(starts) - 1
    while lo < hi:  # the last start at or before offset
        mid = (lo + hi + 1) // 2
        if starts[mid] <= offset:
            lo = mid
        else:
            hi = mid - 1
    return lo + 1, offset - starts[lo] + 1


def _library_lines(blank: str, starts: list[int]) -> set[int]:
    """The lines of the LIBRARY sections."""
    out: set[int] = set()
    for m in _LIBRARY.finditer(blank):
        end = _END_LIBRARY.search(blank, m.end())
        first = _line_col(starts, m.start())[0]
        last = _line_col(starts, end.start())[0] if end else len(starts)
        out.update(range(first, last + 1))
    return out


def _graphical_pous(blank: str, starts: list[int], path: str, diags: DiagnosticBag) -> set[int]:
    """The lines of the POUs with a graphical body, each reported (E182)."""
    out: set[int] = set()
    for m in _GRAPHICAL.finditer(blank):
        head = None
        for h in _POU_START.finditer(blank, 0, m.start()):
            head = h
        if head is None:
            continue
        end = _POU_END.search(blank, m.end())
        first = _line_col(starts, head.start())[0]
        last = _line_col(starts, end.end())[0] if end else len(starts)
        if first in out:
            continue
        out.update(range(first, last + 1))
        language = m.group(1).split("_")[0]
        diags.error(
            "E182",
            f"POU {head.group(1)} is written in {language}: only ST and IL bodies of a CODESYS 2.3 export are imported",
            Pos(path, *_line_col(starts, m.end() - len(m.group(1)) - 1)),
            "export it from CODESYS as ST, or leave it out",
        )
    return out


def _bare_array_values(blank: str) -> list[tuple[int, int]]:
    """(offset of the first value, offset after the last) of each array's
    initial values written without brackets and with more than one value."""
    out = []
    for m in _ARRAY_INIT.finditer(blank):
        depth, first, last, commas = 0, -1, -1, 0
        for t in _VALUE_TOKEN.finditer(blank, m.end()):
            tok = t.group()
            if first < 0:
                if tok == "[":
                    break  # written as IEC has it
                first = t.start()
            if tok in "([" and len(tok) == 1:
                depth += 1
            elif tok in ")]" and len(tok) == 1:
                depth -= 1
            elif tok == ";" and depth == 0:
                break
            elif tok == "," and depth == 0:
                commas += 1
            last = t.end()
        if first >= 0 and commas:
            out.append((first, last))
    return out
