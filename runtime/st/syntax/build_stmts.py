"""The AST builder's statements: assignments, calls, IF, CASE and its labels,
loops, EXIT, CONTINUE, RETURN, jump labels and JMP, and statement lists."""

from __future__ import annotations

from .. import ast
from .build_exprs import ExprBuilder

_ASSIGN_OPS = {"ASSIGN": ":=", "S_ASSIGN": "S=", "R_ASSIGN": "R=", "REF_ASSIGN": "REF=", "QUERY_ASSIGN": "?="}


class StmtBuilder(ExprBuilder):
    """Rule callbacks of statements (see build_base.py)."""

    def body(self, c):
        return [s for s in c if s is not None]

    def _add_stmt(self, node):
        self.ctx.items.append(node)
        return node

    def assign_stmt(self, c):
        target, op, value = c
        return self._add_stmt(ast.Assign(target, value, _ASSIGN_OPS[op.type], pos=self._span(target, value)))

    def call_stmt(self, c):
        call = c[0]
        if not isinstance(call, ast.Call):
            self.ctx.report(
                "E001",
                "an expression alone is not a statement",
                call.pos,
                "assign it with ':=' or, to call a function block, add the argument list: fb();",
            )
            return None
        return self._add_stmt(ast.CallStmt(call, pos=call.pos))

    def set_stmt(self, c):
        return self._add_stmt(ast.SetReset(c[0].type, c[1], pos=self._span(c[0], c[1])))

    def empty_stmt(self, c):
        return None

    def if_stmt(self, c):
        branches = [(c[1], c[2])] + list(c[3:-2])
        return self._add_stmt(ast.If(branches, c[-2], pos=self._span(c[0], c[-1])))

    def elsif_part(self, c):
        return c[0], c[1]

    def case_stmt(self, c):
        return self._add_stmt(ast.Case(c[1], list(c[2:-2]), c[-2], pos=self._span(c[0], c[-1])))

    def case_branch(self, c):
        labels, body = c[:-1], c[-1]
        return ast.CaseBranch(labels, body, pos=self._span(labels[0], body[-1] if body else labels[-1]))

    def case_range(self, c):
        return ast.CaseRange(c[0], c[1], pos=self._span(c[0], c[1]))

    def label_name(self, c):
        t = c[0]
        parts = t.value.split(".")
        node = ast.Name(parts[0], pos=ast.Pos(self.file, t.line, t.column, t.line, t.column + len(parts[0])))
        col = t.column + len(parts[0]) + 1
        for p in parts[1:]:
            col += len(p)
            node = ast.Member(node, p, pos=ast.Pos(self.file, t.line, t.column, t.line, col))
            col += 1
        return node

    def for_stmt(self, c):
        var = ast.Name(c[1].value, pos=self._tpos(c[1]))
        return self._add_stmt(ast.For(var, c[2], c[3], c[4], c[5], pos=self._span(c[0], c[-1])))

    def while_stmt(self, c):
        return self._add_stmt(ast.While(c[1], c[2], pos=self._span(c[0], c[-1])))

    def repeat_stmt(self, c):
        return self._add_stmt(ast.Repeat(c[1], c[2], pos=self._span(c[0], c[-1])))

    def exit_stmt(self, c):
        return self._add_stmt(ast.Exit(pos=self._tpos(c[0])))

    def continue_stmt(self, c):
        return self._add_stmt(ast.Continue(pos=self._tpos(c[0])))

    def return_stmt(self, c):
        return self._add_stmt(ast.Return(pos=self._tpos(c[0])))

    def label_stmt(self, c):
        t = c[0]
        return self._add_stmt(ast.Label(t.value, pos=self._tpos(t)))

    def jmp_stmt(self, c):
        return self._add_stmt(ast.Jump(c[1].value, pos=self._span(c[0], c[1])))
