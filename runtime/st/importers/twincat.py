"""TwinCAT 3 source files read as Structured Text: ``.TcPOU`` (a POU with
its methods, properties and actions), ``.TcDUT`` (a type), ``.TcGVL`` (a
global variable list), ``.TcIO`` (an interface), and ``.plcproj`` (the
project, which lists them).

TwinCAT keeps ST in CDATA: the declaration (``FUNCTION_BLOCK FB_X ...
END_VAR``) and the implementation of each part. Both go into the view at
their own lines and columns (view.LineView), with the ``END_*`` keywords
TwinCAT leaves out placed at the end of the part they close, so positions
are those of the TwinCAT file. Methods and properties follow their block
as TwinCAT's own text export writes them (the grammar attaches a METHOD
after END_FUNCTION_BLOCK to that block); actions go into a second view as
``ACTION Pou.Name:`` blocks.
"""

from __future__ import annotations

import os
import re
from pathlib import PureWindowsPath

from ..ast import Pos
from ..diagnostics import DiagnosticBag
from .view import LineView
from .xmlsafe import PosElement, TextPositions, parse_xml

SOURCE_SUFFIXES = (".tcpou", ".tcdut", ".tcgvl", ".tcio", ".st")
# The POU kind a declaration opens, after its pragmas and comments.
# What may come before a declaration's keyword: blanks, pragmas, comments,
# as one atomic group: a repeated group that could give back would try every
# way of splitting a run of blanks or of '//' before failing (for ever on a
# declaration of blanks).
_LEAD = r"(?>(?:\s|\{[^}]*\}|\(\*.*?\*\)|/\*.*?\*/|//[^\n]*)*)"
_KIND = re.compile(_LEAD + r"(FUNCTION_BLOCK|FUNCTION|PROGRAM)\b", re.S | re.I | re.A)


# A declaration's header, after its pragmas and comments, up to the end of
# its line: "METHOD PUBLIC Close : RTS_IEC_RESULT;" (TwinCAT takes the ';').
_HEADER = re.compile(
    r"(" + _LEAD + r"(?:FUNCTION_BLOCK|FUNCTION|PROGRAM|METHOD|PROPERTY|INTERFACE)\b[^\n;]*?)"
    r";([ \t]*(?://[^\n]*|\(\*.*?\*\))?[ \t]*)$",
    re.S | re.I | re.A | re.M,
)


def _without_header_semicolon(text: str) -> str:
    """A declaration whose header line ends with ';' (which TwinCAT takes and
    IEC 61131-3 does not) with a blank in its place: the columns stay."""
    m = _HEADER.match(text)
    return text if m is None else text[: m.end(1)] + " " + text[m.end(1) + 1 :]


def twincat_views(text: str, path: str, diags: DiagnosticBag) -> list[LineView]:
    """The ST views of a .TcPOU, .TcDUT, .TcGVL or .TcIO file."""
    root = parse_xml(text, path, diags)
    if root is None:
        return []
    lines = text.count("\n") + 1
    main, actions = LineView(lines), LineView(lines)
    r = _Reader(text, path, diags)
    for obj in root.kids():
        if obj.name == "POU":
            r.pou(obj, main, actions)
        elif obj.name in ("DUT", "GVL"):
            r.declaration(obj, main)
        elif obj.name == "Itf":
            r.interface(obj, main)
        else:
            diags.warning(
                "W180",
                f"<{obj.name}> in a TwinCAT file is not read",
                Pos(path, obj.line, obj.col),
                "softplc reads POU, DUT, GVL and Itf objects",
            )
    return [v for v in (main, actions) if v.used]


def plcproj_files(text: str, path: str, diags: DiagnosticBag) -> list[str]:
    """The source files a TwinCAT .plcproj compiles, in its order: each
    <Compile Include="POUs\\MAIN.TcPOU"/>, relative to the project's folder."""
    root = parse_xml(text, path, diags)
    if root is None:
        return []
    base = os.path.dirname(path)
    out = []
    for item in root.walk("Compile"):
        inc = item.get("Include", "")
        if inc.lower().endswith(SOURCE_SUFFIXES):
            out.append(os.path.join(base, *PureWindowsPath(inc).parts))
    return out


class _Reader:
    def __init__(self, text: str, path: str, diags: DiagnosticBag) -> None:
        self.texts = TextPositions(text)
        self.path = path
        self.diags = diags

    def _cdata(self, el: PosElement | None, view: LineView) -> str:
        """Put el's text (a CDATA block) into the view where it is; returns it."""
        if el is None:
            return ""
        text = "".join(el.itertext())
        if el.name == "Declaration":
            text = _without_header_semicolon(text)
        if text.strip():
            view.put(*self.texts.start(el), text)
        return text

    def _implementation(self, obj: PosElement, view: LineView) -> bool:
        """The ST of obj's <Implementation>; False if it is in another language."""
        impl = obj.kid("Implementation")
        if impl is None:
            return True
        langs = impl.kids()
        if langs and langs[0].name != "ST":
            self.diags.error(
                "E182",
                f"{obj.name} {obj.get('Name', '?')} is written in {langs[0].name}: only ST is imported",
                Pos(self.path, impl.line, impl.col),
                "rewrite it in ST; the rest of the file is imported",
            )
            return False
        self._cdata(langs[0] if langs else None, view)
        return True

    def _end(self, obj: PosElement, view: LineView, keyword: str) -> None:
        view.put(obj.end_line, 1, keyword)

    def pou(self, pou: PosElement, main: LineView, actions: LineView) -> None:
        decl = pou.kid("Declaration")
        text = self._cdata(decl, main)
        m = _KIND.match(text)
        if m is None:
            where = decl if decl is not None else pou
            self.diags.error(
                "E183",
                f"POU {pou.get('Name', '?')}: its declaration opens no PROGRAM, FUNCTION or FUNCTION_BLOCK",
                Pos(self.path, where.line, where.col),
                None,
            )
            return
        kind = m.group(1).upper()
        self._implementation(pou, main)
        impl = pou.kid("Implementation")
        self._end(impl if impl is not None else (decl or pou), main, f"END_{kind}")
        for part in pou.kids():
            if part.name == "Method":
                self.method(part, main)
            elif part.name == "Property":
                self.property(part, main)
            elif part.name == "Action":
                name = pou.get("Name", "")
                if not name.replace("_", "a").isalnum():
                    continue  # the POU's declaration names it; the action cannot be placed
                actions.put(part.line, part.col, f"ACTION {name}.{part.get('Name', '')}:")
                self._implementation(part, actions)
                self._end(part, actions, "END_ACTION")

    def method(self, m: PosElement, view: LineView, body: bool = True) -> None:
        self._cdata(m.kid("Declaration"), view)
        if body:
            self._implementation(m, view)
        self._end(m, view, "END_METHOD")

    def property(self, p: PosElement, view: LineView, body: bool = True) -> None:
        self._cdata(p.kid("Declaration"), view)
        for acc in p.kids():
            if acc.name in ("Get", "Set"):
                view.put(acc.line, acc.col, acc.name.upper())
                self._cdata(acc.kid("Declaration"), view)
                if body:
                    self._implementation(acc, view)
                self._end(acc, view, f"END_{acc.name.upper()}")
        self._end(p, view, "END_PROPERTY")

    def declaration(self, obj: PosElement, view: LineView) -> None:
        """A DUT or GVL: its declaration is complete ST."""
        self._cdata(obj.kid("Declaration"), view)

    def interface(self, itf: PosElement, view: LineView) -> None:
        self._cdata(itf.kid("Declaration"), view)
        for part in itf.kids():
            if part.name == "Method":
                self.method(part, view, body=False)
            elif part.name == "Property":
                self.property(part, view, body=False)
        self._end(itf, view, "END_INTERFACE")
