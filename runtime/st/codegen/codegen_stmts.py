"""Code generation of statements, and of the store that ends an assignment.

IF, CASE, FOR, WHILE, REPEAT (with the cooperative watchdog on loop
back-edges: program/context.py says how it counts), EXIT, CONTINUE, RETURN
(statement lists with jump labels: codegen_jumps.py);
an assignment stores the value converted to the target's type (coerce: what
conversions.store_step decides, written in Python).
"""

from __future__ import annotations

import re
from typing import Any

from .. import ast as A
from .. import types as T
from ..check import conversions as C
from ..check.symbols import PropertyInfo, VarSymbol
from ..faults import LOOP_CHECK_EVERY
from ..rtlib import rtlib
from ..rtlib.rt_case import CaseTable
from . import ranges as R
from .codegen_base import elementary, py_literal
from .codegen_facts import join
from .codegen_hoist import HoistGen


def _int_literal(code: str) -> bool:
    """Whether the Python code is an integer literal (a constant bound)."""
    return re.fullmatch(r"-?[0-9]+", code) is not None


#: a CASE of more branches is a table and a tree of ifs, not an elif chain
CASE_CHAIN = 64


class StmtGen(HoistGen):
    """Statements, conversions on store and stores."""

    def _body(self, stmts: list) -> None:
        """A statement list, run once or not at all: the facts after it are
        those that hold either way (codegen_facts.py)."""
        start = len(self.out)
        facts = self.fn.facts
        # what held before: None where no facts are kept, () where none is known
        entry = dict(facts) if facts else None if facts is None else ()
        if any(s.__class__ is A.Label and s.jumped_to for s in stmts):
            self.fn.facts = None  # a JMP may come back to any label: no facts
            self._dispatch(stmts)  # a JMP goes to a label here (codegen_jumps.py)
            self.fn.facts = None if entry is None else {}
            if self.fn.crossing:
                self._after_loop()  # EXIT, CONTINUE or JMP out of it
        else:
            for s in stmts:
                self._stmt(s)
                if self.fn.crossing:
                    self._after_loop()
        if entry is not None and self.fn.facts:
            self.fn.facts = join(entry, self.fn.facts) if entry else {}
        if len(self.out) == start:
            self.emit("pass")

    def _stmt(self, s: A.Stmt) -> None:
        self.pos = s.pos
        if isinstance(s, A.Assign):
            self._facts_before([s.target, s.value])
            self._assign(s)
        elif isinstance(s, A.CallStmt):
            self._facts_before([s.call])
            self._call_stmt(s.call)
        elif isinstance(s, A.If):
            found = self._facts_before([cond for cond, _ in s.branches], narrows=True)
            pre = self._facts_copy()
            exits: list = []
            for i, (cond, body) in enumerate(s.branches):
                self.pos = cond.pos if i else s.pos
                self._facts_enter_branch(pre)
                self.emit(f"{'if' if i == 0 else 'elif'} {self.ex(cond)}:")
                self.indent += 1
                known = self.fn.loop_ranges
                self._facts_narrow(cond, found)  # IF i >= 8 THEN ... samples[i - 8]: no bounds check
                self._body(body)
                exits.append(self.fn.facts)
                self.fn.loop_ranges = known
                self.indent -= 1
            if s.else_body:
                self.emit("else:")
                self.indent += 1
                self._facts_enter_branch(pre)
                self._body(s.else_body)
                exits.append(self.fn.facts)
                self.indent -= 1
            self._facts_branches(pre, exits, bool(s.else_body))
        elif isinstance(s, A.Case):
            self._facts_before([s.selector])
            self._case(s)
        elif isinstance(s, A.For):
            self._for(s)
        elif isinstance(s, A.While):
            self._facts_loop()
            wd = self._loop_budget_take()
            self.emit(f"while {self.ex(s.cond)}:")
            self.indent += 1
            self._watchdog_tick(wd)
            self.fn.loop_kinds.append(("while", wd))
            self._body(s.body)
            self.fn.loop_kinds.pop()
            self.indent -= 1
            self.pos = s.pos
            self._loop_budget_give(wd)
            self._facts_loop()
        elif isinstance(s, A.Repeat):
            self._facts_loop()
            wd = self._loop_budget_take()
            self.emit("while True:")
            self.indent += 1
            self._watchdog_tick(wd)
            self.fn.loop_kinds.append(("repeat", (s.cond, wd)))
            self._body(s.body)
            self.fn.loop_kinds.pop()
            self.pos = s.cond.pos
            self.emit(f"if {self.ex(s.cond)}: break")
            self.indent -= 1
            self.pos = s.pos
            self._loop_budget_give(wd)
            self._facts_loop()
        elif isinstance(s, A.Exit):
            self._leave_loop("break")
        elif isinstance(s, A.Continue):
            if self._leave_through_labels("continue"):
                return
            kind, data = self.fn.loop_kinds[-1]
            if kind == "repeat":
                self.emit(f"if {self.ex(data[0])}: break")
            self._leave_loop("continue")
        elif isinstance(s, A.Return):
            self._store_loop_locals()
            if self.fn.is_function:
                self._function_epilogue()
            else:
                self.emit("return")
        elif isinstance(s, A.SetReset):
            self.emit_store(s.target, "True" if s.kind == "SET" else "False", T.BOOL, None)
        elif isinstance(s, A.Jump):
            self._jump(s)
        elif isinstance(s, A.Label):
            pass  # no JMP names it
        else:
            raise NotImplementedError(type(s).__name__)

    def _leave_loop(self, word: str) -> None:
        if self._leave_through_labels(word):
            return
        kind, data = self.fn.loop_kinds[-1]
        if kind == "for" and word == "break" and data[2]:
            var, cur, _local = data
            self.emit_store(var, cur, var.ty, None, trusted=True)
        self.emit(word)

    def _store_loop_locals(self) -> None:
        """Before RETURN inside loops: give FOR variables their values, and
        every WHILE, REPEAT and list with labels hands its loop budget back."""
        for kind, data in self.fn.loop_kinds:
            if kind == "for" and data[2]:
                var, cur, _local = data
                self.emit_store(var, cur, var.ty, None, trusted=True)
        for kind, data in self.fn.loop_kinds:
            if kind == "while":
                self._loop_budget_give(data)
            elif kind == "repeat":
                self._loop_budget_give(data[1])
            elif kind == "jump":
                self._loop_budget_give(data.wd)

    # The cooperative watchdog (program/context.py): a FOR charges its length
    # to the loop budget before it starts; a WHILE or REPEAT counts down a
    # copy of the budget on every pass (_wd<n>, from _wd<n>s; a check renews
    # both) and charges the passes it made when it ends.

    def _loop_budget_take(self) -> str:
        wd = self.tmp("wd")
        if self.watchdog_checks:
            self.emit(f"{wd} = {wd}s = _ctx.loop_budget")
        return wd

    def _loop_budget_give(self, wd: str) -> None:
        if self.watchdog_checks:
            self.emit(f"_ctx.loop_budget -= {wd}s - {wd}")

    def _watchdog_tick(self, wd: str) -> None:
        if self.watchdog_checks:
            self.emit(f"{wd} -= 1")
            self.emit(f"if {wd} < 0: {wd} = {wd}s = _watchdog()")

    def _for_iterable(self, rng: str, var_type: T.Type, known: range | None = None) -> str:
        """What a FOR loop iterates over: its range, its length charged to
        the loop budget first; when that runs out, _loop checks and slices
        a long range. known: the range, when its bounds are constants."""
        if not self.watchdog_checks:
            return rng
        left = self.tmp("b")
        if known is not None:
            size = str(len(known))
        elif elementary(var_type).bits < 64:
            size = f"len({rng})"
        else:
            size = f"len({rng}[:{LOOP_CHECK_EVERY + 1}])"
        self.emit(f"_ctx.loop_budget = {left} = _ctx.loop_budget - {size}")
        return f"({rng} if {left} >= 0 else _loop({rng}))"

    def _case(self, s: A.Case) -> None:
        sel = self.ex(s.selector)
        if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_.]*", sel):
            t = self.tmp("c")
            self.emit(f"{t} = {sel}")
            sel = t
        pre = self._facts_copy()
        exits: list = []
        if len(s.branches) > CASE_CHAIN:
            self._case_table(s, sel, pre, exits)
        else:
            self._case_chain(s, sel, pre, exits)
        self._facts_branches(pre, exits, bool(s.else_body))

    def _case_branch(self, body: list, pre: dict | None, exits: list) -> None:
        """One branch of a CASE: from the facts before it (pre), its end's added to exits."""
        self._facts_enter_branch(pre)
        self._body(body)
        exits.append(self.fn.facts)

    def _case_chain(self, s: A.Case, sel: str, pre: dict | None, exits: list) -> None:
        first = True
        for br in s.branches:
            conds = []
            for lab in br.labels:
                if isinstance(lab, A.CaseRange):
                    conds.append(f"{int(lab.lo.const)} <= {sel} <= {int(lab.hi.const)}")
                else:
                    conds.append(f"{sel} == {int(lab.const)}")
            self.pos = br.pos
            self.emit(f"{'if' if first else 'elif'} {' or '.join(conds) or 'False'}:")
            first = False
            self.indent += 1
            self._case_branch(br.body, pre, exits)
            self.indent -= 1
        if s.else_body:
            if first:
                self._case_branch(s.else_body, pre, exits)
            else:
                self.emit("else:")
                self.indent += 1
                self._case_branch(s.else_body, pre, exits)
                self.indent -= 1

    def _case_table(self, s: A.Case, sel: str, pre: dict | None, exits: list) -> None:
        """A CASE of many branches: its branch's number from a table (rt_case),
        then a binary tree of ifs on it, as deep as log2 of the branches (an
        elif chain of 10,000 was too deep for Python's compiler)."""
        labels = []
        for k, br in enumerate(s.branches):
            for lab in br.labels:
                lo, hi = (lab.lo.const, lab.hi.const) if isinstance(lab, A.CaseRange) else (lab.const, lab.const)
                labels.append((int(lo), int(hi), k))
        kvar = self.tmp("k")
        self.emit(f"{kvar} = {self.const(CaseTable(labels))}({sel})")
        self._case_tree(s.branches, (0, len(s.branches)), kvar, s.else_body or [], (pre, exits))

    def _case_tree(self, branches: list, span: tuple, k: str, else_body: list, facts: tuple) -> None:
        first, end = span
        if end - first <= CASE_CHAIN // 2:
            for i in range(first, end):
                self.pos = branches[i].pos
                self.emit(f"{'if' if i == first else 'elif'} {k} == {i}:")
                self.indent += 1
                self._case_branch(branches[i].body, *facts)
                self.indent -= 1
            if first == 0 and else_body:  # only the first leaf can meet -1
                self.emit(f"elif {k} < 0:")
                self.indent += 1
                self._case_branch(else_body, *facts)
                self.indent -= 1
            return
        mid = (first + end) // 2
        self.emit(f"if {k} < {mid}:")
        self.indent += 1
        self._case_tree(branches, (first, mid), k, else_body, facts)
        self.indent -= 1
        self.emit("else:")
        self.indent += 1
        self._case_tree(branches, (mid, end), k, else_body, facts)
        self.indent -= 1

    def _for(self, s: A.For) -> None:
        var = s.var
        vty = var.ty
        # bounds convert to the variable's type (FOR i := 1 TO r, r REAL: a W121 narrowing)
        start = self.coerce(self.ex(s.start), s.start.ty, vty, s.start)
        end = self.coerce(self.ex(s.end), s.end.ty, vty, s.end)
        it = self.tmp("i")
        rng = self.tmp("r")
        step = None
        known = None  # the range, when the bounds are constants (and its length an int)
        if s.step is None or isinstance(s.step.const, int):
            step = 1 if s.step is None else s.step.const
            stop = f"{end} + 1" if step > 0 else f"{end} - 1"
            self.emit(f"{rng} = range({start}, {stop}{'' if step == 1 else f', {step}'})")
            if _int_literal(start) and _int_literal(end) and step != 0 and elementary(vty).bits < 64:
                known = range(int(start), int(end) + (1 if step > 0 else -1), step)
        else:
            step_code = self.coerce(self.ex(s.step), s.step.ty, vty, s.step)
            self.emit(f"{rng} = _for_range({start}, {end}, {step_code})")
        self._facts_loop()
        moved = self._hoist(s)  # codegen_hoist.py
        self.emit(f"for {it} in {self._for_iterable(rng, vty, known)}:")
        self.indent += 1
        local = self._loop_local_ok(var.sym, s.body)
        if local:
            self.fn.for_locals[id(var.sym)] = it
            if self.fn.loop_locals is not None:
                self.fn.loop_locals.append((var, it))
            if step is not None and isinstance(s.start.const, int) and isinstance(s.end.const, int):
                self.fn.loop_ranges[id(var.sym)] = (min(s.start.const, s.end.const), max(s.start.const, s.end.const))
        else:
            self.emit_store(var, it, vty, None, trusted=True)
        self.fn.loop_kinds.append(("for", (var, it, local)))
        self._body(s.body)
        self.fn.loop_kinds.pop()
        for node in moved:
            del self.fn.hoisted[node]
        self.fn.for_locals.pop(id(var.sym), None)
        self.fn.loop_ranges.pop(id(var.sym), None)
        self.indent -= 1
        self.emit("else:")
        self.indent += 1
        # IEC: after the loop the variable holds the first value past the end
        if known is not None and R.fits(elementary(vty), (after := known.start + len(known) * known.step,) * 2):
            self.emit_store(var, str(after), vty, None, trusted=True)
        else:
            self.emit_store(var, f"{rng}.start + len({rng}) * {rng}.step", vty, None)
        self.indent -= 1
        if local and self.fn.loop_locals is not None:
            self.emit(f"{it} = None")  # the loop is over: a later fault leaves the variable as it is
        self._facts_loop()

    def _loop_local_ok(self, sym: Any, body: list) -> bool:
        """May the body read the FOR variable from the Python loop local?
        Only when nothing else can observe the stored variable: a local of
        this POU that is not located, global, or reached by any reference
        (REF, ADR, VAR_IN_OUT, =>) nor by an action of the POU; the body
        itself may not assign it (E072)."""
        return (
            isinstance(sym, VarSymbol)
            and sym.owner is not None
            and not sym.owner.actions  # an action called in the loop may read it
            and sym.location is None
            and sym.section != "VAR_IN_OUT"
            and not sym.boxed
            and not sym.address_taken
        )

    # ------------------------------------------------------------ assignment

    def _assign(self, s: A.Assign) -> None:
        if s.op == "S=" or s.op == "R=":
            self.emit(f"if {self.ex(s.value)}:")
            self.indent += 1
            self.emit_store(s.target, "True" if s.op == "S=" else "False", T.BOOL, None)
            self.indent -= 1
            return
        if s.op == "REF=":
            bound = self.cut_ref(self.bind_code(s.value), s.value.ty, C.ref_target(s.target.ty) or s.target.ty)
            self.emit_store(s.target, bound, s.target.ty, None, trusted=True, bind=True)
            return
        if s.op == "?=":  # the assignment attempt: the instance, or NULL (codegen_oop.py)
            self.emit_store(s.target, self._query_code(s.value, s.target.ty), s.target.ty, None, trusted=True)
            return
        tty = T.resolve(s.target.ty)
        if tty.is_aggregate:
            self._facts_stored(s.target)
            self.emit(f"_assign_into({self.ex(s.target)}, {self.ex(s.value)})")
            return
        rng = self._fact_range(s.target, s.value)
        self.fn.bind_at = self.indent  # its reads of array elements may be bound (codegen_reuse.py)
        try:
            self.emit_store(s.target, self.ex(s.value), s.value.ty, s.value)
        finally:
            self.fn.bind_at = None
        if rng is not None and isinstance(s.target, A.Name):
            self._fact_set(s.target.sym, rng)
        elif isinstance(s.target, A.Index):
            self._bind_stored(s.target)  # codegen_reuse.py

    def coerce(self, code: str, src: T.Type, dst: T.Type, e: A.Expr | None) -> str:
        """Convert a value of type src to the representation of dst on store
        (wrap integers, round REAL to 32 bits, truncate strings): what
        happens is conversions.store_step's decision, written here."""
        if e is not None and e.const is not None and C.stores_literal(dst):
            return py_literal(C.const_as(e.const, src, dst))
        step = C.store_step(src, dst, e)
        if step == C.KEEP:
            return self.cut_ref(code, C.ref_target(src), C.ref_target(dst))  # POINTER TO STRING[2] into TO STRING[80]
        if step == C.TO_NULL:
            return "None"
        if step == C.TO_FIRST_ELEMENT:
            s = T.resolve(src)
            assert isinstance(s, T.RefType)
            return self.decay_code(code, s.target)
        if step == C.TO_BYTES:
            return self.byte_view_code(code, src, dst)  # codegen_pointers.py
        d = T.resolve(dst)
        if step == C.TRUNCATE and isinstance(d, T.StringType):
            if d.wide:  # UTF-16 units, never half a character (rt_strings.wcut)
                return f"{self.const(rtlib.wcut)}({code}, {d.length})"
            return f"({code})[:{d.length}]"
        if step == C.CHECK_RANGE and isinstance(d, T.SubrangeType):
            return f"_check_range({self.coerce(code, src, d.base, e)}, {d.lo}, {d.hi})"
        if step == C.TO_BOOL:
            return f"({code} != 0)"
        if step == C.TO_INT:
            return f"int({code})"
        if step == C.TO_FLOAT:
            return f"float({code})"
        if step == C.TO_F32:
            return f"_f32({code})"
        de = T.base_elementary(d)
        se = T.base_elementary(T.resolve(src) if src is not None else d)
        assert de is not None and se is not None  # store_step answers KEEP otherwise
        if step == C.CONVERT:
            return self._converter(se, de, code)
        # WRAP, unless the value provably fits
        if R.fits(de, self._range(e)):
            return code
        return self.wrap(de, code)

    def _converter(self, se: T.ElementaryType, de: T.ElementaryType, code: str) -> str:
        fn = rtlib.make_converter(se, de)
        return f"{self.const(fn)}({code})"

    def emit_store(
        self,
        target: A.Expr,
        value_code: str,
        value_ty: T.Type,
        value_expr: A.Expr | None,
        trusted: bool = False,
        bind: bool = False,
    ) -> None:
        """target := value, with the conversion to the target's type; bind:
        a REFERENCE TO target takes the reference value_code (REF=)."""
        tty = target.ty
        code = value_code if trusted else self.coerce(value_code, value_ty, tty, value_expr)
        self._facts_stored(target)
        if target.implicit_ref is not None and not bind:
            self.emit(f"{self.ref_value(target)}.set({code})")
        elif isinstance(target, (A.Name, A.Member)) and isinstance(target.sym, PropertyInfo):
            self._property_store(target, code)  # codegen_oop.py
        elif isinstance(target, A.Name):
            self._store_name(target.sym, code)
        elif isinstance(target, A.Member) and self._copied_cell(target.sym):
            self.emit(f"{self.ex(target.base)}.{target.sym.pyname}.set({code})")
        elif isinstance(target, A.Member):
            self.emit(f"{self.ex(target.base)}.{target.sym.pyname} = {code}")
        elif isinstance(target, A.Index) and target.via is not None:  # p[i] := v
            self.emit(f"{self.ex(target.via.base)}.set({code})")
        elif isinstance(target, A.Index) and isinstance(T.resolve(target.base.ty), T.StringType):
            base, ix = self.ex(target.base), self.ex(target.indices[0])
            new = f"{self.string_leaf(target)}.with_byte({base}, {ix}, {code})"
            self.emit_store(target.base, new, target.base.ty, None, trusted=True)
        elif isinstance(target, A.Index):
            self.emit(f"{self._index_target(target)} = {code}")
        elif isinstance(target, A.Deref):
            base = self.ex(target.base)
            self.emit(f"{base}.set({code})")
        elif isinstance(target, A.BitAccess):
            bit = int(target.bit.const)
            be = elementary(target.base.ty)
            cur = self.ex(target.base)
            mask = 1 << bit
            full = (1 << be.bits) - 1
            new = f"(({cur}) | {mask} if {code} else ({cur}) & {full ^ mask})"
            if target.size != "X":  # d.%W1 := w: the other bits stay (ed.3 6.5.3)
                width = elementary(tty).bits
                shift, part = bit * width, (1 << width) - 1
                new = f"(({cur}) & {full ^ (part << shift)} | ({code}) << {shift})"
            signed = be.lo is not None and be.lo < 0
            self.emit_store(target.base, self.wrap(be, new) if signed else new, target.base.ty, None, trusted=True)
        elif isinstance(target, A.Located):
            idx = self.accessor(target.addr, T.base_elementary(tty))
            self.emit(f"_A{idx}s({code})")
        else:
            raise NotImplementedError(type(target).__name__)

    def _store_name(self, sym: VarSymbol, code: str) -> None:
        local = self.fn.promoted.get(id(sym))
        if local is not None:  # a PROGRAM's scalar in a local (codegen_locals.py)
            self.fn.promoted_stored.add(id(sym))
            self.emit(f"{local} = {code}")
            return
        if sym.location is not None:
            idx = self.accessor(sym.location, T.base_elementary(sym.type))
            self.emit(f"_A{idx}s({code})")
            return
        if sym.owner is None:
            self.emit(f"_G.{sym.pyname} = {code}")
            return
        if self._temp_local(sym) and sym.owner is self.fn.pou:
            self.emit(f"{sym.pyname} = {code}")
            return
        if self.fn.is_function and sym.owner is self.fn.pou:
            if sym.section == "VAR_IN_OUT":
                self.emit(f"{sym.pyname}.set({code})")
            elif sym.boxed:
                self.emit(f"{sym.pyname}.value = {code}")
            else:
                self.emit(f"{sym.pyname} = {code}")
            return
        if sym.section == "VAR_IN_OUT":
            self.emit(f"{self.fn.self_name}.{sym.pyname}.set({code})")
        else:
            self.emit(f"{self.fn.self_name}.{sym.pyname} = {code}")
