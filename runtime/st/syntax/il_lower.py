"""IL instructions (il_parse.py) lowered to ST on the lines they stand on.

    Lowering(items, out, report, fb_names, indent).run()

The current result (CR) is kept as an ST *expression*, not a variable (its
type is left to the checker): ``LD a / AND b / OR( c / ANDN d / ) / ST x``
becomes ``x := a AND b OR (c AND NOT d);``. Statements are written only
where IL has an effect:

  ST x / STN x      x := cr; / x := NOT cr;  (the CR is then x, or stays
                    what it was when that is a literal or a plain variable)
  S x / R x         IF cr THEN x := TRUE; END_IF; (FALSE for R); on a
                    function block instance: fb(S := cr); (fb(R := cr);)
  S1 R1 CLK CU CD PV IN PT fb     fb(CLK := cr);   (ed.2 Table 53)
  CAL fb(...)       fb(...);  CALC / CALCN: IF cr / IF NOT cr THEN ... END_IF;
  JMP L             JMP L;    JMPC / JMPCN: IF cr / IF NOT cr THEN JMP L; END_IF;
  RET               RETURN;   RETC / RETCN likewise
  label:            label:    (CODESYS ST labels)

After JMPC, JMPCN, RETC and RETCN not taken the CR is known: FALSE after C,
TRUE after CN (IEC: the CR is unchanged, and it was that value). After S,
R, CAL and the FB input operators it stays, as in MatIEC; read again, the
expression is evaluated again: E197 where the instruction changed what it
reads, or where it would call a function again. A CR dropped unread still
makes the function calls in it, as statements. A TRANSITION's IL
(condition) holds LD, operators and calls only; its last CR is written as
the condition.

The CR across a label a jump reaches: when the code after the label reads
the CR, it must do so with operators, function calls and parentheses ending
in ST or STN (the pattern ``LD a / JMP L / ... / L: ADD 1 / ST x``); that
code is then written on each way in: at each jump (with the CR there, TRUE
or FALSE after JMPC/JMPCN) and before the label for the fall-through. Other
reads of a CR across a label are E195. A label no jump names passes the CR
on.

Layout: each piece of ST goes at the line (and, where there is room, the
column) of the IL it comes from, after what is already written (Layout).
A statement starts on the line of its value's first piece, or of the first
DIV, MOD, subscript or dereference in it (where a runtime fault can arise,
so that the fault's line is that instruction's).
"""

from __future__ import annotations

from collections.abc import Callable

from .il_emit import ATOM, ST_OP, UNARY, Ex, Layout, Piece, binop, earliest, negate, wrap
from .il_parse import Instr, Label, Operand

# Instructions that do not read the CR (after a label: the CR is not needed)
_NO_READ = frozenset(("LD", "FORMAL"))
# Instructions that only compute a new CR (what may follow a label the CR crosses)
_PURE = frozenset((*ST_OP, "NOT", "FUNC"))
# What a transition's condition may hold
_CONDITION = frozenset((*_PURE, "LD", "FORMAL", ")"))
# Not inside parentheses (MatIEC's simple_instr_list: operators, LD, ST, calls)
_NOT_IN_PARENS = frozenset(("S", "R", "INPUT", "JMP", "CAL", "RET"))


class Undef:
    """The CR is not defined: why (for the message), and its code."""

    __slots__ = ("why", "code", "hint", "dead")

    def __init__(self, why: str, code: str = "E194", hint: str = "", dead: bool = False) -> None:
        self.why, self.code, self.hint = why, code, hint
        self.dead = dead  # after JMP or RET: no way leads here from above


_START = Undef("at the start of the body", hint="start with LD (or LDN) to load the current result")
_ERROR = Undef("", code="")  # after a reported problem: nothing more is said


Report = Callable[[str, str, int, int, int, str], None]


class Lowering:
    """One IL body to ST into out (a Layout). fb_names: the upper names the
    POU declares as function block instances (S and R on them are calls);
    indent: line -> column of its first token."""

    def __init__(self, items: list, out: Layout, report: Report, fb_names: set, indent: dict) -> None:
        self.items = items
        self.out = out
        self._report = report
        self.fb_names = fb_names
        self.indent = indent
        self.cr: Ex | Undef = _START
        self.stack: list = []  # open parentheses: (the CR before, the Instr)
        # writing a copy of the code after a label: its pieces go where the last
        # went, a statement of them alone on this line (None: not copying)
        self.pin: int | None = None
        self.failed = False
        self.condition = False  # a transition's condition: only the CR, written at the end
        self.groups: dict = {}  # UPPER label -> index of its group's first item
        self.prefix: dict = {}  # group -> (first, last) item of the code after it that reads the CR, or "bad"

    def report(self, code: str, message: str, line: int, col: int, end_col: int, hint: str) -> None:
        """Only the first problem: the body is left out, and what follows
        one problem is often another only because of it."""
        if not self.failed:
            self._report(code, message, line, col, end_col, hint)
        self.failed = True

    # ------------------------------------------------------------ the body

    def run(self) -> None:
        self._labels()
        items, i = self.items, 0
        while i < len(items):
            it = items[i]
            if self.condition and (isinstance(it, Label) or it.op not in _CONDITION):
                what = f"label {it.name}" if isinstance(it, Label) else it.name
                self.report(
                    "E199",
                    f"{what} in a transition's condition",
                    it.line,
                    it.col,
                    it.col + len(what),
                    "the IL of a transition computes its condition: LD, operators, parentheses and function calls; "
                    "the current result at its end is the condition",
                )
                return
            if isinstance(it, Label):
                i = self._group(i)
                continue
            if self.stack and it.op in _NOT_IN_PARENS:
                self.report(
                    "E196",
                    f"{it.name} inside parentheses",
                    it.line,
                    it.col,
                    it.end_col,
                    f"close the parenthesis opened by {self.stack[-1][1].name}( at line {self.stack[-1][1].line} "
                    "first: inside it go operators, LD, ST and function calls",
                )
            else:
                self._step(it)
            i += 1
        if self.stack:
            self._unclosed()
        if self.condition:
            last = items[-1] if items else None
            if isinstance(self.cr, Undef) and isinstance(last, Instr):
                self._read(last, why="the transition's condition")
            elif isinstance(self.cr, Ex):
                self._pieces(self.cr)
                self._put(";", 0, 0)
            return
        self._discard()

    def _unclosed(self) -> None:
        opener = self.stack[-1][1]
        self.report(
            "E193",
            f"{opener.name}( is not closed by ')'",
            opener.line,
            opener.col,
            opener.end_col,
            "end the parenthesised operand with ')' on a line of its own",
        )
        self.stack = []

    def _labels(self) -> None:
        items, jumped = self.items, set()
        for i, it in enumerate(items):
            if isinstance(it, Label):
                group = i if i == 0 or not isinstance(items[i - 1], Label) else self._group_start(i)
                self.groups.setdefault(it.name.upper(), group)
        for it in items:
            if isinstance(it, Instr) and it.op == "JMP":
                g = self.groups.get(it.operands[0].text.upper())
                if g is not None:
                    jumped.add(g)
        for g in jumped:
            self.prefix[g] = self._prefix_of(g)

    def _group_start(self, i: int) -> int:
        while i > 0 and isinstance(self.items[i - 1], Label):
            i -= 1
        return i

    def _prefix_of(self, g: int):
        """The code after the labels at g that reads the CR: (first, last)
        items, ending with ST or STN; None when it does not read the CR;
        "bad" when it reads it otherwise."""
        items, j = self.items, g
        while j < len(items) and isinstance(items[j], Label):
            j += 1
        first = j
        if j >= len(items) or items[j].op in _NO_READ or (items[j].op in ("JMP", "CAL", "RET") and not items[j].cond):
            return None
        depth = 0
        while j < len(items):
            it = items[j]
            if isinstance(it, Label):
                return "bad"
            if it.op == ")":
                if depth == 0:
                    return "bad"
                depth -= 1
            elif it.paren:
                depth += 1
            elif it.op == "ST" and depth == 0:
                return first, j
            elif it.op == "LD" and depth == 0:
                return None  # what came before is never used
            elif it.op not in _PURE and not (depth and it.op in ("LD", "FORMAL", "ST")):
                return "bad"
            j += 1
        return "bad"

    def _group(self, i: int) -> int:
        """The labels from items[i]; returns the index to go on from."""
        items, g = self.items, i
        labels = []
        while i < len(items) and isinstance(items[i], Label):
            labels.append(items[i])
            i += 1
        if self.stack:
            lab = labels[0]
            self.report(
                "E196",
                f"label {lab.name} inside parentheses",
                lab.line,
                lab.col,
                lab.col + len(lab.name),
                f"close the parenthesis opened by {self.stack[-1][1].name}( first",
            )
            self.stack = []
        if g not in self.prefix:  # no jump comes here: the CR goes on
            self._put_labels(labels)
            return i
        prefix = self.prefix[g]
        if isinstance(prefix, tuple):
            first, last = prefix
            if not (isinstance(self.cr, Undef) and self.cr.dead):
                self._apply(self._read(items[first]), prefix, labels[0].line)  # the way in from above
            self._put_labels(labels)
            target = items[last]
            cr = self._atom(target.operands[0])
            self.cr = self._carry(negate(cr, Piece("NOT", 0, 0)) if target.neg else cr)
            return last + 1
        if prefix == "bad":
            lab = labels[0]
            self.report(
                "E195",
                f"the current result crosses label {lab.name}, and the code after it reads it",
                lab.line,
                lab.col,
                lab.col + len(lab.name),
                "store it before the jump and the label (ST tmp) and load it after the label (LD tmp); "
                "softplc carries it across only into operators that end with ST",
            )
        self._discard()
        self._put_labels(labels)
        self.cr = Undef(
            f"after label {labels[0].name}, which a jump reaches",
            hint="load it after the label (LD x): the current result crosses a label only into operators "
            "that end with ST or STN",
        )
        return i

    def _put_labels(self, labels: list) -> None:
        for lab in labels:
            self.out.put(f"{lab.name}:", lab.line, lab.col)

    def _apply(self, value: Ex, prefix: tuple, line: int) -> None:
        """The code after a label (prefix) on value, written here (a
        statement of value's pieces alone: on line)."""
        saved = self.cr, self.stack, self.pin
        self.cr, self.stack, self.pin = value, [], line
        for it in self.items[prefix[0] : prefix[1] + 1]:
            self._step(it)
        self.cr, self.stack, self.pin = saved

    # ------------------------------------------------------------ one instruction

    def _step(self, it: Instr) -> None:
        op = it.op
        if op in ST_OP:
            left = self._read(it)
            if it.paren:
                self.stack.append((left, it))
                self.cr = (
                    self._atom(it.operands[0])
                    if it.operands
                    else Undef(f"at the start of {it.name}(", hint=f"write the operand after '(': {it.name}( b")
                )
                return
            right = self._atom(it.operands[0])
            if it.neg:
                right = negate(right, self._piece("NOT", it.line, 0))
            self.cr = self._binop(left, it, right)
        elif op == ")":
            if not self.stack:
                self.report("E193", "')' without an open parenthesis", it.line, it.col, it.col + 1, _RPAR_HINT)
                return
            inner = self._read(it)
            left, opener = self.stack.pop()
            if inner.prec < UNARY:  # IL's parentheses stay, for the reader
                inner = Ex(wrap(inner), ATOM, inner.reads, inner.calls, risky=inner.risky)
            if opener.neg:
                inner = negate(inner, self._piece("NOT", it.line, 0))
            self.cr = self._binop(left, opener, inner)
        elif op == "LD":
            self._discard()
            self.cr = self._atom(it.operands[0])
            if it.neg:
                self.cr = negate(self.cr, self._piece("NOT", it.line, it.col))
        elif op == "NOT":
            self.cr = negate(self._read(it), self._piece("NOT", it.line, it.col))
        elif op in ("FUNC", "FORMAL"):
            self._function(it)
        elif op == "ST":
            self._store(it)
        elif op in ("S", "R", "INPUT"):
            self._set_or_input(it)
        elif op == "CAL":
            self._cal(it)
        else:
            self._jump_or_return(it)

    def _binop(self, left: Ex, it: Instr, right: Ex) -> Ex:
        sym = ST_OP[it.op]
        risky = it.line if it.op in ("DIV", "MOD") and self.pin is None else 0
        return binop(left, sym, right, self._piece(sym, it.line, it.col), risky)

    def _function(self, it: Instr) -> None:
        """MAX b, c: MAX(cr, b, c); LIMIT( MN := 1, ... ): the call alone."""
        if it.op == "FUNC":
            first = self._read(it, call=True)
            parts = [first, *(self._atom(o) for o in it.operands)]
            pieces = [self._piece(it.name + "(", it.line, it.col)]
            for k, e in enumerate(parts):
                if k:
                    pieces.append(Piece(",", 0, 0))
                pieces.extend(e.pieces)
            pieces.append(Piece(")", 0, 0))
            reads = frozenset().union(*(e.reads for e in parts))
            calls = sum((e.calls for e in parts), ())
            risky = earliest(*(e.risky for e in parts))
        else:
            self._discard()
            args = it.args or []
            pieces = [self._piece(it.name + "(", it.line, it.col), *self._args(args)]
            pieces.append(self._piece(")", *it.close))
            reads = frozenset().union(*(a.value.reads for a in args if a.value is not None))
            calls, risky = (), 0
        e = Ex(pieces, ATOM, reads, (), risky=risky)
        e.calls = (*calls, (it.name, e))
        self.cr = e

    def _args(self, args: list) -> list:
        pieces: list = []
        for k, a in enumerate(args):
            if k:
                pieces.append(Piece(",", 0, 0))
            if a.name is not None:
                head = ("NOT " if a.negated else "") + f"{a.name.value} {a.kind}"
                pieces.append(self._piece(head, a.name.line, a.name.col))
            if a.value is not None:
                pieces.extend(self._atom(a.value).pieces)
        return pieces

    def _store(self, it: Instr) -> None:
        value = self._read(it)
        target = it.operands[0]
        stored = negate(value, Piece("NOT", 0, 0)) if it.neg else value
        self._assign(target, stored, it)
        if value.simple and target.root not in value.reads:
            self.cr = self._carry(value)  # ST leaves the CR as it was
        else:
            cr = self._atom(target)
            self.cr = self._carry(negate(cr, Piece("NOT", 0, 0)) if it.neg else cr)

    def _assign(self, target: Operand, value: Ex, it: Instr) -> None:
        head = self._head(value, it)
        self.out.put(target.text, head, self.indent.get(head, 0), self._src(target.line, target.col))
        self._put(":=", 0, 0)
        self._pieces(value)
        self._put(";", 0, 0)
        value.used = True

    def _set_or_input(self, it: Instr) -> None:
        value = self._read(it)
        target = it.operands[0]
        if it.op == "INPUT" or (target.path and "." not in target.text and target.root in self.fb_names):
            head = self._head(value, it)
            self.out.put(target.text + "(", head, self.indent.get(head, 0), self._src(target.line, target.col))
            self._put(f"{it.name.upper()} :=", 0, 0)
            self._pieces(value)
            self._put(");", 0, 0)
            value.used = True
        else:

            def assign() -> None:
                self._put(target.text, target.line, target.col)
                self._put(":= TRUE;" if it.op == "S" else ":= FALSE;", 0, 0)

            self._if(value, it, assign)
        self._after_effect(value, it, {target.root})

    def _cal(self, it: Instr) -> None:
        fb = it.operands[0]

        def call() -> None:
            self._put(fb.text + "(", fb.line, fb.col)
            for p in self._args(it.args or []):
                self._put(p.text, p.line, p.col)
            self._put(");", *(it.close if it.args is not None else (fb.line, 0)))

        value: Ex | None = None
        if it.cond:
            value = self._read(it)
            self._if(value, it, call)
        else:
            call()
            value = self.cr if isinstance(self.cr, Ex) else None
        if value is not None:
            changed = {fb.root} | {a.value.root for a in it.args or () if a.kind == "=>" and a.value is not None}
            self._after_effect(value, it, changed)

    def _after_effect(self, value: Ex, it: Instr, changed: set) -> None:
        """The CR stays what it was after S, R, CAL and the FB input
        operators: unless the instruction changed what it reads, or reading
        it again would call a function again."""
        if self.cr is not value:
            return
        self.cr = self._carry(value)
        hit = sorted(changed & value.reads)
        if hit:
            self.cr = Undef(
                f"it reads {hit[0]}, which {it.name} {it.operands[0].text} changed",
                code="E197",
                hint="store the current result (ST tmp) before that instruction and load it after it (LD tmp)",
            )
        elif value.calls and value.used:
            self.cr = Undef(
                f"it calls {value.calls[0][0]}, which would be called again",
                code="E197",
                hint=f"store the result of {value.calls[0][0]} (ST tmp) and load it again (LD tmp)",
            )

    def _jump_or_return(self, it: Instr) -> None:
        jump = it.op == "JMP"
        prefix = None
        if jump:
            label = it.operands[0]
            g = self.groups.get(label.text.upper())
            prefix = self.prefix.get(g) if g is not None else None

        def effect(value: Ex | None) -> None:
            if isinstance(prefix, tuple) and value is not None:
                self._apply(value, prefix, it.line)
            if jump:
                self._put("JMP", it.line, it.col)
                self._put(f"{label.text};", label.line, label.col)
            else:
                self._put("RETURN;", it.line, it.col)

        if not it.cond:
            if isinstance(prefix, tuple):
                effect(self._read(it, why=f"label {label.text} reads it"))
            else:
                self._discard()
                effect(None)
            self.cr = Undef(
                f"after {it.name}: nothing leads to this instruction",
                hint="put a label before it, or remove it",
                dead=True,
            )
            return
        value = self._read(it)
        known = "FALSE" if it.neg else "TRUE"  # the CR where the jump is taken
        self._if(value, it, lambda: effect(Ex([Piece(known, 0, 0)], simple=True)))
        self.cr = Ex([Piece("TRUE" if it.neg else "FALSE", 0, 0)], simple=True)

    def _if(self, cond: Ex, it: Instr, body: Callable[[], None]) -> None:
        if it.neg:
            cond = negate(cond, Piece("NOT", 0, 0))
        head = self._head(cond, it)
        self.out.put("IF", head, self.indent.get(head, 0))
        self._pieces(cond)
        self._put("THEN", 0, 0)
        body()
        self._put("END_IF;", 0, 0)
        cond.used = True

    # ------------------------------------------------------------ the CR

    def _read(self, it: Instr, call: bool = False, why: str = "") -> Ex:
        cr = self.cr
        if isinstance(cr, Ex):
            return cr
        if cr.code:
            what = f"{it.name} reads the current result" + (f" ({why})" if why else "")
            if call:
                what = f"{it.name}: a function call takes the current result as its first argument"
            hint = cr.hint
            if call:
                hint += f"; or, if {it.name} is meant as an IL operator: they are LD, ST, S, R, AND, OR, XOR, NOT, "
                hint += "ADD, SUB, MUL, DIV, MOD, GT, GE, EQ, NE, LE, LT, JMP, CAL, RET (with N, C, '(')"
            self.report(cr.code, f"{what}, which is undefined {cr.why}", it.line, it.col, it.end_col, hint)
        self.cr = _ERROR
        return Ex([Piece("FALSE", 0, 0)])

    def _discard(self) -> None:
        """The CR is dropped: function calls in it that nothing evaluated
        are made here as statements (their side effects happen, as in IL)."""
        cr = self.cr
        if isinstance(cr, Ex) and not cr.used:
            for _name, call in cr.calls:
                if not call.used:
                    self._pieces(call)
                    self._put(";", 0, 0)
                    call.used = True

    def _atom(self, o: Operand) -> Ex:
        prec = UNARY if o.signed else ATOM
        return Ex(
            [self._piece(o.text, o.line, o.col)],
            prec,
            o.reads,
            simple=o.literal or o.path,
            risky=o.line if o.risky and self.pin is None else 0,
        )

    def _head(self, e: Ex, it: Instr) -> int:
        """The line a statement reading e starts on: of the first piece of e
        where it may fault, or of its first piece, or (e read before, or
        all of it carried) the instruction's."""
        if e.risky:
            return e.risky
        for p in e.pieces:
            if p.line:
                return p.line
        return it.line if self.pin is None else self.pin

    @staticmethod
    def _carry(e: Ex) -> Ex:
        """e read again by a later instruction: written where that one is."""
        c = Ex([Piece(p.text, 0, 0) for p in e.pieces], e.prec, e.reads, e.calls, e.simple)
        c.used = e.used
        return c

    # ------------------------------------------------------------ writing

    def _piece(self, text: str, line: int, col: int) -> Piece:
        return Piece(text, line, col) if self.pin is None else Piece(text, 0, 0)

    def _put(self, text: str, line: int, col: int) -> None:
        if self.pin is not None:
            line = col = 0
        self.out.put(text, line, col)

    def _src(self, line: int, col: int) -> tuple | None:
        return (line, col) if self.pin is None else None

    def _pieces(self, e: Ex) -> None:
        for p in e.pieces:
            self.out.put(p.text, p.line, p.col)


_RPAR_HINT = "')' ends an operand opened with AND(, OR(, ADD( ...; remove it or open one"
__all__ = ["Layout", "Lowering"]
