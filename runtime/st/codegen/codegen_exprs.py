"""Code generation of expressions, and of references to variables.

Reads of variables (fields, cells, loop locals, the process image),
indices with their bounds checks, operators with IEC semantics (truncating
division, MOD's sign, BOOL against bit-string operators), and the
reference objects REF, ADR, VAR_IN_OUT and => pass.
"""

from __future__ import annotations

import re
from typing import Any

from .. import ast as A
from .. import types as T
from ..check import conversions as C
from ..check.symbols import CallInfo, PropertyInfo, VarSymbol, copied_in_out
from ..rtlib import refs, rt_bytes, rt_varray
from . import ranges as R
from .codegen_base import CodeGenBase, array_type, elementary, py_literal

# Operations of a chain a + b + c ... nested in the generated Python as they
# are in the ST; a longer chain is cut into chunks this long (_long_chain).
CHAIN_CHUNK = 16


class ExprGen(CodeGenBase):
    """Expressions and references."""

    def ex(self, e: A.Expr) -> str:
        if self.fn.hoisted:
            moved = self.fn.hoisted.get(id(e))
            if moved is not None:  # computed before its FOR loop (codegen_hoist.py)
                return moved
        if type(e) is A.Index and e.via is not None:  # p[i]: (p + i elements)^
            return self.ex(e.via)
        if e.implicit_ref is not None:  # a REFERENCE TO stands for its target
            if T.resolve(e.ty).is_aggregate:
                return f"_deref({self.ref_value(e)})"
            return f"{self.ref_value(e)}.get()"
        if e.const is not None and e.ty is not None:
            r = T.resolve(e.ty)
            be = T.base_elementary(r)
            if be is not None or isinstance(r, T.StringType):
                return py_literal(C.const_repr(e.const, be) if be is not None else e.const)
        if isinstance(e, A.Name):
            if isinstance(e.ty, T.NullType):
                return "None"
            return self._read_name(e.sym)
        if isinstance(e, A.Member):
            if e.const is not None:
                return py_literal(e.const)
            if isinstance(e.sym, PropertyInfo):
                return self._property_read(e)  # codegen_oop.py
            if self._copied_cell(e.sym):
                return f"{self.ex(e.base)}.{e.sym.pyname}.get()"
            return f"{self.ex(e.base)}.{e.sym.pyname}"
        if isinstance(e, A.Index):
            return self._index_read(e)  # codegen_reuse.py
        if isinstance(e, A.AssignExpr):  # (x := v): stored when evaluated (checker_stmts.py)
            value = self.coerce(self.ex(e.value), e.value.ty, e.target.ty, e.value)
            return f"{self.const(refs.assign_get)}({self.ref_code(e.target)}, {value})"
        if isinstance(e, A.Deref):
            this = self._this_code(e)  # THIS^, SUPER^ (codegen_oop.py)
            if this is not None:
                return this
            base = self.ex(e.base)
            if T.resolve(e.ty).is_aggregate:
                return f"_deref({base})"
            return f"{base}.get()"
        if isinstance(e, A.BitAccess):
            if e.size != "X":  # d.%W1: the part, unsigned (ed.3 6.5.3)
                width = elementary(e.ty).bits
                return f"({self.ex(e.base)} >> {int(e.bit.const) * width} & {(1 << width) - 1})"
            # bit n of the (two's complement) value: x & 2**n, no shift first
            return f"({self.ex(e.base)} & {1 << int(e.bit.const)} != 0)"
        if isinstance(e, A.Located):
            if e.addr.table is not None:
                return f"_A{self.accessor(e.addr, None)}t"
            return f"_A{self.accessor(e.addr, T.base_elementary(e.ty))}g()"
        if isinstance(e, A.Unary):
            return self._unary(e)
        if isinstance(e, A.Binary):
            return self._binary(e)
        if isinstance(e, A.Call):
            return self._call_expr(e)
        if isinstance(e, A.SchneiderAddress):
            return self.const(e.parts)
        if isinstance(e, A.Literal):
            return py_literal(e.value)
        if isinstance(e, A.EnumLiteral):
            return py_literal(e.const)
        raise NotImplementedError(type(e).__name__)

    def _read_name(self, sym: Any) -> str:
        if not isinstance(sym, VarSymbol):
            if isinstance(sym, PropertyInfo):  # P inside its block: THIS^.P
                return f"{self.fn.self_name}.{sym.getter.pyname}()" if sym.getter else "None"
            raise NotImplementedError("name without a variable")
        loop_local = self.fn.for_locals.get(id(sym))
        if loop_local is not None:
            return loop_local
        local = self.fn.promoted.get(id(sym))
        if local is not None:
            return local
        if sym.location is not None:
            return f"_A{self.accessor(sym.location, T.base_elementary(sym.type))}g()"
        if sym.owner is None:
            return f"_G.{sym.pyname}"
        aggregate = T.resolve(sym.type).is_aggregate
        if self._temp_local(sym) and sym.owner is self.fn.pou:
            return sym.pyname
        if self.fn.is_function and sym.owner is self.fn.pou:
            if sym.section == "VAR_IN_OUT" and not aggregate:
                return f"{sym.pyname}.get()"
            if sym.boxed:
                return f"{sym.pyname}.value"
            return sym.pyname
        if aggregate and self.fn.aliases is not None and sym.section != "VAR_IN_OUT" and not sym.boxed:
            # an array, struct or FB instance of self is never rebound while a body
            # runs (assignment copies into it): read through a local (_aliased_body)
            reads = 2 if self.fn.loop_kinds else 1  # a read in a loop is a read many times
            self.fn.aliases[sym.pyname] = self.fn.aliases.get(sym.pyname, 0) + reads
            return f"\0{sym.pyname}\0"
        base = f"{self.fn.self_name}.{sym.pyname}"
        if sym.section == "VAR_IN_OUT" and not aggregate:
            return f"{base}.get()"
        return base

    def _index_target(self, e: A.Index) -> str:
        code = self.ex(e.base)
        if isinstance(T.resolve(e.base.ty), T.StringType):  # s[i]: a byte (codesys, twincat)
            return f"{self.string_leaf(e)}.byte_at({code}, {self.ex(e.indices[0])})"
        arr = array_type(e.base.ty)
        if arr.variable_length:  # ARRAY[*]: the caller's bounds (st/rtlib/rt_varray.py)
            return self._varray_items(code, e.indices, arr)
        for ix, dim in zip(e.indices, arr.dims):
            code += f"[{self._index_code(ix, dim)}]"
        return code

    def string_leaf(self, e: A.Index) -> str:
        """The byte layout of s in s[i] (st/rtlib/rt_bytes.py StrLeaf)."""
        st = T.resolve(e.base.ty)
        assert isinstance(st, T.StringType)
        return self.const(rt_bytes.StrLeaf(st.length, st.wide))

    def _varray_items(self, base: str, indices: list, arr: T.ArrayType, last: bool = True) -> str:
        """base[i, j] of an ARRAY[*] parameter (a VarArray): each index
        checked against the bounds the caller's array has; without the last
        index if not last."""
        pos = self.const(rt_varray.position)
        code = f"{base}.data"
        for k, (ix, dim) in enumerate(zip(indices if last else indices[:-1], arr.dims)):
            inner = self._index_code(ix, dim) if dim is not None else f"{pos}({self.ex(ix)}, {base}.bounds[{k}])"
            code += f"[{inner}]"
        return code

    def _index_code(self, ix: A.Expr, dim: tuple | None) -> str:
        if dim is None:  # ARRAY[*]: Python's own check, but no negative wrap-around
            return f"_check_index({self.ex(ix)}, 0, 1 << 62)"
        lo, hi = dim
        if isinstance(ix.const, int):
            return str(ix.const - lo)
        code = self.ex(ix)
        if R.within(self._range(ix), lo, hi):
            # the index provably lies inside the bounds (a FOR range, say): no check
            return f"{code} - {lo}" if lo else code
        if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_.]*", code):
            off = f"{code} - {lo}" if lo else code
            return f"({off} if {lo} <= {code} <= {hi} else _out_of_bounds({code}, {lo}, {hi}))"
        t = self.tmp("x")  # the condition runs first and binds the index once
        return f"({t} - {lo} if {lo} <= ({t} := {code}) <= {hi} else _out_of_bounds({t}, {lo}, {hi}))"

    def _unary(self, e: A.Unary) -> str:
        v = self.ex(e.operand)
        if e.op == "NOT":
            be = elementary(e.ty)
            if be.is_bool:
                return f"(not {v})"
            if be.is_bits:
                return f"({v} ^ {(1 << be.bits) - 1})"
            return f"(~{v})"
        if e.op == "-":
            return f"(-{v})"
        return v

    _CMP = {"=": "==", "<>": "!=", "<": "<", ">": ">", "<=": "<=", ">=": ">="}

    def _chained(self, e: A.Binary) -> bool:
        """Whether e's code takes its left operand's as a string (_operation)."""
        if e.impl is not None:
            return e.impl.kind != "pointer"
        return not (e.op in ("=", "<>") and (self._is_ref(e.left.ty) or self._is_ref(e.right.ty)))

    def _binary(self, e: A.Binary) -> str:
        if not self._chained(e):
            if e.impl is not None:
                return self.pointer_op(e)
            return self._ref_comparison(e)
        spine = [e]  # a chain a + b + c ...: its operations from the last one
        while len(spine) <= CHAIN_CHUNK and isinstance(spine[-1].left, A.Binary) and self._chained(spine[-1].left):
            spine.append(spine[-1].left)
        if len(spine) <= CHAIN_CHUNK:  # the usual expression: nested as written
            return self._operation(e, self.ex(e.left), self.ex(e.right))
        return self._long_chain(e)

    def _long_chain(self, e: A.Binary) -> str:
        """A chain of more than CHAIN_CHUNK operations (a + b + c ..., of
        any precedence on the right) without a call per operator and without
        nesting the Python a level per operator (CPython stops at 200
        parentheses): chunks of CHAIN_CHUNK operations, each stored into a
        temporary the next one starts from, in a tuple evaluated left to
        right: (_c := ((a + b) + c) ..., _c := ((_c + d) + e) ..., ...)[-1].
        Each operation is generated as in a short expression (the same
        wrap, rounding and short-circuit rules, the same order)."""
        spine = [e]
        while isinstance(spine[-1].left, A.Binary) and self._chained(spine[-1].left):
            spine.append(spine[-1].left)
        spine.reverse()
        t = self.tmp("c")
        code, steps = self.ex(spine[0].left), []
        for k, node in enumerate(spine):
            if k and k % CHAIN_CHUNK == 0:
                steps.append(f"{t} := {code}")
                code = t
            code = self._operation(node, code, self.ex(node.right))
        return f"({', '.join(steps)}, {code})[-1]"

    def _operation(self, e: A.Binary, lhs: str, rhs: str) -> str:
        """The code of one operation on the codes of its operands."""
        op = e.op
        if e.impl is not None:
            return self._std_invoke(e.impl, [lhs, rhs])
        if op in self._CMP:
            return f"({lhs} {self._CMP[op]} {rhs})"
        be = elementary(e.ty)
        if op in ("AND_THEN", "OR_ELSE"):
            return f"({lhs} {'and' if op == 'AND_THEN' else 'or'} {rhs})"
        if op in ("AND", "OR", "XOR"):
            if be.is_bool:
                if op == "XOR":
                    return f"({lhs} != {rhs})"
                if self.profile.short_circuit or not self._has_call(e.right):
                    return f"({lhs} {'and' if op == 'AND' else 'or'} {rhs})"
                return f"({lhs} {'&' if op == 'AND' else '|'} {rhs})"
            return f"({lhs} {'&' if op == 'AND' else '|' if op == 'OR' else '^'} {rhs})"
        divisor = e.right.const
        if (
            op in ("/", "MOD")
            and be.is_intlike
            and isinstance(divisor, int)
            and divisor > 0
            and not isinstance(divisor, bool)
        ):
            pyop = "//" if op == "/" else "%"
            lr = self._range(e.left)
            if lr is not None and lr[0] >= 0:
                return f"({lhs} {pyop} {divisor})"
            t = self.tmp("d")  # truncate toward zero / sign of the dividend (IEC)
            return f"({t} {pyop} {divisor} if ({t} := {lhs}) >= 0 else -(-{t} {pyop} {divisor}))"
        if op == "/" and be.is_intlike:
            return f"_idiv({lhs}, {rhs})"
        if op == "MOD":
            return f"_imod({lhs}, {rhs})"
        if op == "/":
            nonzero = isinstance(e.right.const, (int, float)) and e.right.const != 0
            code = f"({lhs} / {rhs})" if nonzero else f"_rdiv({lhs}, {rhs})"
        elif op == "**":
            code = f"_expt({lhs}, {rhs})"
        else:
            code = f"({lhs} {op} {rhs})"
        # REAL: binary32 after every operation (IEC 61131-3 ed.3 Table 10: REAL is
        # IEC 60559 single). The double result of + - * / on two binary32 values
        # rounds to the same binary32 as the exact one (binary64 has 53 >= 2*24+2
        # bits: double rounding is innocuous), so one rounding per operation
        # gives the FPU's result; LREAL and mixed REAL/LREAL stay double.
        return f"_f32({code})" if be is T.REAL else code

    @staticmethod
    def _is_ref(ty: T.Type | None) -> bool:
        return ty is not None and isinstance(T.resolve(ty), (T.RefType, T.NullType, T.InterfaceType))

    @staticmethod
    def _is_instance(ty: T.Type | None) -> bool:
        return ty is not None and isinstance(T.resolve(ty), T.FBType)

    def _ref_comparison(self, e: A.Binary) -> str:
        """r = NULL, r <> 0, r1 = r2: whether two references designate the
        same storage (NULL and the 0 CODESYS allows are no reference)."""
        # an FB instance compared with an interface (itf = inst) is itself: the interface holds it
        sides = [side if self._is_ref(side.ty) or self._is_instance(side.ty) else None for side in (e.left, e.right)]
        codes = ["None" if side is None or isinstance(side.ty, T.NullType) else self.ex(side) for side in sides]
        negate = "not " if e.op == "<>" else ""
        if "None" in codes:
            other = codes[1] if codes[0] == "None" else codes[0]
            return f"({other} is {negate}None)"
        return f"({negate}_same_ref({codes[0]}, {codes[1]}))"

    @staticmethod
    def _has_call(e: A.Expr) -> bool:
        todo = [e]  # a loop, not a call per operator: a chain may be 10,000 long
        while todo:
            e = todo.pop()
            if isinstance(e, A.AssignExpr):  # a store: evaluated as a call is
                return True
            if isinstance(e, (A.Name, A.Member)) and isinstance(e.sym, PropertyInfo):
                return True  # a property's read calls its getter
            if isinstance(e, A.Call):
                info = e.target
                if isinstance(info, CallInfo) and info.kind == "operator":
                    todo.append(info.args[0])
                    continue
                return True
            for attr in ("left", "right", "operand", "base"):
                sub = getattr(e, attr, None)
                if isinstance(sub, A.Expr):
                    todo.append(sub)
            if isinstance(e, A.Index):
                todo.extend(e.indices)
        return False

    # ------------------------------------------------------------ references

    def ref_value(self, e: A.Expr) -> str:
        """The reference a use of a REFERENCE TO holds (its binding)."""
        if isinstance(e, A.Name):
            return self._read_name(e.sym)
        if isinstance(e, A.Member):
            return f"{self.ex(e.base)}.{e.sym.pyname}"
        if isinstance(e, A.Index):
            return self._index_target(e)
        if isinstance(e, A.Call):
            return self._call_expr(e)
        raise NotImplementedError(f"REFERENCE TO in {type(e).__name__}")

    def cut_ref(self, code: str, actual: T.Type | None, formal: T.Type | None) -> str:
        """A reference to a string of type actual used as one to formal:
        cut what is stored through it at the actual's length when the
        formal is longer (IEC 61131-3 ed.3 6.4.2: a string never exceeds
        its declared length)."""
        a, f = T.resolve(actual) if actual is not None else None, T.resolve(formal) if formal is not None else None
        if isinstance(a, T.StringType) and isinstance(f, T.StringType) and a.length < f.length:
            return f"{self.const(refs.cut_ref)}({code}, {a.length}, {a.wide})"
        return code

    def bind_code(self, e: A.Expr) -> str:
        """What a REFERENCE TO bound to e holds (REF=, a reference parameter):
        NULL and 0 bind it to nothing."""
        if isinstance(T.resolve(e.ty), T.NullType) or e.const == 0:
            return "None"
        return self.ref_code(e)

    def _copied_cell(self, sym) -> bool:
        """A scalar VAR_IN_OUT of an FB kept as the instance's own cell
        (Profile.fb_in_out_copied): inst.io is read and set through it."""
        return isinstance(sym, VarSymbol) and copied_in_out(sym, self.profile) and not T.resolve(sym.type).is_aggregate

    def ref_code(self, e: A.Expr) -> str:
        """A reference to the storage of an lvalue (REF, ADR, VAR_IN_OUT, =>)."""
        if type(e) is A.Index and e.via is not None:
            return self.ref_code(e.via)
        if e.implicit_ref is not None:  # the storage a REFERENCE TO designates
            return self.ref_value(e)
        ty = T.resolve(e.ty)
        if ty.is_aggregate:
            return self.ex(e)
        if isinstance(e, A.Name):
            sym = e.sym
            if sym.location is not None:
                idx = self.accessor(sym.location, T.base_elementary(sym.type))
                return f"_AccessorRef(_A{idx}g, _A{idx}s)"
            if sym.owner is None:
                return f"_AttrRef(_G, {sym.pyname!r})"
            if self.fn.is_function and sym.owner is self.fn.pou:
                if sym.section == "VAR_IN_OUT" or sym.boxed:
                    return sym.pyname
                raise NotImplementedError("reference to an unboxed FUNCTION local")
            if sym.section == "VAR_IN_OUT":
                return f"{self.fn.self_name}.{sym.pyname}"
            return f"_AttrRef({self.fn.self_name}, {sym.pyname!r})"
        if isinstance(e, A.Member):
            if self._copied_cell(e.sym):
                return f"{self.ex(e.base)}.{e.sym.pyname}"
            return f"_AttrRef({self.ex(e.base)}, {e.sym.pyname!r})"
        if isinstance(e, A.Index) and isinstance(T.resolve(e.base.ty), T.StringType):  # ADR(s[i]): a byte view
            return f"{self.string_leaf(e)}.byte_ref({self.ref_code(e.base)}, {self.ex(e.indices[0])})"
        if isinstance(e, A.Index) and array_type(e.base.ty).variable_length:
            base = self.ex(e.base)
            arr = array_type(e.base.ty)
            k = len(e.indices) - 1
            last = e.indices[-1]
            inner = (
                self._index_code(last, arr.dims[k])
                if arr.dims[k] is not None
                else f"{self.const(rt_varray.position)}({self.ex(last)}, {base}.bounds[{k}])"
            )
            return f"_ItemRef({self._varray_items(base, e.indices, arr, last=False)}, {inner})"
        if isinstance(e, A.Index):
            base = self.ex(e.base)
            arr = array_type(e.base.ty)
            for ix, dim in list(zip(e.indices, arr.dims))[:-1]:
                base += f"[{self._index_code(ix, dim)}]"
            return f"_ItemRef({base}, {self._index_code(e.indices[-1], arr.dims[-1])})"
        if isinstance(e, A.Deref):
            return self.ex(e.base)
        if isinstance(e, A.Located):
            idx = self.accessor(e.addr, T.base_elementary(e.ty))
            return f"_AccessorRef(_A{idx}g, _A{idx}s)"
        if isinstance(e, A.BitAccess):  # an output bound to w.3 or d.%W1
            be = elementary(e.base.ty)
            width = 1 if e.size == "X" else elementary(e.ty).bits
            signed = be.lo is not None and be.lo < 0
            shift = int(e.bit.const) * width
            return f"{self.const(refs.PartRef)}({self.ref_code(e.base)}, {shift}, {width}, {be.bits}, {signed})"
        raise NotImplementedError(f"reference to {type(e).__name__}")
