"""A graphical SFC body (PLCopen TC6 ``<SFC>``, as Beremiz and CODESYS
export it) written as the textual SFC of IEC 61131-3 ed.3 6.7, which the
compiler runs (build_sfc.py, checker_sfc.py, codegen_sfc.py, rt_sfc.py).

Each piece stands at the line of the element it comes from: a step's
``STEP name: associations END_STEP`` at its ``<step>``, a transition's
``TRANSITION FROM s1 TO (s2, s3) := condition; END_TRANSITION`` at its
``<transition>``, an inline action's ``ACTION Step_inline1: ...
END_ACTION`` at its ``<action>``. A condition is an inline ST expression,
the name of one of the POU's ``<transitions>`` (its body, in any imported
language, written as ``TRANSITION name FROM ... : body END_TRANSITION``
at the named transition's own lines for its first use, a copy at the
``<transition>`` for a further one), a BOOL variable, or a graph wired to
it (sfc_wired.py: the blocks it calls go into an ACTION of their own, S
on the initial step).

Of the transitions that leave one step (a selection divergence) the first
in IEC order fires: lower ``priority`` attribute first, then left to right
(``<position x>``), then document order; written as PRIORITY where the
text order would differ. Problems: E182 (a body's language not imported),
E183, E210-E216, W210, W212 (sfc_graph.py, sfc_codesys.py).
"""

from __future__ import annotations

from .bodies import LANGUAGES, BodyOut, body_language, supported, translate
from .sfc_codesys import sfc_settings
from .sfc_graph import Assoc, Chart, Transition
from .sfc_text import ST_FORMS, has_line_comment, one_line, st_form
from .sfc_wired import Wired, wired_condition
from .view import LineView
from .xmlsafe import PosElement


def sfc_body(lang: PosElement, out: BodyOut) -> None:
    """The <SFC> body lang as textual SFC into out (a bodies.LANGUAGES entry)."""
    chart = Chart(lang, out).read()
    sfc_settings(out.owner, out)
    _Writer(chart, out).write()


class _Named:
    """A transition of the POU's <transitions>, translated once: its body
    (a view at its own lines), the text between its header and its body,
    and the text before END_TRANSITION."""

    def __init__(self, el: PosElement, name: str) -> None:
        self.el = el
        self.name = name
        self.body: LineView | None = None
        self.marker = ":"
        self.closing = ""
        self.used = False  # written at its own lines (its first use)
        self.failed = False
        self.close_at = el.end_line  # the line of END_TRANSITION (after an ST text that ends in no // comment)


class _Writer:
    def __init__(self, chart: Chart, out: BodyOut) -> None:
        self.chart = chart
        self.out = out
        self.named = self._named_transitions()
        # per transition: (anchor line, a function that writes it)
        self.pieces: list = []

    # ------------------------------------------------------------ the POU's named transitions

    def _named_transitions(self) -> dict:
        owner = self.out.owner
        holder = owner.kid("transitions") if owner is not None else None
        found: dict = {}
        for el in holder.kids("transition") if holder is not None else []:
            name = self.chart.ident(el.get("name", ""), el, "a transition's name")
            if name is None:
                continue
            if name.upper() in found:
                self.out.error("E183", f"a second transition named {name} in {self.out.pou}", el)
                continue
            found[name.upper()] = _Named(el, name)
        return found

    def _translate(self, named: _Named) -> bool:
        """named's body into its own view, once; False (reported) when it
        cannot be imported."""
        if named.body is not None or named.failed:
            return not named.failed
        lang = body_language(named.el.kid("body"))
        if not supported(lang):
            named.failed = True
            self.out.error(
                "E182",
                f"transition {named.name} is written in {lang.name if lang is not None else 'no language'}: "
                "softplc does not import that language here",
                named.el,
                "write its condition in ST (an expression, or statements assigning the transition's name)",
            )
            return False
        assert lang is not None
        view = LineView(len(self.out.view.lines))
        sub = BodyOut(view, self.out.texts, self.out.path, self.out.diags, self.out.pou, named.el)
        if lang.name == "ST":
            holder = lang.kids()[0] if lang.kids() else lang
            text = "".join(holder.itertext())
            named.marker, named.closing = ST_FORMS[st_form(text)]
            if not has_line_comment(text):
                named.close_at = self.out.texts.start(holder)[0] + text.rstrip().count("\n")
        translate(lang, sub)
        for d in sub.decls:
            self.out.declare(d)
        named.body = view
        return True

    # ------------------------------------------------------------ writing

    def write(self) -> None:
        chart = self.chart
        for step in chart.steps:
            if step.first:
                self.pieces.append((step.el.line, 0, lambda s=step: self._step(s)))
        for inline in chart.inlines:
            self.pieces.append((inline.el.line, 0, lambda i=inline: self._inline(i)))
        transitions = []
        for t in chart.transitions:
            plan = self._plan(t)
            if plan is not None:
                transitions.append((t, *plan))
        priorities = _priorities([(t, anchor) for t, anchor, _w in transitions])
        for t, anchor, writer in transitions:
            priority = priorities.get(t)
            self.pieces.append((anchor, t.index + 1, lambda w=writer, p=priority: w(p)))
        for _line, _k, piece in sorted(self.pieces, key=lambda p: (p[0], p[1])):
            piece()

    def _step(self, step) -> None:
        el, put = step.el, self.out.put
        put(el.line, el.col, f"{'INITIAL_STEP' if step.initial else 'STEP'} {step.name}:")
        for k, assoc in enumerate(step.assocs):
            put(min(el.line + 1 + k, el.end_line), el.col + 4, assoc.text())
        put(el.end_line, el.col, "END_STEP")
        for assoc in step.assocs:
            if assoc.once:  # a CODESYS entry or exit action: its statements once, not in the final scan too
                once = f"ACTION {assoc.once}: IF {assoc.once}.Q THEN {assoc.action}(); END_IF; END_ACTION"
                put(el.end_line, el.col, once, origin=(assoc.el.line, assoc.el.col))

    def _inline(self, inline) -> None:
        if not supported(inline.lang):
            self.out.error(
                "E182",
                f"an action of step {inline.name.rsplit('_inline', 1)[0]} is written in {inline.lang.name}: "
                "softplc does not import that language here",
                inline.el,
                "write the action in ST",
            )
            for step in self.chart.steps:
                step.assocs[:] = [a for a in step.assocs if a.el is not inline.el]
            return
        el = inline.el
        self.out.put(el.line, el.col, f"ACTION {inline.name}:")
        translate(inline.lang, self.out)
        self.out.put(el.end_line, el.col, "END_ACTION")

    def _plan(self, t: Transition) -> tuple | None:
        """(anchor line, writer(priority)) of t; None when its condition
        cannot be imported (reported)."""
        cond = t.condition
        kids = cond.kids() if cond is not None else []
        if not kids:
            self.out.error("E216", "a transition without a condition", t.el, "give it a condition, e.g. TRUE")
            return None
        kind = kids[0]
        if kind.name == "inline":
            return self._inline_condition(t, kind)
        if kind.name == "reference":
            name = self.chart.ident(kind.get("name", ""), kind, "a condition's name")
            if name is None:
                return None
            named = self.named.get(name.upper())
            if named is None:  # a BOOL variable
                return t.el.line, lambda p: self._expression(t, p, t.el.line, ((kind.line, kind.col), name))
            if not self._translate(named):
                return None
            if not named.used:
                named.used = True
                return named.el.line, lambda p: self._named_here(t, named, p)
            return t.el.line, lambda p: self._named_copy(t, named, p)
        if kind.name == "connectionPointIn":
            wired = wired_condition(self.chart, t, kind)
            if wired is None:
                return None
            if wired.calls.written:
                action = self._calls_action(t)
                return t.el.line, lambda p: self._wired_calls(t, wired, action, p)
            at = ((t.el.line, t.el.col), wired.expr)
            return t.el.line, lambda p: self._expression(t, p, t.el.line, at, wired.origin)
        self.out.error("E216", f"a condition <{kind.name}>: softplc does not import it", kind, None)
        return None

    def _inline_condition(self, t: Transition, inline: PosElement) -> tuple | None:
        lang = inline.kids()[0] if inline.kids() else None
        if lang is None or lang.name != "ST":
            self.out.error(
                "E216",
                f"an inline condition in {lang.name if lang is not None else 'no language'}: only ST is imported",
                inline,
                "write the condition as an ST expression, or wire it to contacts or blocks in the chart",
            )
            return None
        holder = lang.kids()[0] if lang.kids() else lang
        text = "".join(holder.itertext())
        if not text.strip():
            self.out.error("E216", "an empty inline condition", inline, "write an ST expression, e.g. level > 80")
            return None
        return t.el.line, lambda p: self._expression(t, p, t.el.line, (self.out.texts.start(holder), text))

    def _header(self, t: Transition, priority: int | None, name: str | None = None) -> str:
        return (
            "TRANSITION"
            + (f" {name}" if name else "")
            + (f" (PRIORITY := {priority})" if priority is not None else "")
            + f" FROM {_steps(t.sources)} TO {_steps(t.targets)}"
        )

    def _expression(
        self, t: Transition, priority: int | None, anchor: int, cond: tuple, origin: tuple | None = None
    ) -> None:
        """TRANSITION ... := cond; END_TRANSITION, the header at the anchor
        line, cond = ((line, col), text); origin: where text comes from
        when it is not placed there."""
        (line, col), text = cond
        self.out.put(anchor, t.el.col, self._header(t, priority) + " :=")
        self.out.put(line, col, text, origin)
        # after the condition on its last line, unless a // comment ends that line
        last = t.el.end_line if has_line_comment(text) else line + text.count("\n")
        self.out.put(last, t.el.col, "; END_TRANSITION")

    def _calls_action(self, t: Transition) -> str:
        """The ACTION holding the block calls of t's wired condition, named
        after the transition and associated S with the initial step: they
        run every cycle (sfc_wired.py)."""
        lid = t.el.get("localId", "")
        name = f"T{lid if lid.isdigit() else t.index}_blocks"
        taken = {s.name.upper() for s in self.chart.steps} | set(self.named)
        while name.upper() in taken:
            name += "_"
        initial = next((s for s in self.chart.steps if s.initial), None)
        if initial is not None:
            initial.assocs.append(Assoc(name, "S", t.el))
        return name

    def _wired_calls(self, t: Transition, wired: Wired, name: str, priority: int | None) -> None:
        """ACTION name: the calls END_ACTION, then the transition reading
        what they give, on the <transition>'s lines."""
        el = t.el
        self.out.put(el.line, el.col, f"ACTION {name}:")
        self.out.view.absorb(wired.calls)
        self.out.lowered(min(wired.calls.written), max(wired.calls.written))
        self.out.put(el.end_line, el.col, f"END_ACTION {self._header(t, priority)} :=")
        self.out.put(el.end_line, el.col, wired.expr, wired.origin)
        self.out.put(el.end_line, el.col, "; END_TRANSITION")

    def _named_here(self, t: Transition, named: _Named, priority: int | None) -> None:
        """The first use of a named transition: at its own lines."""
        el = named.el
        assert named.body is not None
        self.out.put(el.line, el.col, f"{self._header(t, priority, named.name)} {named.marker}".rstrip())
        self.out.view.absorb(named.body)
        self.out.put(named.close_at, el.col, f"{named.closing}END_TRANSITION")

    def _named_copy(self, t: Transition, named: _Named, priority: int | None) -> None:
        """A further use of a named transition: its body's lines copied in
        order onto the lines of the <transition> (the last of them holding
        what does not fit), each with the position it comes from (for
        diagnostics and faults: those of the named transition's text)."""
        el, view = t.el, named.body
        assert view is not None
        self.out.put(el.line, el.col, f"{self._header(t, priority, named.name)} {named.marker}".rstrip())
        rows = [(n, view.pad[n], view.lines[n][view.pad[n] :]) for n in sorted(view.written)]
        room = list(range(el.line + 1, el.end_line + 1)) or [el.line]
        joined = None
        if len(rows) > len(room):
            keep = len(room) - 1
            joined = (rows[keep][0], rows[keep][1], one_line([text for _n, _pad, text in rows[keep:]]))
            rows = [*rows[:keep], joined]
        for line, (n, pad, text) in zip(room, rows, strict=False):
            self.out.put(line, pad + 1, text, (n, pad + 1))
            if (n, pad, text) is not joined and line != el.line:  # the pieces placed apart in the body itself
                self.out.view.origins.extend((line, c, ol, oc) for ln, c, ol, oc in view.origins if ln == n)
        if view.lowered:
            self.out.lowered(room[0], room[min(len(rows), len(room)) - 1])
        self.out.put(el.end_line, el.col, f"{named.closing}END_TRANSITION")


def _steps(names: list) -> str:
    return names[0] if len(names) == 1 else "(" + ", ".join(names) + ")"


def _priorities(placed: list) -> dict:
    """PRIORITY for the transitions that share a source step, where their
    text order (anchor line, document order) is not the IEC order: lower
    priority attribute, then left to right, then document order. Ranks of
    one order over all of them, so every shared step sees its own."""
    iec = sorted((t for t, _a in placed), key=lambda t: (t.priority, t.x, t.index))
    anchor = {id(t): (a, t.index) for t, a in placed}
    sharing: dict = {}
    for t, _a in placed:
        for s in t.sources:
            sharing.setdefault(s.upper(), []).append(t)
    groups = [g for g in sharing.values() if len(g) > 1]
    if not any(
        any(t.priority for t in g)
        or sorted(g, key=lambda t: anchor[id(t)]) != sorted(g, key=lambda t: (t.priority, t.x, t.index))
        for g in groups
    ):
        return {}
    shared = {id(t) for g in groups for t in g}
    return {t: k + 1 for k, t in enumerate(t for t in iec if id(t) in shared)}


LANGUAGES["SFC"] = sfc_body  # graphical SFC bodies
