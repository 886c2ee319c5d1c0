"""What pragmas mean: MatIEC's embedded C ``{{ ... }}`` and the CODESYS and
TwinCAT ``{attribute '...'}`` pragmas.

lexer.py blanks every pragma out of the text and parser.py attaches each
to the item that follows it (``pragmas`` of a POU, VAR block, declaration,
type or statement); nothing in a pragma is ever ST, so none can be a
syntax error. This module says what softplc makes of them:

* ``{{ C code }}`` (MatIEC, so OpenPLC and Beremiz: C pasted into the
  generated C) is ignored with W102 in every profile: softplc compiles to
  Python and runs no C, so the program does less than it does there, and
  the warning says so. ``matiec`` warns too: that is where it matters.
* ``{attribute 'name'}`` and ``{attribute 'name' := 'value'}`` (CODESYS,
  TwinCAT): ``qualified_only`` before a VAR_GLOBAL list and ``hide``
  before a declaration are honoured (namespaces.py), so are
  ``qualified_only`` and ``strict`` before an enumeration's TYPE
  (types.EnumType, read by checker_exprs.py, checker_operators.py and
  conversions.py); ``call_after_init``
  (a method called after FB_init) and ``monitoring := 'call'`` (a property
  read by calling it) are ignored with W103; ``monitoring := 'variable'``
  is what softplc does anyway. Every other attribute, and every other
  pragma (``{warning ...}``, ``{region ...}``, ``{info ...}``), is ignored
  silently: CODESYS has dozens (pack_mode, noinit, TcLinkTo ...) that
  change nothing a program computes here, and softplc's own test runner
  reads ``test`` and ``timeout`` (runtime/testing/discover.py).
"""

from __future__ import annotations

import re
from typing import Any

from .. import ast
from ..diagnostics import DiagnosticBag

EMBEDDED_C_SHOWN = 40  # characters of the C code quoted in W102
_ATTRIBUTE = re.compile(r"attribute\s+'([^']*)'(?:\s*:=\s*'([^']*)')?\s*\Z", re.IGNORECASE)
# Attributes accepted with W103: what softplc does instead.
IGNORED_ATTRIBUTES = {
    "call_after_init": "no method runs after FB_init here; call it from the block's code",
    ("monitoring", "call"): "a watched property shows its variable, not the result of a call",
}


def attribute(pragma: str) -> tuple | None:
    """(name lower-cased, value or None) of an ``attribute 'name' [:= 'value']``
    pragma text, else None."""
    m = _ATTRIBUTE.match(pragma.strip())
    return (m.group(1).strip().lower(), m.group(2)) if m else None


def has_attribute(node: Any, name: str) -> bool:
    """Whether one of node's pragmas is ``{attribute 'name' ...}``."""
    return any((a := attribute(str(p))) is not None and a[0] == name for p in getattr(node, "pragmas", ()))


def attribute_value(node: Any, name: str) -> str | None:
    """The value of node's ``{attribute 'name' := 'value'}`` pragma (the
    first one), else None."""
    for p in getattr(node, "pragmas", ()):
        a = attribute(str(p))
        if a is not None and a[0] == name:
            return a[1]
    return None


def is_embedded_c(text: str) -> bool:
    """The text of a ``{{ ... }}`` pragma as the lexer keeps it ('{ ... }')."""
    return text.startswith("{")


def warn_ignored(pragmas: list, path: str, diags: DiagnosticBag) -> None:
    """W102 for each MatIEC ``{{ ... }}`` of a file, W103 for each attribute
    accepted but not honoured (pragmas: lexer.Pragma)."""
    for p in pragmas:
        pos = ast.Pos(path, p.line, p.col, p.end_line, p.end_col)
        if not is_embedded_c(p.text):
            a = attribute(p.text)
            why = None
            if a is not None:
                why = IGNORED_ATTRIBUTES.get(a[0]) or IGNORED_ATTRIBUTES.get((a[0], (a[1] or "").lower()))
            if why is not None:
                diags.warning("W103", f"{{{p.text}}} is ignored", pos, why)
            continue
        code = " ".join(p.text[1:-1].split())
        if len(code) > EMBEDDED_C_SHOWN:
            code = code[: EMBEDDED_C_SHOWN - 3] + "..."
        diags.warning(
            "W102",
            f"embedded C code {{{{ {code} }}}} is ignored: softplc runs no C",
            pos,
            "write it in ST (MatIEC, OpenPLC and Beremiz run it; here the program goes on without it)",
        )
