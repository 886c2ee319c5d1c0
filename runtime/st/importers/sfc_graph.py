"""A graphical SFC body (PLCopen TC6 0201 ``<SFC>``) read as a chart: its
steps with their action associations, its transitions with the steps
before and after them, its inline actions. sfc.py writes the chart as the
textual SFC (IEC 61131-3 ed.3 6.7).

The XML holds the graph as connections: every element names the elements
before it (``<connectionPointIn><connection refLocalId>``). A transition's
source steps are found walking back through selection divergences and
simultaneous convergences; its target steps walking forward through
selection convergences, simultaneous divergences and jumps. Problems are
coded diagnostics at the element (E210-E215); an element with a problem is
left out, the rest of the chart is read.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..rtlib.rt_sfc import QUALIFIERS, TIMED
from .bodies import BodyOut
from .sfc_codesys import codesys_step
from .xmlsafe import PosElement

# what may come before each element of the sequence (TC6 0201; a connector
# may follow one of its own kind: a wider divergence drawn as two)
_BEFORE = {
    "step": {"transition", "selectionConvergence", "simultaneousDivergence"},
    "jumpStep": {"transition", "selectionConvergence", "simultaneousDivergence"},
    "transition": {"step", "selectionDivergence", "simultaneousConvergence"},
    "selectionDivergence": {"step", "selectionDivergence", "simultaneousConvergence"},
    "selectionConvergence": {"transition", "selectionConvergence"},
    "simultaneousDivergence": {"transition", "selectionConvergence", "simultaneousDivergence"},
    "simultaneousConvergence": {"step", "simultaneousConvergence"},
    "macroStep": {"transition", "selectionConvergence", "simultaneousDivergence"},
}
_SEQUENCE = set(_BEFORE)
_NAMES = {
    "step": "a step",
    "jumpStep": "a jump",
    "macroStep": "a macro step",
    "transition": "a transition",
    "selectionDivergence": "a selection divergence",
    "selectionConvergence": "a selection convergence",
    "simultaneousDivergence": "a simultaneous divergence",
    "simultaneousConvergence": "a simultaneous convergence",
    "actionBlock": "an action block",
}


class _BadAction(Exception):
    """An <action> that makes no association (E215); args: the message."""


@dataclass(eq=False)
class Assoc:
    """An action association of a step: action(qualifier[, duration][, indicator])."""

    action: str
    qualifier: str
    el: PosElement
    duration: str | None = None
    indicator: str | None = None
    # a CODESYS entry or exit action: run once, through an action of its own
    # that calls it while its Q is TRUE (sfc.py), named here
    once: str | None = None

    def text(self) -> str:
        args = [self.qualifier, *(a for a in (self.duration, self.indicator) if a)]
        return f"{self.once or self.action}({', '.join(args)});"


@dataclass(eq=False)
class Step:
    el: PosElement
    name: str
    initial: bool
    assocs: list = field(default_factory=list)
    first: bool = True  # the first element of its name (a CODESYS duplicate is not)


@dataclass(eq=False)
class Inline:
    """An action written in the action block itself: an ACTION of its own."""

    el: PosElement  # the <action>
    name: str
    lang: PosElement


@dataclass(eq=False)
class Transition:
    el: PosElement
    sources: list
    targets: list
    index: int  # document order
    priority: int = 0  # the priority attribute (lower first)
    x: int = 0  # left to right
    condition: PosElement | None = None


class Chart:
    """The chart of one <SFC> element (read() reports its problems)."""

    def __init__(self, sfc: PosElement, out: BodyOut) -> None:
        self.sfc = sfc
        self.out = out
        self.nodes: dict[str, PosElement] = {}
        self.succ: dict[str, list] = {}
        self.steps: list[Step] = []
        self.step_of: dict[str, Step] = {}  # localId -> step
        self.by_name: dict[str, Step] = {}  # UPPER name -> its first step
        self.transitions: list[Transition] = []
        self.inlines: list[Inline] = []
        self.bad: set = set()  # ids of elements with a reported problem
        self.graph: object = None  # the FBD/LD graph drawn in the chart (sfc_wired.py), False: unreadable

    # ------------------------------------------------------------ reading

    def read(self) -> Chart:
        for el in self.sfc.kids():
            lid = el.get("localId")
            if lid is None:
                continue
            if lid in self.nodes:
                self.error(
                    "E211", f"localId {lid} is used twice in the chart", el, "give every element its own localId"
                )
                continue
            self.nodes[lid] = el
        for el in self.sfc.kids():
            if el.name in _SEQUENCE and el is self.nodes.get(el.get("localId", "")):
                for ref in self.inputs(el):
                    self.succ.setdefault(ref, []).append(el)
        for el in self.sfc.kids():
            if el.name in _SEQUENCE and el is self.nodes.get(el.get("localId", "")):
                self._check_links(el)
        for el in self.sfc.kids("step"):
            self._step(el)
        for el in self.sfc.kids("macroStep"):
            self.error(
                "E214",
                "a macro step: softplc does not import macro steps",
                el,
                "draw the macro step's sequence into the chart (its steps and transitions in place of the macro step)",
            )
        for el in self.sfc.kids("actionBlock"):
            self._action_block(el)
        for k, el in enumerate(self.sfc.kids("transition")):
            self._transition(el, k)
        return self

    def error(self, code: str, message: str, el: PosElement, hint: str | None = None) -> None:
        self.bad.add(id(el))
        self.out.error(code, message, el, hint)

    def inputs(self, el: PosElement) -> list:
        """The localIds el's connectionPointIn children connect it to (a
        continuation stands for its connector's input)."""
        refs = []
        for cpi in el.kids("connectionPointIn"):
            for c in cpi.kids("connection"):
                ref = c.get("refLocalId")
                if ref is not None:
                    refs.extend(self._through_connectors(ref, set()))
        return refs

    def _through_connectors(self, ref: str, seen: set) -> list:
        el = self.nodes.get(ref)
        if el is None or el.name != "continuation" or ref in seen:
            return [ref]
        seen.add(ref)
        out = []
        for conn in self.sfc.kids("connector"):
            if conn.get("name") == el.get("name"):
                for cpi in conn.kids("connectionPointIn"):
                    for c in cpi.kids("connection"):
                        if c.get("refLocalId") is not None:
                            out.extend(self._through_connectors(c.get("refLocalId", ""), seen))
        return out or [ref]

    def _check_links(self, el: PosElement) -> None:
        """E211 for a connection to nothing or from what cannot come before
        el; E212 for a divergence or convergence with one branch."""
        refs = self.inputs(el)
        if not refs and el.name != "step":
            where = "below the step it leaves" if el.name == "transition" else "to what comes before it"
            self.error("E210", f"{_NAMES[el.name]} with nothing before it", el, f"connect it {where}")
            return
        for ref in refs:
            before = self.nodes.get(ref)
            if before is None:
                self.error(
                    "E211",
                    f"{_NAMES[el.name]} is connected to localId {ref}, which the chart does not have",
                    el,
                    "connect it again in the editor and export the project again",
                )
            elif before.name not in _BEFORE[el.name]:
                self.error(
                    "E211",
                    f"{_NAMES[el.name]} cannot follow {_NAMES.get(before.name, '<' + before.name + '>')} "
                    f"(localId {ref})",
                    el,
                    "steps and transitions alternate: a step, then a transition, then a step",
                )
        lid = el.get("localId", "")
        if el.name in ("selectionDivergence", "simultaneousDivergence") and len(self.succ.get(lid, [])) < 2:
            self._one_branch(el, "goes on in")
        if el.name in ("selectionConvergence", "simultaneousConvergence") and len(refs) < 2:
            self._one_branch(el, "joins")

    def _one_branch(self, el: PosElement, verb: str) -> None:
        self.error(
            "E212",
            f"{_NAMES[el.name]} {verb} {'fewer than two branches'}",
            el,
            "a divergence or convergence joins two branches or more: connect the others, or remove it",
        )

    # ------------------------------------------------------------ steps and actions

    def _step(self, el: PosElement) -> None:
        name = self.ident(el.get("name", ""), el, "a step's name")
        if name is None:
            return
        dup, found = codesys_step(el, self.out)
        assocs = [
            Assoc(action, qualifier, attr, once=once and f"_{name}_{once}") for action, qualifier, attr, once in found
        ]
        step = Step(el, name, el.get("initialStep") == "true", assocs)
        first = self.by_name.get(name.upper())
        if first is not None and dup:
            step.first = False  # CODESYS: the same step drawn twice
            first.assocs.extend(assocs)
            step.assocs = first.assocs
        else:
            self.by_name.setdefault(name.upper(), step)
        self.steps.append(step)
        self.step_of[el.get("localId", "")] = step

    def _action_block(self, block: PosElement) -> None:
        refs = self.inputs(block)
        if not refs:
            self.error(
                "E210", "an action block connected to no step", block, "connect it to the step whose actions it holds"
            )
            return
        step = self.step_of.get(refs[0])
        if step is None:
            before = self.nodes.get(refs[0])
            what = _NAMES.get(before.name, f"<{before.name}>") if before is not None else f"localId {refs[0]}"
            self.error("E211", f"an action block is connected to {what}, not to a step", block, None)
            return
        for act in block.kids("action"):
            try:
                assoc = self._assoc(act, step)
            except _BadAction as exc:
                self.error(
                    "E215",
                    str(exc),
                    act,
                    "an association is a qualifier (N, S, R, P, L, D ...), a duration for L, D, SD, DS, SL",
                )
                continue
            if assoc is not None:
                step.assocs.append(assoc)

    def _assoc(self, act: PosElement, step: Step) -> Assoc | None:
        """The association an <action> makes (None: a name reported E183)."""
        qualifier = (act.get("qualifier") or "N").strip().upper()
        if qualifier not in QUALIFIERS:
            raise _BadAction(f"the qualifier {act.get('qualifier')!r} is none of {', '.join(QUALIFIERS)}")
        duration = (act.get("duration") or "").strip() or None
        if qualifier in TIMED and duration is None:
            raise _BadAction(f"the qualifier {qualifier} takes a duration, and the action has none")
        if qualifier not in TIMED and duration is not None:
            raise _BadAction(f"the qualifier {qualifier} takes no duration ({duration!r} given)")
        if duration is not None and not _is_time(duration):
            raise _BadAction(f"the duration {duration!r} is neither a TIME literal nor a variable")
        indicator = (act.get("indicator") or "").strip() or None
        if indicator is not None and self.ident(indicator, act, "an indicator") is None:
            return None
        ref = act.kid("reference")
        inline = act.kid("inline")
        if ref is not None:
            name = self.ident(ref.get("name", ""), ref, "an action's name")
            if name is None:
                return None
        elif inline is not None and inline.kids():
            name = f"{step.name}_inline{sum(1 for i in self.inlines if i.name.startswith(step.name + '_inline')) + 1}"
            self.inlines.append(Inline(act, name, inline.kids()[0]))
        else:
            raise _BadAction("an action that names no action and holds no body")
        return Assoc(name, qualifier, act, duration, indicator)

    def ident(self, name: str, el: PosElement, what: str) -> str | None:
        """name if it is an ST identifier (E183 otherwise)."""
        if name and name.isascii() and name.replace("_", "a").isalnum() and not name[0].isdigit():
            return name
        self.bad.add(id(el))
        self.out.error("E183", f"{what} {name!r} is not an ST identifier", el)
        return None

    # ------------------------------------------------------------ transitions

    def _transition(self, el: PosElement, index: int) -> None:
        if id(el) in self.bad:
            return
        sources = self._sources(el)
        targets = self._targets(el)
        if sources is None or targets is None:
            return
        t = Transition(el, _unique(sources), _unique(targets), index, condition=el.kid("condition"))
        t.priority = _int_attr(el.get("priority"))
        pos = el.kid("position")
        t.x = _int_attr(pos.get("x") if pos is not None else None)
        self.transitions.append(t)

    def _sources(self, t: PosElement) -> list | None:
        refs = self.inputs(t)
        out: list = []
        for ref in refs:
            if not self._back(ref, out, set()):
                return None
        return out

    def _back(self, ref: str, out: list, seen: set) -> bool:
        el = self.nodes.get(ref)
        if el is None or id(el) in self.bad:
            return False
        if ref in seen:
            return True
        seen.add(ref)
        if el.name == "step":
            step = self.step_of.get(ref)
            if step is None:
                return False
            out.append(step.name)
            return True
        if el.name in ("selectionDivergence", "simultaneousConvergence"):
            return all(self._back(r, out, seen) for r in self.inputs(el))
        return False

    def _targets(self, t: PosElement) -> list | None:
        nexts = self.succ.get(t.get("localId", ""), [])
        if not nexts:
            self.error("E210", "a transition that leads to no step", t, "connect a step (or a jump) below it")
            return None
        out: list = []
        for el in nexts:
            if not self._forward(el, out, set()):
                return None
        return out

    def _forward(self, el: PosElement, out: list, seen: set) -> bool:
        if id(el) in self.bad:
            return False
        if id(el) in seen:
            return True
        seen.add(id(el))
        if el.name == "step":
            step = self.step_of.get(el.get("localId", ""))
            if step is not None:
                out.append(step.name)
            return step is not None
        if el.name == "jumpStep":
            return self._jump(el, out)
        if el.name in ("selectionConvergence", "simultaneousDivergence"):
            nexts = self.succ.get(el.get("localId", ""), [])
            if not nexts:
                self.error(
                    "E210", f"{_NAMES[el.name]} that leads to no step", el, "connect a step (or a jump) below it"
                )
                return False
            return all(self._forward(n, out, seen) for n in nexts)
        return False

    def _jump(self, el: PosElement, out: list) -> bool:
        name = self.ident(el.get("targetName", ""), el, "a jump's target")
        if name is None:
            return False
        step = self.by_name.get(name.upper())
        if step is None:
            self.error(
                "E213",
                f"a jump to '{name}', which is not a step of the chart",
                el,
                "name one of the steps: " + ", ".join(s.name for s in self.steps if s.first)[:200],
            )
            return False
        out.append(step.name)
        return True


def _unique(names: list) -> list:
    out: list = []
    for n in names:
        if n.upper() not in (o.upper() for o in out):
            out.append(n)
    return out


def _int_attr(value: str | None) -> int:
    v = (value or "").strip()
    try:
        return int(float(v)) if v else 0
    except (ValueError, OverflowError):  # (not a number; inf or 1e999)
        return 0


def _is_time(text: str) -> bool:
    """A TIME literal (T#2s, TIME#1h_30m) or a variable (tDelay, GVL.tDelay):
    nothing that could end the association or open a comment."""
    return text.isascii() and all(c.isalnum() or c in "_#.+-" for c in text) and not text[0].isdigit()
