"""The checker's statements, and what an assignment may write to.

Assignments, IF, CASE, FOR, WHILE, REPEAT, EXIT/CONTINUE, SET/RESET; the
lvalues and whether they are writable (CONSTANT, inputs, FB outputs).
"""

from __future__ import annotations

import bisect

from .. import ast as A
from .. import types as T
from ..profile import names_where
from ..rtlib.rt_sfc import ACTION_TYPE, STEP_TYPE
from .checker_base import CheckerBase, Scope
from .symbols import POUInfo, PropertyInfo, VarSymbol


class StmtChecks(CheckerBase):
    """Statements and assignment targets."""

    def _stmts(self, body: list, scope: Scope) -> None:
        for s in body:
            try:
                self._stmt(s, scope)
            except RecursionError:
                self.d.error("E006", "statement nested too deeply", s.pos, "split it up")

    def _stmt(self, s: A.Stmt, scope: Scope) -> None:
        if isinstance(s, A.Assign):
            self._assign(s, scope)
        elif isinstance(s, A.CallStmt):
            self.call(s.call, scope, as_statement=True)
        elif isinstance(s, A.If):
            for cond, body in s.branches:
                self._bool_cond(cond, scope, "IF")
                self._stmts(body, scope)
            if s.else_body:
                self._stmts(s.else_body, scope)
        elif isinstance(s, A.Case):
            self._case(s, scope)
        elif isinstance(s, A.For):
            self._for(s, scope)
        elif isinstance(s, A.While):
            self._bool_cond(s.cond, scope, "WHILE")
            self._loop_body(s.body, scope)
        elif isinstance(s, A.Repeat):
            self._loop_body(s.body, scope)
            self._bool_cond(s.cond, scope, "UNTIL")
        elif isinstance(s, (A.Exit, A.Continue)):
            if scope.loops == 0:
                word = "EXIT" if isinstance(s, A.Exit) else "CONTINUE"
                self.d.error(
                    "E070", f"{word} outside a loop", s.pos, "EXIT and CONTINUE belong inside FOR, WHILE or REPEAT"
                )
        elif isinstance(s, A.Return):
            if scope.sfc_part is not None:
                self.d.error(
                    "E156",
                    f"RETURN in {scope.sfc_part} of an SFC body",
                    s.pos,
                    "it would end the POU's whole cycle; use IF to skip the rest",
                )
        elif isinstance(s, (A.Label, A.Jump)):
            pass  # where a JMP goes: checker_jumps.py
        elif isinstance(s, A.SetReset):
            ty = self.lvalue(s.target, scope)
            if ty is not None and not self._is_bool(ty):
                self.d.error("E020", f"{s.kind} needs a BOOL target, not {ty}", s.target.pos)
        else:
            self.d.error("E005", "unsupported statement", s.pos)

    def _loop_body(self, body: list, scope: Scope) -> None:
        scope.loops += 1
        self._stmts(body, scope)
        scope.loops -= 1

    def _bool_cond(self, cond: A.Expr, scope: Scope, what: str) -> None:
        ty = self.expr(cond, scope, expected=T.BOOL)
        if ty is not None and not self._is_bool(ty):
            self.d.error("E020", f"the {what} condition is {ty}, not BOOL", cond.pos, "compare it, e.g. x <> 0")

    def assign_expr(self, e: A.AssignExpr, scope: Scope) -> T.Type | None:
        """(target := value) used as a value, where the profile allows it
        (CODESYS "Assignment as expression"): the target is assigned as by a
        statement when the expression is evaluated, and its value is the
        target's after the store. Elementary targets only."""
        if not self.profile.assignment_expressions:
            self.d.error(
                "E032",
                "an assignment is a statement, not a value",
                e.pos,
                "assign on a line of its own, then use the variable (the "
                f"{names_where(lambda p: p.assignment_expressions)} profiles take an assignment as a value)",
            )
            self.expr(e.value, scope)
            return None
        tty = self.lvalue(e.target, scope)
        if tty is None:
            self.expr(e.value, scope)
            return None
        vty = self.expr(e.value, scope, expected=tty)
        target = e.target
        if (
            T.resolve(tty).is_aggregate
            or T.is_reference(tty)
            or isinstance(target, (A.BitAccess, A.Located))
            or (isinstance(target, A.Index) and isinstance(T.resolve(target.base.ty), T.StringType))
            or (isinstance(target, (A.Name, A.Member)) and isinstance(target.sym, PropertyInfo))
        ):
            self.d.error(
                "E032",
                f"an assignment to {tty} cannot be used as a value here",
                e.pos,
                "assign on a line of its own, then use the variable (a variable of an elementary type or "
                "a STRING may be assigned within an expression)",
            )
            return None
        if vty is None or not self.check_convertible(vty, tty, e.value, "the assignment"):
            return None
        self._mark_boxed(target, scope)  # stored through a reference (codegen_exprs.py)
        return tty

    def _assign(self, s: A.Assign, scope: Scope) -> None:
        if s.op == "?=":
            self._assignment_attempt(s, scope)  # checker_oop.py
            return
        if s.op == "REF=":
            self.ref_bind(s, scope)
            return
        tty = self.lvalue(s.target, scope)
        if tty is None:
            self.expr(s.value, scope)
            return
        vty = self.expr(s.value, scope, expected=tty)
        if vty is None:
            return
        if s.op in ("S=", "R="):
            if not self._is_bool(tty) or not self._is_bool(vty):
                self.d.error("E020", f"{s.op} needs BOOL on both sides", s.pos)
            return
        self.check_convertible(vty, tty, s.value, "the assignment")

    def _case(self, s: A.Case, scope: Scope) -> None:
        sty = self.expr(s.selector, scope)
        if sty is None:
            for br in s.branches:
                self._stmts(br.body, scope)
            return
        se = T.resolve(sty)
        sbase = T.base_elementary(se)
        if not (isinstance(se, T.EnumType) or (sbase is not None and sbase.is_intlike)):
            self.d.error("E060", f"CASE needs an integer or enumeration selector, not {sty}", s.selector.pos)
        seen = LabelSet()
        for br in s.branches:
            for lab in br.labels:
                if isinstance(lab, A.CaseRange):
                    lo = self._case_label(lab.lo, sty, scope)
                    hi = self._case_label(lab.hi, sty, scope)
                    if lo is None or hi is None:
                        continue
                    if hi < lo:
                        self.d.error("E060", f"empty CASE range {lo}..{hi}", lab.pos)
                        continue
                else:
                    lo = hi = self._case_label(lab, sty, scope)
                    if lo is None or hi is None:
                        continue
                ppos = seen.add(lo, hi, lab.pos)
                if ppos is not None:
                    self.d.error(
                        "E061", "CASE label overlaps an earlier one", lab.pos, f"the earlier label is at {ppos}"
                    )
            self._stmts(br.body, scope)
        if s.else_body:
            self._stmts(s.else_body, scope)

    def _case_label(self, e: A.Expr, sty: T.Type, scope: Scope) -> int | None:
        ty = self.expr(e, scope, expected=sty)
        if ty is None:
            return None
        if e.const is None or isinstance(e.const, (str, float)):
            self.d.error(
                "E060", "a CASE label must be a constant", e.pos, "use literals, enumeration values or CONSTANTs"
            )
            return None
        self.check_convertible(ty, sty, e, "the CASE label")
        return int(e.const)

    def _for(self, s: A.For, scope: Scope) -> None:
        vty = self.lvalue(s.var, scope)
        ve = T.base_elementary(vty) if vty is not None else None
        if vty is not None and (ve is None or not ve.is_intlike or isinstance(T.resolve(vty), T.EnumType)):
            self.d.error("E071", f"the FOR variable must be an integer, not {vty}", s.var.pos)
            vty = None
        for part in (s.start, s.end, s.step):
            if part is None:
                continue
            pty = self.expr(part, scope, expected=vty)
            if pty is not None and vty is not None:
                self.check_convertible(pty, vty, part, "the FOR bound")
        if s.step is not None and s.step.const == 0:
            self.d.error("E071", "FOR step 0 never ends", s.step.pos)
        sym = s.var.sym if isinstance(s.var, A.Name) else None
        scope.for_vars.append(sym)
        self._loop_body(s.body, scope)
        scope.for_vars.pop()

    def _is_lvalue_expr(self, e: A.Expr) -> bool:
        return isinstance(e, (A.Name, A.Member, A.Index, A.Deref, A.BitAccess, A.Located))

    def lvalue(self, e: A.Expr, scope: Scope) -> T.Type | None:
        ty = self.expr(e, scope)
        if ty is None:
            return None
        if not self._is_lvalue_expr(e):
            self.d.error(
                "E031", "this expression cannot be assigned to", e.pos, "the left side of := must be a variable"
            )
            return None
        self._check_writable(e, scope)
        return ty

    def _check_writable(self, e: A.Expr, scope: Scope) -> None:
        if e.implicit_ref is not None:
            return  # writes through a REFERENCE TO, like r^ := ...
        if isinstance(e, A.Name):
            sym = e.sym
            if isinstance(sym, PropertyInfo):
                self._assigned.add(id(e))
                if sym.setter is None:
                    self.d.error("E147", f"PROPERTY {sym.name} has no SET: it cannot be assigned", e.pos)
                return
            if not isinstance(sym, VarSymbol):
                self.d.error("E031", f"'{e.name}' is not a variable", e.pos)
                return
            if sym.constant:
                self.d.error(
                    "E030",
                    f"'{sym.name}' is a CONSTANT",
                    e.pos,
                    "remove CONSTANT from its declaration or assign another variable",
                )
            elif sym.type is STEP_TYPE:
                self.d.error(
                    "E157",
                    f"'{sym.name}' is an SFC step: its flags X and T are set by the sequence",
                    e.pos,
                    "change the step through the transitions; an action can set a variable instead",
                )
            elif sym.type is ACTION_TYPE:
                self.d.error(
                    "E157",
                    f"'{sym.name}' is an SFC action: its flags Q and A are set by the action control",
                    e.pos,
                    "change the action through its steps' qualifiers (S, R, ...); it can set a variable instead",
                )
            elif sym.section == "VAR_INPUT" and sym.owner is not None and sym.owner is scope.pou:
                self._own_input_assigned(sym, e.pos)
            elif sym in scope.for_vars:
                self.d.error(
                    "E072",
                    f"the FOR variable '{sym.name}' must not be changed in the loop",
                    e.pos,
                    "use EXIT to leave the loop early, or a WHILE loop",
                )
        elif isinstance(e, A.Member):
            sym = e.sym
            base_ty = T.resolve(e.base.ty) if e.base.ty is not None else None
            if isinstance(sym, PropertyInfo):
                self._assigned.add(id(e))
                if sym.setter is None:
                    self.d.error("E147", f"PROPERTY {sym.name} has no SET: it cannot be assigned", e.pos)
                    return
                if isinstance(e.base, A.Name) and isinstance(e.base.sym, POUInfo):
                    return  # Prog.P := v: a PROGRAM's property (checker_oop.py)
            if isinstance(base_ty, T.FBType) and isinstance(sym, VarSymbol):
                if self.internal_written(e):  # checker_exprs.py
                    return
                if sym.section == "VAR_OUTPUT" and not self.inside_fb(scope, base_ty.pou):
                    self.d.error(
                        "E030",
                        f"'{sym.name}' is an output of {base_ty.name}; it is written by the block, not from outside",
                        e.pos,
                        "read it after the call, e.g. x := inst.Q",
                    )
                    return
            self._check_writable(e.base, scope)
        elif isinstance(e, A.Index) and e.via is not None:
            return  # p[i]: written through the pointer, as p^
        elif isinstance(e, (A.Index, A.BitAccess)):
            self._check_writable(e.base, scope)
        elif isinstance(e, A.Located) and e.addr.table is not None:
            self.d.error(
                "E031",
                f"the word table {e.addr.text} cannot be assigned as a whole",
                e.pos,
                "assign its words one by one",
            )

    def _own_input_assigned(self, sym: VarSymbol, pos: A.Pos) -> None:
        """An input assigned inside its own POU: E030 where the profile
        reads inputs only (IEC), W130 where it lets the POU change them
        (CODESYS, TwinCAT, MatIEC: the value holds until the next call
        passes another)."""
        owner = sym.owner.name if sym.owner is not None else "its POU"
        if self.profile.own_input_assignment == "error":
            self.d.error(
                "E030",
                f"'{sym.name}' is an input of {owner} and cannot be assigned inside it",
                pos,
                "copy it into a local VAR and change that "
                f"(the {names_where(lambda p: p.own_input_assignment != 'error')} profiles allow it)",
            )
        else:
            self.d.warning(
                "W130",
                f"'{sym.name}' is an input of {owner}: assigning it inside changes what the caller passed",
                pos,
                "copy it into a local VAR and change that (IEC 61131-3 reads inputs only)",
            )


class LabelSet:
    """The CASE labels seen so far, as disjoint intervals sorted by their
    start: whether a new one overlaps is a binary search, so a CASE of
    n labels checks in n log n (a list of pairs compared with each other
    took 82 s for 40,000). A label that overlaps one is not added (it is
    reported); the earlier label named is the one lowest in value."""

    __slots__ = ("los", "his", "where")

    def __init__(self) -> None:
        self.los: list = []
        self.his: list = []
        self.where: list = []

    def add(self, lo: int, hi: int, pos) -> object | None:
        """Add lo..hi (at pos); the position of a label it overlaps, if any."""
        i = bisect.bisect_left(self.his, lo)  # the first interval ending at lo or later
        if i < len(self.los) and self.los[i] <= hi:
            return self.where[i]
        self.los.insert(i, lo)
        self.his.insert(i, hi)
        self.where.insert(i, pos)
        return None
