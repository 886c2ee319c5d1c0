"""The bodies of an imported POU, action, method or transition, each
language to ST in a view.

    out = BodyOut(view, texts, path, diags)
    if translate(lang_element, out):        # <ST>, <IL>, <FBD>, <LD>, <SFC>
        ...  out.decls: the hidden variables the body needs (VAR of its POU)

A language is a function ``(element, out) -> None`` in ``LANGUAGES``,
keyed by the element's name in a PLCopen ``<body>`` (TC6 0201: ST, IL,
FBD, LD, SFC). It writes ST with ``out.put(line, column, text)`` at the
line and column of the XML it comes from, so diagnostics and runtime
faults point into the XML file (view.LineView), and declares a variable
it needs beyond the POU's own (an edge's memory, an intermediate value)
with ``out.declare("name : TYPE;")``: the caller puts those in a VAR block
of the POU (of the method, for a method's body). ST that it writes from
another language it marks with ``out.lowered(first, last)``: a JMP there
is the language's own, allowed in every profile.

A problem is ``ImportProblem(message, element, hint)``: an E183 at the
element, and the body is left out.
"""

from __future__ import annotations

from collections.abc import Callable

from ..ast import Pos
from ..diagnostics import DiagnosticBag
from .view import LineView
from .xmlsafe import PosElement, TextPositions


class ImportProblem(Exception):
    """An element that cannot become ST; args: message, element, hint."""


class BodyOut:
    """Where a body's ST goes, and what the body needs beside it."""

    def __init__(
        self,
        view: LineView,
        texts: TextPositions,
        path: str,
        diags: DiagnosticBag,
        pou: str = "",
        owner: PosElement | None = None,
    ) -> None:
        self.view = view
        self.texts = texts
        self.path = path
        self.diags = diags
        self.pou = pou  # the POU the body belongs to (for messages)
        self.owner = owner  # the element whose <body> it is (<pou>: an SFC reads its <transitions>)
        self.decls: list[str] = []  # hidden variables: "name : TYPE;" each

    def put(self, line: int, col: int, text: str, origin: tuple | None = None, sep: str = " ") -> None:
        """text at (line, col); origin: the (line, column) it comes from when
        that is elsewhere; sep: what separates it from the line's text
        before it (view.LineView.put)."""
        self.view.put(line, col, text, origin=origin, sep=sep)

    def declare(self, decl: str) -> None:
        """A variable of the POU the body needs ("name : TYPE;" or with an
        initial value), declared once."""
        if decl not in self.decls:
            self.decls.append(decl)

    def lowered(self, first: int, last: int) -> None:
        self.view.mark_lowered(first, last)

    def error(self, code: str, message: str, el: PosElement | None, hint: str | None = None) -> None:
        line, col = (el.line, el.col) if el is not None else (1, 1)
        self.diags.error(code, message, Pos(self.path, line, col), hint)

    def warning(self, code: str, message: str, el: PosElement | None, hint: str | None = None) -> None:
        line, col = (el.line, el.col) if el is not None else (1, 1)
        self.diags.warning(code, message, Pos(self.path, line, col), hint)


def st_body(lang: PosElement, out: BodyOut) -> None:
    """<ST><xhtml:p>text</xhtml:p></ST> (or the text in <ST> itself): put
    where it stands."""
    holder = lang.kids()[0] if lang.kids() else lang
    text = "".join(holder.itertext())
    line, col = out.texts.start(holder)
    out.put(line, col, text, origin=(line, col))  # (its first line's tokens there, whatever shares the line)


def il_body(lang: PosElement, out: BodyOut) -> None:
    """<IL><xhtml:p>text</xhtml:p></IL>: put where it stands, like ST; the
    parser lowers it to ST (st/syntax/il.py): it follows the POU's VAR blocks, or
    the ACTION header, in the view."""
    st_body(lang, out)


LANGUAGES: dict[str, Callable[[PosElement, BodyOut], None]] = {"ST": st_body, "IL": il_body}
_graphical = False  # whether fbd.py, ld.py and sfc.py, which add FBD, LD and SFC, are loaded


def _languages() -> dict[str, Callable[[PosElement, BodyOut], None]]:
    """LANGUAGES, the graphical ones loaded on first need (they are not
    imported with a program of plain ST)."""
    global _graphical
    if not _graphical:
        from . import fbd, ld, sfc  # noqa: F401  (each adds its language to LANGUAGES)

        _graphical = True
    return LANGUAGES


def body_language(body: PosElement | None) -> PosElement | None:
    """The language element of a <body> (its first child but documentation
    and addData), or None."""
    if body is None:
        return None
    langs = [k for k in body.kids() if k.name not in ("documentation", "addData")]
    return langs[0] if langs else None


def supported(lang: PosElement | None) -> bool:
    return lang is not None and lang.name in _languages()


def translate(lang: PosElement, out: BodyOut) -> None:
    """The body in lang's language as ST into out (supported(lang) first)."""
    _languages()[lang.name](lang, out)
