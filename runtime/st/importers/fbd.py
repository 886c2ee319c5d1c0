"""The elements of an FBD network (PLCopen TC6 0201) as ST: variables,
blocks, connectors, jumps, labels and returns (network.py orders them).

- ``inVariable``: its <expression>, read where a wire takes it (as Beremiz
  does); ``outVariable``: ``target := value;`` (nothing, with W202, when no
  wire reaches it: Beremiz leaves it out too); ``inOutVariable``: both (its
  assignment first, then what reads it). negated/edge/storage modifiers on
  them as on a coil.
- ``block`` with an instanceName, or of a FUNCTION_BLOCK type: one call a
  network evaluation with the connected inputs (``inst(IN := ..., PT :=
  ...);``), its outputs read as ``inst.Q``. A standard function: an
  expression, where it is read (pure; a hidden variable of its result type
  when two inputs read it and the type can be told). A user FUNCTION: called
  once, in evaluation order, into hidden variables of its result and output
  types. EN/ENO as in ST calls; an output variable fed by a block whose EN
  is connected is written only when its ENO is TRUE (Beremiz, CODESYS).
  Negated inputs and outputs: NOT; an input's edge: a hidden R_TRIG/F_TRIG.
- ``connector``/``continuation``: the connector's value, by name.
- ``jump`` (``IF cond THEN JMP label; END_IF;``), ``label`` (``label:``),
  ``return`` (``IF cond THEN RETURN; END_IF;``), ordered like the rest.
"""

from __future__ import annotations

from .bodies import LANGUAGES
from .network import (
    IDENT,
    IS_UNIT,
    KINDS,
    UNIT,
    VALUE,
    Expr,
    GraphError,
    Link,
    Net,
    Node,
    group,
    st_text,
    translate_graph,
)
from .xmlsafe import PosElement


def text_origin(net: Net, el: PosElement) -> tuple[int, int]:
    """(line, column) of the first non-blank character of el's text."""
    line, col = net.out.texts.start(el)
    raw = el.text or ""
    lead = raw[: len(raw) - len(raw.lstrip())]
    if "\n" in lead:
        return line + lead.count("\n"), len(lead) - lead.rfind("\n")
    return line, col + len(lead)


def expression(net: Net, node: Node, child: str = "expression") -> Expr:
    """The checked ST text of node's <expression> (or <variable>), at its origin."""
    el = node.el.kid(child)
    if el is None:
        raise GraphError("E200", f"this {node.kind} has no <{child}>", node.el, f"give it an <{child}>")
    text = st_text(el.text, el)
    return [(text, text_origin(net, el))]


def modified(net: Net, node: Node, expr: Expr, negated: bool, edge: str) -> Expr:
    if negated:
        expr = [("NOT", node.origin), *group(expr, node, always=True)]
    if edge in ("rising", "falling"):
        expr = net.edge(edge, expr, node)
    return expr


def assign(net: Net, node: Node, target: Expr, value: Expr, storage: str = "") -> None:
    """target := value, or a SET/RESET of target; guarded by the ENO of the
    block value comes from when that block's EN is connected."""
    o = node.origin
    if storage in ("set", "reset"):
        stmt = [
            ("IF", o),
            *value,
            ("THEN", o),
            *target,
            (":= TRUE;" if storage == "set" else ":= FALSE;", o),
            ("END_IF;", o),
        ]
    else:
        stmt = [*target, (":=", o), *value, (";", o)]
    guard = eno_guard(net, node)
    net.emit([("IF", o), *guard, ("THEN", o), *stmt, ("END_IF;", o)] if guard else stmt)


def eno_guard(net: Net, node: Node) -> Expr | None:
    links = node.ins[0].links if node.ins else []
    if len(links) != 1:
        return None
    src = net.g.nodes.get(links[0].ref)
    if src is None or src.kind != "block" or (links[0].param or "").upper() == "ENO":
        return None
    en = next((p for p in src.ins if p.param.upper() == "EN" and p.links), None)
    if en is None:
        return None
    return net.link_value(Link(src.id, "ENO", links[0].el, None))


# ---------------------------------------------------------------- variables


def in_variable(net: Net, node: Node, link: Link) -> Expr:
    expr = expression(net, node)
    text, origin = expr[0]
    if text != group([(text, origin)], node)[0][0]:
        expr = [("(", node.origin), (text, origin), (")", node.origin)]
    return modified(net, node, expr, node.el.get("negated") == "true", node.el.get("edge", ""))


def out_variable(net: Net, node: Node) -> None:
    if not node.ins[0].links:  # nothing to write (Beremiz leaves it out of its ST)
        net.out.warning(
            "W202",
            f"this {node.kind} is not connected: nothing is written to it",
            node.el,
            "connect it, or delete it",
        )
        return
    value = net.value(node.ins[0], node)
    assert value is not None
    el = node.el
    negated = el.get("negated", el.get("negatedIn", "false")) == "true"
    value = modified(net, node, value, negated, el.get("edge", ""))
    assign(net, node, expression(net, node), value, el.get("storage", ""))


def in_out_value(net: Net, node: Node, link: Link) -> Expr:
    return modified(net, node, expression(net, node), node.el.get("negatedOut") == "true", "")


def in_out_is_unit(net: Net, node: Node) -> bool:
    return bool(node.ins and node.ins[0].links)


# ---------------------------------------------------------------- connectors, jumps


def continuation(net: Net, node: Node, link: Link) -> Expr:
    conn = net.g.connector(node)
    value = net.value(conn.ins[0], conn) if conn.ins else None
    if value is None:
        raise GraphError("E202", "this connector is not connected", conn.el, "connect its input")
    return value


def _label(node: Node) -> str:
    name = (node.el.get("label") or "").strip()
    if not IDENT.fullmatch(name):
        raise GraphError("E200", f"{name!r} is not a label name", node.el, "name the label with an ST identifier")
    return name


def _guarded(net: Net, node: Node, stmt: str) -> None:
    o = node.origin
    cond = net.value(node.ins[0], node, required=False) if node.ins else None
    net.emit([("IF", o), *cond, ("THEN", o), (stmt, o), ("END_IF;", o)] if cond else [(stmt, o)])


def jump(net: Net, node: Node) -> None:
    _guarded(net, node, f"JMP {_label(node)};")


def label(net: Net, node: Node) -> None:
    net.emit([(f"{_label(node)}:", node.origin)])


def return_(net: Net, node: Node) -> None:
    _guarded(net, node, "RETURN;")


# ---------------------------------------------------------------- blocks


def _type(node: Node) -> str:
    name = (node.el.get("typeName") or "").strip()
    if not IDENT.fullmatch(name):
        raise GraphError(
            "E200", f"a block with typeName {name!r}", node.el, "give the block the name of a function or FB"
        )
    return name


def block_kind(net: Net, node: Node) -> str:
    """'fb' (called once: an instance), 'function' (a user FUNCTION: called
    once into hidden variables) or 'std' (a standard function: an expression)."""
    kind = net.project.block_kind(_type(node))
    instance = (node.el.get("instanceName") or "").strip()
    if instance:
        if not IDENT.fullmatch(instance):
            raise GraphError("E200", f"{instance!r} is not an instance name", node.el, "name it with an ST identifier")
        return "fb"
    if kind == "fb":
        raise GraphError(
            "E200", f"the {_type(node)} block has no instanceName", node.el, "name the instance it calls (instanceName)"
        )
    return kind


def _inouts(node: Node) -> set[str]:
    holder = node.el.kid("inOutVariables")
    return {v.get("formalParameter", "").upper() for v in holder.kids("variable")} if holder is not None else set()


def _arguments(net: Net, node: Node, kind: str) -> Expr:
    """The call's arguments: positional for a function with every input
    connected and no EN, formal otherwise (only the connected ones)."""
    o = node.origin
    points = node.ins
    formal = kind != "std" or any(p.param.upper() == "EN" or not p.links for p in points)
    pieces: Expr = []
    for p in points:
        required = kind != "fb" and p.param.upper() != "EN" or p.param.upper() in _inouts(node)
        value = net.value(p, node, required=required)
        if value is None:
            continue
        if not formal:
            pieces += [*([(",", o)] if pieces else []), *value]
            continue
        if not IDENT.fullmatch(p.param):
            raise GraphError("E200", f"{p.param!r} is not a parameter name", p.el, None)
        pieces += [*([(",", o)] if pieces else []), (f"{p.param} :=", o), *value]
    return pieces


def _output(net: Net, node: Node, link: Link) -> tuple[str, PosElement | None]:
    """The formal parameter of node's output that link reads: named, or the
    output at the link's end point, or the only output."""
    if link.param:
        for param, var, _ in node.outs:
            if param.upper() == link.param.upper():
                return param, var
        if link.param.upper() == "ENO":
            return "ENO", None
        raise GraphError("E201", f"the {_type(node)} block has no output {link.param}", link.el, None)
    at = [(p, v) for p, v, point in node.outs if point is not None and point == link.end]
    if len(at) == 1:
        return at[0]
    if len(node.outs) == 1:
        return node.outs[0][0], node.outs[0][1]
    raise GraphError(
        "E201", f"a connection from the {_type(node)} block that names no output", link.el, 'add formalParameter="..."'
    )


def _is_result(net: Net, node: Node, param: str) -> bool:
    """Whether param is a function's value (OUT, '', its own name)."""
    pou = net.project.pous.get(_type(node).upper())
    return param.upper() not in (pou.outputs if pou is not None else {}) and param.upper() not in _inouts(node)


def block_value(net: Net, node: Node, link: Link) -> Expr:
    kind = block_kind(net, node)
    param, var = _output(net, node, link)
    o = node.origin
    if param.upper() in _inouts(node):
        point = next(p for p in node.ins if p.param.upper() == param.upper())
        expr = net.value(point, node)
        assert expr is not None
    elif kind == "fb":
        expr = [(f"{node.el.get('instanceName', '').strip()}.{param}", o)]
    elif kind == "function":
        expr = [(_function_temp(net, node, param), o)]
    elif param.upper() == "ENO":
        en = next((p for p in node.ins if p.param.upper() == "EN"), None)
        expr = (net.value(en, node, required=False) if en is not None else None) or [("TRUE", o)]
    else:
        name = _type(node)
        types = {p.param.upper(): _wire_type(net, p) for p in node.ins}
        expr = net.shared(
            node, net.types.of_function(name, types), lambda: [(f"{name}(", o), *_arguments(net, node, "std"), (")", o)]
        )
    if var is not None:
        expr = modified(net, node, expr, var.get("negated") == "true", var.get("edge", ""))
    return expr


def _wire_type(net: Net, point) -> str | None:
    """The type of an input's value where it can be told."""
    if len(point.links) != 1:
        return None
    src = net.g.nodes.get(point.links[0].ref)
    if src is None:
        return None
    if src.kind in ("inVariable", "inOutVariable"):
        el = src.el.kid("expression")
        return net.types.of_text(el.text or "") if el is not None else None
    if src.kind in ("contact", "coil", "leftPowerRail"):
        return "BOOL"
    if src.kind == "block" and (src.el.get("instanceName") or "").strip():
        inst = src.el.get("instanceName", "").strip()
        ty = net.types.scope.get(inst.upper()) or _type(src)
        return net.project.fb_output(ty, point.links[0].param or "")
    return None


def _function_temp(net: Net, node: Node, param: str) -> str:
    """The hidden variable holding a user function's output param."""
    pou = net.project.pous[_type(node).upper()]
    if param.upper() == "ENO":
        ty: str | None = "BOOL"
    elif _is_result(net, node, param):
        ty, param = pou.result, ""
    else:
        ty = pou.outputs.get(param.upper())
    if ty is None:
        raise GraphError(
            "E200", f"the type of {_type(node)}'s output {param or 'value'} is not known here", node.el, None
        )
    return net.hidden("F", node, ty, param)


def block_unit(net: Net, node: Node) -> None:
    kind = block_kind(net, node)
    o = node.origin
    args = _arguments(net, node, kind)
    if kind == "fb":
        net.emit([(f"{node.el.get('instanceName', '').strip()}(", o), *args, (");", o)])
        return
    outs: Expr = []
    result = ""
    read = [lk for n in net.g.nodes.values() for p in n.ins for lk in p.links if lk.ref == node.id]
    used = {_output(net, node, lk)[0] for lk in read}
    for param in sorted(used):
        if param.upper() in _inouts(node):
            continue
        if _is_result(net, node, param) and param.upper() != "ENO":
            result = _function_temp(net, node, param)
        else:
            outs += [(",", o), (f"{param} => {_function_temp(net, node, param)}", o)]
    if outs and not args:
        outs = outs[1:]
    call = [(f"{_type(node)}(", o), *args, *outs, (")", o)]
    net.emit([(f"{result} :=", o), *call, (";", o)] if result else [*call, (";", o)])


def block_is_unit(net: Net, node: Node) -> bool:
    return block_kind(net, node) != "std"


VALUE.update(
    inVariable=in_variable,
    inOutVariable=in_out_value,
    continuation=continuation,
    connector=lambda net, node, link: _connector_value(net, node),
    block=block_value,
)
UNIT.update(outVariable=out_variable, inOutVariable=out_variable, jump=jump, label=label, block=block_unit)
UNIT["return"] = return_
IS_UNIT.update(inOutVariable=in_out_is_unit, block=block_is_unit)
KINDS.update(
    ("inVariable", "outVariable", "inOutVariable", "block", "connector", "continuation", "jump", "label", "return")
)


def _connector_value(net: Net, node: Node) -> Expr:
    value = net.value(node.ins[0], node) if node.ins else None
    if value is None:
        raise GraphError("E202", "this connector is not connected", node.el, "connect its input")
    return value


LANGUAGES["FBD"] = translate_graph
