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
from .codegen_base import CodeGenBase, elementary, py_literal


def _int_literal(code: str) -> bool:
    """Whether the Python code is an integer literal (a constant bound)."""
    return re.fullmatch(r"-?[0-9]+", code) is not None


#: a CASE of more branches is a table and a tree of ifs, not an elif chain
CASE_CHAIN = 64


class StmtGen(CodeGenBase):
    """Statements, conversions on store and stores."""

    def _body(self, stmts: list) -> None:
        start = len(self.out)
        if any(s.__class__ is A.Label and s.jumped_to for s in stmts):
            self._dispatch(stmts)  # a JMP goes to a label here (codegen_jumps.py)
            if self.fn.crossing:
                self._after_loop()  # EXIT, CONTINUE or JMP out of it
        else:
            for s in stmts:
                self._stmt(s)
                if self.fn.crossing:
                    self._after_loop()
        if len(self.out) == start:
            self.emit("pass")

    def _stmt(self, s: A.Stmt) -> None:
        self.pos = s.pos
        if isinstance(s, A.Assign):
            self._assign(s)
        elif isinstance(s, A.CallStmt):
            self._call_stmt(s.call)
        elif isinstance(s, A.If):
            for i, (cond, body) in enumerate(s.branches):
                self.pos = cond.pos if i else s.pos
                self.emit(f"{'if' if i == 0 else 'elif'} {self.ex(cond)}:")
                self.indent += 1
                known = self.fn.loop_ranges
                if i == 0:  # IF i >= 8 THEN ... samples[i - 8]: no bounds check
                    self.fn.loop_ranges = self._narrowed(cond, dict(known))
                self._body(body)
                self.fn.loop_ranges = known
                self.indent -= 1
            if s.else_body:
                self.emit("else:")
                self.indent += 1
                self._body(s.else_body)
                self.indent -= 1
        elif isinstance(s, A.Case):
            self._case(s)
        elif isinstance(s, A.For):
            self._for(s)
        elif isinstance(s, A.While):
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
        elif isinstance(s, A.Repeat):
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

    _BOUNDS = {">=": (0, None), ">": (1, None), "<=": (None, 0), "<": (None, -1), "=": (0, 0)}
    _MIRROR = {">=": "<=", ">": "<", "<=": ">=", "<": ">", "=": "="}

    def _narrowed(self, cond: A.Expr, known: dict) -> dict:
        """The ranges of FOR variables (read from their loop locals, constant
        bounds) where cond is TRUE: i >= 8, 8 <= i, i < n AND i > 0 narrow
        the range of i. A FOR variable cannot change in its loop's body."""
        if not isinstance(cond, A.Binary):
            return known
        if cond.op in ("AND", "AND_THEN") and T.base_elementary(cond.ty) is T.BOOL:
            return self._narrowed(cond.right, self._narrowed(cond.left, known))
        op, var, const = cond.op, cond.left, cond.right
        if not isinstance(var, A.Name):
            op, var, const = self._MIRROR.get(op, ""), cond.right, cond.left
        if op not in self._BOUNDS or not isinstance(var, A.Name) or id(var.sym) not in known:
            return known
        c = const.const
        if not isinstance(c, int) or isinstance(c, bool):
            return known
        lo, hi = known[id(var.sym)]
        dlo, dhi = self._BOUNDS[op]
        lo = lo if dlo is None else max(lo, c + dlo)
        hi = hi if dhi is None else min(hi, c + dhi)
        if lo <= hi:  # else the body never runs: leave it as it was
            known[id(var.sym)] = (lo, hi)
        return known

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
        if len(s.branches) > CASE_CHAIN:
            self._case_table(s, sel)
            return
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
            self._body(br.body)
            self.indent -= 1
        if s.else_body:
            if first:
                self._body(s.else_body)
            else:
                self.emit("else:")
                self.indent += 1
                self._body(s.else_body)
                self.indent -= 1

    def _case_table(self, s: A.Case, sel: str) -> None:
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
        self._case_tree(s.branches, 0, len(s.branches), kvar, s.else_body or [])

    def _case_tree(self, branches: list, first: int, end: int, k: str, else_body: list) -> None:
        if end - first <= CASE_CHAIN // 2:
            for i in range(first, end):
                self.pos = branches[i].pos
                self.emit(f"{'if' if i == first else 'elif'} {k} == {i}:")
                self.indent += 1
                self._body(branches[i].body)
                self.indent -= 1
            if first == 0 and else_body:  # only the first leaf can meet -1
                self.emit(f"elif {k} < 0:")
                self.indent += 1
                self._body(else_body)
                self.indent -= 1
            return
        mid = (first + end) // 2
        self.emit(f"if {k} < {mid}:")
        self.indent += 1
        self._case_tree(branches, first, mid, k, else_body)
        self.indent -= 1
        self.emit("else:")
        self.indent += 1
        self._case_tree(branches, mid, end, k, else_body)
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
        self.emit(f"for {it} in {self._for_iterable(rng, vty, known)}:")
        self.indent += 1
        local = self._loop_local_ok(var.sym, s.body)
        if local:
            self.fn.for_locals[id(var.sym)] = it
            if step is not None and isinstance(s.start.const, int) and isinstance(s.end.const, int):
                self.fn.loop_ranges[id(var.sym)] = (min(s.start.const, s.end.const), max(s.start.const, s.end.const))
        else:
            self.emit_store(var, it, vty, None, trusted=True)
        self.fn.loop_kinds.append(("for", (var, it, local)))
        self._body(s.body)
        self.fn.loop_kinds.pop()
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
            self.emit(f"_assign_into({self.ex(s.target)}, {self.ex(s.value)})")
            return
        self.emit_store(s.target, self.ex(s.value), s.value.ty, s.value)

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
