"""What an FBD/LD network needs to know of the project around it: which
blocks are user FUNCTIONs or FUNCTION_BLOCKs, their result and output types,
the variables the body sees and their types, and the type of a value on a
wire where one can be told (network.py keeps a function's value in a hidden
variable of that type when several inputs read it).

The PLCopen file is read once more for this (``Project.of(out)``, kept per
file): a body translator is given its own element only.
"""

from __future__ import annotations

import re
import weakref

from ..diagnostics import DiagnosticBag
from .bodies import BodyOut
from .xmlsafe import PosElement, TextPositions, parse_xml

_ELEMENTARY = {
    t.lower(): t
    for t in (
        "BOOL SINT INT DINT LINT USINT UINT UDINT ULINT REAL LREAL TIME LTIME DATE LDATE DT LDT TOD LTOD "
        "BYTE WORD DWORD LWORD CHAR WCHAR STRING WSTRING DATE_AND_TIME TIME_OF_DAY"
    ).split()
}
# the outputs of the standard function blocks (IEC 61131-3 ed.3 6.6.3)
_FB_OUTPUTS = {
    "TON": {"Q": "BOOL", "ET": "TIME"},
    "TOF": {"Q": "BOOL", "ET": "TIME"},
    "TP": {"Q": "BOOL", "ET": "TIME"},
    "LTON": {"Q": "BOOL", "ET": "LTIME"},
    "LTOF": {"Q": "BOOL", "ET": "LTIME"},
    "LTP": {"Q": "BOOL", "ET": "LTIME"},
    "CTU": {"Q": "BOOL", "CV": "INT"},
    "CTD": {"Q": "BOOL", "CV": "INT"},
    "CTUD": {"QU": "BOOL", "QD": "BOOL", "CV": "INT"},
    "R_TRIG": {"Q": "BOOL"},
    "F_TRIG": {"Q": "BOOL"},
    "SR": {"Q1": "BOOL"},
    "RS": {"Q1": "BOOL"},
}
STANDARD_FBS = frozenset(_FB_OUTPUTS)
_BOOLEAN = frozenset(("GT", "GE", "EQ", "LE", "LT", "NE"))
_SAME_AS_INPUT = {  # function -> the input whose type is the result's
    "ADD": None,
    "SUB": None,
    "MUL": None,
    "DIV": None,
    "MOD": None,
    "MAX": None,
    "MIN": None,
    "ABS": None,
    "MOVE": None,
    "NEG": None,
    "AND": None,
    "OR": None,
    "XOR": None,
    "NOT": None,
    "SHL": "IN",
    "SHR": "IN",
    "ROL": "IN",
    "ROR": "IN",
    "SQRT": None,
    "LIMIT": "IN",
    "SEL": "IN0",
    "MUX": "IN0",
}
_TYPED_LITERAL = re.compile(r"([A-Za-z_]+)#[A-Za-z0-9_.:+-]+")
_TIME_PREFIX = {"T": "TIME", "TIME": "TIME", "LT": "LTIME", "LTIME": "LTIME", "D": "DATE", "DATE": "DATE"}
_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

_CACHE: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()


def _type_name(t: PosElement | None) -> str | None:
    """An elementary or derived type's name, None for others."""
    if t is None or not t.kids():
        return None
    k = t.kids()[0]
    if k.name.lower() in _ELEMENTARY:
        return _ELEMENTARY[k.name.lower()]
    if k.name == "derived" and _IDENT.fullmatch(k.get("name", "")):
        return k.get("name", "")
    return None


def _vars(block: PosElement) -> dict[str, str | None]:
    return {v.get("name", "").upper(): _type_name(v.kid("type")) for v in block.kids("variable")}


class Pou:
    """A user POU's kind, result type and outputs (UPPER name -> type)."""

    def __init__(self, el: PosElement) -> None:
        self.el = el
        self.kind = el.get("pouType", "")
        itf = el.kid("interface")
        self.result = _type_name(itf.kid("returnType")) if itf is not None else None
        self.outputs: dict[str, str | None] = {}
        self.variables: dict[str, str | None] = {}
        self.inouts: set[str] = set()
        for block in itf.kids() if itf is not None else []:
            found = _vars(block)
            self.variables.update(found)
            if block.name == "outputVars":
                self.outputs.update(found)
            if block.name == "inOutVars":
                self.inouts.update(found)


class Project:
    """The POUs and global variables of the file a body comes from."""

    def __init__(self, root: PosElement | None) -> None:
        self.pous: dict[str, Pou] = {}
        self.globals: dict[str, str | None] = {}
        self.spans: list[tuple[int, int, Pou]] = []
        if root is None:
            return
        for el in root.walk("pou"):
            p = Pou(el)
            self.pous[el.get("name", "").upper()] = p
            self.spans.append((el.line, el.end_line, p))
        for gv in root.walk("globalVars"):
            self.globals.update(_vars(gv))

    @classmethod
    def of(cls, out: BodyOut) -> Project:
        found = _CACHE.get(out.texts)
        if found is None:
            found = cls(parse_xml(out.texts.raw, out.path, DiagnosticBag()))
            _CACHE[out.texts] = found
        return found

    def pou_at(self, el: PosElement) -> Pou | None:
        """The innermost POU whose element holds el."""
        inside = [p for first, last, p in self.spans if first <= el.line <= last]
        return max(inside, key=lambda p: p.el.line) if inside else None

    def block_kind(self, type_name: str) -> str:
        """'fb', 'function' (a user FUNCTION) or 'std' (a standard function,
        or one the project does not define: a library's)."""
        p = self.pous.get(type_name.upper())
        if p is not None:
            return "fb" if p.kind in ("functionBlock", "program") else "function"
        return "fb" if type_name.upper() in STANDARD_FBS else "std"

    def fb_output(self, type_name: str, param: str) -> str | None:
        p = self.pous.get(type_name.upper())
        if p is not None:
            return p.outputs.get(param.upper())
        return _FB_OUTPUTS.get(type_name.upper(), {}).get(param.upper())


class Types:
    """The types of the values on a body's wires, where they can be told."""

    def __init__(self, project: Project, here: PosElement) -> None:
        self.project = project
        pou = project.pou_at(here)
        self.scope: dict[str, str | None] = dict(project.globals)
        if pou is not None:
            self.scope.update(pou.variables)

    def of_text(self, text: str) -> str | None:
        """The type of an input variable's expression: a variable, an FB
        instance's output, a Boolean or typed literal; None otherwise."""
        t = text.strip()
        if t.upper() in ("TRUE", "FALSE"):
            return "BOOL"
        m = _TYPED_LITERAL.fullmatch(t)
        if m:
            prefix = m.group(1).upper()
            return _TIME_PREFIX.get(prefix) or _ELEMENTARY.get(prefix.lower())
        parts = t.split(".")
        if not all(_IDENT.fullmatch(p) for p in parts):
            return None
        ty = self.scope.get(parts[0].upper())
        if len(parts) == 1 or ty is None:
            return ty if len(parts) == 1 else None
        return self.project.fb_output(ty, parts[1]) if len(parts) == 2 else None

    @staticmethod
    def of_function(name: str, inputs: dict[str, str | None]) -> str | None:
        """A standard function's result type from its inputs' types
        (formal parameter UPPER -> type or None)."""
        n = name.upper()
        if n in _BOOLEAN:
            return "BOOL"
        if "_TO_" in n or n.startswith("TO_"):
            target = n.rsplit("_TO_", 1)[-1] if "_TO_" in n else n[3:]
            return _ELEMENTARY.get(target.lower())
        if n in _SAME_AS_INPUT:
            which = _SAME_AS_INPUT[n]
            if which is not None:
                return inputs.get(which)
            known = {t for p, t in inputs.items() if p != "EN" and t is not None}
            return known.pop() if len(known) == 1 else None
        return None


def project_of(out: BodyOut) -> Project:
    return Project.of(out)


__all__ = ["STANDARD_FBS", "Pou", "Project", "TextPositions", "Types", "project_of"]
