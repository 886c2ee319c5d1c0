"""A transition condition wired to the chart's own graph (TC6: the
transition's ``<condition><connectionPointIn>``), in the two shapes that
need no FBD/LD evaluation: a variable or literal (``<inVariable>``, as
CODESYS writes every transition: ``<expression>TRUE</expression>``), and
a series of contacts from the left power rail (``var AND NOT var2``). A
graph with blocks, parallel branches or edge contacts is E216 (the FBD/LD
evaluation of the graphical bodies will take it).
"""

from __future__ import annotations

from .sfc_graph import Chart, Transition
from .xmlsafe import PosElement

_NOT_TEXT = ("\n", ";", "//", "(*", "*)", "/*", "{", "}")


def wired_condition(chart: Chart, t: Transition, cpi: PosElement) -> tuple | None:
    """(anchor line, (line, column), expression) of t's wired condition:
    an <inVariable> drawn just before the transition (CODESYS) is where
    the condition is written; else the <condition>. None: reported."""
    refs = chart.inputs(t.condition) if t.condition is not None else []
    el = chart.nodes.get(refs[0]) if len(refs) == 1 else None
    if el is not None and el.name == "inVariable":
        expr = el.kid("expression")
        text = _expression(chart, expr if expr is not None else el)
        if text is None:
            return None
        negated = el.get("negated") == "true"
        kids = chart.sfc.kids()
        k = next(i for i, x in enumerate(kids) if x is t.el)
        if not negated and expr is not None and k > 0 and kids[k - 1] is el:
            return el.line, chart.out.texts.start(expr), text
        return t.el.line, (cpi.line, cpi.col), f"NOT ({text})" if negated else text
    if el is not None and el.name == "contact":
        text = _contacts(chart, el)
        return None if text is None else (t.el.line, (cpi.line, cpi.col), text)
    what = f"<{el.name}>" if el is not None else "more than one element" if refs else "nothing"
    chart.out.error(
        "E216",
        f"a transition condition wired to {what}: softplc imports a wired condition only as a variable "
        "or a series of contacts, not yet a graph of blocks",
        t.condition or t.el,
        "write the condition as an inline ST expression, or as a named transition in ST",
    )
    return None


def _contacts(chart: Chart, el: PosElement) -> str | None:
    """The AND of a series of contacts back to the left power rail."""
    parts: list = []
    seen: set = set()
    while el.name == "contact" and id(el) not in seen:
        seen.add(id(el))
        if (el.get("edge") or "none") != "none":
            chart.out.error(
                "E216",
                f"a condition with an edge contact ({el.get('edge')}): not imported yet",
                el,
                "write the condition as an inline ST expression with R_TRIG/F_TRIG in an action",
            )
            return None
        var = el.kid("variable")
        text = _expression(chart, var if var is not None else el)
        if text is None:
            return None
        text = text if all(c.isalnum() or c in "_.#[]" for c in text) else f"({text})"
        parts.append(f"NOT {text}" if el.get("negated") == "true" else text)
        refs = chart.inputs(el)
        nxt = chart.nodes.get(refs[0]) if len(refs) == 1 else None
        if nxt is None:
            chart.out.error(
                "E216",
                "a condition's contacts in parallel or unconnected: not imported yet",
                el,
                "write the condition as an inline ST expression",
            )
            return None
        el = nxt
    if el.name != "leftPowerRail":
        chart.out.error("E216", f"a condition's contact follows <{el.name}>: not imported yet", el, None)
        return None
    return " AND ".join(parts)


def _expression(chart: Chart, el: PosElement) -> str | None:
    """An element's text as one ST expression (nothing that would end it
    or open a comment)."""
    text = "".join(el.itertext()).strip()
    if not text or any(bad in text for bad in _NOT_TEXT):
        chart.out.error(
            "E216",
            f"{text[:40]!r} is not one line of ST expression" if text else "an empty expression",
            el,
            "a wired condition's variable holds a variable, a literal or an expression on one line",
        )
        return None
    return text
