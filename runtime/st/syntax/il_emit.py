"""The pieces of ST that il_lower.py writes: the current result as an
expression (Ex, built with binop and negate, parenthesised by IEC
precedence) and the lines it goes on (Layout)."""

from __future__ import annotations

# ST precedence (build_exprs.py): a higher number binds tighter
PREC = {"OR": 1, "XOR": 2, "AND": 3, "=": 4, "<>": 4, "<": 5, ">": 5, "<=": 5, ">=": 5, "+": 6, "-": 6}
PREC.update({"*": 7, "/": 7, "MOD": 7})
ST_OP = {"AND": "AND", "OR": "OR", "XOR": "XOR", "ADD": "+", "SUB": "-", "MUL": "*", "DIV": "/", "MOD": "MOD"}
ST_OP.update({"GT": ">", "GE": ">=", "EQ": "=", "NE": "<>", "LE": "<=", "LT": "<"})
UNARY = 9
ATOM = 10


class Piece:
    __slots__ = ("text", "line", "col")

    def __init__(self, text: str, line: int, col: int) -> None:
        self.text, self.line, self.col = text, line, col


class Ex:
    """The CR as an ST expression: its pieces, the precedence of its top
    operator, the names it reads, the function calls in it (name, Ex),
    whether it is a literal or a plain variable (simple), the first line
    where it may fault (risky, 0: none), whether a statement has read it."""

    __slots__ = ("pieces", "prec", "reads", "calls", "simple", "risky", "used")

    def __init__(self, pieces, prec=ATOM, reads=frozenset(), calls=(), simple=False, risky=0) -> None:
        self.pieces: list = pieces
        self.prec = prec
        self.reads: frozenset = reads
        self.calls: tuple = calls
        self.simple = simple
        self.risky = risky
        self.used = False


def earliest(*lines: int) -> int:
    """The first of the lines that are not 0 (0 if none)."""
    found = [n for n in lines if n]
    return min(found) if found else 0


def wrap(e: Ex) -> list:
    first, last = e.pieces[0], e.pieces[-1]
    return [Piece("(", first.line, max(first.col - 1, 0)), *e.pieces, Piece(")", last.line, 0)]


def binop(left: Ex, op: str, right: Ex, at: Piece, risky: int = 0) -> Ex:
    p = PREC[op]
    lp = wrap(left) if left.prec < p else left.pieces
    rp = wrap(right) if right.prec <= p else right.pieces
    return Ex(
        [*lp, at, *rp],
        p,
        left.reads | right.reads,
        left.calls + right.calls,
        risky=earliest(left.risky, right.risky, risky),
    )


def negate(e: Ex, at: Piece) -> Ex:
    pieces = wrap(e) if e.prec < UNARY else e.pieces
    return Ex([at, *pieces], UNARY, e.reads, e.calls, risky=e.risky)


# Two pieces that would open or close a comment if they touched (%I* then ')')
_COMMENTS = frozenset(("(*", "*)", "//", "/*", "*/"))


class Layout:
    """The ST text of a body's lines, written in order: a piece goes at its
    line and column, or after what is already there (line 0: where the
    last piece went). ``where``: line -> [(first column, column after, IL
    line, IL column)] of the pieces that come from a place in the IL (their
    own, unless put elsewhere: src), for il.relocate. ``plain``: the same
    lines with one blank between pieces, for a reader (export-st)."""

    def __init__(self, first: int, last: int) -> None:
        self.lines = dict.fromkeys(range(first, last + 1), "")
        self.plain = dict.fromkeys(range(first, last + 1), "")
        self.cur = first
        self.where: dict = {}

    def put(self, text: str, line: int, col: int, src: tuple | None = None) -> None:
        if src is None and col > 0:
            src = (line, col)
        if line < self.cur:
            line = self.cur
        self.cur = line
        s = self.lines[line]
        if len(s) < col - 1:
            s += " " * (col - 1 - len(s))
        elif s and (s[-1] not in " (" and text[0] not in "),;" or s[-1] + text[0] in _COMMENTS):
            s += " "
        if src is not None:
            self.where.setdefault(line, []).append((len(s) + 1, len(s) + 1 + len(text), *src))
        self.lines[line] = s + text
        p = self.plain[line]
        apart = p and (p[-1] != "(" and text[0] not in "),;" or p[-1] + text[0] in _COMMENTS)
        self.plain[line] = p + (" " if apart else "") + text
