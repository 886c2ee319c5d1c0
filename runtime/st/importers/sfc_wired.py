"""A transition condition wired to a graph drawn in the chart (TC6: the
transition's ``<condition><connectionPointIn>``): an ``<inVariable>`` (as
CODESYS draws every condition), LD contacts from the left rail, FBD
blocks. network.py evaluates it (``condition``): an ST expression, and
the statements it needs before it (function block calls, edge memories).

Those statements run every cycle, as Beremiz runs them (in an action of
the initial step, S) and CODESYS (which evaluates every transition each
cycle unless CalcActiveTransOnly): they become an ACTION of their own,
associated S with the initial step, and the condition reads the blocks'
outputs as that action left them.
"""

from __future__ import annotations

from dataclasses import dataclass

from .bodies import BodyOut, ImportProblem
from .network import Graph, GraphError, condition
from .sfc_graph import Chart, Transition
from .view import LineView
from .xmlsafe import PosElement


@dataclass(eq=False)
class Wired:
    """A wired condition: its expression (with the original position of an
    inVariable's text, else None) and the statements it needs (a view at
    the transition's lines; empty for a plain expression)."""

    expr: str
    origin: tuple | None
    calls: LineView


def wired_condition(chart: Chart, t: Transition, cpi: PosElement) -> Wired | None:
    """t's condition wired from cpi; None when it cannot be evaluated
    (reported at the element, with network.py's code)."""
    out = chart.out
    if chart.graph is None:
        try:
            chart.graph = Graph(chart.sfc, out, foreign=True)
        except GraphError as exc:
            code, message, el, hint = exc.args
            out.error(code, message, el, hint)
            chart.graph = False
    if not isinstance(chart.graph, Graph):
        return None
    calls = LineView(len(out.view.lines))
    sub = BodyOut(calls, out.texts, out.path, out.diags, out.pou, out.owner)
    first = t.el.line + 1 if t.el.end_line > t.el.line else t.el.line
    try:
        expr = condition(chart.graph, cpi, sub, first, t.el.end_line)
    except GraphError as exc:  # (one condition() raises before it turns them into ImportProblem)
        code, message, el, hint = exc.args
        out.error(code, message, el, hint)
        return None
    except ImportProblem as exc:
        message, el, hint = exc.args
        code, sep, rest = message.partition(": ")
        if not (sep and len(code) == 4 and code[0] in "EW" and code[1:].isdigit()):
            code, rest = "E216", message
        out.error(code, rest, el if el is not None else t.el, hint)
        return None
    for d in sub.decls:
        out.declare(d)
    return _positioned(chart, cpi, Wired(expr, None, calls))


def _positioned(chart: Chart, cpi: PosElement, wired: Wired) -> Wired:
    """A condition wired straight to an <inVariable>: its own text, with
    the position of its <expression> for the positions of its tokens."""
    refs = [c.get("refLocalId", "") for c in cpi.kids("connection")]
    el = chart.nodes.get(refs[0]) if len(refs) == 1 else None
    expr = el.kid("expression") if el is not None and el.name == "inVariable" else None
    raw = "".join(expr.itertext()) if expr is not None else ""
    text = raw.strip()
    if expr is None or "\n" in text or wired.expr not in (text, f"( {text} )"):
        return wired
    line, col = chart.out.texts.start(expr)
    if "\n" in raw[: raw.index(text)]:
        return wired
    return Wired(text, (line, col + raw.index(text)), wired.calls)
