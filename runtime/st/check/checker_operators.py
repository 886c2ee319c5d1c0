"""The checker's operators: the type and folded value of each operation.

Unary, logical, comparison, arithmetic and time arithmetic; a constant
result when the operands are constant. The function forms of the operators
(ADD(a, b, c), NOT(IN := x)) are checked as the operator expression they
stand for.
"""

from __future__ import annotations

from typing import Any

from .. import ast as A
from .. import types as T
from ..rtlib import rtlib
from .checker_base import CheckerBase, Scope
from .conversions import common_type, const_repr, is_flexible
from .oop import interface_accepts
from .symbols import CallInfo

# IEC 61131-3 ed.3 Table 29-31: the standard functions that are the operators
# written as functions. ADD(a, b, c) is (a + b) + c: it is checked, folded and
# generated as that expression, so both forms follow the same type rules
# (ADD(INT, DINT) is DINT, ADD(TOD, TIME) is ADD_TOD_TIME, AND of two WORDs
# is a WORD). EXPT and MOVE stay ordinary standard functions.
OPERATOR_FUNCTIONS = {
    "ADD": "+",
    "SUB": "-",
    "MUL": "*",
    "DIV": "/",
    "MOD": "MOD",
    "AND": "AND",
    "OR": "OR",
    "XOR": "XOR",
    "NOT": "NOT",
}


class OperatorChecks(CheckerBase):
    """Typing and folding operators."""

    def operator_call(self, e: A.Call, func: Any, scope: Scope) -> T.Type | None:
        """ADD(a, b, c), AND(IN1 := a, IN2 := b), NOT(x) ...: the arguments
        bound like a standard function's (positional, or formal IN1, IN2 ...
        / IN), then checked as the operator expression, left to right."""
        args = self._std_args(e, func, scope)
        if args is None:
            self._check_args_loosely(e, scope)
            return None
        op = OPERATOR_FUNCTIONS[func.name]
        lowered: A.Expr
        if op == "NOT":
            lowered = A.Unary("NOT", args[0], pos=e.pos)
        else:
            lowered = args[0]
            for a in args[1:]:
                lowered = A.Binary(op, lowered, a, pos=e.pos, spelling=func.name)
        ty = self.expr(lowered, scope)
        if ty is None:
            return None
        e.target = CallInfo("operator", args=[lowered])
        e.const = lowered.const
        return ty

    @staticmethod
    def _label(e: A.Binary) -> str:
        """How a diagnostic names the operation: ADD, or '+'."""
        return e.spelling or f"'{e.op}'"

    def _unary(self, e: A.Unary, scope: Scope, expected: T.Type | None) -> T.Type | None:
        ty = self.expr(e.operand, scope, expected)
        if ty is None:
            return None
        be = T.base_elementary(ty)
        c = e.operand.const
        if e.op == "NOT":
            if be is not None and (be.is_bool or be.is_bits or (be.is_integer and self.profile.bitwise_on_integers)):
                if isinstance(T.resolve(ty), T.EnumType):
                    be = None
                else:
                    if c is not None:
                        e.const = (not c) if be.is_bool else self._wrap_const(be, ~c)
                    return be
            self.d.error("E023", f"NOT needs BOOL or a bit string, not {ty}", e.pos)
            return None
        if be is None or not (
            be.is_integer or be.is_real or be.category == T.DURATION or (be.is_bits and self.profile.int_bits_mix)
        ):
            self.d.error("E023", f"unary {e.op} needs a number, not {ty}", e.pos)
            return None
        if c is not None:
            e.const = -c if e.op == "-" else c
            if is_flexible(e.operand) and e.op == "-" and isinstance(c, int):
                # -32768 is an INT literal, not the negation of a DINT; beside a
                # LINT, -9223372036854775808 is a LINT, not the negation of a ULINT
                exp = T.base_elementary(expected) if expected is not None else None
                if exp is not None and exp.is_integer and exp.lo is not None and exp.lo < 0 and T.int_fits(exp, -c):
                    return exp
                if exp is None or (exp.is_integer and exp.lo is not None and exp.lo < 0 and not T.int_fits(be, -c)):
                    for cand in (T.INT, T.DINT, T.LINT):
                        if T.int_fits(cand, -c):
                            return cand
        return be

    def _wrap_const(self, t: T.ElementaryType, v: int) -> int:
        return rtlib.wrap(t, v)

    def _binary(self, e: A.Binary, scope: Scope, expected: T.Type | None) -> T.Type | None:
        op = e.op
        if self._takes_context(e.left, scope) and not self._takes_context(e.right, scope):
            # `Idle = state`: the enumerator takes the type of the other side
            rt = self.expr(e.right, scope)
            lt = self.expr(e.left, scope, expected=rt)
            if lt is None or rt is None:
                return None
        else:
            lt = self.expr(e.left, scope)
            rt = self.expr(e.right, scope, expected=lt if self._takes_context(e.right, scope) else None)
            if lt is None or rt is None:
                return None
            if is_flexible(e.left) and not is_flexible(e.right):
                lt = self.expr(e.left, scope, expected=rt)
                if lt is None:
                    return None
        if op in ("+", "-", "<", ">", "<=", ">=") and (
            isinstance(T.resolve(lt), T.RefType) or isinstance(T.resolve(rt), T.RefType)
        ):
            return self.pointer_binary(e, lt, rt)
        if op in ("AND", "OR", "XOR", "AND_THEN", "OR_ELSE"):
            return self._logical(e, lt, rt)
        if op in ("=", "<>", "<", ">", "<=", ">="):
            return self._comparison(e, lt, rt)
        ty = self._arithmetic(e, lt, rt, expected)
        if ty is T.LREAL and expected is not None and T.base_elementary(expected) is T.REAL and is_flexible(e):
            # literals only, into a REAL: computed in REAL as REAL#0.1 + REAL#0.2
            # would be (binary32 after every operation, IEC 61131-3 ed.3 6.4.2)
            lt = self.expr(e.left, scope, expected)
            rt = self.expr(e.right, scope, expected)
            if lt is None or rt is None:
                return None
            ty = self._arithmetic(e, lt, rt, expected)
        return ty

    def _takes_context(self, e: A.Expr, scope: Scope) -> bool:
        """An untyped literal, or a bare enumerator name that is no variable:
        its type comes from the other operand (`state <> Idle` with Idle an
        enumerator of several types picks the one of state, as CODESYS and
        TwinCAT do)."""
        if is_flexible(e) or self.is_context_trunc(e):
            return True
        if not isinstance(e, A.Name):
            return False
        key = e.name.upper()
        pou = scope.pou
        if pou is not None and (key in pou.vars or (pou.result is not None and key == pou.name.upper())):
            return False
        return key not in self.globals and len(self.enumerators.get(key, ())) > 1

    def _logical(self, e: A.Binary, lt: T.Type, rt: T.Type) -> T.Type | None:
        le, re_ = T.base_elementary(lt), T.base_elementary(rt)
        if le is not None and re_ is not None and le.is_bool and re_.is_bool:
            ty = T.BOOL
        elif e.op in ("AND_THEN", "OR_ELSE"):
            self.d.error("E023", f"{e.op} needs BOOL operands", e.pos)
            return None
        elif le is not None and re_ is not None and self._bitwise_ok(le) and self._bitwise_ok(re_):
            common = self._common(le, re_, e)
            if common is None:
                return None
            ty = common
        else:
            self.d.error(
                "E023",
                f"{e.op} needs BOOL or bit-string operands, not {lt} and {rt}",
                e.pos,
                "compare numbers first, e.g. (x > 0) AND (y > 0)",
            )
            return None
        lc, rc = e.left.const, e.right.const
        if lc is not None and rc is not None:
            if ty.is_bool:
                e.const = {
                    "AND": lc and rc,
                    "AND_THEN": lc and rc,
                    "OR": lc or rc,
                    "OR_ELSE": lc or rc,
                    "XOR": lc != rc,
                }[e.op]
            else:
                e.const = {"AND": lc & rc, "OR": lc | rc, "XOR": lc ^ rc}[e.op]
        return ty

    def _bitwise_ok(self, t: T.ElementaryType) -> bool:
        return t.is_bool or t.is_bits or (t.is_integer and self.profile.bitwise_on_integers)

    def _comparison(self, e: A.Binary, lt: T.Type, rt: T.Type) -> T.Type | None:
        lres, rres = T.resolve(lt), T.resolve(rt)
        if (lres is not rres) and (isinstance(lres, T.EnumType) or isinstance(rres, T.EnumType)):
            lt, rt = self._loose_enum(lt), self._loose_enum(rt)  # CODESYS: a non-strict one is an integer
            lres, rres = T.resolve(lt), T.resolve(rt)
        ok = False
        if isinstance(lres, T.EnumType) or isinstance(rres, T.EnumType):
            ok = lres is rres
        elif isinstance(lres, T.StringType) and isinstance(rres, T.StringType):
            ok = lres.wide == rres.wide
        elif isinstance(lres, (T.RefType, T.NullType, T.InterfaceType)) or isinstance(
            rres, (T.RefType, T.NullType, T.InterfaceType)
        ):
            # r = 0 / r <> 0 is how CODESYS and TwinCAT test for NULL (an interface too)
            def refish(t, side, other):
                # itf = inst: whether itf designates that instance (CODESYS)
                instance = isinstance(other, T.InterfaceType) and interface_accepts(t, other)
                return isinstance(t, (T.RefType, T.NullType, T.InterfaceType)) or side.const == 0 or instance

            ok = e.op in ("=", "<>") and refish(lres, e.left, rres) and refish(rres, e.right, lres)
        else:
            le, re_ = T.base_elementary(lres), T.base_elementary(rres)
            if le is not None and re_ is not None:
                if le.is_bool and re_.is_bool:
                    ok = True
                elif le.is_time or re_.is_time:
                    ok = le.category == re_.category
                elif le.is_char or re_.is_char:  # by code; CHAR with CHAR, WCHAR with WCHAR
                    ok = le is re_
                elif self._common(le, re_, e, report=False) is not None:
                    ok = True
        if not ok:
            self.d.error("E020", f"cannot compare {lt} with {rt}", e.pos, "convert one side so both have the same type")
            return None
        lc, rc = e.left.const, e.right.const
        if lc is not None and rc is not None and not isinstance(lres, T.RefType):
            import operator

            fn = {
                "=": operator.eq,
                "<>": operator.ne,
                "<": operator.lt,
                ">": operator.gt,
                "<=": operator.le,
                ">=": operator.ge,
            }[e.op]
            e.const = fn(lc, rc)
        return T.BOOL

    def _common(
        self, le: T.ElementaryType, re_: T.ElementaryType, e: A.Expr, report: bool = True
    ) -> T.ElementaryType | None:
        c = common_type(le, re_, self.profile)
        if c is None and report:
            self.d.error(
                "E020",
                f"no common type for {le} and {re_}",
                e.pos,
                f"convert one side explicitly, e.g. {le.name}_TO_{re_.name}(...)",
            )
        return c

    def _loose_enum(self, ty: T.Type) -> T.Type:
        """An enumeration without {attribute 'strict'} as its base integer
        type where the profile says so (CODESYS, TwinCAT), else ty."""
        r = T.resolve(ty)
        if isinstance(r, T.EnumType) and self.profile.loose_enums and not r.strict:
            return r.base
        return ty

    def _arithmetic(self, e: A.Binary, lt: T.Type, rt: T.Type, expected: T.Type | None) -> T.Type | None:
        op = e.op
        lt, rt = self._loose_enum(lt), self._loose_enum(rt)
        le, re_ = T.base_elementary(lt), T.base_elementary(rt)
        if le is None or re_ is None or isinstance(T.resolve(lt), T.EnumType) or isinstance(T.resolve(rt), T.EnumType):
            strict = next((t for t in (T.resolve(lt), T.resolve(rt)) if isinstance(t, T.EnumType) and t.strict), None)
            hint = None
            if strict is not None and self.profile.loose_enums:
                hint = f"{strict.name} is {{attribute 'strict'}}: no arithmetic on its values"
            self.d.error("E023", f"{self._label(e)} needs numbers, not {lt} and {rt}", e.pos, hint)
            return None
        if le.is_time or re_.is_time:
            return self._time_arith(e, le, re_)
        num = (T.SIGNED, T.UNSIGNED, T.REALCAT)
        bits_ok = self.profile.int_bits_mix
        for t, side in ((le, e.left), (re_, e.right)):
            if not (t.category in num or (t.is_bits and bits_ok)):
                self.d.error("E023", f"{self._label(e)} needs numbers, not {t.name}", side.pos)
                return None
        if op == "**":
            ty = T.REAL if le is T.REAL and re_ in (T.REAL, T.SINT, T.INT, T.USINT, T.UINT) else T.LREAL
            if le.is_real:
                ty = le
        else:
            common = self._common(le, re_, e)
            if common is None:
                return None
            ty = common
        if op == "MOD" and not ty.is_intlike:
            self.d.error("E023", "MOD needs integers", e.pos, "use x - TRUNC(x / y) * y for REAL")
            return None
        lc, rc = e.left.const, e.right.const
        if lc is not None and rc is not None:
            e.const = self._fold_arith(op, lc, rc, ty, e)
        elif op in ("/", "MOD") and rc == 0 and ty.is_intlike:
            self.d.error("E027", "division by the constant zero", e.right.pos)
        return ty

    def _fold_arith(self, op: str, a: Any, b: Any, ty: T.ElementaryType, e: A.Expr) -> Any:
        if ty is T.REAL:
            # REAL folds as it runs: the operands as binary32, the result rounded to it
            if op != "**":  # EXPT's exponent keeps its own type
                a, b = const_repr(a, ty), const_repr(b, ty)
            r = self._fold_arith(op, a, b, T.LREAL, e)
            return None if r is None else const_repr(r, ty)
        try:
            if op == "+":
                return a + b
            if op == "-":
                return a - b
            if op == "*":
                return a * b
            if op == "/":
                return rtlib.idiv(int(a), int(b)) if ty.is_intlike else rtlib.rdiv(float(a), float(b))
            if op == "MOD":
                return rtlib.imod(int(a), int(b))
            if op == "**":
                return rtlib.expt(float(a), float(b))
        except ZeroDivisionError:
            self.d.error("E027", "division by the constant zero", e.pos)
        except OverflowError:
            self.d.error("E022", "constant expression overflows", e.pos)
        return None

    def _time_arith(self, e: A.Binary, le: T.ElementaryType, re_: T.ElementaryType) -> T.Type | None:
        op = e.op
        cat = (le.category, re_.category)
        name = None
        ty = None
        if cat == (T.DURATION, T.DURATION) and op in ("+", "-"):
            ty = T.LTIME if T.LTIME in (le, re_) else T.TIME
            if le is not re_:
                name = ("ADD_" if op == "+" else "SUB_") + "LTIME"
        elif le.category == T.DURATION and op in ("*", "/") and (re_.is_integer or re_.is_real):
            ty = le
            name = ("MUL_" if op == "*" else "DIV_") + ("LTIME" if le is T.LTIME else "TIME")
        elif cat == (T.TODCAT, T.DURATION) and op in ("+", "-"):
            ty, name = le, ("ADD_TOD_TIME" if op == "+" else "SUB_TOD_TIME")
        elif cat == (T.DTCAT, T.DURATION) and op in ("+", "-"):
            ty, name = le, ("ADD_DT_TIME" if op == "+" else "SUB_DT_TIME")
        elif op == "-" and le.category == re_.category and le.category in (T.DATECAT, T.TODCAT, T.DTCAT):
            ty = T.TIME
            name = {T.DATECAT: "SUB_DATE_DATE", T.TODCAT: "SUB_TOD_TOD", T.DTCAT: "SUB_DT_DT"}[le.category]
        if ty is None:
            self.d.error(
                "E023",
                f"{self._label(e)} is not defined for {le.name} and {re_.name}",
                e.pos,
                "durations add to durations, dates and times of day; a duration multiplies by a number",
            )
            return None
        if name is not None:
            if le.bits == 64 or re_.bits == 64:
                lname = {
                    "ADD_TOD_TIME": "ADD_LTOD_LTIME",
                    "SUB_TOD_TIME": "SUB_LTOD_LTIME",
                    "ADD_DT_TIME": "ADD_LDT_LTIME",
                    "SUB_DT_TIME": "SUB_LDT_LTIME",
                    "SUB_DATE_DATE": "SUB_LDATE_LDATE",
                    "SUB_TOD_TOD": "SUB_LTOD_LTOD",
                    "SUB_DT_DT": "SUB_LDT_LDT",
                }.get(name)
                if lname in self.std:
                    name = lname
                    if ty is T.TIME:
                        ty = T.LTIME
            func = self.std.get(name)
            if func is None:
                self.d.error("E023", f"{self._label(e)} on {le.name} and {re_.name} is not available", e.pos)
                return None
            e.impl = CallInfo("std", func=func, rtypes=(ty, le, re_), param_types=[le, re_])
        return ty
