"""Code generation of calls: functions, FB instances, standard, native.

User FUNCTIONs (keyword arguments, outputs through references), function
block instances (inputs, call, outputs), standard functions (a few inlined:
MIN, MAX, LIMIT, SEL, MOVE, shifts and integer conversions), builtins and
native functions.
"""

from __future__ import annotations

import re

from .. import ast as A
from .. import types as T
from ..check import conversions as C
from ..check.symbols import CallInfo, VarSymbol, copied_in_out
from ..native import CallSite
from ..rtlib import rt_varray
from . import ranges as R
from .codegen_base import CodeGenBase, elementary, py_literal


class CallGen(CodeGenBase):
    """Calls."""

    def _call_expr(self, e: A.Call) -> str:
        info: CallInfo = e.target
        if info.kind == "std":
            pts = info.param_types or []
            args = [self._std_arg(a, pts[i] if i < len(pts) else None) for i, a in enumerate(info.args)]
            code = self._std_invoke(info, args)
            if info.rtypes and T.base_elementary(info.rtypes[0]) is T.REAL and not self._exact_in_real(info):
                code = f"_f32({code})"  # SQRT, SIN, EXPT ... of a REAL: its binary32 result
            if info.en is not None or info.eno is not None:  # EN/ENO: st/codegen/codegen_eno.py
                return self.gated_value(info, code, e.ty, info.eno)
            return code
        if info.kind == "operator":  # ADD(a, b): the operator expression a + b
            if info.en is not None or info.eno is not None:
                return self.gated_value(info, self.ex(info.args[0]), e.ty, info.eno)
            return self.ex(info.args[0])
        if info.kind == "function":
            return self.function_gate(info, self._function_call(info))
        if info.kind == "method":
            return self._method_invoke(e, info)  # codegen_oop.py
        if info.kind == "builtin":
            if info.func == "TIME":
                return "_NOW_MS"  # the task clock, set once per cycle by the runner
            if info.func == "LTIME":
                return "_NOW_NS"
            if info.func == "ADR":
                return self.adr_code(info.args[0])
            if info.func == "REF":
                return self.ref_code(info.args[0])
            if info.func == "__ISVALIDREF":
                arg = info.args[0]
                if arg.implicit_ref is None:  # a VAR_IN_OUT: bound by a call of its POU
                    sym = arg.sym
                    own = self.fn.is_function and sym.owner is self.fn.pou
                    return f"({sym.pyname if own else f'{self.fn.self_name}.{sym.pyname}'} is not None)"
                return f"({self.ref_value(arg)} is not None)"
            if info.func == "__QUERYINTERFACE":
                src, dst = info.args
                return f"_query_into({self._query_code(src, dst.ty)}, {self.ref_code(dst)})"
            if info.func in ("LOWER_BOUND", "UPPER_BOUND"):  # of an ARRAY[*] (st/check/checker_arrays.py)
                dim = int(info.args[1].const) - 1
                return f"{self.ex(info.args[0])}.bounds[{dim}][{0 if info.func == 'LOWER_BOUND' else 1}]"
            return py_literal(e.const)
        if info.kind == "native":
            if info.func.site:  # the values in their common type, then where the call is (st/native.py)
                typed = [self.coerce(self.ex(a), a.ty, t, a) for a, t in zip(info.args, info.rtypes)]
                site = CallSite(e.pos.file, e.pos.line, e.pos.col, tuple(info.rtypes))
                return f"_native({self.const(info.func)}, {', '.join([*typed, self.const(site)])})"
            values = [self.ex(a) for a in info.args]
            # the service stores words into the tables: it needs each table's signedness (st/native.py)
            tables = [t for t in map(T.resolve, info.rtypes) if isinstance(t, T.ArrayType)]
            signed = [str(elementary(t.elem).category == T.SIGNED) for t in tables]
            return f"_native({', '.join([self.const(info.func), *values, *signed])})"
        raise NotImplementedError(info.kind)

    # Standard functions whose REAL result is already a binary32 value: one of
    # their arguments (or its negation), or a conversion, which rounds itself.
    _REAL_EXACT = frozenset(("ABS", "MIN", "MAX", "LIMIT", "SEL", "MUX", "MOVE"))

    @classmethod
    def _exact_in_real(cls, info: CallInfo) -> bool:
        name = info.func.name
        return name in cls._REAL_EXACT or "_TO_" in name or name.startswith("TO_")

    def _std_arg(self, a: A.Expr, param_type: T.Type | None) -> str:
        """An argument of a standard function; an integer into a REAL/LREAL
        parameter becomes a float of it (MAX(i, r) is a REAL, never i), and
        a REAL into an integer parameter (W121 where the profile allows it:
        MAX(1.5, i) with i an INT is an INT) the integer it converts to."""
        code = self.ex(a)
        if param_type is not None and a.ty is not None and isinstance(T.resolve(param_type), T.RefType):
            return self.coerce(code, a.ty, param_type, a)  # POINTER TO BYTE: a byte view of any pointer; 0 NULL
        if param_type is None or a.ty is None:
            return code
        pe, ae = T.base_elementary(param_type), T.base_elementary(a.ty)
        if pe is None or ae is None:
            return code
        if (pe.is_real and ae.is_intlike and a.const is None) or (pe.is_intlike and ae.is_real):
            return self.coerce(code, a.ty, param_type, a)
        return code

    _INLINE_2 = {"MAX": "max", "MIN": "min"}

    def _std_invoke(self, info: CallInfo, args: list) -> str:
        func = info.func
        name = func.name
        rty = T.base_elementary(info.rtypes[0]) if info.rtypes else None
        # a few hot functions inline (same results as the library versions)
        if name == "ABS" and len(args) == 1 and rty is not None and not rty.is_intlike:
            return f"abs({args[0]})"
        if name in self._INLINE_2 and len(args) >= 2 and rty is not None and (rty.is_intlike or rty.is_real):
            return f"{self._INLINE_2[name]}({', '.join(args)})"
        if name == "SEL" and len(args) == 3:
            return f"({args[2]} if {args[0]} else {args[1]})"
        if name == "MOVE" and len(args) == 1:
            return args[0]
        if name == "LIMIT" and rty is not None and (rty.is_intlike or rty.is_real):
            # IEC 61131-3 Table 28: MIN(MAX(IN, MN), MX), as the library's _limit
            # and the folding: MN > MX gives MX
            return f"min(max({args[1]}, {args[0]}), {args[2]})"
        inline = self._inline_shift(info, args) or self._inline_conversion(info, args)
        if inline is not None:
            return inline
        fn = self.const(func.impl)
        if func.typed:
            args = [self.const(info.rtypes), *args]
        if func.context:  # the ExecContext first: the clock, the running task
            args = ["_ctx", *args]
        return f"{fn}({', '.join(args)})"

    def _inline_shift(self, info: CallInfo, args: list) -> str | None:
        """SHL/SHR/ROL/ROR of an unsigned bit string by a constant count."""
        name = info.func.name
        if name not in R.WRAPPING_FUNCS:
            return None
        t = T.base_elementary(info.rtypes[0])
        n = info.args[1].const
        if t is None or not t.is_bits:
            return None
        w, mask = t.bits, (1 << t.bits) - 1
        if n is None and name in ("SHL", "SHR"):
            count, value = self._range(info.args[1]), self._range(info.args[0])
            if R.within(count, 0, w - 1) and R.within(value, 0, mask):
                if name == "SHR":
                    return f"({args[0]} >> {args[1]})"
                if count is not None and value is not None and value[1] << count[1] <= mask:
                    return f"({args[0]} << {args[1]})"  # SHL(WORD#1, j), j in 0..15: never past the width
                return f"({args[0]} << {args[1]} & {mask})"
            return None
        if not isinstance(n, int) or isinstance(n, bool) or n < 0:
            return None
        x = args[0]
        value = self._range(info.args[0])
        if not R.within(value, 0, mask):
            x, value = f"({x} & {mask})", (0, mask)
        if name in ("ROL", "ROR"):
            n %= w
            if n == 0:
                return x
            if not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_.]*", x):
                tmp = self.tmp("s")
                first, x = f"({tmp} := {x})", tmp
            else:
                first = x
            a, b = ("<<", ">>") if name == "ROL" else (">>", "<<")
            return f"(({first} {a} {n} | {x} {b} {w - n}) & {mask})"
        if n >= w:
            return "0"
        if name == "SHL":
            if value is not None and value[1] << n <= mask:
                return f"({x} << {n})"  # SHL(w AND 16#F, 12): never past the width
            return f"({x} << {n} & {mask})"
        return f"({x} >> {n})"

    def _inline_conversion(self, info: CallInfo, args: list) -> str | None:
        """<T>_TO_<U> between integer/bit-string types and into REAL/LREAL."""
        func = info.func
        if func.typed or "_TO_" not in func.name or "BCD" in func.name or len(func.params) != 1:
            return None
        head, _, tail = func.name.partition("_TO_")
        if head not in T.ELEMENTARY or tail not in T.ELEMENTARY:
            return None  # a library's HOST_TO_BE16 is no conversion
        src = T.ELEMENTARY.get(func.params[0][1].upper())
        dst = T.base_elementary(info.rtypes[0])
        if src is None or dst is None or not src.is_intlike:
            return None
        x = args[0]
        if dst.is_intlike:
            if R.fits(dst, self._range(info.args[0])):
                return x
            return self.wrap(dst, x)
        if (
            dst is T.LREAL
            and src.bits <= 32
            or dst is T.REAL
            and C.widens_to(src, T.REAL)
            or dst is T.REAL
            and R.within(self._range(info.args[0]), -(1 << 24), 1 << 24)
        ):
            return f"float({x})"  # exact: the integer fits the mantissa
        if dst is T.REAL and src.bits <= 53:
            return f"_f32({x})"  # one rounding, as the integer converts to double exactly
        return None

    def _function_call(self, info: CallInfo) -> str:
        pou = info.pou
        assert pou is not None  # a call of kind 'function' names its POU
        return f"{pou.pyname}({self._function_args(info)})"

    def _function_args(self, info: CallInfo, positional: bool = False) -> str:
        """The keyword arguments of a FUNCTION's or METHOD's call
        (positional: the leading inputs given without their names, which
        is a little faster to call)."""
        pou = info.pou
        assert pou is not None
        given = {p.name.upper(): (p, a) for p, a in info.inputs}
        given.update({p.name.upper(): (p, a) for p, a in info.inouts})
        parts = []
        for p in pou.params("VAR_INPUT", "VAR_IN_OUT"):
            got = given.get(p.name.upper())
            if got is None:
                parts.append(f"{p.pyname}=None" if p.section == "VAR_IN_OUT" else "")
                continue
            _, a = got
            if T.is_reference(p.type):  # bound to the argument (CODESYS)
                bound = self.cut_ref(self.bind_code(a), a.ty, C.ref_target(p.type))
                parts.append(f"{p.pyname}={bound if p.section == 'VAR_INPUT' else f'_CellRef({bound})'}")
            elif p.section == "VAR_IN_OUT":
                parts.append(f"{p.pyname}={self.inout_arg(p, a)}")
            elif T.resolve(p.type).is_aggregate:
                parts.append(f"{p.pyname}=_copy_value({self.ex(a)})")
            else:
                parts.append(f"{p.pyname}={self.coerce(self.ex(a), a.ty, p.type, a)}")
        if positional:
            for i, part in enumerate(parts):
                if not part:
                    break
                parts[i] = part.split("=", 1)[1]
        for p, target, negated in info.outputs:
            if negated:
                raise NotImplementedError("negated outputs of a FUNCTION")
            parts.append(f"_o_{p.pyname}={self.cut_ref(self.ref_code(target), target.ty, p.type)}")
        return ", ".join(x for x in parts if x)

    def inout_arg(self, p, a: A.Expr) -> str:
        """What a VAR_IN_OUT receives: a reference, or for an ARRAY[*] the
        array with its bounds (st/rtlib/rt_varray.py)."""
        pt, at = T.resolve(p.type), T.resolve(a.ty)
        if isinstance(pt, T.ArrayType) and pt.variable_length and isinstance(at, T.ArrayType):
            if at.variable_length:
                return self.ex(a)
            return f"{self.const(rt_varray.VarArray)}({self.ex(a)}, {self.const(tuple(at.dims))})"
        return self.cut_ref(self.ref_code(a), a.ty, p.type)

    def _call_stmt(self, e: A.Call) -> None:
        info: CallInfo = e.target
        if info.kind not in ("fb", "action"):
            self.emit(self.ex(e))
            return
        # an action inside its own POU: a method of the instance running
        inst = self.fn.self_name if info.instance is None else self.ex(info.instance)
        alias = re.fullmatch("\0([A-Za-z0-9_]+)\0", inst)
        if alias is not None and self.fn.aliases is not None:
            # an instance of self read through its local (codegen_pous.py _aliased_body):
            # the call reads it several times
            self.fn.aliases[alias.group(1)] += 2
        elif info.inputs or info.inouts or info.outputs or not re.fullmatch(r"[A-Za-z_][A-Za-z0-9_.]*", inst):
            t = self.tmp("fb")  # an instance never changes identity: look it up once
            self.emit(f"{t} = {inst}")
            inst = t
        if info.en is not None:  # IEC 61131-3 ed.3 6.6.1.6: nothing of the call unless EN
            self.emit(f"if {self.ex(info.en)}:")
            self.indent += 1
            self._fb_call_body(info, inst)
            self.indent -= 1
            self.emit("else:")
            self.indent += 1
            self.fb_skipped(info, inst)
            self.indent -= 1
            return
        self._fb_call_body(info, inst)

    @staticmethod
    def _exact_class(info: CallInfo) -> str | None:
        """The class of an FB instance that is built from its declared type
        (a variable of a PROGRAM, FB or the globals, a struct member or an
        array element, not reached through a VAR_IN_OUT, a reference, a
        pointer or a FUNCTION's input, which may hold an instance of a
        derived block): its body is called as Class.__call__(inst), which
        Python 3.11 calls faster than the instance (no slot lookup)."""
        e = info.instance
        if info.kind != "fb" or e is None:
            return None
        t = T.resolve(e.ty)
        if not isinstance(t, T.FBType) or t.pou is None or t.pou.kind != "FUNCTION_BLOCK":
            return None
        while True:
            if e.implicit_ref is not None:
                return None
            sym = getattr(e, "sym", None)
            if isinstance(e, (A.Name, A.Member)) and (
                not isinstance(sym, VarSymbol) or sym.section == "VAR_IN_OUT" or sym.boxed
            ):
                return None
            if isinstance(e, A.Name):
                # a FUNCTION's or METHOD's input is a copy of the argument (of its class)
                owner = sym.owner if isinstance(sym, VarSymbol) else None
                return str(t.pou.pyname) if owner is None or owner.kind in ("PROGRAM", "FUNCTION_BLOCK") else None
            if isinstance(e, A.Member) or (isinstance(e, A.Index) and e.via is None):
                e = e.base
                if not T.resolve(e.ty).is_aggregate:
                    return None
                continue
            return None

    def _fb_call_body(self, info: CallInfo, inst: str) -> None:
        for p, a in info.inputs:
            if T.is_reference(p.type):  # bound to the argument (CODESYS)
                self.emit(f"{inst}.{p.pyname} = {self.bind_code(a)}")
                continue
            code = self.ex(a) if T.resolve(p.type).is_aggregate else self.coerce(self.ex(a), a.ty, p.type, a)
            if T.resolve(p.type).is_aggregate:
                self.emit(f"_assign_into({inst}.{p.pyname}, {code})")
            else:
                self.emit(f"{inst}.{p.pyname} = {code}")
        copied = [(p, a) for p, a in info.inouts if copied_in_out(p, self.profile)]
        for p, a in info.inouts:
            if (p, a) in copied:  # the instance's own copy (MatIEC): in before the call, out after
                code = self.ex(a)
                is_aggregate = T.resolve(p.type).is_aggregate
                self.emit(
                    f"_assign_into({inst}.{p.pyname}, {code})" if is_aggregate else f"{inst}.{p.pyname}.set({code})"
                )
                continue
            if T.is_reference(p.type):
                ref = f"_CellRef({self.cut_ref(self.bind_code(a), a.ty, C.ref_target(p.type))})"
            else:
                ref = self.inout_arg(p, a)
            self.emit(f"{inst}.{p.pyname} = {ref}")
        if info.kind == "action":
            self.emit(self._action_invoke(info, inst))
        else:
            cls = self._exact_class(info)
            self.emit(f"{cls}.__call__({inst})" if cls is not None else f"{inst}()")
        for p, a in copied:
            if T.resolve(p.type).is_aggregate:
                self.emit(f"_assign_into({self.ex(a)}, {inst}.{p.pyname})")
            else:
                cut = isinstance(T.resolve(a.ty), T.StringType)  # cut to the argument's length
                self.emit_store(a, f"{inst}.{p.pyname}.get()", p.type, None, trusted=not cut)
        for p, target, negated in info.outputs:
            val = f"{inst}.{p.pyname}"
            if negated:
                val = f"(not {val})"
            if T.resolve(target.ty).is_aggregate:
                self.emit(f"_assign_into({self.ex(target)}, {val})")
            else:
                src = A.Name(p.name, ty=T.BOOL if negated else p.type)
                self.emit_store(target, val, src.ty, src)
