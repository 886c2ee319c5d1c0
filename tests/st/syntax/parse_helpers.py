"""Helpers of the parser's tests: parse ST text, and show what came out."""

from __future__ import annotations

from pathlib import Path

from softplc.runtime.st import ast
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.syntax.parser import parse_source

REPO = Path(__file__).resolve().parents[3]


def parse(text: str, path: str = "test.st"):
    diags = DiagnosticBag()
    sf = parse_source(text, path, diags)
    return sf, diags.items


def ok(text: str, path: str = "test.st") -> ast.SourceFile:
    sf, diags = parse(text, path)
    assert not [d for d in diags if d.is_error], "\n".join(d.format() for d in diags)
    return sf


def body(text: str) -> list:
    """The statements of a file of bare statements."""
    [pou] = ok(text).decls
    return pou.body


def expr(text: str):
    [stmt] = body(f"x := {text};")
    return stmt.value


def errors(text: str) -> list:
    return [d for d in parse(text)[1] if d.is_error]


def show(e) -> str:
    """A compact, unambiguous rendering of an expression."""
    if isinstance(e, ast.Binary):
        return f"({e.op} {show(e.left)} {show(e.right)})"
    if isinstance(e, ast.Unary):
        return f"({e.op} {show(e.operand)})"
    if isinstance(e, ast.Name):
        return e.name
    if isinstance(e, ast.Literal):
        return repr(e.value)
    if isinstance(e, ast.Member):
        return f"{show(e.base)}.{e.name}"
    if isinstance(e, ast.BitAccess):
        return f"{show(e.base)}.%X{show(e.bit)}"
    if isinstance(e, ast.Index):
        return f"{show(e.base)}[{', '.join(show(i) for i in e.indices)}]"
    if isinstance(e, ast.Deref):
        return f"{show(e.base)}^"
    if isinstance(e, ast.Call):
        return f"{show(e.callee)}({', '.join(show(a) for a in e.args)})"
    if isinstance(e, ast.Arg):
        value = "" if e.value is None else show(e.value)
        if e.name is None:
            return value
        return f"{'NOT ' if e.negated else ''}{e.name}{' => ' if e.output else ' := '}{value}".rstrip()
    if isinstance(e, ast.Located):
        return e.addr.text
    if isinstance(e, ast.EnumLiteral):
        return f"{e.type_name}#{e.value_name}"
    if isinstance(e, ast.SchneiderAddress):
        return "ADR#" + ".".join(e.parts)
    if isinstance(e, ast.CaseRange):
        return f"{show(e.lo)}..{show(e.hi)}"
    raise AssertionError(f"no rendering for {e!r}")


def span(node) -> tuple:
    p = node.pos
    return p.line, p.col, p.end_line, p.end_col
