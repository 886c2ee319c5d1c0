"""Structured Text tokens, for the parser (parser.py and parse_stack.py).

Two passes:

``strip_comments`` blanks comments (``(* *)``, ``//``, ``/* */``) and
pragmas ``{...}`` out with spaces, keeping every line and column where it
was, and collects the pragmas. Whether ``(* *)`` comments nest is the
profile's choice (``Profile.nested_comments``); nested comments are beyond a
regular lexer.

``Lexer.tokens`` cuts the rest into ``Tok``s with one compiled regular
expression made from the terminals of grammar.lark. It is contextual the way
ST needs: it asks the parser which token types the current state accepts
(``accepts``) to decide

  * soft keywords: SET, RESET, AT, ON, TASK, RETAIN, ... are keywords only
    where the grammar expects them and names elsewhere (``rs(SET := x)``);
    reserved keywords (IF, END_IF, ...) are keywords everywhere;
  * ``LABEL_NAME``: a name followed by ':', ',' or '..' where a CASE label
    may stand (a label can follow a statement, LALR sees one token);
    ``JUMP_LABEL``: a name followed by ':' where a statement starts and no
    CASE label can (so in a CASE branch, 'name:' after a statement starts
    the next branch, as before);
  * JMP and ACTION are keywords only where a name follows them;
  * ``S=`` / ``R=`` / ``REF=`` after an assignment target;
  * ``w.0.1``: after '.', digits are a bit number, never the real 0.1;
  * the function forms of the operators (IEC 61131-3 ed.3 Table 29-31):
    AND, OR, XOR, NOT and MOD followed by '(' where an operand may stand
    are a NAME (``AND(a, b)``, ``NOT(IN := x)``); after a token that ends
    an operand (a name, a literal, ')', ']', '^') they stay operators
    (``a AND (b)``). LALR merges the lookaheads of a reduction, so the
    parser's row alone cannot tell the two apart. ``NOT (x)`` with one
    positional argument is the operator again (build_exprs.py).

lark's contextual lexer could do most of this (with a postlexer for the
reserved words); this one is about twice as fast, and speed matters here.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

from ..limits import MAX_COMMENT_DEPTH
from ..profile import names_where

if TYPE_CHECKING:
    from .lark_adapter import Terminal


class Tok:
    """A token. Tokens never span lines (strings and comments cannot), so
    the end is on the start line. Fields match lark's Token."""

    __slots__ = ("type", "value", "start_pos", "line", "column", "end_column")

    def __init__(self, type: str, value: str, start_pos: int, line: int, column: int) -> None:
        self.type = type
        self.value = value
        self.start_pos = start_pos
        self.line = line
        self.column = column
        self.end_column = column + len(value)

    @property
    def end_line(self) -> int:
        return self.line

    @property
    def end_pos(self) -> int:
        return self.start_pos + len(self.value)

    def __repr__(self) -> str:
        return f"Tok({self.type}, {self.value!r}, {self.line}:{self.column})"


# ---------------------------------------------------------------- comments and pragmas


class Pragma:
    """``{text}``: where it was and what was inside the braces (stripped)."""

    __slots__ = ("text", "line", "col", "end_line", "end_col")

    def __init__(self, text: str, start: tuple, end: tuple) -> None:
        self.text = text
        self.line, self.col = start
        self.end_line, self.end_col = end


_COMMENT_START = re.compile(r"\(\*|\*\)|/\*|//|\{|'|\"")
_NESTED = re.compile(r"\(\*|\*\)")
_STRING_AT = {"'": re.compile(r"'(?:[^'$\n]|\$[^\n])*'"), '"': re.compile(r'"(?:[^"$\n]|\$[^\n])*"')}
_NOT_NEWLINE = re.compile(r"[^\n]")


def line_col(text: str, offset: int) -> tuple:
    """1-based (line, column) of a character offset."""
    line = text.count("\n", 0, offset) + 1
    return line, offset - (text.rfind("\n", 0, offset) + 1) + 1


def _closer(text: str, start: int, opener: str, closer: str, kind: str, error: Callable) -> int:
    """Where the first closer after the opener at start is, or -1 after an
    E004 (the comment or pragma then runs to the end of the text)."""
    close = text.find(closer, start + len(opener))
    if close < 0:
        error(
            "E004",
            f"unterminated {kind}: '{opener}' is never closed",
            start,
            start + len(opener),
            f"close it with '{closer}'",
        )
    return close


def strip_comments(text: str, error: Callable, nested: bool = True) -> tuple:
    """Return (text with comments and pragmas blanked, [Pragma]).
    ``error(code, message, start_offset, end_offset, hint)`` reports a problem.
    nested: ``(* *)`` comments nest (CODESYS, TwinCAT), or the first ``*)``
    ends one (IEC 61131-3 ed.2 2.1.5, MatIEC)."""
    if not any(c in text for c in "(/{*"):
        return text, []
    pieces, pragmas = [], []
    done = pos = 0  # text[:done] is in pieces; the scan resumes at pos
    inner_open = -1  # not nesting: where the last comment holding a '(*' started
    while True:
        m = _COMMENT_START.search(text, pos)
        if m is None:
            break
        start, what = m.start(), m.group()
        if what in ("'", '"'):
            s = _STRING_AT[what].match(text, start)
            pos = s.end() if s else start + 1  # the lexer reports unterminated strings
            continue
        if what == "*)":
            hint = "remove it, or open the comment with '(*'"
            if inner_open >= 0:
                line = line_col(text, inner_open)[0]
                hint = (
                    f"(* *) comments do not nest in this profile: the comment at line {line} ended at its "
                    f"first '*)'; they nest in {names_where(lambda p: p.nested_comments)}"
                )
            error("E001", "'*)' without a matching '(*'", start, start + 2, hint)
            end = start + 2
        elif what == "//":
            nl = text.find("\n", start)
            end = len(text) if nl < 0 else nl
        elif what == "/*":
            close = _closer(text, start, "/*", "*/", "comment", error)
            end = len(text) if close < 0 else close + 2
        elif what == "{" and text.startswith("{{", start):
            # MatIEC's embedded C, {{ ... }}: it may hold single braces and
            # span lines; the first '}}' ends it. Its text keeps one brace
            # each side ('{ ... }'), which tells it from other pragmas.
            close = _closer(text, start, "{{", "}}", "pragma", error)
            end = len(text) if close < 0 else close + 2
            if close >= 0:
                pragmas.append(Pragma(text[start + 1 : end - 1], line_col(text, start), line_col(text, end)))
        elif what == "{":
            close = _closer(text, start, "{", "}", "pragma", error)
            end = len(text) if close < 0 else close + 1
            if close >= 0:
                pragmas.append(Pragma(text[start + 1 : close].strip(), line_col(text, start), line_col(text, end)))
        elif not nested:  # "(*": the first '*)' ends it
            close = _closer(text, start, "(*", "*)", "comment", error)
            end = len(text) if close < 0 else close + 2
            if close >= 0 and text.find("(*", start + 2, close) >= 0:
                inner_open = start
        else:  # "(*": comments nest
            end = _nested_comment_end(text, start, error)
        pieces.append(text[done:start])
        pieces.append(_NOT_NEWLINE.sub(" ", text[start:end]))
        done = pos = end
    pieces.append(text[done:])
    return "".join(pieces), pragmas


def _nested_comment_end(text: str, start: int, error: Callable) -> int:
    """The end of the nesting (* *) comment at start (the text's end, with
    E004, when it is never closed)."""
    depth, p, deep, first_close = 1, start + 2, False, -1
    while depth:
        n = _NESTED.search(text, p)
        if n is None:
            break
        if n.group() == "(*":
            depth += 1
        else:
            depth -= 1
            if first_close < 0:
                first_close = n.start()
        p = n.end()
        if depth > MAX_COMMENT_DEPTH and not deep:
            deep = True  # reported once; the comment still ends at its own '*)'
            error(
                "E008",
                f"comments nested too deeply (more than {MAX_COMMENT_DEPTH} levels)",
                n.start(),
                p,
                "(* *) comments nest: close the inner ones, or use // for a line",
            )
    if not depth:
        return p
    hint = "(* *) comments nest in this profile: every '(*' inside needs its own '*)'"
    if first_close >= 0:
        line = line_col(text, first_close)[0]
        hint += f"; in {names_where(lambda p: not p.nested_comments)} (no nesting) it would end at line {line}"
    error("E004", "unterminated comment: '(*' is never closed", start, start + 2, hint)
    return len(text)


# ---------------------------------------------------------------- tokens

_WHITESPACE = "[ \t\f\r\n\v]*"
_SKIP_WHITESPACE = re.compile(_WHITESPACE)
# Characters that can start some token; a run of others is one E002.
INVALID_RUN = re.compile(r"[^A-Za-z0-9_\s%'\"()\[\];:,.=<>+\-*/&^#]+")
# Regular-expression terminals, in the order they are tried (first match
# wins, so a longer form comes before its prefix: HASH_LIT before NAME,
# REAL before INT). Others are tried only where the parser accepts them.
_ORDER = ("HASH_LIT", "C_HEX", "BASED_INT", "REAL", "INT", "LOCATED", "BIT_REF", "NAME", "STRING_LIT", "WSTRING_LIT")
_CONTEXTUAL = ("S_ASSIGN", "R_ASSIGN", "REF_ASSIGN", "LABEL_NAME", "JUMP_LABEL")
# Soft keywords that stay names unless what follows fits: 'JMP done;' but
# 'jmp := 1;', 'ACTION Reset:' but 'action := 2;' (and 'actions := 3;').
_SOFT_FOLLOW = {
    "JMP": re.compile(r"[ \t\f\r\n\v]+[A-Za-z_]"),
    "ACTION": re.compile(r"[ \t\f\r\n\v]+[A-Za-z_]"),
    "ACTIONS": re.compile(r"[ \t\f\r\n\v]+[A-Za-z_]"),
}
# Reserved operator keywords that are also standard functions (AND(a, b)).
_OPERATOR_FUNCTIONS = frozenset(("AND", "OR", "XOR", "NOT", "MOD"))
_OPEN_PAREN = re.compile(r"[ \t\f\r\n\v]*\(")
# The SFC keywords that open an element (build_sfc.py) are soft: where a
# statement could start too, they are keywords only when what follows reads
# like SFC (a name; for TRANSITION also FROM or '(PRIORITY'), so that
# ``step := 1;`` and ``action();`` stay statements.
_SFC_OPENERS = frozenset(("INITIAL_STEP", "STEP", "TRANSITION", "ACTION"))
_SFC_FOLLOWS = re.compile(r"[ \t\f\r\n\v]+[a-z_]", re.ASCII | re.IGNORECASE)
_PRIORITY_FOLLOWS = re.compile(r"[ \t\f\r\n\v]*\([ \t\f\r\n\v]*PRIORITY\b", re.ASCII | re.IGNORECASE)
# After a name, what makes it the start of a statement: the soft keywords
# of object-oriented ST are names there (Get := 1; property := x;): LALR
# merges the states after a type name and after a VAR block, so the
# parser's row has GET after METHOD Get : INT, and METHOD, PROPERTY after
# the VAR blocks of any POU.
_STARTS_STATEMENT = re.compile(r"[ \t]*(?::=|\?=|[(.\[^])")
_OOP_SOFT = frozenset(
    ("GET", "METHOD", "PROPERTY", "INTERFACE", "ABSTRACT", "FINAL", "PUBLIC", "PRIVATE", "PROTECTED")
    + ("INTERNAL", "VAR_INST")
)
# Tokens that end an operand: after them AND, OR ... are operators.
_ENDS_OPERAND = frozenset(
    ("NAME", "INT", "REAL", "BASED_INT", "C_HEX", "HASH_LIT", "STRING_LIT", "WSTRING_LIT", "LOCATED", "BIT_REF")
    + ("TRUE", "FALSE", "RPAR", "RSQB", "DEREF", "SET", "RESET")
)


class Lexer:
    """Built once from the grammar's terminals; ``tokens`` runs per text."""

    def __init__(self, terminals: dict[str, Terminal], reserved: frozenset) -> None:
        self.keywords: dict[str, str] = {}  # 'END_IF' -> terminal name
        punct: dict[str, str] = {}  # ':=' -> terminal name
        for name, t in terminals.items():
            if t.literal is not None:
                value = t.literal.upper()
                (self.keywords if value.isidentifier() else punct)[value] = name
        self.reserved = frozenset(n for v, n in self.keywords.items() if v in reserved)
        self.punct = punct
        groups = [f"(?P<{n}>{terminals[n].regexp})" for n in _ORDER]
        groups.append("(?P<PUNCT>" + "|".join(re.escape(p) for p in sorted(punct, key=len, reverse=True)) + ")")
        self.master = re.compile(_WHITESPACE + "(?:" + "|".join(groups) + ")", re.ASCII)
        self.contextual = [(n, re.compile(terminals[n].regexp, re.ASCII)) for n in _CONTEXTUAL]
        self.int_re = re.compile(terminals["INT"].regexp, re.ASCII)

    @staticmethod
    def _sfc_follows(kw: str, text: str, pos: int) -> bool:
        """Whether the SFC keyword kw, ending at pos, opens an SFC element."""
        if _SFC_FOLLOWS.match(text, pos):
            return True
        return kw == "TRANSITION" and _PRIORITY_FOLLOWS.match(text, pos) is not None

    def tokens(
        self, text: str, accepts: Callable[[], dict | None], bad: Callable, fits: Callable[[str], bool] = bool
    ) -> Iterator[Tok]:
        """The tokens of text (comments already blanked). accepts() gives
        the token types the parser takes next (None: any, while skipping).
        bad(offset, line, column) is called where no token starts and
        returns (offset to go on from, token to yield or None).
        fits(type): would the parser really take a token of that type
        (LALR rows offer some that a later reduction refuses)?"""
        match, keywords, reserved, punct = self.master.match, self.keywords, self.reserved, self.punct
        pos, line, line_start, n = 0, 1, 0, len(text)
        prev = ""  # the kind of the last token
        while True:
            m = match(text, pos)
            if m is None:
                space = _SKIP_WHITESPACE.match(text, pos)
                start = space.end() if space else pos
                newlines = text.count("\n", pos, start)
                if newlines:
                    line += newlines
                    line_start = text.rfind("\n", pos, start) + 1
                if start >= n:
                    return
                pos, tok = bad(start, line, start - line_start + 1)
                if tok is not None:
                    yield tok
                continue
            # (every alternative of the master pattern is a named group)
            kind: str = m.lastgroup  # type: ignore[assignment]
            start = m.start(kind)
            newlines = text.count("\n", pos, start)
            if newlines:
                line += newlines
                line_start = text.rfind("\n", pos, start) + 1
            value = m.group(kind)
            pos = m.end()
            if kind == "PUNCT":
                kind = punct[value]
            elif kind == "NAME":
                kw = keywords.get(value.upper())
                if kw is None or kw not in reserved:
                    row = accepts()
                    if row is None:
                        kind = kw or kind
                    else:
                        for name, regex in self.contextual:
                            if name in row:
                                cm = regex.match(text, start)
                                if cm:
                                    # LALR merges rows: is it a CASE label, a jump label, or neither?
                                    if name == "JUMP_LABEL" or "JUMP_LABEL" in row:
                                        if not fits(name):
                                            continue
                                    kind, value, pos = name, cm.group(), cm.end()
                                    break
                        else:
                            if kw is not None and kw in row:
                                kind = kw
                                follow = _SOFT_FOLLOW.get(kw)
                                if follow is not None and not follow.match(text, pos):
                                    kind = "NAME"
                                elif kw in _SFC_OPENERS and "NAME" in row and not self._sfc_follows(kw, text, pos):
                                    kind = "NAME"
                                elif kw in _OOP_SOFT and _STARTS_STATEMENT.match(text, pos):
                                    kind = "NAME"
                else:
                    kind = kw
                    if kw in _OPERATOR_FUNCTIONS and prev not in _ENDS_OPERAND and _OPEN_PAREN.match(text, pos):
                        row = accepts()
                        if row is not None and "NAME" in row:
                            kind = "NAME"  # AND(a, b): the function form
            elif kind == "REAL":
                row = accepts()
                if row is not None and "REAL" not in row and "INT" in row:
                    digits = self.int_re.match(text, start)
                    if digits is not None:  # (always: a REAL starts with digits)
                        value = digits.group()  # w.0.1: bit 0, then .1
                        kind, pos = "INT", start + len(value)
            prev = kind
            yield Tok(kind, value, start, line, start - line_start + 1)
