"""The checker's calls of standard functions (fblocks/iec/functions.py):
the arguments matched to the parameters, generic parameters resolved
(ANY_NUM, ANY_BIT ...), the result typed, a call of constants folded;
what CallChecks.call hands on (checker_calls.py).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from .. import ast as A
from .. import types as T
from ..rtlib import rt_strings
from .checker_base import CheckerBase, Scope
from .conversions import const_repr, conversion_exists, generic_fit, is_flexible, same_type, string_result
from .symbols import CallInfo


class StdCallChecks(CheckerBase):
    def _check_args_loosely(self, e: A.Call, scope: Scope) -> None:
        for a in e.args:
            if a.value is not None:
                self.expr(a.value, scope)

    def _std_args(self, e: A.Call, func, scope: Scope) -> list | None:
        """Match the call's arguments to the parameters of a standard
        function; returns the argument expressions in parameter order."""
        params = list(func.params)
        n_fixed = len(params)
        args = e.args
        if func.extensible:
            n_fixed -= 1
        out: list = []
        if any(a.name is not None for a in args):
            by_name = {}
            for a in args:
                if a.name is None or a.output:
                    self.d.error("E041", f"{func.name}: mix of named and positional arguments", a.pos)
                    return None
                by_name[a.name.upper()] = a
            names = [p[0].upper() for p in params]
            if func.extensible:  # IN1, IN2, ... beyond the fixed ones
                base = names[-1].rstrip("0123456789")
                digits = names[-1][len(base) :]
                i = int(digits) + 1 if digits else len(names)
                while True:
                    nxt = f"{base}{i}"
                    if nxt in by_name and nxt not in names:
                        names.append(nxt)
                        i += 1
                    else:
                        break
            for a in args:
                if a.name.upper() not in names:
                    self.d.error(
                        "E040",
                        f"{func.name} has no parameter '{a.name}'",
                        a.pos,
                        f"its parameters are: {', '.join(p[0] for p in params)}",
                    )
                    return None
            for n in names:
                if n not in by_name:
                    self.d.error("E041", f"{func.name}: parameter '{n}' is missing", e.pos)
                    return None
                out.append(by_name[n].value)
        else:
            out = [a.value for a in args]
            for a in args:
                if a.output:
                    self.d.error("E040", f"{func.name} has no outputs", a.pos)
                    return None
        need = len(params)
        if len(out) < need or (not func.extensible and len(out) > need):
            self.d.error(
                "E041",
                f"{func.name} takes {'at least ' if func.extensible else ''}{need} argument(s), {len(out)} given",
                e.pos,
                f"{func.name}({', '.join(p[0] for p in params)})",
            )
            return None
        return out

    def trunc_for(self, expected: T.Type | None, func):
        """TRUNC of the integer type expected where the profile takes it from
        the context (Profile.trunc_from_context, MatIEC: one TRUNC per
        integer type, IEC 61131-3 ed.2 Table 22), else func (DINT)."""
        be = T.base_elementary(expected) if expected is not None else None
        if self.profile.trunc_from_context and be in T.INTEGERS:
            return self.std.get(f"TRUNC_{be.name}", func)
        return func

    def is_context_trunc(self, e: A.Expr) -> bool:
        """A call of TRUNC that takes its type from the context (see trunc_for)."""
        return (
            self.profile.trunc_from_context
            and isinstance(e, A.Call)
            and isinstance(e.callee, A.Name)
            and e.callee.name.upper() == "TRUNC"
            and "TRUNC" not in self.pous
        )

    def _spec_type(self, spec: str) -> T.Type | None:
        """The type of a concrete typespec (fblocks/iec/functions.py): an
        elementary type, STRING or WSTRING (any length), or POINTER TO an
        elementary type (any pointer passes as a byte view of its target)."""
        key = spec.upper()
        if key in ("STRING", "WSTRING"):
            return T.StringType(self.profile.default_string_length, key == "WSTRING")
        if key.startswith("POINTER TO "):
            target = T.ELEMENTARY.get(key[len("POINTER TO ") :].strip())
            return T.RefType(target, pointer=True) if target is not None else None
        return T.ELEMENTARY.get(key)

    def _std_call(self, e: A.Call, func, scope: Scope) -> T.Type | None:
        args = self._std_args(e, func, scope)
        if args is None:
            self._check_args_loosely(e, scope)
            return None
        specs = [p[1] for p in func.params]
        while len(specs) < len(args):
            specs.append(specs[-1])
        # 1) type every argument; untyped literals wait for their type variable
        arg_types: list = []
        for a, spec in zip(args, specs):
            exp = self._spec_type(spec) if ":" not in spec else None
            arg_types.append(self.expr(a, scope, expected=exp))
        if any(t is None for t in arg_types):
            return None
        # 2) unify type variables
        bindings: dict = {}
        for a, spec, t in zip(args, specs, arg_types):
            if ":" not in spec:
                continue
            var, gen = spec.split(":", 1)
            if is_flexible(a):
                continue
            cur = bindings.get(var)
            bindings[var] = t if cur is None else self._unify(cur, t, e)
            if bindings[var] is None:
                return None
        for _a, spec, t in zip(args, specs, arg_types):
            if ":" in spec:
                var = spec.split(":", 1)[0]
                if var not in bindings:
                    bindings[var] = t  # only literals: their own type
        for var, bound in list(bindings.items()):
            gen = next(sp.split(":", 1)[1] for sp in specs if sp.startswith(var + ":"))
            bindings[var] = generic_fit(bound, gen, self.profile)
        # 3) check membership and convertibility
        param_types: list = []
        for i, (a, spec, t) in enumerate(zip(args, specs, arg_types)):
            if ":" in spec:
                var, gen = spec.split(":", 1)
                want = bindings[var]
                if not T.is_generic_member(want, gen):
                    self.d.error("E020", f"{func.name}: {want} is not {gen}", a.pos)
                    return None
                if is_flexible(a):
                    arg_types[i] = self.expr(a, scope, expected=want)
                self.check_convertible(arg_types[i], want, a, f"the argument of {func.name}")
                param_types.append(want)
            elif spec.upper() in T.GENERICS:
                t = generic_fit(t, spec, self.profile)
                if not T.is_generic_member(t, spec) and not self._enum_conversion(func, t):
                    self.d.error("E020", f"{func.name}: argument {i + 1} is {t}, expected {spec}", a.pos)
                    return None
                param_types.append(t)
            else:
                want = self._spec_type(spec)
                if want is None:
                    self.d.error("E020", f"{func.name}: unknown parameter type {spec}", a.pos)
                    return None
                self.check_convertible(t, want, a, f"argument {i + 1} of {func.name}")
                param_types.append(want)
        ret = func.ret
        if ":" in ret:
            ret = ret.split(":", 1)[0]
        if ret in bindings:
            rty = bindings[ret]
        elif ret.upper() in ("STRING", "WSTRING"):
            rty = T.StringType(255, ret.upper() == "WSTRING")
        else:
            rty = T.ELEMENTARY.get(ret.upper())
            if rty is None:
                self.d.error("E020", f"{func.name}: unknown result type {ret}", e.pos)
                return None
        rty = string_result(func.name, rty, arg_types)  # CONCAT(a, b) may be as long as both
        wide = rt_strings.WIDE.get(func.impl)  # LEN of a WSTRING counts UTF-16 units
        if wide is not None and any(isinstance(t, T.StringType) and t.wide for t in map(T.resolve, param_types)):
            func = replace(func, impl=wide)
        if func.typed and func.name.startswith("TO_") and not conversion_exists(arg_types[0], rty):
            self.d.error("E020", f"{func.name}: there is no conversion from {arg_types[0]}", args[0].pos)
            return None
        e.target = CallInfo("std", func=func, args=args, param_types=param_types, rtypes=(rty, *arg_types))
        if all(a.const is not None for a in args) and self._foldable(func):
            try:
                e.const = self._call_impl(func, e.target, [a.const for a in args])
            except Exception:  # not foldable; evaluated at run time
                e.const = None
            if e.const is not None and T.base_elementary(rty) is T.REAL:
                e.const = const_repr(e.const, T.REAL)  # SQRT(REAL#2.0) is a binary32 value
        return rty

    def _enum_conversion(self, func, t: T.Type) -> bool:
        """TO_STRING(e), TO_INT(e) of an enumeration (profile.enum_conversions):
        its base type's value, or its name (rt_convert.make_converter)."""
        return (
            self.profile.enum_conversions
            and func.typed
            and func.name.startswith("TO_")
            and isinstance(T.resolve(t), T.EnumType)
        )

    _FOLDABLE_NAMES = (
        "ABS",
        "SQRT",
        "MAX",
        "MIN",
        "LIMIT",
        "SEL",
        "MUX",
        "SHL",
        "SHR",
        "ROL",
        "ROR",
        "LEN",
        "CONCAT",
        "LEFT",
        "RIGHT",
        "MID",
        "TRUNC",
        "EXPT",
        "MOVE",
    )

    def _foldable(self, func) -> bool:
        if func.context:  # reads the clock or the task at run time
            return False
        return "_TO_" in func.name or func.name.startswith("TO_") or func.name in self._FOLDABLE_NAMES

    def _call_impl(self, func, info: CallInfo, values: list) -> Any:
        if func.typed:
            return func.impl(info.rtypes, *values)
        return func.impl(*values)

    def _unify(self, a: T.Type, b: T.Type, e: A.Expr) -> T.Type | None:
        if same_type(a, b):
            return a
        for one, other in ((a, b), (b, a)):  # SEL(c, NULL, REF(x)): NULL is no reference of that type
            if isinstance(T.resolve(one), T.NullType) and isinstance(T.resolve(other), T.RefType):
                return other
        ae, be = T.base_elementary(a), T.base_elementary(b)
        ra, rb = T.resolve(a), T.resolve(b)
        if isinstance(ra, T.StringType) and isinstance(rb, T.StringType):
            return a if ra.length >= rb.length else b
        if ae is not None and be is not None and not isinstance(T.resolve(a), T.EnumType):
            c = self._common(ae, be, e)
            return c
        self.d.error("E020", f"arguments of types {a} and {b} do not match", e.pos)
        return None
