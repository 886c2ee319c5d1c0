"""The AST builder's expressions: operators by precedence, operands, literals,
names, member and index access, calls and their arguments."""

from __future__ import annotations

from .. import ast
from ..limits import MAX_OPERATORS
from .build_base import BuilderBase
from .lexer import Tok
from .literals import (
    LiteralError,
    parse_based,
    parse_c_hex,
    parse_hash_literal,
    parse_int,
    parse_located,
    parse_real,
    parse_string,
)

_BINARY_OPS = {
    "OR": "OR",
    "OR_ELSE": "OR_ELSE",
    "XOR": "XOR",
    "AND": "AND",
    "AMP": "AND",
    "AND_THEN": "AND_THEN",
    "EQ": "=",
    "NE": "<>",
    "LT": "<",
    "GT": ">",
    "LE": "<=",
    "GE": ">=",
    "PLUS": "+",
    "MINUS": "-",
    "STAR": "*",
    "SLASH": "/",
    "MOD": "MOD",
    "POW": "**",
}
_PRECEDENCE = {
    "OR": 1,
    "OR_ELSE": 1,
    "XOR": 2,
    "AND": 3,
    "AMP": 3,
    "AND_THEN": 3,
    "EQ": 4,
    "NE": 4,
    "LT": 5,
    "GT": 5,
    "LE": 5,
    "GE": 5,
    "PLUS": 6,
    "MINUS": 6,
    "STAR": 7,
    "SLASH": 7,
    "MOD": 7,
    "POW": 8,
}
_UNARY_OPS = {"MINUS": "-", "PLUS": "+", "NOT": "NOT"}


class ExprBuilder(BuilderBase):
    """Rule callbacks of expressions (see build_base.py)."""

    def expr(self, c):
        """operand, op, operand, ... -> Binary nodes by IEC precedence
        (all operators associate to the left)."""
        file = self.file
        if len(c) // 2 > MAX_OPERATORS:  # operand, op, operand, ...: len(c) // 2 operators
            # a bound on the time and memory one expression takes (docs/reference/language.md "Limits")
            self.ctx.report(
                "E006",
                f"expression too long (more than {MAX_OPERATORS:,} operators)",
                self._span(c[0], c[-1]),
                "split it, using intermediate variables",
                always=True,
            )
            return c[0]
        operands, ops = [c[0]], []

        def combine():
            op, right = ops.pop(), operands.pop()
            left = operands.pop()
            lp, rp = left.pos, right.pos
            operands.append(
                ast.Binary(
                    _BINARY_OPS[op.type], left, right, pos=ast.Pos(file, lp.line, lp.col, rp.end_line, rp.end_col)
                )
            )

        for i in range(1, len(c), 2):
            op = c[i]
            rank = _PRECEDENCE[op.type]
            while ops and _PRECEDENCE[ops[-1].type] >= rank:
                combine()
            ops.append(op)
            operands.append(c[i + 1])
        while ops:
            combine()
        return operands[0]

    def unary(self, c):
        op, operand = c
        return ast.Unary(_UNARY_OPS[op.type], operand, pos=self._span(op, operand))

    def paren(self, c):
        node = c[1]  # no node of its own; the inner one spans the parentheses
        node.pos = self._span(c[0], c[2])
        return node

    def _number(self, token, parse, kind: str, fallback, **extra) -> ast.Literal:
        """A numeric literal; a malformed one is reported (E003) and read as
        the fallback so that checking goes on."""
        try:
            value = parse(token.value)
        except LiteralError as e:
            self._literal_error(e, token)
            value = fallback
        if "__" in token.value:
            extra["doubled_underscore"] = True
        return ast.Literal(kind, value, pos=self._tpos(token), **extra)

    def int_lit(self, c):
        return self._number(c[0], parse_int, "int", 0)

    def real_lit(self, c):
        return self._number(c[0], parse_real, "real", 0.0)

    def based_lit(self, c):
        return self._number(c[0], parse_based, "int", 0)

    def c_hex_lit(self, c):
        return self._number(c[0], parse_c_hex, "int", 0, c_hex=True)

    def hash_lit(self, c):
        try:
            node = parse_hash_literal(c[0].value)
        except LiteralError as e:
            self._literal_error(e, c[0])
            node = ast.Literal("int", 0)
        if isinstance(node, ast.Literal) and node.kind in ("int", "real") and "__" in c[0].value:
            node.doubled_underscore = True
        node.pos = self._tpos(c[0])
        return node

    def string_lit(self, c):
        t = c[0]
        try:
            value = parse_string(t.value)
        except LiteralError as e:
            self._literal_error(e, t)
            value = ""
        return ast.Literal("wstring" if t.type == "WSTRING_LIT" else "string", value, pos=self._tpos(t))

    def bool_lit(self, c):
        return ast.Literal("bool", c[0].type == "TRUE", pos=self._tpos(c[0]))

    def name(self, c):
        t = c[0]
        return ast.Name(t.value, pos=ast.Pos(self.file, t.line, t.column, t.end_line, t.end_column))

    def _address(self, t: Tok) -> ast.LocatedAddress:
        try:
            return parse_located(t.value)
        except LiteralError as e:
            self._literal_error(e, t)
            return ast.LocatedAddress("M", "", (0,), text=t.value)

    def located(self, c):
        return ast.Located(self._address(c[0]), pos=self._tpos(c[0]))

    def member(self, c):
        base, t = c
        if isinstance(base, ast.Name):
            self.qualified_bases.add(base.name.upper())
        return ast.Member(base, t.value, pos=self._span(base, t))

    def bit_access(self, c):
        base, t = c
        size = "X"
        if t.type == "BIT_REF":  # %X3, or a partial access %B0 %W1 %D0 %L0
            size = t.value[1].upper()
            t = Tok("INT", t.value[2:], t.start_pos + 2, t.line, t.column + 2)
        return ast.BitAccess(base, self.int_lit([t]), size, pos=self._span(base, t))

    def index(self, c):
        return ast.Index(c[0], list(c[2:-1]), pos=self._span(c[0], c[-1]))

    def deref(self, c):
        return ast.Deref(c[0], pos=self._span(c[0], c[1]))

    def assign_expr(self, c):
        """(target := value) as an expression (CODESYS), or target := value
        unparenthesised as a condition or an assignment's value; the checker
        decides."""
        if len(c) == 3:
            return ast.AssignExpr(c[0], c[2], pos=self._span(c[0], c[2]))
        return ast.AssignExpr(c[1], c[3], pos=self._span(c[0], c[4]))

    def paren_deref(self, c):
        """(expr)^: the parenthesised pointer, dereferenced (CODESYS)."""
        return ast.Deref(self.paren(c[:3]), pos=self._span(c[0], c[3]))

    def call(self, c):
        callee, lpar, args, rpar = c
        if (
            isinstance(callee, ast.Name)
            and callee.name.upper() == "NOT"
            and len(args) == 1
            and args[0].name is None
            and not args[0].output
            and args.trailing_comma is None
        ):
            # NOT (x): the lexer made NOT a name (NOT(IN := x) is the function);
            # with one positional argument it is the operator, as it always was
            operand = args[0].value
            operand.pos = self._span(lpar, rpar)
            return ast.Unary("NOT", operand, pos=self._span(callee, rpar))
        return ast.Call(callee, args, trailing_comma=args.trailing_comma, pos=self._span(callee, rpar))

    def arg_list(self, c):
        # (c may be a list the parser reuses: read it, never change it)
        comma = c[-1] if c and isinstance(c[-1], Tok) else None
        return ast.ArgList(
            (
                a if isinstance(a, ast.Arg) else ast.Arg(None, a, pos=a.pos)
                for a in c
                if a is not None and a is not comma
            ),
            self._span(comma, comma) if comma is not None else None,
        )

    def named_arg(self, c):
        return ast.Arg(c[0].value, c[1], pos=self._span(c[0], c[1]))

    def output_arg(self, c):
        name, arrow, target = c
        return ast.Arg(name.value, target, output=True, pos=self._span(name, target if target is not None else arrow))

    def negated_output_arg(self, c):
        _, name, _, target = c
        return ast.Arg(name.value, target, output=True, negated=True, pos=self._span(c[0], target))
