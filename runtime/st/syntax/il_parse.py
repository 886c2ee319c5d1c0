"""IL bodies read into instructions (il.py finds them, il_lower.py makes ST
of them).

    items = read_il(lines, first_line, lexer, report)   # [Label | Instr]

IEC 61131-3 ed.2 3.2 (ed.3 7.2): one instruction per line, after optional
``label:`` (a label may stand alone on its line); an operator with its
modifiers (N, C, '(') and its operand, or a function name and its operands,
or ``)``. ``CAL fb(...)`` and a formal function call ``LIMIT( MN := 1, ...)``
may spread their argument list over several lines.

Tokens are those of the ST lexer (its master expression, lexer.py), so a
literal, a name or an address means here what it means in ST; an operand is
kept as the source text of its tokens, which only tokens of the kinds below
make up: nothing else of the input reaches the ST that il_lower.py writes.
Every problem is reported with a code at its line and column (E190-E198,
E002/E004 for characters and strings, as in ST) and the body is not lowered.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from .st_grammar import RESERVED

# The spelled operators: name -> (operator, N, C). Table 52 of ed.2 and NOT
# of ed.3; S1 ... PT are the input operators of Table 53 (an FB call).
OPS: dict[str, tuple[str, bool, bool]] = {}
for _op in ("LD", "ST", "AND", "OR", "XOR"):
    OPS[_op] = (_op, False, False)
    OPS[_op + "N"] = (_op, True, False)
for _op in ("S", "R", "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT", "NOT"):
    OPS[_op] = (_op, False, False)
for _op in ("JMP", "CAL", "RET"):
    OPS[_op] = (_op, False, False)
    OPS[_op + "C"] = (_op, False, True)
    OPS[_op + "CN"] = (_op, True, True)
FB_INPUTS = frozenset(("S1", "R1", "CLK", "CU", "CD", "PV", "IN", "PT"))
for _op in FB_INPUTS:
    OPS[_op] = ("INPUT", False, False)
# Operators that take '(' (the deferred operation of 3.2.2)
PAREN_OPS = frozenset(("AND", "OR", "XOR", "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT"))
# Operators without an operand
BARE_OPS = frozenset(("NOT", "RET"))
# What the operand of each operator is: a variable (written to), a label, an
# FB instance, or any operand (a variable or a literal)
_TARGET_OPS = frozenset(("ST", "S", "R", "INPUT", "CAL"))

LITERALS = frozenset(("INT", "REAL", "BASED_INT", "C_HEX", "HASH_LIT", "STRING_LIT", "WSTRING_LIT"))
_NUMBERS = frozenset(("INT", "REAL", "BASED_INT", "HASH_LIT"))
# Punctuation an array subscript may hold (ST expressions of names and literals)
_INDEX_PUNCT = frozenset(("+", "-", "*", "/", "**", "(", ")", ",", ".", "[", "]", "^", "=", "<>", "<", ">", "<=", ">="))
_INDEX_WORDS = frozenset(("AND", "OR", "XOR", "NOT", "MOD", "TRUE", "FALSE"))


@dataclass(slots=True)
class Tk:
    """A token of an IL line: kind is the ST terminal (NAME, INT, ...) or,
    for punctuation, the text itself. start/end: offsets in the line."""

    kind: str
    value: str
    line: int
    start: int
    end: int

    @property
    def col(self) -> int:
        return self.start + 1


@dataclass(slots=True)
class Operand:
    """An operand as its source text (validated tokens and blanks)."""

    text: str
    line: int
    col: int
    end_col: int
    literal: bool = False  # a literal (not written to)
    path: bool = False  # a variable of names and dots only (no index, no ^)
    reads: frozenset = frozenset()  # the names it reads, upper case
    risky: bool = False  # an index or a dereference: may fault
    signed: bool = False  # a literal with a sign: -1

    @property
    def root(self) -> str:
        return self.text.split(".", 1)[0].strip().upper()


@dataclass(slots=True)
class Arg:
    """An argument of CAL fb(...) or of a formal function call."""

    name: Tk | None  # None: positional
    kind: str = ":="  # ':=' or '=>'
    negated: bool = False  # NOT q => x
    value: Operand | None = None


@dataclass(slots=True)
class Instr:
    op: str  # LD ST S R AND ... NOT JMP CAL RET INPUT ) FUNC FORMAL
    line: int
    col: int
    end_col: int
    name: str = ""  # as written: the operator, the function or FB input name
    neg: bool = False
    cond: bool = False
    paren: bool = False
    operands: list = field(default_factory=list)  # [Operand]
    args: list | None = None  # [Arg] for CAL fb(...) and FORMAL
    close: tuple = (0, 0)  # (line, col) of the ')' ending the argument list


@dataclass(slots=True)
class Label:
    name: str
    line: int
    col: int


class ILError(Exception):
    """code, message, token or (line, col, end_col), hint."""


Report = Callable[[str, str, int, int, int, str], None]


def tokenize(text: str, line: int, lexer) -> list:
    """The tokens of one line of blanked text. Raises ILError at a
    character no token starts with, or a string not closed on the line."""
    master, punct = lexer.master, lexer.punct
    toks, pos, n = [], 0, len(text)
    while pos < n:
        m = master.match(text, pos)
        if m is None:
            while pos < n and text[pos] in " \t\f\r\v":
                pos += 1
            if pos >= n:
                break
            ch = text[pos]
            if ch in "'\"":
                raise ILError("E004", "unterminated string", (line, pos + 1, n + 1), f"close it with {ch} on its line")
            raise ILError("E002", f"invalid character {ch!r}", (line, pos + 1, pos + 2), None)
        group = str(m.lastgroup)
        value = m.group(group)
        kind = value if group == "PUNCT" and value in punct else group
        toks.append(Tk(kind, value, line, m.start(group), m.end()))
        pos = m.end()
    return toks


def _reserved(t: Tk) -> bool:
    return t.kind == "NAME" and t.value.upper() in RESERVED and t.value.upper() not in ("TRUE", "FALSE")


class _Reader:
    """The instructions of a body's lines (each already tokenized)."""

    def __init__(self, rows: list, texts: dict) -> None:
        self.rows = rows  # [(line, [Tk])], the non-empty lines
        self.texts = texts  # line -> its blanked text
        self.r = 0  # the row being read
        self.items: list = []

    def run(self, report: Report) -> list:
        while self.r < len(self.rows):
            line, toks = self.rows[self.r]
            try:
                self.line(toks)
            except ILError as e:
                _report(report, e)
            self.r += 1
        return self.items

    def line(self, toks: list) -> None:
        i = 0
        while i + 1 < len(toks) and toks[i].kind == "NAME" and toks[i + 1].kind == ":":
            if _reserved(toks[i]):
                raise ILError("E198", f"{toks[i].value} is a keyword, not a label", toks[i], "rename the label")
            self.items.append(Label(toks[i].value, toks[i].line, toks[i].col))
            i += 2
        if i < len(toks):
            self.instruction(toks, i)

    # ------------------------------------------------------------ instructions

    def instruction(self, toks: list, i: int) -> None:
        t = toks[i]
        if t.kind == ")":
            self._nothing_after(toks, i + 1, ")")
            self.items.append(Instr(")", t.line, t.col, t.col + 1, ")"))
            return
        if t.kind == "&":  # & and &N: AND (Table 52)
            neg = i + 1 < len(toks) and toks[i + 1].kind == "NAME" and toks[i + 1].value.upper() == "N"
            neg = neg and toks[i + 1].start == t.end
            end = toks[i + 1] if neg else t
            ins = Instr("AND", t.line, t.col, end.end + 1, "&N" if neg else "&", neg=neg)
            self._operator(ins, toks, i + (2 if neg else 1))
            return
        spec = OPS.get(t.value.upper()) if t.kind == "NAME" else None
        if spec is None and (t.kind != "NAME" or _reserved(t)):
            raise ILError(
                "E190",
                f"{t.value!r} is not an IL operator",
                t,
                "an instruction is an operator (LD, ST, AND, ADD, JMP, CAL, ...) or a function name, "
                "and its operand; one instruction per line",
            )
        if spec is None:
            self._misspelled(t, t.value.upper())
            self._function(t, toks, i + 1)
            return
        op, neg, cond = spec
        self._operator(Instr(op, t.line, t.col, t.col + len(t.value), t.value, neg=neg, cond=cond), toks, i + 1)

    @staticmethod
    def _misspelled(t: Tk, up: str) -> None:
        """ADDN, LDC, JMPN ...: an operator with a modifier it does not take."""
        base = _MISSPELLED.get(up)
        if base is not None:
            raise ILError(
                "E190",
                f"{t.value}: {base} does not take that modifier",
                t,
                "N negates the operand of LD, ST, AND, OR, XOR (LDN, ANDN); C and CN make JMP, CAL, RET "
                "conditional (JMPC, JMPCN)",
            )

    def _operator(self, ins: Instr, toks: list, i: int) -> None:
        op = ins.op
        if i < len(toks) and toks[i].kind == "(" and op not in ("CAL",):
            if op not in PAREN_OPS:
                raise ILError("E190", f"{ins.name} takes no '('", toks[i], _PAREN_HINT)
            ins.paren, ins.end_col = True, toks[i].col + 1
            i += 1
        if op in BARE_OPS:
            self._nothing_after(toks, i, ins.name)
        elif op == "JMP":
            t = self._need(toks, i, ins, "a label: JMP done")
            if t.kind != "NAME" or _reserved(t):
                raise ILError(
                    "E198",
                    f"{ins.name} needs a label, not {t.value!r}",
                    t,
                    "JMP done, with done: before an instruction",
                )
            ins.operands.append(Operand(t.value, t.line, t.col, t.col + len(t.value), path=True))
            self._nothing_after(toks, i + 1, ins.name)
        elif ins.paren and i >= len(toks):
            pass  # AND( alone: the parenthesis starts with LD
        else:
            self._need(toks, i, ins, "an operand: " + _EXAMPLE.get(op, f"{ins.name} x"))
            operand, i = self.operand(toks, i)
            if op in _TARGET_OPS and (operand.literal or not operand.reads):
                raise ILError(
                    "E198",
                    f"{ins.name} needs a variable, not {operand.text}",
                    (operand.line, operand.col, operand.end_col),
                    "ST, S and R write to a variable; CAL and S1, R1, CLK, CU, CD, PV, IN, PT name a function block "
                    "instance",
                )
            ins.operands.append(operand)
            if op == "CAL" and i < len(toks) and toks[i].kind == "(":
                ins.args, ins.close = self.arguments(toks, i + 1)
                self.items.append(ins)
                return
            self._nothing_after(toks, i, ins.name)
        self.items.append(ins)

    def _function(self, t: Tk, toks: list, i: int) -> None:
        """A function call: MAX b (the current result is the first argument),
        or the formal form LIMIT( MN := 1, MX := 5 ) without it."""
        ins = Instr("FUNC", t.line, t.col, t.col + len(t.value), t.value)
        if i < len(toks) and toks[i].kind in (":=", ":", ".", "[", "^"):
            raise ILError(
                "E190",
                f"'{t.value} {toks[i].value}' is not an IL instruction",
                t,
                "a body is IL or ST, not both: in IL, LD the value and ST it into the variable (LD 0 / ST x)",
            )
        if i < len(toks) and toks[i].kind == "(":
            ins.op = "FORMAL"
            ins.args, ins.close = self.arguments(toks, i + 1)
            self.items.append(ins)
            return
        while i < len(toks):
            operand, i = self.operand(toks, i)
            ins.operands.append(operand)
            if i < len(toks):
                if toks[i].kind != ",":
                    raise ILError("E192", f"unexpected {toks[i].value!r} after the operand", toks[i], _ONE_HINT)
                i += 1
                self._need(toks, i, ins, "an operand after ','")
        self.items.append(ins)

    def _need(self, toks: list, i: int, ins: Instr, what: str) -> Tk:
        if i >= len(toks):
            raise ILError("E191", f"{ins.name} needs {what}", (ins.line, ins.col, ins.end_col), _OPERAND_HINT)
        return toks[i]

    @staticmethod
    def _nothing_after(toks: list, i: int, name: str) -> None:
        if i < len(toks):
            t = toks[i]
            what = "takes no operand" if t.kind not in (",", ":") else f"is not followed by {t.value!r}"
            raise ILError("E192", f"{name} {what}", (t.line, t.col, t.col + len(t.value)), _ONE_HINT)

    # ------------------------------------------------------------ operands

    def operand(self, toks: list, i: int) -> tuple:
        """(Operand, index after it) from toks[i]: a literal, an address or
        a variable (a.b, a[i], p^, w.0)."""
        first = t = toks[i]
        if t.kind in ("-", "+") and i + 1 < len(toks) and toks[i + 1].kind in _NUMBERS and toks[i + 1].start == t.end:
            last = toks[i + 1]
            return self._make(first, last, literal=True, signed=True), i + 2
        if t.kind in LITERALS or (t.kind == "NAME" and t.value.upper() in ("TRUE", "FALSE")):
            return self._make(first, t, literal=True), i + 1
        if t.kind == "LOCATED":
            return self._make(first, t, reads=frozenset((t.value.upper(),))), i + 1
        if t.kind != "NAME" or _reserved(t):
            raise ILError("E198", f"{t.value!r} is not an operand", t, _OPERAND_HINT)
        reads, risky, path = {t.value.upper()}, False, True
        i += 1
        while i < len(toks):
            t = toks[i]
            if t.kind == "." and i + 1 < len(toks) and toks[i + 1].kind in ("NAME", "INT", "REAL", "BIT_REF"):
                if toks[i + 1].kind == "NAME" and _reserved(toks[i + 1]):
                    raise ILError("E198", f"{toks[i + 1].value} is a keyword", toks[i + 1], _OPERAND_HINT)
                i += 2
            elif t.kind == "[":
                i, names = self._index(toks, i)
                reads |= names
                risky, path = True, False
            elif t.kind == "^":
                risky, path = True, False
                i += 1
            elif t.kind == ".":
                raise ILError("E198", "a name must follow '.'", t, _OPERAND_HINT)
            else:
                break
        return self._make(first, toks[i - 1], reads=frozenset(reads), risky=risky, path=path), i

    def _index(self, toks: list, i: int) -> tuple:
        """The subscript [ ... ] at toks[i]: (index after ']', names read)."""
        depth, start = 0, toks[i]
        names: set = set()
        while i < len(toks):
            t = toks[i]
            if t.kind in ("[", "("):
                depth += 1
            elif t.kind in ("]", ")"):
                depth -= 1
                if depth == 0:
                    return i + 1, names
            elif t.kind == "NAME":
                up = t.value.upper()
                if up in RESERVED and up not in _INDEX_WORDS:
                    raise ILError("E198", f"{t.value} is a keyword", t, _OPERAND_HINT)
                names.add(up)
            elif t.kind not in LITERALS and t.kind not in ("LOCATED", "BIT_REF") and t.kind not in _INDEX_PUNCT:
                raise ILError("E198", f"unexpected {t.value!r} in a subscript", t, _OPERAND_HINT)
            i += 1
        raise ILError("E198", "'[' is not closed on its line", start, _OPERAND_HINT)

    def _make(self, first: Tk, last: Tk, **kw) -> Operand:
        text = self.texts[first.line][first.start : last.end]
        return Operand(text, first.line, first.col, last.end + 1, **kw)

    def arguments(self, toks: list, i: int) -> tuple:
        """The arguments after '(' at toks[i - 1], to the matching ')' (on
        this line or a later one): ([Arg], (line, col) of ')')."""
        args: list = []
        want, comma = True, None  # an argument may come next; the ',' before it
        opener = toks[i - 1]
        while True:
            while i >= len(toks):  # the list goes on on the next line
                if self.r + 1 >= len(self.rows):
                    raise ILError("E193", "the argument list is not closed by ')'", opener, "close it with ')'")
                self.r += 1
                toks, i = self.rows[self.r][1], 0
            t = toks[i]
            if t.kind == ")":
                if comma is not None:
                    raise ILError("E198", "an argument is missing after ','", comma, _ARG_HINT)
                self._nothing_after(toks, i + 1, ")")
                return args, (t.line, t.col)
            if not want:
                if t.kind != ",":
                    raise ILError("E198", f"unexpected {t.value!r} in the argument list", t, _ARG_HINT)
                want, comma = True, t
                i += 1
                continue
            arg, i = self._argument(toks, i)
            args.append(arg)
            want, comma = False, None

    def _argument(self, toks: list, i: int) -> tuple:
        t = toks[i]
        nxt = toks[i + 1] if i + 1 < len(toks) else None
        if t.kind == "NAME" and t.value.upper() == "NOT" and nxt is not None and nxt.kind == "NAME":
            if i + 2 < len(toks) and toks[i + 2].kind == "=>":
                value, j = self._output(toks, i + 3)
                return Arg(nxt, "=>", True, value), j
        if t.kind == "NAME" and not _reserved(t) and nxt is not None and nxt.kind in (":=", "=>"):
            if nxt.kind == "=>":
                value, j = self._output(toks, i + 2)
                return Arg(t, "=>", False, value), j
            if i + 2 >= len(toks):
                raise ILError("E198", f"{t.value} := needs a value on its line", nxt, _ARG_HINT)
            value, j = self.operand(toks, i + 2)
            return Arg(t, ":=", False, value), j
        value, j = self.operand(toks, i)
        return Arg(None, ":=", False, value), j

    def _output(self, toks: list, i: int) -> tuple:
        if i >= len(toks) or toks[i].kind in (",", ")"):
            return None, i
        value, j = self.operand(toks, i)
        if value.literal:
            raise ILError(
                "E198",
                f"an output goes to a variable, not {value.text}",
                (value.line, value.col, value.end_col),
                _ARG_HINT,
            )
        return value, j


_MISSPELLED = {
    name: base
    for base, names in {
        "ADD": "ADDN",
        "SUB": "SUBN",
        "MUL": "MULN",
        "DIV": "DIVN",
        "MOD": "MODN",
        "JMP": "JMPN JMPNC",
        "CAL": "CALN CALNC",
        "RET": "RETN RETNC",
        "LD": "LDC LDCN",
        "ST": "STC STCN",
        "AND": "ANDC",
        "OR": "ORC",
        "XOR": "XORC",
    }.items()
    for name in names.split()
}
_PAREN_HINT = "'(' follows AND, OR, XOR, ADD, SUB, MUL, DIV, MOD, GT, GE, EQ, NE, LE, LT: AND( b ... )"
_ONE_HINT = "one instruction per line; only a function call takes several operands (MAX b, c)"
_OPERAND_HINT = "an operand is a variable (a, a.b, a[i], %IX0.1) or a literal (5, -1, 2.5, T#1s, INT#5, 'text')"
_ARG_HINT = "arguments are name := operand, name => variable, or operands in order: CAL t(IN := x, PT := T#1s)"
_EXAMPLE = {
    "LD": "LD x",
    "ST": "ST x",
    "S": "S x (set x to TRUE when the current result is TRUE)",
    "R": "R x (reset x to FALSE when the current result is TRUE)",
    "CAL": "CAL fb or CAL fb(IN := x)",
    "INPUT": "a function block instance: CLK trig",
}


def _report(report: Report, e: ILError) -> None:
    code, message, where, hint = e.args
    line, col, end = (where.line, where.col, where.col + len(where.value)) if isinstance(where, Tk) else where
    report(code, message, line, col, end, hint)


def read_il(texts: dict, first: int, last: int, lexer, report: Report) -> list:
    """The labels and instructions of lines first..last (texts: line ->
    blanked text). Problems go to report(code, message, line, col, end_col,
    hint); the lines with one are left out."""
    rows = []
    for n in range(first, last + 1):
        text = texts[n]
        if not text.strip():
            continue
        try:
            toks = tokenize(text, n, lexer)
        except ILError as e:
            _report(report, e)
            continue
        if toks:
            rows.append((n, toks))
    return _Reader(rows, texts).run(report)
