"""FBD and LD networks (PLCopen TC6 0201) as ST: the graph, the order of
evaluation, and the value of a wire.

    graph = Graph(lang, out)               # the elements of an <FBD>/<LD>/<SFC>
    Net(graph, out).body()                 # the network's ST, in evaluation order
    condition(graph, point_in, out) -> str # an SFC transition's wired condition

Every element has a ``localId``; an input (``<connectionPointIn>``) holds
``<connection refLocalId="N" formalParameter="OUT"/>``: the value of N's
output OUT (several connections into one point: the OR of their power flows,
as LD draws parallel branches). The elements of each language are handlers
in ``VALUE`` (what an output of an element is, as an ST expression) and
``UNIT`` (the statement an element is: an assignment, an FB call, a jump),
registered by fbd.py and ld.py.

Evaluation order: the ``executionOrderId`` the project gives (Beremiz and
CODESYS's CFC write it), the units without one after those, else data flow:
a unit after the units whose outputs it reads, ties by position (top to
bottom, then left to right, then document order), a loop (a connection back
to an earlier unit) evaluated in position order, the connection back giving
the value of the previous evaluation (IEC 61131-3 ed.3 8.2.2 "feedback").
A loop through functions alone has no value to give back: E203.

The ST of a body goes on the lines of its element, one statement a line in
evaluation order, each piece with the (line, column) of the XML element it
comes from as its origin (view.LineView.put): diagnostics and runtime faults
point at the element, wherever its statement stands.
"""

from __future__ import annotations

import heapq
import re
from collections.abc import Callable
from dataclasses import dataclass, field

from .bodies import BodyOut, ImportProblem
from .graphtypes import Project, Types
from .xmlsafe import PosElement

Piece = tuple[str, tuple[int, int]]
Expr = list[Piece]

MAX_EXPR_CHARS = 20_000  # an inlined value beyond this is E207
_KEYWORDS = frozenset(
    "IF THEN ELSIF ELSE CASE OF FOR TO BY DO WHILE REPEAT UNTIL RETURN EXIT CONTINUE JMP VAR "
    "FUNCTION FUNCTION_BLOCK PROGRAM METHOD ACTION TYPE STRUCT".split()
)
_STRING = re.compile(r"'(?:[^'$\n]|\$[^\n])*'|\"(?:[^\"$\n]|\$[^\n])*\"")
_WORD = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_SIMPLE = re.compile(r"[A-Za-z0-9_#.%\[\]^']*")
IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def st_text(text: str | None, el: PosElement, what: str = "expression") -> str:
    """The text of an <expression> or <variable> as one ST expression: no
    ';', comment, pragma or line break outside its strings, brackets
    balanced, no statement keyword (E206 otherwise)."""
    t = (text or "").strip()
    bare = _STRING.sub("''", t)
    depth, bad = 0, not t
    for ch in bare:
        depth += 1 if ch in "([" else -1 if ch in ")]" else 0
        bad = bad or depth < 0
    words = {w.upper() for w in _WORD.findall(bare)}
    if (
        bad
        or depth
        or any(s in bare for s in (";", "(*", "*)", "//", "/*", "{", "}", "\n", "\r", '"', "'''"))
        or words & _KEYWORDS
        or any(w.startswith("END_") for w in words)
    ):
        raise GraphError("E206", f"{t[:60]!r} is not an ST {what}", el, "write one ST expression, on one line")
    return t


def wrapped(text: str) -> str:
    """text in parentheses unless it is one operand already."""
    return text if _SIMPLE.fullmatch(text) else f"({text})"


class GraphError(Exception):
    """A coded problem of a network; args: code, message, element, hint."""


def _int_attr(el: PosElement, name: str) -> int:
    v = (el.get(name) or "0").strip()
    return int(v) if v.isdigit() else 0


@dataclass(eq=False)
class Link:
    """One <connection>: the output param of the element ref."""

    ref: str
    param: str | None
    el: PosElement
    end: tuple[int, int] | None  # its last <position>: where it meets the output (when param is not named)


@dataclass(eq=False)
class PointIn:
    """An input of an element: a <connectionPointIn> and its connections."""

    el: PosElement  # the element holding it (the <variable> of a block, or the element)
    links: list[Link]
    param: str = ""
    negated: bool = False
    edge: str = ""


@dataclass(eq=False)
class Node:
    """An element of the network."""

    id: str
    kind: str
    el: PosElement
    order: int  # executionOrderId, 0 when not given
    key: tuple  # (y, x, document index): position order
    ins: list[PointIn] = field(default_factory=list)
    outs: list[tuple[str, PosElement, tuple[int, int] | None]] = field(default_factory=list)  # (param, variable, point)

    @property
    def origin(self) -> tuple[int, int]:
        return (self.el.line, self.el.col)


def _xy(el: PosElement | None) -> tuple[int, int] | None:
    if el is None:
        return None
    try:
        return int(float(el.get("x", "0"))), int(float(el.get("y", "0")))
    except (ValueError, OverflowError):  # (not a number; inf or 1e999)
        return None


def _links(cp: PosElement | None) -> list[Link]:
    if cp is None:
        return []
    found = []
    for c in cp.kids("connection"):
        ref = (c.get("refLocalId") or "").strip()
        if not ref:
            raise GraphError(
                "E201", "a <connection> without refLocalId", c, "every connection names the element it comes from"
            )
        points = c.kids("position")
        found.append(Link(ref, c.get("formalParameter"), c, _xy(points[-1]) if points else None))
    return found


_TAKES_INPUT = frozenset(("outVariable", "inOutVariable", "coil", "contact", "jump", "return", "connector"))
_IGNORED = frozenset(("comment", "rightPowerRail", "documentation", "addData", "vendorElement"))


class Graph:
    """The elements of a network by localId, with their inputs and outputs.
    foreign: element kinds that belong to another language drawn in the
    same body (an SFC's steps): kept out of the graph without an error."""

    def __init__(self, lang: PosElement, out: BodyOut, foreign: bool = False) -> None:
        self.lang = lang
        self.nodes: dict[str, Node] = {}
        self.connectors: dict[str, Node] = {}
        for index, el in enumerate(lang.kids()):
            if el.name in _IGNORED:
                continue
            if el.name not in KINDS:
                if foreign:
                    continue
                raise GraphError(
                    "E205",
                    f"<{el.name}> is not an element softplc reads in an {lang.name} body",
                    el,
                    "redraw it with the standard elements (blocks, variables, contacts, coils)",
                )
            node = self._node(el, index)
            if node.id in self.nodes:
                raise GraphError("E200", f"localId {node.id} is given twice", el, "each element has its own localId")
            self.nodes[node.id] = node
            if node.kind == "connector":
                name = node.el.get("name", "")
                if name.upper() in self.connectors:
                    raise GraphError(
                        "E204", f"two connectors are named {name!r}", el, "give each connector its own name"
                    )
                self.connectors[name.upper()] = node

    def _node(self, el: PosElement, index: int) -> Node:
        lid = (el.get("localId") or "").strip()
        if not lid:
            raise GraphError("E200", f"<{el.name}> without a localId", el, "every element of a network has a localId")
        xy = _xy(el.kid("position")) or (0, 0)
        node = Node(lid, el.name, el, _int_attr(el, "executionOrderId"), (xy[1], xy[0], index))
        if el.name == "block":
            for section in ("inputVariables", "inOutVariables"):
                holder = el.kid(section)
                for v in holder.kids("variable") if holder is not None else []:
                    cp = v.kid("connectionPointIn")
                    node.ins.append(
                        PointIn(
                            v, _links(cp), v.get("formalParameter", ""), v.get("negated") == "true", v.get("edge", "")
                        )
                    )
            for section in ("outputVariables", "inOutVariables"):
                holder = el.kid(section)
                for v in holder.kids("variable") if holder is not None else []:
                    cpo = v.kid("connectionPointOut")
                    rel = _xy(cpo.kid("relPosition")) if cpo is not None else None
                    point = (xy[0] + rel[0], xy[1] + rel[1]) if rel is not None else None
                    node.outs.append((v.get("formalParameter", ""), v, point))
        else:
            cp = el.kid("connectionPointIn")
            if cp is not None or el.name in _TAKES_INPUT:  # its modifiers are its own (a coil's): fbd.py, ld.py
                node.ins.append(PointIn(el, _links(cp)))
        return node

    def node(self, link: Link) -> Node:
        found = self.nodes.get(link.ref)
        if found is None:
            raise GraphError(
                "E201",
                f"a connection to localId {link.ref}, which no element of this body has",
                link.el,
                "connect it to an element of the same network",
            )
        return found

    def connector(self, cont: Node) -> Node:
        name = cont.el.get("name", "")
        found = self.connectors.get(name.upper())
        if found is None:
            raise GraphError(
                "E204", f"no connector named {name!r} for this continuation", cont.el, "draw the connector"
            )
        return found


# kind -> value(net, node, link) -> Expr: the value of the output link reads
VALUE: dict[str, Callable] = {}
# kind -> unit(net, node) -> None: the statement(s) of a unit, emitted
UNIT: dict[str, Callable] = {}
# kind -> is_unit(net, node) -> bool (when not every element of the kind is one)
IS_UNIT: dict[str, Callable] = {}
KINDS: set[str] = set()


class Net:
    """The ST of one graph: statements in evaluation order, values of wires."""

    def __init__(self, graph: Graph, out: BodyOut, first: int, last: int) -> None:
        self.g = graph
        self.out = out
        self.line, self.last = first, last
        self.project = Project.of(out)
        self.types = Types(self.project, graph.lang)
        self.done: set[str] = set()  # units and shared values already emitted
        self.temps: dict[tuple, str] = {}  # (node id, param) -> hidden variable holding it
        self.busy: list[Node] = []  # values being worked out (a loop among them is E203)
        self.uses = self._uses()

    # ------------------------------------------------------------ output

    def emit(self, pieces: Expr) -> None:
        """One statement on the next line of the body, each piece at its origin."""
        before = ""
        for text, origin in pieces:
            tight = before.endswith("(") or text.startswith((")", ",", ";", "."))
            self.out.put(self.line, 1, text, origin, "" if tight else " ")
            before = text
        if self.line < self.last:
            self.line += 1

    def hidden(self, stem: str, node: Node, ty: str, param: str = "") -> str:
        """A hidden variable of the POU for node (an edge's R_TRIG, a value
        read twice), declared once."""
        key = (node.id, stem, param)
        if key not in self.temps:
            suffix = f"_{param}" if param and IDENT.fullmatch(param) else ""
            self.temps[key] = f"_{stem}{node.id}{suffix}" if node.id.isdigit() else f"_{stem}{len(self.temps)}{suffix}"
            self.out.declare(f"{self.temps[key]} : {ty};")
        return self.temps[key]

    # ------------------------------------------------------------ values

    def value(self, point: PointIn, owner: Node, required: bool = True) -> Expr | None:
        """The value of an input: its connections (several: their OR), then
        its negation and edge modifiers. None when it is not connected and
        not required (E202 when it is)."""
        if not point.links:
            if required:
                what = f"input {point.param} of " if point.param else ""
                raise GraphError(
                    "E202", f"{what}this {owner.kind} is not connected", point.el, "connect it, or delete it"
                )
            return None
        parts = [self.link_value(link) for link in point.links]
        expr = parts[0]
        for more in parts[1:]:
            expr = [*group(expr, owner), ("OR", owner.origin), *group(more, owner)]
        if point.negated:
            expr = [("NOT", owner.origin), *group(expr, owner, always=True)]
        if point.edge in ("rising", "falling"):
            expr = self.edge(point.edge, expr, owner, point.param)
        return expr

    def edge(self, edge: str, expr: Expr, owner: Node, param: str = "") -> Expr:
        """A rising/falling edge of expr: a hidden R_TRIG/F_TRIG, called
        once per evaluation (where its value is first read)."""
        fb = "R_TRIG" if edge == "rising" else "F_TRIG"
        name = self.hidden("RT" if edge == "rising" else "FT", owner, fb, param)
        if name not in self.done:
            self.done.add(name)
            self.emit([(f"{name}(CLK :=", owner.origin), *expr, (");", owner.origin)])
        return [(f"{name}.Q", owner.origin)]

    def link_value(self, link: Link) -> Expr:
        node = self.g.node(link)
        if node in self.busy:
            start = self.busy.index(node)
            if not any(self.is_unit(n) for n in self.busy[start:]):
                raise GraphError(
                    "E203",
                    "an algebraic loop: this value depends on itself through functions alone",
                    node.el,
                    "break the loop with a variable (an output variable read back) or a function block",
                )
        handler = VALUE.get(node.kind)
        if handler is None:
            raise GraphError("E201", f"a connection from a <{node.kind}>, which has no output", link.el, None)
        self.busy.append(node)
        try:
            expr = handler(self, node, link)
        finally:
            self.busy.pop()
        if sum(len(t) for t, _ in expr) > MAX_EXPR_CHARS:
            raise GraphError(
                "E207",
                "the value on this wire is too large to write as one expression",
                node.el,
                "store intermediate results in variables (output variables read back)",
            )
        return expr

    def shared(self, node: Node, ty: str | None, make: Callable[[], Expr], uses: int | None = None) -> Expr:
        """node's value, once per evaluation: in a hidden variable of type
        ty when more than one input reads it (uses: how many do, the
        connections to node unless given), else the expression itself (and
        so when ty is not known: a pure value read again)."""
        if ty is None or (self.uses.get(node.id, 0) if uses is None else uses) <= 1:
            return make()
        name = self.hidden("V", node, ty)
        if "value:" + node.id not in self.done:
            self.done.add("value:" + node.id)
            self.emit([(f"{name} :=", node.origin), *make(), (";", node.origin)])
        return [(name, node.origin)]

    def _uses(self) -> dict[str, int]:
        uses: dict[str, int] = {}
        for n in self.g.nodes.values():
            for p in n.ins:
                for link in p.links:
                    uses[link.ref] = uses.get(link.ref, 0) + 1
        return uses

    # ------------------------------------------------------------ order

    def is_unit(self, node: Node) -> bool:
        test = IS_UNIT.get(node.kind)
        return test(self, node) if test is not None else node.kind in UNIT

    def deps(self, node: Node) -> set[str]:
        """The units node's inputs read (through elements that are values)."""
        found: set[str] = set()
        seen: set[str] = set()
        stack = [link for p in node.ins for link in p.links]
        while stack:
            link = stack.pop()
            src = self.g.nodes.get(link.ref)
            if src is None or src.id in seen:
                continue
            seen.add(src.id)
            if self.is_unit(src):
                found.add(src.id)
                continue
            if src.kind == "continuation":
                conn = self.g.connectors.get(src.el.get("name", "").upper())
                if conn is not None:
                    stack.extend(link for p in conn.ins for link in p.links)
            stack.extend(link for p in src.ins for link in p.links)
        return found

    def reach(self, node: Node) -> set[str]:
        """The units node reads, and those they read in turn (every block a
        condition needs called: an SR feeding the TON it reads too)."""
        found: set[str] = set()
        todo = [node]
        while todo:
            for unit in self.deps(todo.pop()) - found:
                found.add(unit)
                if unit in self.g.nodes:
                    todo.append(self.g.nodes[unit])
        return found

    def order(self) -> list[Node]:
        units = [n for n in self.g.nodes.values() if self.is_unit(n)]
        ordered = sorted((n for n in units if n.order > 0), key=lambda n: (n.order, n.key))
        rest = [n for n in units if n.order <= 0]
        return ordered + self._data_flow(rest)

    def _data_flow(self, units: list[Node]) -> list[Node]:
        """units after those they read, ties by position; the loops
        (strongly connected parts) in position order."""
        ids = {n.id: n for n in units}
        deps = {n.id: self.deps(n) & ids.keys() for n in units}
        comp = _components(list(ids), deps)
        members: dict[int, list[Node]] = {}
        for nid, c in comp.items():
            members.setdefault(c, []).append(ids[nid])
        waits = {c: {comp[d] for m in ms for d in deps[m.id]} - {c} for c, ms in members.items()}
        heap = [(min(m.key for m in ms), c) for c, ms in members.items() if not waits[c]]
        heapq.heapify(heap)
        result: list[Node] = []
        while heap:
            _, c = heapq.heappop(heap)
            result.extend(sorted(members[c], key=lambda n: n.key))
            for other, w in waits.items():
                if c in w:
                    w.discard(c)
                    if not w:
                        heapq.heappush(heap, (min(m.key for m in members[other]), other))
        return result

    def body(self) -> None:
        for node in self.order():
            if node.id not in self.done:
                self.done.add(node.id)
                UNIT[node.kind](self, node)


def _components(ids: list[str], deps: dict[str, set[str]]) -> dict[str, int]:
    """Strongly connected components (Tarjan, iterative): id -> component."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on: set[str] = set()
    stack: list[str] = []
    comp: dict[str, int] = {}
    counter = 0
    for root in ids:
        if root in index:
            continue
        work = [(root, iter(sorted(deps[root])))]
        index[root] = low[root] = counter
        counter += 1
        stack.append(root)
        on.add(root)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = counter
                    counter += 1
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(sorted(deps[w]))))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp[w] = index[v]
                    if w == v:
                        break
    return comp


def group(expr: Expr, owner: Node, always: bool = False) -> Expr:
    """expr in parentheses when it is more than one operand."""
    text = "".join(t for t, _ in expr)
    if not always and _SIMPLE.fullmatch(text):
        return expr
    return [("(", owner.origin), *expr, (")", owner.origin)]


def translate_graph(lang: PosElement, out: BodyOut) -> None:
    """An <FBD> or <LD> body as ST (bodies.LANGUAGES): its statements on
    its lines in evaluation order, JMP allowed there (lowered)."""
    try:
        net = Net(Graph(lang, out), out, lang.line, lang.end_line)
        net.body()
    except GraphError as exc:
        code, message, el, hint = exc.args
        out.error(code, message, el, hint)
        return
    out.lowered(lang.line, lang.end_line)


def condition(graph: Graph, point: PosElement, out: BodyOut, line: int | None = None, last: int | None = None) -> str:
    """The BOOL ST expression an SFC transition's <condition> wired into an
    FBD/LD graph drawn in the SFC body gives (contacts, blocks, variables
    connected to its <connectionPointIn>).

    graph: ``Graph(sfc_element, out, foreign=True)`` (the SFC's own elements
    are left out); point: the transition's <connectionPointIn> (several
    connections: their OR). The FB calls and edge memories the condition
    needs are written with out.put before it, one statement a line from
    ``line`` on (never past ``last``; both the point's line when not
    given), in data-flow order, and the hidden
    variables it needs declared with out.declare; so call it where those
    statements may run each time the condition is evaluated (the transition's
    evaluation), and mark the lines lowered. The result is one expression
    (no ';', on one line) whose pieces are not positioned: put it at the
    transition. Raises ImportProblem (an E183 at the element) when the graph
    cannot give a value; the element's own code is in the message.
    """
    first = point.line if line is None else line
    net = Net(graph, out, first, first if last is None else last)
    holder = Node("transition", "transition", point, 0, (0, 0, 0), [PointIn(point, _links(point), "")])
    try:
        for unit in net._data_flow([graph.nodes[i] for i in sorted(net.reach(holder)) if i in graph.nodes]):
            if unit.id not in net.done:
                net.done.add(unit.id)
                UNIT[unit.kind](net, unit)
        expr = net.value(holder.ins[0], holder)
    except GraphError as exc:
        code, message, el, hint = exc.args
        raise ImportProblem(f"{code}: {message}", el, hint) from None
    assert expr is not None
    return "".join(t if not i else " " + t for i, (t, _) in enumerate(expr))
