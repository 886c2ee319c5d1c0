"""What every part of the AST builder shares: the parse it builds for, and
source positions of tokens and nodes.

The builder's methods are the grammar's rule callbacks: the parser calls
``method(builder, children)`` when it reduces the rule (st_grammar.py binds
them), and the value returned is what the parent rule gets as a child.
The builder is made per parse (one instance, one file). The parts:
build_exprs.py (expressions and literals), build_stmts.py (statements),
build_decls.py (declarations, POUs, configurations: the complete builder).
"""

from __future__ import annotations

from typing import Any, Protocol

from .. import ast
from ..diagnostics import DiagnosticBag
from .lexer import Tok
from .literals import LiteralError


class BuildContext(Protocol):
    """The parse a builder works for."""

    path: str
    diags: DiagnosticBag
    items: list  # nodes a pragma can attach to, in the order built
    pou_headers: list  # (POU, start, header end): pragmas there go to the POU

    def report(
        self, code: str, message: str, pos: ast.Pos, hint: str | None = None, always: bool = False, calm: int = 0
    ) -> None: ...


# A child of a rule: a Tok, or a node built by another rule.
Child = Any


def start_of(x: Child) -> tuple:
    if isinstance(x, Tok):
        return x.line, x.column
    return x.pos.line, x.pos.col


def end_of(x: Child) -> tuple:
    if isinstance(x, Tok):
        return x.end_line, x.end_column
    return x.pos.end_line, x.pos.end_col


class BuilderBase:
    """Positions and error reports; the rule methods are in the subclasses."""

    def __init__(self, ctx: BuildContext) -> None:
        self.ctx = ctx
        self.file = ctx.path
        self.qualified_bases: set = set()  # names before a '.' (ast.SourceFile)

    def _tpos(self, t: Tok) -> ast.Pos:
        return ast.Pos(self.file, t.line, t.column, t.end_line, t.end_column)

    def _span(self, first: Child, last: Child) -> ast.Pos:
        return ast.Pos(self.file, *start_of(first), *end_of(last))

    def _literal_error(self, e: LiteralError, tok: Tok) -> None:
        self.ctx.report("E003", e.message, self._tpos(tok), e.hint, always=True)
