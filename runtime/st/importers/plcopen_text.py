"""What an attribute or a text of a PLCopen XML file may become in ST.

Nothing from the file is pasted into ST unchecked: a name becomes ST only
as an identifier (or a dotted one), an integer only as digits, and a value
(an initial value, an array bound, a string length, an FB_init input) only
as the tokens of an expression. ``st_value`` lexes it with the ST lexer
(lexer.py, the parser's own) after the comment pass: a comment or pragma
opener, a ';' or ':', a reserved keyword (END_VAR ...), a character no
token starts with, or an unbalanced bracket is refused, so a value cannot
end its declaration or hide the text after it. A duration is an IEC
literal (``T#20ms``) or an XSD duration (``PT0.5S``, as TC6 0201 types
``<task interval>``), made a ``T#`` literal. A pragma is
``{attribute 'name' := 'value'}`` with a name of word characters and a
value without quotes or braces.

Each function returns the ST text or raises ImportProblem (E183 at the
element, bodies.py).
"""

from __future__ import annotations

import re
from decimal import Decimal

from ..syntax.lexer import strip_comments
from ..syntax.st_grammar import grammar
from .bodies import ImportProblem
from .xmlsafe import PosElement

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z", re.ASCII)
_LITERALS = frozenset(("INT", "REAL", "BASED_INT", "C_HEX", "HASH_LIT", "STRING_LIT", "WSTRING_LIT", "TRUE", "FALSE"))
_OPERATORS = frozenset(("AND", "OR", "XOR", "NOT", "MOD", "AND_THEN", "OR_ELSE"))
_EXPR_PUNCT = frozenset(
    ("LPAR", "RPAR", "DOT", "PLUS", "MINUS", "STAR", "SLASH", "POW", "AMP", "LT", "LE", "NE", "EQ", "GT", "GE", "DEREF")
)
# Initial values add initialisers: [1, 2(5)], (x := 1, y := 2).
_VALUE_PUNCT = _EXPR_PUNCT | {"LSQB", "RSQB", "COMMA", "ASSIGN"}
_CLOSERS = {"RPAR": "LPAR", "RSQB": "LSQB"}
_XSD_DURATION = re.compile(
    r"(-)?P(?:(\d+)Y)?(?:(\d+)M)?(?:(\d+)D)?(?:T(?:(\d+)H)?(?:(\d+)M)?(?:(\d+(?:\.\d+)?)S)?)?\Z", re.ASCII
)
_IEC_DURATION = re.compile(r"(?:L?TIME|L?T)#", re.IGNORECASE | re.ASCII)
_ATTRIBUTE_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_.\-]*\Z", re.ASCII)
_NS = {"d": 86_400 * 10**9, "h": 3_600 * 10**9, "m": 60 * 10**9, "s": 10**9, "ms": 10**6, "us": 10**3, "ns": 1}


def ident(name: str | None, el: PosElement | None, what: str = "") -> str:
    """An identifier, or a dotted one (``GVL.x``, ``MQTT.ITF``)."""
    name = (name or "").strip()
    if not name or not all(_IDENT.match(p) for p in name.split(".")):
        raise ImportProblem(f"{what + ' ' if what else ''}{name!r} is not an ST identifier", el, None)
    return name


def integer(value: str | None, el: PosElement | None, what: str = "") -> str:
    v = (value or "").strip()
    if not v.lstrip("+-").isdigit() or not v.isascii():
        raise ImportProblem(f"{what + ' ' if what else ''}{value!r} is not an integer", el, None)
    return v


def _tokens(text: str, el: PosElement | None, what: str) -> list:
    if "\n" in text or "\r" in text:
        raise ImportProblem(f"{what} {text!r} spans lines: it cannot be an ST value here", el, None)
    blanked, pragmas = strip_comments(text, lambda *a: None)
    if blanked != text or pragmas:
        raise ImportProblem(f"{what} {text!r} holds a comment or pragma: it cannot be an ST value here", el, None)
    bad: list = []

    def invalid(offset: int, line: int, col: int) -> tuple:
        bad.append(offset)
        return len(text), None

    toks = list(grammar().lexer.tokens(text, lambda: None, invalid))
    if bad:
        raise ImportProblem(f"{what} {text!r} cannot be an ST value here", el, None)
    return toks


def st_value(
    text: str | None, el: PosElement | None, what: str = "the value", allowed: frozenset = _VALUE_PUNCT
) -> str:
    """An initial value (a literal, a constant expression, an array or
    structure initialiser) as ST tokens: nothing that could end the
    declaration it stands in."""
    text = (text or "").strip()
    toks = _tokens(text, el, what)
    if not toks:
        raise ImportProblem(f"{what} is empty", el, None)
    reserved = grammar().lexer.reserved
    depth: list = []
    for t in toks:
        word = _IDENT.match(t.value) is not None
        if t.type in _LITERALS or t.type in _OPERATORS:
            continue
        if word and t.type not in reserved:
            continue  # a name (a soft keyword is a name in an expression)
        if t.type in allowed:
            if t.type in ("LPAR", "LSQB"):
                depth.append(t.type)
            elif t.type in _CLOSERS and (not depth or depth.pop() != _CLOSERS[t.type]):
                raise ImportProblem(f"{what} {text!r}: '{t.value}' closes nothing", el, None)
            continue
        raise ImportProblem(f"{what} {text!r} cannot be an ST value here ('{t.value}')", el, None)
    if depth:
        raise ImportProblem(f"{what} {text!r}: a bracket is not closed", el, None)
    return text


def st_const(text: str | None, el: PosElement | None, what: str) -> str:
    """A constant expression (an array bound, a string length): a number,
    a constant's name (``ciN``, ``GVL.N``) or arithmetic on them; the
    checker evaluates it."""
    text = (text or "").strip()
    if text.lstrip("+-").isdigit() and text.isascii():
        return text
    for t in _tokens(text, el, what):
        if t.type == "STRING_LIT" or t.type == "WSTRING_LIT":
            raise ImportProblem(f"{what} {text!r} is not a constant expression", el, None)
    return st_value(text, el, what, _EXPR_PUNCT)


def address(text: str | None, el: PosElement | None) -> str:
    """A located address (%IX0.0, %QW4, %MD*): one address token."""
    text = (text or "").strip()
    toks = _tokens(text, el, "the address")
    if len(toks) != 1 or toks[0].type not in ("LOCATED", "BIT_REF") or not text.startswith("%"):
        raise ImportProblem(f"the address {text!r} is not a located address such as %IX0.0", el, None)
    return text


def duration(text: str | None, el: PosElement | None, what: str = "the interval") -> str:
    """An IEC duration literal (T#20ms, TIME#1s) as it is, or an XSD
    duration (PT0.5S, PT1M30S, P1DT2H) as a T# literal."""
    text = (text or "").strip()
    if _IEC_DURATION.match(text):
        toks = _tokens(text, el, what)
        if len(toks) == 1 and toks[0].type == "HASH_LIT":
            return text
    m = _XSD_DURATION.match(text)
    if m is None or text in ("P", "PT") or text.endswith("T"):
        raise ImportProblem(
            f"{what} {text!r} is no duration",
            el,
            "write an IEC literal (T#500ms) or an XSD duration (PT0.5S)",
        )
    sign, years, months, days, hours, minutes, seconds = m.groups()
    if years or months:
        raise ImportProblem(f"{what} {text!r} counts years or months, which have no fixed length", el, None)
    ns = int(days or 0) * _NS["d"] + int(hours or 0) * _NS["h"] + int(minutes or 0) * _NS["m"]
    ns += int(Decimal(seconds or "0") * _NS["s"])
    if Decimal(seconds or "0") * _NS["s"] % 1:
        raise ImportProblem(f"{what} {text!r} is finer than a nanosecond", el, None)
    parts = []
    for unit, size in _NS.items():
        if ns >= size:
            parts.append(f"{ns // size}{unit}")
            ns %= size
    return ("-" if sign else "") + "T#" + ("".join(parts) or "0ms")


def pragma(name: str | None, value: str | None, el: PosElement | None) -> str:
    """``{attribute 'name'}`` or ``{attribute 'name' := 'value'}``."""
    name = (name or "").strip()
    if not _ATTRIBUTE_NAME.match(name):
        raise ImportProblem(f"the attribute name {name!r} cannot be written as a pragma", el, None)
    if value is None or value == "":
        return f"{{attribute '{name}'}}"
    if any(c in value for c in "'{}$") or not value.isprintable():
        raise ImportProblem(f"the value {value!r} of attribute {name!r} cannot be written as a pragma", el, None)
    return f"{{attribute '{name}' := '{value}'}}"
