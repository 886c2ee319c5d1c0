"""The checker's ACTIONs: giving each action to its POU, and calling one.

An action is more code of a PROGRAM or FUNCTION_BLOCK that works on the
POU's variables and declares none of its own (CODESYS "Object: Action";
IEC 61131-3 ed.3 has them as the actions of SFC). Written inside the POU
after its body (IEC ed.3, Beremiz export) or on its own as ``ACTION
Pou.Name:`` (CODESYS/TwinCAT text export). Called ``Name();`` inside the
POU and ``inst.Name(...)`` on an FB instance, where the arguments are the
block's own inputs and outputs, as in a call of the instance (CODESYS:
``Inst.Reset(In := FALSE);``).

E047 is a declaration problem (unknown POU, a FUNCTION, twice the same
name, a name a variable has), E048 a call problem.
"""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from .checker_base import CheckerBase, Scope
from .oop import find_action
from .symbols import ActionInfo, CallInfo, POUInfo, pyname


class ActionChecks(CheckerBase):
    """ACTION blocks and their calls."""

    def _collect_actions(self, files: list) -> None:
        """Give every action to its POU (after _collect: all POUs known)."""
        for sf in files:
            for decl in sf.decls:
                if isinstance(decl, A.POU):
                    pou = self.pous.get(decl.name.upper())
                    if pou is not None and pou.node is decl:
                        for act in decl.actions:
                            self._add_action(pou, act)
                elif isinstance(decl, A.Action):
                    self._top_level_action(decl)

    def _top_level_action(self, act: A.Action) -> None:
        if act.pou_name is None:
            self.d.error(
                "E047",
                f"ACTION {act.name} outside a POU does not say whose action it is",
                act.name_pos,
                f"write ACTION Pou.{act.name}: (the PROGRAM or FUNCTION_BLOCK it belongs to), or put it inside "
                "the POU after its statements",
            )
            return
        pou = self.pous.get(act.pou_name.upper())
        if pou is None:
            self.d.error(
                "E047",
                f"ACTION {act.pou_name}.{act.name}: there is no POU '{act.pou_name}'",
                act.name_pos,
                self._suggest(act.pou_name.upper(), [p.name for p in self.pous.values()])
                or "declare the PROGRAM or FUNCTION_BLOCK the action belongs to",
            )
            return
        self._add_action(pou, act)

    def _add_action(self, pou: POUInfo, act: A.Action) -> None:
        if pou.kind == "FUNCTION":
            self.d.error(
                "E047",
                f"ACTION {act.name}: {pou.name} is a FUNCTION, and only PROGRAMs and FUNCTION_BLOCKs have actions",
                act.name_pos,
                "make it a FUNCTION_BLOCK, or the action a FUNCTION",
            )
            return
        key = act.name.upper()
        other = pou.actions.get(key)
        if other is not None:
            self.d.error(
                "E047",
                f"{pou.name} has two actions '{act.name}'",
                act.name_pos,
                f"the first is at {other.node.name_pos}; rename one",
            )
            return
        pou.actions[key] = ActionInfo(act.name, act, pou, pyname("a_", act.name))
        self.action_names.add(key)

    def _check_actions(self, pou: POUInfo) -> None:
        """The bodies of pou's actions, in the POU's scope (after its
        variables are declared)."""
        for key, act in list(pou.actions.items()):
            var = pou.vars.get(key)
            sfc = self.is_sfc_action(pou, key)  # its flags variable has its name (checker_sfc.py)
            if var is not None and not sfc:
                self.d.error(
                    "E047",
                    f"{pou.name} has a variable and an action named '{act.name}'",
                    act.node.name_pos,
                    f"the variable is declared at {var.pos}; rename one",
                )
                del pou.actions[key]
                continue
            scope = Scope(pou)
            if sfc:
                scope.sfc_part = "an ACTION"
            self._stmts(act.node.body, scope)
            self._check_jumps(act.node.body)

    # ------------------------------------------------------------ calls

    def own_action_call(self, e: A.Call, scope: Scope, as_statement: bool) -> bool:
        """``Act();`` inside the POU (one of its actions, or its METHODs, as
        CODESYS and TwinCAT allow): True when the name is an action of the
        POU that is being checked."""
        assert isinstance(e.callee, A.Name)
        pou = self.owner_fb(scope)  # a METHOD's: its block's
        if pou is None:
            return False
        act = find_action(pou, e.callee.name.upper())  # its own, or inherited (EXTENDS)
        if act is None:
            return False
        self._own_action_call(e, act, scope, as_statement)
        return True

    def _own_action_call(self, e: A.Call, act: ActionInfo, scope: Scope, as_statement: bool) -> None:
        if e.args:
            self.d.error(
                "E048",
                f"the action {act.name} takes no arguments inside {act.pou.name}",
                e.pos,
                "assign the variables before the call: the action works on them",
            )
            self._check_args_loosely(e, scope)
        self._action_call(e, act, None, scope, as_statement)

    def member_action_call(self, e: A.Call, scope: Scope, as_statement: bool) -> bool:
        """``inst.Act(...)`` or ``Prog.Act()``: True when e calls an action
        (checked here), False when it is some other call."""
        callee = e.callee
        assert isinstance(callee, A.Member)
        key = callee.name.upper()
        if key not in self.action_names:
            return False  # no action has the name: the usual instance call
        base = callee.base
        if isinstance(base, A.Name):
            bkey = base.name.upper()
            is_var = scope.pou is not None and bkey in scope.pou.vars or bkey in self.globals
            prog = self.pous.get(bkey)
            if not is_var and prog is not None and prog.kind == "PROGRAM" and key in prog.actions:
                act = prog.actions[key]
                if prog is scope.pou:  # Prog.Act inside Prog: its own action
                    self._own_action_call(e, act, scope, as_statement)
                    return True
                self.d.error(
                    "E048",
                    f"{prog.name}.{callee.name}: a PROGRAM's action is called only inside that PROGRAM here",
                    e.pos,
                    "programs are started by tasks and have no instance to call from elsewhere (E043); "
                    f"call {callee.name}() inside {prog.name}, or make {prog.name} a FUNCTION_BLOCK",
                )
                self._check_args_loosely(e, scope)
                return True
        bty = self.expr(base, scope)
        if bty is None:
            self._check_args_loosely(e, scope)
            return True
        fbt = T.resolve(bty)
        act = find_action(fbt.pou, key) if isinstance(fbt, T.FBType) else None
        if act is None:
            return False
        self._action_call(e, act, base, scope, as_statement)
        return True

    def _action_call(self, e: A.Call, act: ActionInfo, inst: A.Expr | None, scope: Scope, as_statement: bool) -> None:
        if not as_statement:
            self.d.error(
                "E048",
                f"calling the action {act.name} is a statement, not a value",
                e.pos,
                "call it on its own line, then read the variables it sets",
            )
        info = CallInfo("action", pou=act.pou, func=act, instance=inst)
        if inst is not None:
            self._bind_args(e, act.pou, info, scope, is_fb=True)
        e.target = info
