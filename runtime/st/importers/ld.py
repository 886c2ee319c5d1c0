"""The elements of an LD network (PLCopen TC6 0201) as ST: power rails,
contacts and coils (blocks and variables in LD are FBD's: fbd.py).

The power flow is a BOOL: the left rail is TRUE, a contact gives the flow
it receives AND its variable (NO), AND NOT it (NC, negated="true"), AND the
rising (P, edge="rising") or falling (N) edge of its variable, detected by a
hidden R_TRIG/F_TRIG called every evaluation, whatever the flow. Several
connections into one point are their OR (parallel branches). A coil writes
the flow it receives to its variable: plain, negated (NOT), SET
(storage="set": TRUE when the flow is), RESET, P/N (edge: TRUE for the one
evaluation where the flow rises/falls); it passes the flow on to its right.
The right rail is ignored. A flow two elements read is kept in a hidden BOOL
so it is evaluated once.
"""

from __future__ import annotations

from .bodies import LANGUAGES
from .fbd import assign, expression, modified
from .network import IS_UNIT, KINDS, UNIT, VALUE, Expr, GraphError, Link, Net, Node, group, translate_graph


def _power(net: Net, node: Node) -> Expr | None:
    """The flow into node (None: the left rail itself)."""
    value = net.value(node.ins[0], node) if node.ins else None
    if value is None:
        raise GraphError("E202", f"this {node.kind} is not connected on its left", node.el, "connect it to the rail")
    return None if [t for t, _ in value] == ["TRUE"] else value


def contact(net: Net, node: Node, link: Link) -> Expr:
    def make() -> Expr:
        var = expression(net, node, "variable")
        term = modified(net, node, var, node.el.get("negated") == "true", node.el.get("edge", ""))
        flow = _power(net, node)
        return term if flow is None else [*group(flow, node), ("AND", node.origin), *group(term, node)]

    return net.shared(node, "BOOL", make)


def coil_flow(net: Net, node: Node) -> Expr:
    """The flow through a coil: read by the coil and by what its right side feeds."""

    def make() -> Expr:
        return _power(net, node) or [("TRUE", node.origin)]

    return net.shared(node, "BOOL", make, uses=1 + net.uses.get(node.id, 0))


def coil(net: Net, node: Node) -> None:
    flow = coil_flow(net, node)
    el = node.el
    storage = el.get("storage", "")
    if storage not in ("set", "reset"):
        flow = modified(net, node, flow, el.get("negated") == "true", el.get("edge", ""))
    assign(net, node, expression(net, node, "variable"), flow, storage)


VALUE.update(
    leftPowerRail=lambda net, node, link: [("TRUE", node.origin)],
    contact=contact,
    coil=lambda net, node, link: coil_flow(net, node),
)
UNIT.update(coil=coil)
IS_UNIT.update(contact=lambda net, node: False)
KINDS.update(("leftPowerRail", "contact", "coil"))

LANGUAGES["LD"] = translate_graph
