"""The checker's SFC part: the textual Sequential Function Chart of a
PROGRAM or FUNCTION_BLOCK (IEC 61131-3 ed.3 6.7, ed.2 2.6).

Each step becomes a variable of the POU (``s.X``, ``s.T``: rt_sfc.STEP_TYPE,
read-only to the program), each ACTION one too (``a.Q``, ``a.A``:
rt_sfc.ACTION_TYPE) and an action of the POU (checker_actions.py: a
method, called by the network while A and by ``a();`` or ``inst.a();``
like any ACTION); the result, ``SfcInfo`` on ``POUInfo.sfc``, is
what codegen_sfc.py emits. Diagnostics:

  E150  no INITIAL_STEP, or more than one
  E151  a transition names a step the network does not have
  E152  a step or action declared twice, or named like a variable or
        another ACTION of the POU
  E153  a transition condition that is not BOOL
  E154  an association names neither an ACTION nor a BOOL variable
  E155  a bad qualifier, a timed one without its TIME, or a time where
        none is taken
  E156  RETURN in an action or a transition's statements
  E157  a step flag written by the program
  W150  a step no transition path from the initial step reaches
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .. import ast as A
from .. import ast_sfc
from .. import types as T
from ..rtlib.rt_sfc import ACTION_TYPE, QUALIFIERS, STEP_TYPE, TIMED
from .checker_base import CheckerBase, Scope
from .symbols import ActionInfo, POUInfo, VarSymbol, pyname


@dataclass(eq=False)
class SfcTransitionInfo:
    node: ast_sfc.SfcTransition
    sources: tuple  # step indices
    targets: tuple
    name_sym: VarSymbol | None = None  # the name the statements assign (``: ... END_TRANSITION``)


@dataclass(eq=False)
class SfcActionInfo:
    name: str
    pos: A.Pos
    body: list | None = None  # an ACTION's statements, or
    target: A.Name | None = None  # the BOOL variable the action sets
    flags: VarSymbol | None = None  # an ACTION's Q and A
    method: str | None = None  # the pyname of an ACTION's method


@dataclass(eq=False)
class SfcInfo:
    """A checked SFC network: steps (their variables) in source order, the
    initial step's index, transitions in priority order, actions, and per
    step its associations (action index, qualifier, duration Expr or None)."""

    steps: list
    nodes: list = field(default_factory=list)  # the SfcStep of each step
    initial: int = 0
    transitions: list = field(default_factory=list)
    actions: list = field(default_factory=list)
    assocs: list = field(default_factory=list)
    by_name: dict = field(default_factory=dict)  # UPPER action name -> index in actions


class SfcChecks(CheckerBase):
    """Steps, transitions, actions and their associations."""

    def _declare_sfc(self, pou: POUInfo) -> None:
        """The steps as variables of the POU (before any body is checked)."""
        net: ast_sfc.SfcNetwork | None = pou.node.sfc
        if net is None:
            return
        info = SfcInfo([])
        initial: list = []
        for step in net.steps:
            key = step.name.upper()
            if key in pou.vars:
                self._sfc_twice(step.name, step.pos, pou.vars[key].pos)
                continue
            sym = VarSymbol(step.name, "VAR", STEP_TYPE, step.pos, pyname("v_", step.name), pou)
            # the initial step is active from the start (ed.3 6.7.2)
            sym.init_value = ("struct", {"X": True}) if step.initial else None
            self._inited.add(id(sym))
            pou.vars[key] = sym
            if step.initial:
                initial.append(step)
                info.initial = len(info.steps)
            info.steps.append(sym)
            info.nodes.append(step)
        for act in net.actions:
            self._declare_sfc_action(pou, act, info)
        for key, outside in list(pou.actions.items()):
            # ACTION Pou.Name outside the POU: how CODESYS and TwinCAT export
            # the actions of an SFC POU (each is an object of its own)
            if key not in info.by_name and key not in pou.vars:
                self._sfc_action_flags(pou, outside.node, info, outside.pyname)
        if not initial:
            self.d.error(
                "E150",
                f"the SFC network of {pou.name} has no INITIAL_STEP",
                net.pos,
                "make the step the sequence starts in INITIAL_STEP name: ... END_STEP",
            )
        for extra in initial[1:]:
            self.d.error(
                "E150",
                f"a second INITIAL_STEP '{extra.name}' in {pou.name}",
                extra.pos,
                f"an SFC network has one initial step; the first is '{initial[0].name}' at {initial[0].pos}",
            )
        pou.sfc = info

    def _declare_sfc_action(self, pou: POUInfo, act: ast_sfc.SfcAction, info: SfcInfo) -> None:
        """An ACTION of the network: its flags variable and its method."""
        key = act.name.upper()
        first = pou.vars.get(key)
        if first is not None:
            self._sfc_twice(act.name, act.pos, first.pos)
            return
        other = pou.actions.get(key)
        if other is not None:  # ACTION Pou.Name outside the POU
            self._sfc_twice(act.name, act.pos, other.node.name_pos)
            return
        node = A.Action(act.name, act.body, pos=act.pos, name_pos=act.pos)
        method = pyname("a_", act.name)
        pou.actions[key] = ActionInfo(act.name, node, pou, method)
        self.action_names.add(key)
        self._sfc_action_flags(pou, node, info, method)

    def _sfc_action_flags(self, pou: POUInfo, node: A.Action, info: SfcInfo, method: str) -> None:
        # ed.3 6.7.4: an action's Q (and A) can be read as name.Q; CODESYS
        # and TwinCAT have the same as the implicit variable _name.x
        key = node.name.upper()
        flags = VarSymbol(node.name, "VAR", ACTION_TYPE, node.name_pos, pyname("v_", node.name), pou)
        self._inited.add(id(flags))
        pou.vars[key] = flags
        info.by_name[key] = len(info.actions)
        info.actions.append(SfcActionInfo(node.name, node.name_pos, body=node.body, flags=flags, method=method))

    def is_sfc_action(self, pou: POUInfo, key: str) -> bool:
        """Whether key names an ACTION of pou's SFC network (its flags
        variable has the same name)."""
        info = pou.sfc
        return info is not None and key in info.by_name and info.actions[info.by_name[key]].flags is not None

    def _sfc_twice(self, name: str, pos: A.Pos, first: A.Pos) -> None:
        self.d.error("E152", f"'{name}' is declared twice", pos, f"the first declaration is at {first}")

    def _check_sfc(self, pou: POUInfo) -> None:
        info: SfcInfo | None = pou.sfc
        if info is None:
            return
        net: ast_sfc.SfcNetwork = pou.node.sfc
        index = {s.name.upper(): i for i, s in enumerate(info.steps)}
        self._sfc_actions(pou, info)
        order = []
        for k, tr in enumerate(net.transitions):
            scope = Scope(pou)
            priority = 0
            if tr.priority is not None:
                priority = self._const_int(tr.priority, scope, "a PRIORITY") or 0
            sources = self._sfc_steps(tr.sources, index)
            targets = self._sfc_steps(tr.targets, index)
            t = SfcTransitionInfo(tr, sources or (), targets or ())
            if tr.cond is not None:
                self._sfc_condition(tr.cond, scope)
            elif tr.body is not None and tr.name is not None:
                t.name_sym = VarSymbol(tr.name, "VAR_TEMP", T.BOOL, tr.pos, pyname("t_", tr.name), pou)
                scope.names[tr.name.upper()] = t.name_sym
                scope.sfc_part = "a TRANSITION"
                self._stmts(tr.body, scope)
            if sources is not None and targets is not None:
                order.append((priority, k, t))
        # lower PRIORITY first, then source order (ed.3 6.7.3: left to right)
        info.transitions = [t for _p, _k, t in sorted(order, key=lambda x: x[:2])]
        self._sfc_reachable(info)

    def _sfc_steps(self, names: list, index: dict) -> tuple | None:
        out = []
        for name, pos in names:
            i = index.get(name.upper())
            if i is None:
                self.d.error(
                    "E151",
                    f"the transition names '{name}', which is not a step",
                    pos,
                    self._suggest(name.upper(), list(index)) or "declare it with STEP name: ... END_STEP",
                )
                return None
            out.append(i)
        return tuple(out)

    def _sfc_condition(self, cond: A.Expr, scope: Scope) -> None:
        ty = self.expr(cond, scope, T.BOOL)
        if ty is not None and not self._is_bool(ty):
            self.d.error(
                "E153",
                f"a transition condition must be BOOL, not {ty}",
                cond.pos,
                "compare it, e.g. level >= 80",
            )

    def _sfc_actions(self, pou: POUInfo, info: SfcInfo) -> None:
        """The associations of each step (an association to a BOOL variable
        adds that variable as an action; the ACTIONs are declared)."""
        for step in info.nodes:
            assocs = []
            for a in step.assocs:
                found = self._sfc_association(pou, a, info, info.by_name)
                if found is not None:
                    assocs.append(found)
            info.assocs.append(assocs)

    def _sfc_association(self, pou: POUInfo, a: ast_sfc.SfcAssoc, info: SfcInfo, by_name: dict) -> tuple | None:
        scope = Scope(pou)
        key = a.action.upper()
        action = by_name.get(key)
        if action is None:
            target = A.Name(a.action, pos=a.pos)
            if key in pou.vars or key in self.globals:
                ty = self.lvalue(target, scope)
                if ty is not None and not self._is_bool(ty):
                    self.d.error(
                        "E154",
                        f"'{a.action}' is {ty}: an action is an ACTION or a BOOL variable",
                        a.pos,
                        f"declare ACTION {a.action}: ... END_ACTION, or associate a BOOL variable",
                    )
                    return None
                if ty is None:
                    return None
                action = by_name[key] = len(info.actions)
                info.actions.append(SfcActionInfo(a.action, a.pos, target=target))
            else:
                self.d.error(
                    "E154",
                    f"no action '{a.action}'",
                    a.pos,
                    self._suggest(key, [x.name for x in info.actions] + [v.name for v in pou.vars.values()])
                    or f"declare ACTION {a.action}: ... END_ACTION, or a BOOL variable",
                )
                return None
        return self._sfc_qualifier(a, scope, action)

    def _sfc_qualifier(self, a: ast_sfc.SfcAssoc, scope: Scope, action: int) -> tuple | None:
        """(action, qualifier, duration Expr or None) from the arguments: the
        qualifier first (N when there are none), then the duration of a timed
        one, then indicator variables (ed.3 6.7.4; checked, not used)."""
        args = list(a.args)
        qualifier = "N"
        if args:
            first = args.pop(0)
            spelled = first.name.upper() if isinstance(first, A.Name) else None
            if spelled not in QUALIFIERS:
                self.d.error(
                    "E155",
                    "an action association starts with its qualifier",
                    first.pos,
                    f"one of {', '.join(QUALIFIERS)}, e.g. {a.action}(N) or {a.action}(L, T#5s)",
                )
                return None
            qualifier = spelled
        duration = None
        if qualifier in TIMED:
            if not args:
                self.d.error(
                    "E155",
                    f"the qualifier {qualifier} takes a duration",
                    a.pos,
                    f"write {a.action}({qualifier}, T#5s) or name a TIME variable",
                )
                return None
            duration = args.pop(0)
            ty = self.expr(duration, scope, T.TIME)
            if ty is None:
                return None
            if T.resolve(ty) is not T.TIME:
                self.d.error("E155", f"the duration of {qualifier} must be TIME, not {ty}", duration.pos)
                return None
        for ind in args:
            if not isinstance(ind, A.Name):
                self.d.error(
                    "E155",
                    "after the qualifier (and its duration) only indicator variables may follow",
                    ind.pos,
                    None if qualifier in TIMED else f"the qualifier {qualifier} takes no duration",
                )
                return None
            self.expr(ind, scope)
        return (action, qualifier, duration)

    def _sfc_reachable(self, info: SfcInfo) -> None:
        """W150 for each step no sequence of transitions reaches from the
        initial step (a convergence needs all its steps reached)."""
        if not info.steps:
            return
        reached = {info.initial}
        grew = True
        while grew:
            grew = False
            for t in info.transitions:
                if set(t.sources) <= reached and not set(t.targets) <= reached:
                    reached.update(t.targets)
                    grew = True
        for i, sym in enumerate(info.steps):
            if i not in reached:
                self.d.warning(
                    "W150",
                    f"step '{sym.name}' is never reached from the initial step",
                    sym.pos,
                    "add a transition to it, or remove it",
                )
