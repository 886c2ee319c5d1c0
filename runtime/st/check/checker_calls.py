"""The checker's calls: binding and typing every kind of call.

User FUNCTIONs, function block instances, the builtins TIME, LTIME, REF,
ADR and SIZEOF, and native functions (st/native.py); the standard
functions (generic parameters, folding) in checker_std_calls.py.
"""

from __future__ import annotations

from .. import ast as A
from .. import native
from .. import types as T
from ..native import NativeFunction
from ..profile import names_where
from .checker_base import BUILTINS, Scope
from .checker_operators import OPERATOR_FUNCTIONS
from .checker_std_calls import StdCallChecks
from .conversions import generic_fit, is_flexible, same_type
from .oop import extends_fb, fb_hint
from .symbols import CallInfo, POUInfo, PropertyInfo, VarSymbol, copied_in_out


class CallChecks(StdCallChecks):
    """Binding and typing every kind of call."""

    def call(self, e: A.Call, scope: Scope, as_statement: bool, expected: T.Type | None = None) -> T.Type | None:
        self.trailing_comma(e.trailing_comma)
        callee = e.callee
        hit = self._oop_call(e, scope, as_statement)  # methods, SUPER^() (checker_oop.py)
        if hit is not None:
            return hit[0]
        if isinstance(callee, A.Name):
            key = callee.name.upper()
            local = None
            if scope.pou is not None:
                local = scope.pou.vars.get(key)
                sfc_action = local is not None and self.is_sfc_action(scope.pou, key)  # its flags share its name
                if (local is None or sfc_action) and self.own_action_call(e, scope, as_statement):
                    return None
            if local is None and key not in self.pous:
                local = self.globals.get(key)
            if local is not None:
                return self._fb_call(e, callee, scope, as_statement)
            pou = self.pous.get(key)
            if pou is not None:
                if pou.kind == "FUNCTION":
                    return self._user_function_call(e, pou, scope)
                if pou.kind == "PROGRAM":
                    self.d.error(
                        "E043",
                        f"'{pou.name}' is a PROGRAM; programs are started by tasks",
                        e.pos,
                        "assign it to a TASK in the CONFIGURATION, or make it a FUNCTION_BLOCK and call an instance",
                    )
                else:
                    self.d.error(
                        "E043",
                        f"'{pou.name}' is a FUNCTION_BLOCK type, not an instance",
                        e.pos,
                        f"declare an instance (inst : {pou.name};) and call inst(...)",
                    )
                self._check_args_loosely(e, scope)
                return None
            native = self.natives.get(key)
            if native is not None:
                return self._native_call(e, native, scope)
            if key in BUILTINS:
                return self._builtin_call(e, key, scope)
            if key == "__QUERYINTERFACE":
                return self._query_interface(e, scope)
            func = self.std.get(key)
            if key == "TRUNC" and func is not None:
                func = self.trunc_for(expected, func)
            if func is not None:
                written = e.args
                gate = self.split_en_eno(e, scope)  # EN/ENO: st/check/checker_eno.py
                if not gate.ok:
                    e.args = written
                    self._check_args_loosely(e, scope)
                    return None
                if key in OPERATOR_FUNCTIONS:
                    ty = self.operator_call(e, func, scope)
                else:
                    ty = self._std_call(e, func, scope)
                e.args = written
                self.attach_gate(e, gate)
                return ty
            self.d.error(
                "E043",
                f"unknown function '{callee.name}'{self._elsewhere(callee.name)}",
                callee.pos,
                self._suggest(key, list(self.pous) + list(self.std) + list(BUILTINS)) or "declare it as a FUNCTION",
            )
            self._check_args_loosely(e, scope)
            return None
        if isinstance(callee, A.Member) and self.member_action_call(e, scope, as_statement):
            return None  # inst.Act(...)
        if isinstance(callee, (A.Member, A.Index, A.Deref)):  # inst.sub(...), timers[i](...), r^(...)
            return self._fb_call(e, callee, scope, as_statement)
        self.d.error("E043", "this cannot be called", e.pos)
        return None

    def _fb_call(self, e: A.Call, inst: A.Expr, scope: Scope, as_statement: bool, typed: bool = False) -> T.Type | None:
        ity = inst.ty if typed else self.expr(inst, scope)
        if ity is None:
            self._check_args_loosely(e, scope)
            return None
        fbt = T.resolve(ity)
        if not isinstance(fbt, T.FBType):
            self.d.error("E043", f"'{self._describe(inst)}' is {ity}, not a function block instance", inst.pos)
            self._check_args_loosely(e, scope)
            return None
        if not as_statement:
            self.d.error(
                "E043",
                "a function block call is a statement, not a value",
                e.pos,
                f"call it on its own line, then read an output, e.g. {self._describe(inst)}.Q",
            )
        info = CallInfo("fb", pou=fbt.pou, instance=inst)
        self._bind_args(e, fbt.pou, info, scope, is_fb=True)
        e.target = info
        return None

    def _describe(self, e: A.Expr) -> str:
        if isinstance(e, A.Name):
            return e.name
        if isinstance(e, A.Member):
            return f"{self._describe(e.base)}.{e.name}"
        return "expression"

    def _user_function_call(self, e: A.Call, pou: POUInfo, scope: Scope) -> T.Type | None:
        info = CallInfo("function", pou=pou)
        self._bind_args(e, pou, info, scope, is_fb=False)
        e.target = info
        return pou.return_type if pou.return_type is not None else T.BOOL

    def _bind_args(self, e: A.Call, pou: POUInfo, info: CallInfo, scope: Scope, is_fb: bool) -> None:
        positional = self._positional_params(e, pou)
        bound: set = set()
        pos_i = 0
        seen_formal = False
        for a in e.args:
            if a.name is None:
                if seen_formal:
                    self.d.error(
                        "E041",
                        "a positional argument after a named one",
                        a.pos,
                        "name every argument, or put positional ones first",
                    )
                if pos_i >= len(positional):
                    self.d.error("E041", f"too many arguments for {pou.name} (it takes {len(positional)})", a.pos)
                    if a.value is not None:
                        self.expr(a.value, scope)
                    continue
                param = positional[pos_i]
                pos_i += 1
            else:
                seen_formal = True
                param = pou.vars.get(a.name.upper())
                if param is None and a.name.upper() == "EN":  # IEC 61131-3 ed.3 6.6.1.6
                    self.en_argument(a, info, scope)
                    continue
                if param is None and a.name.upper() == "ENO":
                    param = self.implicit_eno(pou)
                if param is None or param.section not in ("VAR_INPUT", "VAR_IN_OUT", "VAR_OUTPUT"):
                    names = [v.name for v in pou.params("VAR_INPUT", "VAR_IN_OUT", "VAR_OUTPUT")]
                    self.d.error(
                        "E040",
                        f"{pou.name} has no parameter '{a.name}'",
                        a.pos,
                        f"its parameters are: {', '.join(names)}" if names else f"{pou.name} takes no parameters",
                    )
                    if a.value is not None:
                        self.expr(a.value, scope)
                    continue
            key = param.name.upper()
            if key in bound:
                self.d.error("E041", f"parameter '{param.name}' is given twice", a.pos)
                continue
            bound.add(key)
            if param.section == "VAR_OUTPUT":
                if not a.output and a.name is not None:  # positional: the target variable
                    self.d.error(
                        "E040",
                        f"'{param.name}' is an output; bind it with =>",
                        a.pos,
                        f"write {param.name} => variable",
                    )
                    continue
                if a.value is None:
                    continue
                tty = self.lvalue(a.value, scope)
                if tty is not None:
                    src = T.BOOL if a.negated else param.type
                    self.check_convertible(
                        src, tty, A.Name(param.name, pos=a.pos, ty=param.type), f"output '{param.name}'"
                    )
                info.outputs.append((param, a.value, a.negated))
                continue
            if a.output:
                self.d.error("E040", f"'{param.name}' is an input; pass it with :=", a.pos)
                continue
            if a.value is None:
                continue
            if T.is_reference(param.type):  # a REFERENCE TO parameter is bound to the argument
                if self.bind_argument(param, a.value, scope):
                    (info.inouts if param.section == "VAR_IN_OUT" else info.inputs).append((param, a.value))
                continue
            if param.section == "VAR_IN_OUT":
                vty = self.expr(a.value, scope)
                if vty is None:
                    continue
                if not self._is_lvalue_expr(a.value):
                    self.d.error(
                        "E042",
                        f"VAR_IN_OUT '{param.name}' needs a variable, not an expression",
                        a.value.pos,
                        "pass a variable: it is passed by reference",
                    )
                    continue
                self._check_writable(a.value, scope)
                if not self._inout_compatible(vty, param.type):
                    self.d.error(
                        "E020",
                        f"VAR_IN_OUT '{param.name}' is {param.type}; got {vty}",
                        a.value.pos,
                        fb_hint(vty, param.type) or "a reference parameter needs exactly its type",
                    )
                    continue
                self._mark_boxed(a.value, scope)
                info.inouts.append((param, a.value))
            else:
                vty = self.expr(a.value, scope, expected=param.type)
                if vty is not None and param.generic is not None:  # st/check/checker_generics.py
                    self.generic_argument(param, vty, a.value)
                elif vty is not None:
                    self.check_convertible(vty, param.type, a.value, f"input '{param.name}'")
                info.inputs.append((param, a.value))
        for param in pou.params("VAR_IN_OUT"):
            if param.name.upper() not in bound and not copied_in_out(param, self.profile):
                self.d.error(
                    "E042",
                    f"VAR_IN_OUT '{param.name}' of {pou.name} is not connected",
                    e.pos,
                    f"pass a variable: {param.name} := myVar",
                )
        for _, target, _n in info.outputs:
            self._mark_boxed(target, scope)

    @staticmethod
    def _positional_params(e: A.Call, pou: POUInfo) -> list:
        """The parameters a call's positional arguments bind, in order. A
        non-formal call lists the parameters in declaration order, outputs
        included, EN and ENO left out (IEC 61131-3 ed.3 6.6.1.4.2; TwinCAT:
        "the order of declaration ... is used for nonformal calls"):
        SPLIT_TOD(t, h, m, s, ms). A call with no more positional arguments
        than inputs and in-outs binds those alone, outputs skipped."""
        ins = pou.params("VAR_INPUT", "VAR_IN_OUT")
        if sum(1 for a in e.args if a.name is None) <= len(ins):
            return ins
        return [v for v in pou.params("VAR_INPUT", "VAR_IN_OUT", "VAR_OUTPUT") if v.name.upper() not in ("EN", "ENO")]

    def _inout_compatible(self, arg: T.Type, param: T.Type) -> bool:
        a, p = T.resolve(arg), T.resolve(param)
        if isinstance(p, T.ArrayType) and isinstance(a, T.ArrayType) and p.variable_length:
            return len(a.dims) == len(p.dims) and same_type(a.elem, p.elem)
        if isinstance(p, T.StringType) and isinstance(a, T.StringType):
            return a.wide == p.wide
        return same_type(a, p) or extends_fb(a, p)

    def _mark_boxed(self, e: A.Expr, scope: Scope) -> None:
        """A FUNCTION local passed by reference lives in a cell."""
        if isinstance(e, (A.Name, A.Member)) and isinstance(e.sym, PropertyInfo):
            self.d.error(
                "E147",
                f"PROPERTY {e.sym.name} is not a variable: it cannot be passed by reference",
                e.pos,
                "read it into a variable, pass that, and assign the property after the call",
            )
            return
        while isinstance(e, A.BitAccess) or (isinstance(e, A.Index) and isinstance(T.resolve(e.base.ty), T.StringType)):
            e = e.base  # => w.3, ADR(s[i]): the reference is to w, to s
        if isinstance(e, A.Name) and isinstance(e.sym, VarSymbol):
            e.sym.address_taken = True
        if (
            isinstance(e, A.Name)
            and isinstance(e.sym, VarSymbol)
            and e.sym.owner is not None
            and e.sym.owner.kind == "FUNCTION"
            and not T.resolve(e.sym.type).is_aggregate
        ):
            e.sym.boxed = True

    # ---------------------------------------------------------------- builtins

    def _builtin_call(self, e: A.Call, key: str, scope: Scope) -> T.Type | None:
        args = list(e.args)
        if key == "__ISVALIDREF":
            ty = self.isvalidref(e, scope)
            e.target = CallInfo("builtin", func=key, args=[args[0].value] if ty is not None else [])
            return ty
        if key in ("TIME", "LTIME"):
            if args:
                self.d.error(
                    "E041",
                    f"{key}() takes no arguments",
                    e.pos,
                    f"{key}() reads the task clock; to convert use TO_{key}(x)",
                )
                return None
            e.target = CallInfo("builtin", func=key)
            return T.TIME if key == "TIME" else T.LTIME
        if key in ("LOWER_BOUND", "UPPER_BOUND"):
            return self.bound_call(e, key, scope)  # st/check/checker_arrays.py
        if len(args) != 1 or args[0].name is not None or args[0].value is None:
            self.d.error("E041", f"{key} takes one argument", e.pos)
            return None
        a = args[0].value
        if key == "SIZEOF":
            e.target = CallInfo("builtin", func=key, args=[a])
            return self.sizeof_call(e, a, scope)
        ty = self.expr(a, scope)
        if ty is None:
            return None
        e.target = CallInfo("builtin", func=key, args=[a])
        if key == "ADR" and isinstance(a, A.Literal) and a.kind in ("string", "wstring"):
            if self.profile.adr_of_literal:  # ADR('TRUE'): to a copy of the text (profile.py)
                return T.RefType(ty, pointer=True)
            self.d.error(
                "E031",
                "ADR needs a variable, not a string literal",
                a.pos,
                f"declare a CONSTANT STRING and take its ADR (the "
                f"{names_where(lambda p: p.adr_of_literal)} profiles take ADR('text'))",
            )
            return None
        if not self._is_lvalue_expr(a) or (isinstance(a, A.Located)):
            self.d.error("E031", f"{key} needs a variable", a.pos)
            return None
        self._mark_boxed(a, scope)
        if isinstance(a, A.BitAccess):
            self.d.error("E031", f"{key} of a single bit is not possible", a.pos)
            return None
        return T.RefType(ty, pointer=(key == "ADR"))

    # ---------------------------------------------------------------- native functions

    def _native_call(self, e: A.Call, fn: NativeFunction, scope: Scope) -> T.Type | None:
        """A call of a native function (st/native.py): positional arguments,
        or every one named, checked against the declaration's parameter
        kinds; the arguments of parameters that share a type variable get
        one common type."""
        vals = self._native_args(e, fn)
        if vals is None:
            self._check_args_loosely(e, scope)
            return None
        found = [
            self.expr(v, scope, expected=T.BOOL if p.kind == native.BOOL else None) for p, v in zip(fn.params, vals)
        ]
        tys = [t for t in found if t is not None]
        if len(tys) < len(found):
            return None
        if any(p.same for p in fn.params):
            common = self._native_common(e, fn, vals, tys, scope)
            if common is None:
                return None
            tys = common
        for i, (param, ty, value) in enumerate(zip(fn.params, tys, vals)):
            table = T.resolve(ty)
            if not self._native_arg_fits(param, ty):
                self.d.error("E020", f"{fn.name}: {param.label(i + 1)} must be {param.expected}", value.pos)
            elif param.kind == native.WORDS and param.min_words and isinstance(table, T.ArrayType):
                dims = table.dims[0]
                if dims is not None and dims[1] - dims[0] + 1 < param.min_words:
                    self.d.error("E020", f"{fn.name}: {param.label(i + 1)} needs {param.min_words} words", value.pos)
        e.target = CallInfo("native", func=fn, args=vals, rtypes=tuple(tys))
        return T.ELEMENTARY[fn.result]

    def _native_args(self, e: A.Call, fn: NativeFunction) -> list | None:
        """The argument of each parameter in order (a parameter's default
        where a call by name leaves it out), or None after E041."""
        args = e.args
        if any(a.value is None or a.output for a in args):
            self.d.error("E041", f"{fn.name} has no outputs to connect", e.pos, fn.usage)
            return None
        if not any(a.name is not None for a in args):
            if len(args) == len(fn.params):
                return [a.value for a in args]
            self.d.error("E041", f"{fn.name} takes {len(fn.params)} positional arguments", e.pos, fn.usage)
            return None
        if any(a.name is None for a in args):
            self.d.error("E041", f"{fn.name}: name every argument or none", e.pos, fn.usage)
            return None
        given: dict = {}
        for a in args:
            key = a.name.upper()
            if key in given or not any(p.name.upper() == key for p in fn.params):
                known = ", ".join(p.name for p in fn.params)
                what = "twice" if key in given else f"is not an input of {fn.name} ({known})"
                self.d.error("E041", f"'{a.name}' {what}", a.pos, fn.usage)
                return None
            given[key] = a.value
        vals = []
        for p in fn.params:
            value = given.get(p.name.upper())
            if value is None and p.default is not None:
                value = A.Literal("string" if isinstance(p.default, str) else "bool", p.default, pos=e.pos)
            if value is None:
                self.d.error("E041", f"{fn.name} needs its input {p.name}", e.pos, fn.usage)
                return None
            vals.append(value)
        return vals

    def _native_common(self, e: A.Call, fn: NativeFunction, vals: list, tys: list, scope: Scope) -> list | None:
        """The argument types with every type variable bound to the common
        type of its arguments (an untyped literal takes the others' type)."""
        bindings: dict = {}
        for param, value, ty in zip(fn.params, vals, tys):
            if param.same and param.kind == native.ANY and not is_flexible(value):
                bindings.setdefault(param.same, ty)  # each keeps its type: only a literal takes it
            elif param.same and not is_flexible(value):
                cur = bindings.get(param.same)
                bindings[param.same] = ty if cur is None else self._unify(cur, ty, e)
                if bindings[param.same] is None:
                    return None
        out = list(tys)
        for i, (param, value, ty) in enumerate(zip(fn.params, vals, tys)):
            if not param.same or (param.kind == native.ANY and not is_flexible(value)):
                continue
            want = bindings.setdefault(param.same, ty)  # only literals: the first one's type
            if param.kind == native.ANY_REAL:
                want = bindings[param.same] = generic_fit(want, "ANY_REAL", self.profile)
            if is_flexible(value):
                got = self.expr(value, scope, expected=want)
                if got is None:
                    return None
                self.check_convertible(got, want, value, f"argument {i + 1} of {fn.name}")
            out[i] = want
        return [bindings[p.same] if p.same and p.kind != native.ANY else t for p, t in zip(fn.params, out)]

    @staticmethod
    def _native_arg_fits(param: native.Param, ty: T.Type) -> bool:
        if param.kind == native.BOOL:
            be = T.base_elementary(ty)
            return be is not None and be.is_bool
        if param.kind == native.ANY_ELEMENTARY:
            return isinstance(T.resolve(ty), T.EnumType) or T.is_generic_member(ty, "ANY_ELEMENTARY")
        if param.kind == native.ANY_REAL:
            return T.is_generic_member(ty, "ANY_REAL")
        if param.kind == native.ADDRESS:
            return isinstance(ty, T.SchneiderAddrType)
        if param.kind == native.STRING:
            return isinstance(T.resolve(ty), T.StringType)
        if param.kind == native.ANY_INT:
            be = T.base_elementary(ty)
            return be is not None and be.is_intlike
        if param.kind == native.ANY:
            return not isinstance(T.resolve(ty), T.FBType)
        t = T.resolve(ty)  # WORDS: a one-dimensional table of 16-bit words
        if not isinstance(t, T.ArrayType) or len(t.dims) != 1:
            return False
        elem = T.base_elementary(t.elem)
        return elem is not None and elem.bits == 16
