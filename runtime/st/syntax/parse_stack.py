"""The LALR(1) parser's stacks for one parse: feeding a token (with undo on
rejection), reading tokens, and error reports with their limits.

The table comes from st_grammar.py; a reduction calls the rule's builder
method (build_*.py), so the value stack holds tokens and AST nodes. Error
recovery (parse_recovery.py) and the driver (parser.py) build on this.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from .. import ast
from ..diagnostics import DiagnosticBag
from ..limits import MAX_ERRORS
from .lexer import Tok, line_col
from .st_grammar import Grammar


class TooDeep(Exception):
    """More than MAX_NESTING entries on the parser's stack (E006; it grows
    by 1-4 entries per level: a parenthesis, a unary operator, IF in IF);
    args: the token."""


class GiveUp(Exception):
    """MAX_ERRORS reported: the rest of the file is not worth reading."""


class Rejected(Exception):
    """The parser does not accept this token here."""


class ParserCore:
    """The state of one parse: stacks, tokens, reports."""

    def __init__(self, text: str, path: str, diags: DiagnosticBag, g: Grammar) -> None:
        self.g = g
        self.raw = text
        self.text = text  # with comments blanked (set by the driver)
        self.path = path
        self.diags = diags
        self.items: list = []  # nodes a pragma can attach to
        self.pou_headers: list = []  # (POU, start, header end)
        self.errors = 0
        self.calm = 0  # tokens to shift before the next error is reported
        self.comment_trouble = False
        self.skipping = False  # recovery is reading tokens: no parser context
        self.strays: dict = {}  # END_* whose block recovery dropped -> how many
        self.last: Tok | None = None
        self.state_stack = [g.start_state]
        self.value_stack: list = []
        self.tokens: Iterator[Tok] = iter(())
        self.builder: Any = g.builder(self)  # the AST builder (build_decls.AstBuilder)

    # -- diagnostics
    def report(
        self, code: str, message: str, pos: ast.Pos, hint: str | None = None, always: bool = False, calm: int = 0
    ) -> None:
        """Add an error, unless it is an echo of the previous one (``always``
        overrides). ``calm``: errors at that many next tokens are echoes."""
        quiet = self.calm and not always
        self.calm = max(self.calm, calm)
        if quiet:
            return
        self.errors += 1
        if self.errors > MAX_ERRORS:
            raise GiveUp
        self.diags.error(code, message, pos, hint)

    def _pos_at(self, line: int, col: int, end_col: int = 0) -> ast.Pos:
        return ast.Pos(self.path, line, col, line, end_col or col + 1)

    def _tok_pos(self, t: Tok) -> ast.Pos:
        if t.type == "$END":
            return self._eof_pos()
        return ast.Pos(self.path, t.line, t.column, t.line, t.end_column)

    def _eof_pos(self) -> ast.Pos:
        line, col = line_col(self.raw, len(self.raw))
        return ast.Pos(self.path, line, col, line, col)

    # -- the stacks
    def _feed(self, token: Tok, is_end: bool = False) -> Any:
        """Shift the token, after the reductions it calls for (building their
        values), and return the value of the start rule if it ended the
        parse. LALR may reduce before it notices that the token does not fit
        (a statement list into a body, say); on rejection (``Rejected``)
        those reductions are taken back, so that recovery sees the stack as
        it was."""
        states, values = self.state_stack, self.value_stack
        rows, gotos, builder, end_state = self.g.rows, self.g.goto, self.builder, self.g.end_state
        chains = self.g.unit_chains
        ttype = token.type
        undo: list[Any] | None = None  # top states (pass-throughs) and (action, children[, length])
        while True:
            top = states[-1]
            action: Any = rows[top].get(ttype)  # a state (int), a Reduce or None
            if action.__class__ is int:  # (the fastest test)
                states.append(action)
                values.append(token)
                return None
            if action is None:
                if undo:
                    self._undo(undo)
                raise Rejected
            if action.unit:  # a chain of pass-throughs: one new top state
                goto = chains.get((states[-2], top, ttype))
                if goto is None:
                    goto = self.g.unit_chain(states[-2], top, ttype)
                states[-1] = goto
                if undo is None:
                    undo = []
                undo.append(top)
                if is_end and goto == end_state:
                    return values[-1]
                continue
            size = action.size
            if size:
                children = values[-size:]
                del states[-size:]
                del values[-size:]
            else:
                children = []
            if undo is None:
                undo = []
            alias = action.alias
            undo.append((action, children) if alias is None else (action, children, len(children[alias])))
            build = action.build
            value = children[0] if build is None else build(builder, children)
            goto = gotos[states[-1]][action.origin]
            states.append(goto)
            values.append(value)
            if is_end and goto == end_state:
                return value

    def _undo(self, undo: list) -> None:
        states, values, gotos = self.state_stack, self.value_stack, self.g.goto
        for entry in reversed(undo):
            if entry.__class__ is int:  # pass-throughs: the top state they replaced
                states[-1] = entry
                continue
            action, children = entry[0], entry[1]
            states.pop()
            values.pop()
            if len(entry) == 3:
                del children[action.alias][entry[2] :]
            for symbol in action.symbols:  # the states the children were shifted with
                states.append(gotos[states[-1]][symbol])
            values.extend(children)

    def _synthetic(self, ttype: str, at: Tok, after: bool = True) -> Tok:
        """A token the parser is given by recovery, placed just after (or on) at."""
        t = Tok(
            ttype,
            self.g.spelling(ttype),
            at.end_pos if after else at.start_pos,
            at.line,
            at.end_column if after else at.column,
        )
        t.end_column = t.column  # it takes no room in the text
        return t

    # -- tokens
    def _end_token(self) -> Tok:
        line, col = line_col(self.text, len(self.text))
        return Tok("$END", "", len(self.text), line, col)

    def _next_token(self) -> Tok:
        """The next token, read without parser context (while skipping)."""
        self.skipping = True
        try:
            tok = next(self.tokens, None)
        finally:
            self.skipping = False
        if tok is None:
            return self._end_token()
        self.last = tok
        return tok
