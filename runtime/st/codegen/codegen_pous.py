"""Code generation of declarations: a class per POU and STRUCT, globals.

One class with ``__slots__`` per PROGRAM, FUNCTION_BLOCK and STRUCT, one
plain function per FUNCTION, the class of the globals, and the code that
builds initial values from the checker's plans.
"""

from __future__ import annotations

import itertools
import re
from bisect import bisect_right
from typing import Any

from .. import ast as A
from .. import types as T
from ..check.symbols import POUInfo, copied_in_out
from .codegen_base import FnState, py_literal
from .codegen_locals import stored_first
from .codegen_sfc import SFC_SLOT, SFC_SLOT_TYPE, SfcGen


class PouGen(SfcGen):
    """Classes, functions and initial values."""

    def _struct_class(self, st: T.StructType) -> None:
        self.pos = None
        cls = st.pyclass
        self.emit("")
        self.emit(f"class {cls}:")
        self.indent += 1
        slots = [f.pyname for f in st.fields.values()]
        self.emit(f"__slots__ = ({''.join(repr(s) + ', ' for s in slots)})")
        meta = [(f.name, f.pyname, f.type, "FIELD") for f in st.fields.values()]
        self.emit(f"_VARS_ = {self.const(tuple(meta))}")
        self.emit("")
        self.emit("def __init__(self):")
        self.indent += 1
        scope = FnState(None)
        self.fn = scope
        if not st.fields:
            self.emit("pass")
        for f in st.fields.values():
            self._emit_init(f"self.{f.pyname}", f.type, f.init_value)
        self.indent -= 1
        self._assign_copy_methods(cls, [(f.pyname, f.type) for f in st.fields.values()])
        self.indent -= 1

    def _assign_copy_methods(self, cls: str, fields: list) -> None:
        self.emit("")
        self.emit("def _assign(self, o):")
        self.indent += 1
        if not fields:
            self.emit("pass")
        for name, ty in fields:
            if T.resolve(ty).is_aggregate:
                self.emit(f"_assign_into(self.{name}, o.{name})")
            else:
                self.emit(f"self.{name} = o.{name}")
        self.indent -= 1
        self.emit("")
        self.emit("def _copy(self):")
        self.indent += 1
        self.emit(f"n = {cls}.__new__({cls})")
        for name, ty in fields:
            if T.resolve(ty).is_aggregate:
                self.emit(f"n.{name} = _copy_value(self.{name})")
            else:
                self.emit(f"n.{name} = self.{name}")
        self.emit("return n")
        self.indent -= 1

    # ------------------------------------------------------------ initial values

    def _default_code(self, ty: T.Type) -> str:
        declared = T.declared_default(ty)
        if declared is not None:
            return self._aggregate_expr(ty, declared) if T.resolve(ty).is_aggregate else py_literal(declared)
        t = T.resolve(ty)
        if isinstance(t, T.ElementaryType):
            return "False" if t.is_bool else ("0.0" if t.is_real else "0")
        if isinstance(t, T.StringType):
            return "''"
        if isinstance(t, T.EnumType):
            return str(next(iter(t.values.values()), 0))
        if isinstance(t, T.SubrangeType):
            return str(t.lo if not t.lo <= 0 <= t.hi else 0)
        if isinstance(t, T.RefType):
            return "None"
        if isinstance(t, T.StructType):
            return f"{t.pyclass}()"
        if isinstance(t, T.FBType):
            return f"{t.pou.pyname}()"
        if isinstance(t, T.ArrayType):
            return self._array_code(t, None)
        return "None"

    def _scalar_plan_code(self, ty: T.Type, plan: Any) -> str:
        if plan is None or _is_ref_plan(plan):  # a REF() inside an aggregate: set by _emit_ref_inits
            return self._default_code(ty)
        return py_literal(plan)

    def _array_code(self, t: T.ArrayType, plan: Any) -> str:
        """An expression building an array from its plan's runs (checker:
        init_value). Its size follows the runs, not the elements: a block
        of equal elements is one repetition ([0] * 100, [Point() for _ in
        range(100)], nested for each dimension)."""
        if t.variable_length:
            return "None"
        sizes = [hi - lo + 1 for lo, hi in t.dims]
        strides = [1] * len(sizes)
        for d in range(len(sizes) - 2, -1, -1):
            strides[d] = strides[d + 1] * sizes[d + 1]
        runs = plan[1] if plan is not None else [(strides[0] * sizes[0], None)]
        starts = list(itertools.accumulate((n for n, _p in runs), initial=0))
        aggregate = T.resolve(t.elem).is_aggregate
        last = len(sizes) - 1

        def element(p: Any) -> str:
            return self._aggregate_expr(t.elem, p) if aggregate else self._scalar_plan_code(t.elem, p)

        def repeat(code: str, n: int, distinct: bool) -> str:
            return f"[{code} for _ in range({n})]" if distinct else f"[{code}] * {n}"

        def uniform(dim: int, p: Any) -> str:
            if dim == last:
                return repeat(element(p), sizes[dim], aggregate)
            return repeat(uniform(dim + 1, p), sizes[dim], True)

        def build(dim: int, offset: int) -> str:
            stride, end = strides[dim], offset + sizes[dim] * strides[dim]
            pieces: list = []
            loose: list = []  # single items, gathered into one list display
            i = offset
            while i < end:
                r = bisect_right(starts, i) - 1
                run_end = min(starts[r + 1], end)
                if dim == last:
                    n, code, distinct = run_end - i, element(runs[r][1]), aggregate
                elif i + stride <= run_end:
                    n, code, distinct = (run_end - i) // stride, uniform(dim + 1, runs[r][1]), True
                else:  # a block that several runs share
                    n, code, distinct = 1, build(dim + 1, i), True
                if n >= 4:
                    if loose:
                        pieces.append("[" + ", ".join(loose) + "]")
                        loose = []
                    pieces.append(repeat(code, n, distinct))
                else:
                    loose += [code] * n
                i += n * stride
            if loose or not pieces:
                pieces.append("[" + ", ".join(loose) + "]")
            return " + ".join(pieces)

        return build(0, 0)

    def _aggregate_expr(self, ty: T.Type, plan: Any) -> str:
        """An expression building an aggregate with an initial value plan."""
        t = T.resolve(ty)
        if isinstance(plan, tuple) and plan[0] == "fbinit":  # FB_X(nStart := 5) (codegen_oop.py)
            return self._fb_init_construct(ty, plan)
        if isinstance(t, T.ArrayType):
            return self._array_code(t, plan)
        if plan is None:
            return self._default_code(t)
        # struct/FB with field plans: built by a small helper taking a lambda list
        if not isinstance(t, (T.StructType, T.FBType)):
            raise TypeError(f"{ty} takes no field values")
        cls = t.pyclass if isinstance(t, T.StructType) else t.pou.pyname
        setters = []
        for key, sub in plan[1].items():
            attr, fty = self._member_attr(t, key)
            if T.resolve(fty).is_aggregate:
                setters.append((attr, self._aggregate_expr(fty, sub)))
            elif sub is not None and not _is_ref_plan(sub):
                setters.append((attr, py_literal(sub)))
        args = ", ".join(f"({attr!r}, {code})" for attr, code in setters)
        return f"_with_fields({cls}(), ({args}{',' if setters else ''}))"

    @staticmethod
    def _holds_instance(ty: T.Type) -> bool:
        """Whether a value of type ty is or holds an FB instance."""
        seen: set = set()
        todo = [ty]
        while todo:
            t = T.resolve(todo.pop())
            if isinstance(t, T.FBType):
                return True
            if id(t) in seen:
                continue
            seen.add(id(t))
            if isinstance(t, T.ArrayType):
                todo.append(t.elem)
            elif isinstance(t, T.StructType):
                todo += [f.type for f in t.fields.values() if f.type is not None]
        return False

    def _emit_ref_inits(self) -> None:
        """The references the last variables' initialisers take, now that
        every variable they may designate exists."""
        for target, call, pos, ty in self._ref_inits:
            self.pos = pos
            if isinstance(call, tuple):  # ('expr', init, its type): computed now (codesys, twincat)
                _kind, init, ety = call
                self.emit(f"{target} = {self.coerce(self.ex(init), ety, ty, init)}")
                continue
            # REF(x) / ADR(x) (as the variable's type: ADR(arr) into a POINTER TO INT), or the
            # variable a REFERENCE TO is bound to
            code = self.coerce(self.ex(call), call.ty, ty, None) if isinstance(call, A.Call) else self.ref_code(call)
            self.emit(f"{target} = {code}")
        self._ref_inits = []

    def _ref_plans(self, code: str, ty: T.Type, plan: Any):
        """(where, REF() call) for each reference an aggregate's initial
        value takes: its fields and elements, at any depth."""
        t = T.resolve(ty)
        if isinstance(plan, tuple) and plan[0] == "fbinit":
            plan = plan[2]  # the instance's own initial values, if any
        if _is_ref_plan(plan):
            yield code, plan[1], ty
        elif isinstance(plan, tuple) and plan[0] == "struct" and isinstance(t, (T.StructType, T.FBType)):
            for key, sub in plan[1].items():
                attr, fty = self._member_attr(t, key)
                yield from self._ref_plans(f"{code}.{attr}", fty, sub)
        elif isinstance(plan, tuple) and plan[0] == "array" and isinstance(t, T.ArrayType):
            sizes = [hi - lo + 1 for lo, hi in t.dims]
            flat = 0
            for count, sub in plan[1]:
                if sub is not None and (_is_ref_plan(sub) or T.resolve(t.elem).is_aggregate):
                    for i in range(flat, flat + count):
                        path, rest = "", i
                        for size in reversed(sizes):
                            path, rest = f"[{rest % size}]{path}", rest // size
                        yield from self._ref_plans(code + path, t.elem, sub)
                flat += count

    def _member_attr(self, t: T.StructType | T.FBType, key: str) -> tuple:
        if isinstance(t, T.StructType):
            f = t.fields[key]
            return f.pyname, f.type
        v = t.pou.vars[key]
        return v.pyname, v.type

    def _emit_init(self, target: str, ty: T.Type, plan: Any, ref_target: str | None = None) -> None:
        """target = the initial value. A reference's REF() initialiser is
        kept for _emit_ref_inits (to ref_target, if the variable is boxed
        after this): it may designate storage initialised after it."""
        t = T.resolve(ty)
        if isinstance(plan, tuple) and plan[0] == "ref":
            self.emit(f"{target} = None")
            self._ref_inits.append((ref_target or target, plan[1], self.pos, ty))
            return
        if isinstance(plan, tuple) and plan[0] == "expr":  # computed after the constant ones, in order
            self.emit(f"{target} = {self._default_code(ty)}")
            self._ref_inits.append((ref_target or target, plan, self.pos, ty))
            return
        if t.is_aggregate:
            self.emit(f"{target} = {self._aggregate_expr(ty, plan)}")
            self._ref_inits += [(path, call, self.pos, rty) for path, call, rty in self._ref_plans(target, t, plan)]
        else:
            self.emit(f"{target} = {self._scalar_plan_code(ty, plan)}")

    def _hidden(self, syms) -> None:
        """_HIDDEN_: the names of {attribute 'hide'} variables, which
        listings leave out (valuejson.encode_instance)."""
        hidden = frozenset(v.name for v in syms if v.hidden)
        if hidden:
            self.emit(f"_HIDDEN_ = {self.const(hidden)}")

    # ------------------------------------------------------------ POU classes

    def _fb_class(self, pou: POUInfo) -> None:
        self.pos = pou.node.pos
        self.fn = self._body_state(pou)
        self.emit("")
        self.emit(self._class_header(pou))  # class X, or class X(Base) (codegen_oop.py)
        self.indent += 1
        stored = [v for v in pou.vars.values() if v.location is None and not self._temp_local(v)]
        located = [v for v in pou.vars.values() if v.location is not None]
        own = [v for v in stored if v.owner is pou]  # a base class has the inherited ones
        hidden = [(SFC_SLOT, SFC_SLOT_TYPE)] if pou.sfc is not None else []  # not a variable
        slots = [v.pyname for v in own] + [h[0] for h in hidden]
        self.emit(f"__slots__ = ({''.join(repr(n) + ', ' for n in slots)})")
        meta = [(v.name, v.pyname, v.type, v.section) for v in pou.vars.values() if not self._temp_local(v)]
        self.emit(f"_VARS_ = {self.const(tuple(meta))}")
        self._hidden(pou.vars.values())
        for v in located:
            idx = self.accessor(v.location, T.base_elementary(v.type))
            self.emit(f"{v.pyname} = property(lambda self: _A{idx}g())")
        self.emit("")
        self.emit(f"def __init__(self{self._init_params(pou)}):")  # FB_init inputs (codegen_oop.py)
        self.indent += 1
        self.emit("pass")
        for v in pou.vars.values():
            self.pos = v.pos
            if v.location is not None:
                if v.init_value is not None:
                    idx = self.accessor(v.location, T.base_elementary(v.type))
                    self.emit(f"_A{idx}s({py_literal(v.init_value)})")
                continue
            if copied_in_out(v, self.profile):  # the instance's own copy (MatIEC)
                if T.resolve(v.type).is_aggregate:
                    self._emit_init(f"self.{v.pyname}", v.type, v.init_value)
                else:
                    self.emit(f"self.{v.pyname} = _CellRef({self._scalar_plan_code(v.type, v.init_value)})")
                continue
            if v.section == "VAR_IN_OUT":
                self.emit(f"self.{v.pyname} = None")
                continue
            if self._temp_local(v):
                continue
            self._emit_init(f"self.{v.pyname}", v.type, v.init_value)
        self._emit_ref_inits()
        if pou.sfc is not None:
            self._sfc_init(pou)
        self._fb_init_calls(pou)  # FB_init, base first (codegen_oop.py)
        self.indent -= 1
        plan = tuple((name, T.resolve(ty).is_aggregate) for name, ty in [(v.pyname, v.type) for v in stored] + hidden)
        self.emit("")
        self.emit(f"_COPY_ = {self.const(plan)}")  # for _slot_assign and _slot_copy (st/values.py)
        self.emit("_assign = _slot_assign")
        self.emit("_copy = _slot_copy")
        self.emit("")
        self.pos = pou.node.pos
        self.emit("def __call__(self):")
        self.indent += 1
        self._eno_true(pou)
        self._temps_init(pou)
        if pou.sfc is not None:
            self._sfc_body(pou)
        else:
            self._aliased_body(pou.node.body)
        self.indent -= 1
        for act in pou.actions.values():  # an ACTION: a method on the same variables
            self.pos = act.node.pos
            self.fn = self._body_state(pou)
            self.emit("")
            self.emit(f"def {act.pyname}(self):")
            self.indent += 1
            self._temps_init(pou)
            self._aliased_body(act.node.body)
            self.indent -= 1
        self._oop_members(pou)
        self.indent -= 1

    def _loop_faults(self, start: int, body: int, opened: bool) -> None:
        """A FOR loop whose body reads its loop local (codegen_stmts._for)
        stores the variable only after the loop; a fault, the watchdog or a
        stop inside it would leave the value from before the loop, which the
        monitor then shows. The body is wrapped in a handler that stores the
        local of each loop still running (its local is None before the loop
        and after it), then raises again. opened: the body is inside
        _locals_begin's try already (the handler joins it, before its
        finally); else a try is opened around the body's lines. Costs a None
        per loop at the start and after each loop, nothing per pass."""
        loops, self.fn.loop_locals = self.fn.loop_locals, None
        if not loops:
            return
        pad = "    " * (self.indent - 1 if opened else self.indent)  # the function's level
        if not opened:
            self.out[body:] = [("    " + text if text else text, at) for text, at in self.out[body:]]
            self.out.insert(body, (f"{pad}try:", self.pos))
        self.out[start:start] = [(f"{pad}{it} = None", self.pos) for _var, it in loops]
        if opened:
            self.indent -= 1
        self.emit("except:")  # the generated module has no builtins: everything that may raise
        self.indent += 1
        for var, it in loops:
            self.emit(f"if {it} is not None:")
            self.indent += 1
            self.emit_store(var, it, var.ty, None, trusted=True)
            self.indent -= 1
        self.emit("raise")
        if not opened:
            self.indent -= 1

    def _aliased_body(self, stmts: list) -> None:
        """The statements of a body of self (a PROGRAM's or FB's, an action's),
        reading the arrays, structs and FB instances of self that it reads
        more than once (or in a loop) through locals bound first (_a_<name> = self.<name>):
        a local is one load, an attribute two. They are never rebound while
        the body runs (an assignment copies into them; online change and
        retain replace them between cycles), so the local is the attribute."""
        start, pos = len(self.out), self.pos
        self.fn.aliases = {}
        self.fn.loop_locals = []
        promoted = self._locals_begin(stmts)
        body = len(self.out)
        self._body(stmts)
        self._loop_faults(start, body, bool(promoted))
        self._locals_end(promoted)
        aliases, self.fn.aliases = self.fn.aliases, None
        if not aliases:
            return
        local = {name: f"_a_{name}" if n > 1 else f"{self.fn.self_name}.{name}" for name, n in aliases.items()}
        marker = re.compile("\0([A-Za-z0-9_]+)\0")
        for i in range(start, len(self.out)):
            text, at = self.out[i]
            if "\0" in text:
                self.out[i] = (marker.sub(lambda m: local[m.group(1)], text), at)
        pad = "    " * self.indent
        binds = [(f"{pad}_a_{name} = {self.fn.self_name}.{name}", pos) for name, n in aliases.items() if n > 1]
        self.out[start:start] = binds

    def _eno_true(self, pou: POUInfo) -> None:
        """ENO is TRUE when the body starts (IEC 61131-3 ed.3 6.6.1.6); only
        a POU whose ENO is named anywhere has one (st/check/checker_eno.py)."""
        eno = pou.vars.get("ENO")
        if eno is not None and eno.section == "VAR_OUTPUT" and self._is_bool_type(eno.type):
            self.pos = pou.node.pos
            self._store_name(eno, "True")

    @staticmethod
    def _is_bool_type(ty: T.Type) -> bool:
        be = T.base_elementary(ty)
        return be is not None and be.is_bool

    def _temps_init(self, pou: POUInfo) -> None:
        """VAR_TEMP is re-initialised on every call (IEC)."""
        for v in pou.vars.values():
            if v.section == "VAR_TEMP":
                self.pos = v.pos
                target = v.pyname if self._temp_local(v) else f"self.{v.pyname}"
                self._emit_init(target, v.type, v.init_value)
        self._emit_ref_inits()

    def _function(self, pou: POUInfo, method: bool = False) -> None:
        """A FUNCTION, or (method) a METHOD or PROPERTY accessor of the
        class being emitted: the same, with self first."""
        self.pos = pou.node.pos
        self.fn = self._body_state(pou)
        inputs = pou.params("VAR_INPUT", "VAR_IN_OUT")
        outputs = pou.params("VAR_OUTPUT")
        params = []
        for v in inputs:
            if v.section == "VAR_IN_OUT" or T.resolve(v.type).is_aggregate:
                params.append(f"{v.pyname}=None")
            else:
                params.append(f"{v.pyname}={self._scalar_plan_code(v.type, v.init_value)}")
        params += [f"_o_{v.pyname}=None" for v in outputs]
        if method:
            params.insert(0, "self")
        self.emit("")
        self.emit(f"def {pou.pyname}({', '.join(params)}):")
        self.indent += 1
        for v in inputs:
            if v.section == "VAR_INPUT" and T.resolve(v.type).is_aggregate:
                self.pos = v.pos
                self.emit(f"if {v.pyname} is None:")
                self.indent += 1
                self._emit_init(v.pyname, v.type, v.init_value)
                self.indent -= 1
            if v.boxed and v.section == "VAR_INPUT":
                self.emit(f"{v.pyname} = _CellRef({v.pyname})")
        res = pou.result
        # no default for a scalar result the body stores first (an aggregate's store copies into it)
        first = (
            self.optimise
            and res is not None
            and not res.boxed
            and not T.resolve(res.type).is_aggregate
            and stored_first(pou.node.body, res)
        )
        if res is not None and not first:
            self.emit(f"r_result = {self._default_code(res.type)}")
            if res.boxed:
                self.emit("r_result = _CellRef(r_result)")
        for v in pou.vars.values():
            if v.section in ("VAR", "VAR_OUTPUT", "VAR_TEMP", "VAR_STAT"):
                self.pos = v.pos
                self._emit_init(v.pyname, v.type, v.init_value, f"{v.pyname}.value" if v.boxed else None)
                if v.boxed:
                    self.emit(f"{v.pyname} = _CellRef({v.pyname})")
        self._emit_ref_inits()
        self._eno_true(pou)
        self._body(pou.node.body)
        self._function_epilogue()
        self.indent -= 1

    def _function_epilogue(self) -> None:
        pou = self.fn.pou
        assert pou is not None  # only a FUNCTION's body ends with an epilogue
        outputs = pou.params("VAR_OUTPUT")
        for v in outputs:
            val = f"{v.pyname}.value" if v.boxed else v.pyname
            self.emit(f"if _o_{v.pyname} is not None: _o_{v.pyname}.set({val})")
        if pou.result is None:
            self.emit("return False")
        elif pou.result.boxed:
            self.emit("return r_result.value")
        elif not outputs and self._return_stored():
            pass
        else:
            self.emit("return r_result")

    def _return_stored(self) -> bool:
        """`Name := x;` just before the return (the body's last statement,
        or the one before RETURN): `return x` instead of `r_result = x`
        followed by `return r_result`. The line before, at the same indent,
        is the statement run just before (Python has no jumps into a block);
        it keeps its ST position, which a fault in x reports."""
        head = "    " * self.indent + "r_result = "
        if not self.out or not self.out[-1][0].startswith(head):
            return False
        line, pos = self.out[-1]
        self.out[-1] = ("    " * self.indent + "return " + line[len(head) :], pos)
        return True

    def _globals_class(self) -> None:
        self.pos = None
        self.fn = FnState(None, "self")
        gl = self.prog.globals
        stored = [g for g in gl if g.location is None]
        self.emit("")
        self.emit("class _Globals:")
        self.indent += 1
        self.emit(f"__slots__ = ({''.join(repr(g.pyname) + ', ' for g in stored)})")
        meta = [(g.name, g.pyname, g.type, "VAR_GLOBAL") for g in gl]
        self.emit(f"_VARS_ = {self.const(tuple(meta))}")
        self._hidden(gl)
        for g in gl:
            if g.location is not None:
                idx = self.accessor(g.location, T.base_elementary(g.type))
                self.emit(f"{g.pyname} = property(lambda self: _A{idx}g())")
        self.emit("")
        self.emit("def __init__(self):")
        self.indent += 1
        self.emit("pass")
        # FB instances last: their initial values may take references to other globals
        for g in sorted(gl, key=lambda g: self._holds_instance(g.type)):
            self.pos = g.pos
            if g.location is not None:
                if g.init_value is not None:
                    idx = self.accessor(g.location, T.base_elementary(g.type))
                    self.emit(f"_A{idx}s({py_literal(g.init_value)})")
                continue
            self._emit_init(f"self.{g.pyname}", g.type, g.init_value)
        self._emit_ref_inits()
        self.indent -= 1
        self.indent -= 1


def _is_ref_plan(plan: Any) -> bool:
    """Whether an initial value plan (checker_decls.init_value) is a REF()."""
    return isinstance(plan, tuple) and plan[0] == "ref"
