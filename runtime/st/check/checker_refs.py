"""The checker's references: CODESYS REFERENCE TO, REF= and __ISVALIDREF.

A REFERENCE TO is dereferenced implicitly wherever it is used (CODESYS,
"Data Type: REFERENCE TO"): the checker types such a use as the target type
and notes the reference's own type in ``Expr.implicit_ref``; REF= binds it,
``__ISVALIDREF`` tests it, and a call binds a VAR_INPUT reference to the
variable passed. A reference type cannot be the element of an ARRAY, nor the
target of a POINTER, REF_TO or REFERENCE TO (E160, as in CODESYS).
"""

from __future__ import annotations

from typing import Any

from .. import ast as A
from .. import sizes
from .. import types as T
from .checker_base import CheckerBase, Scope
from .conversions import same_type
from .oop import extends_fb, fb_hint
from .symbols import VarSymbol


def spec_kind(spec: A.RefTypeSpec) -> str:
    """The declaration's own words: REF_TO, POINTER TO, REFERENCE TO."""
    return "REFERENCE TO" if spec.reference else "POINTER TO" if spec.pointer else "REF_TO"


class RefChecks(CheckerBase):
    """REFERENCE TO: implicit dereference, binding, validity."""

    def _not_a_reference(self, ty: T.Type, what: str, pos: A.Pos) -> bool:
        if not T.is_reference(ty):
            return True
        self.d.error(
            "E160",
            f"a REFERENCE TO cannot be {what}",
            pos,
            "use POINTER TO or REF_TO there (CODESYS allows no array, pointer or reference of references)",
        )
        return False

    def implicit_deref(self, e: A.Expr, ty: T.Type | None) -> T.Type | None:
        """A use of a REFERENCE TO stands for its target (a variable, a
        member, an element, a call's result)."""
        if ty is not None and T.is_reference(ty) and isinstance(e, (A.Name, A.Member, A.Index, A.Call)):
            e.implicit_ref = ty
            r = T.resolve(ty)
            assert isinstance(r, T.RefType)
            return r.target
        return ty

    def ref_bind(self, s: A.Assign, scope: Scope) -> None:
        """target REF= value: a REFERENCE TO (or REF_TO) designates value."""
        tty = self.lvalue(s.target, scope)
        if tty is None:
            self.expr(s.value, scope)
            return
        rt = T.resolve(s.target.implicit_ref if s.target.implicit_ref is not None else tty)
        if not isinstance(rt, T.RefType):
            self.expr(s.value, scope)
            self.d.error(
                "E020",
                f"REF= needs a reference on the left, not {tty}",
                s.target.pos,
                "declare it REFERENCE TO or REF_TO; to copy a value use :=",
            )
            return
        self._bindable(rt, s.value, scope, "REF=")

    def bind_argument(self, param: VarSymbol, value: A.Expr, scope: Scope) -> bool:
        """A REFERENCE TO input or in-out, bound to the variable passed."""
        rt = T.resolve(param.type)
        assert isinstance(rt, T.RefType)
        return self._bindable(rt, value, scope, f"'{param.name}'")

    def _bindable(self, rt: T.RefType, value: A.Expr, scope: Scope, what: str) -> bool:
        """Whether value is what a reference of type rt may designate: a
        variable of its target type, another REFERENCE TO it, or NULL/0."""
        vty = self.expr(value, scope)
        if vty is None:
            return False
        if isinstance(T.resolve(vty), T.NullType) or (isinstance(value, A.Literal) and value.const == 0):
            return True  # bound to nothing
        if not same_type(rt.target, vty) and not extends_fb(vty, rt.target):
            hint = fb_hint(vty, rt.target) or f"bind it to a variable of type {rt.target}"
            self.d.error("E020", f"{what} is {rt}; got {vty}", value.pos, hint)
            return False
        if not self._is_lvalue_expr(value) or isinstance(value, (A.BitAccess, A.Located)):
            self.d.error(
                "E031",
                f"{what} needs a variable to designate",
                value.pos,
                "a reference designates storage; copy the value into a variable first",
            )
            return False
        self._mark_boxed(value, scope)
        return True

    def reference_init(self, ty: T.Type, init: A.Expr, scope: Scope, what: str, ref_ok: bool) -> Any:
        """r : REFERENCE TO INT := x; binds r to x before the first cycle
        (CODESYS: in a declaration := binds, as REF= does in the code)."""
        rt = T.resolve(ty)
        assert isinstance(rt, T.RefType)
        if not self._bindable(rt, init, scope, f"'{what}'"):
            return None
        if isinstance(T.resolve(init.ty), T.NullType) or init.const == 0:
            return None
        if not ref_ok or not self._fixed_place(init):
            self.d.error(
                "E024",
                f"'{what}' cannot start bound to this variable",
                init.pos,
                "only a variable's own declaration may bind it, to a variable at a fixed place "
                "(constant indices); bind it in the code with REF=",
            )
            return None
        return ("ref", init)

    def sizeof_call(self, e: A.Call, a: A.Expr, scope: Scope) -> T.Type | None:
        """SIZEOF(variable) or SIZEOF(type): its size in bytes as CODESYS
        lays it out on a 64-bit target (st/sizes.py), a UDINT constant."""
        ty = self._type_named(a, scope)
        if ty is None:
            ty = self.expr(a, scope)
            if ty is None:
                return None
        size = sizes.sizeof(ty)
        if size is None:
            self.d.error(
                "E162",
                f"the size of {ty} is not known",
                a.pos,
                "SIZEOF takes an elementary type, a string, an array of fixed bounds, a structure or a reference",
            )
            return None
        e.const = size
        return T.UDINT if size < (1 << 32) else T.ULINT

    def _type_named(self, a: A.Expr, scope: Scope) -> T.Type | None:
        """The type a SIZEOF argument names, unless a variable has the name."""
        if not isinstance(a, A.Name):
            return None
        key = a.name.upper()
        if (scope.pou is not None and key in scope.pou.vars) or key in self.globals:
            return None
        ty = self.types.get(key) or T.ELEMENTARY.get(key)
        if ty is not None:
            a.ty = ty
        return ty

    def isvalidref(self, e: A.Call, scope: Scope) -> T.Type | None:
        """__ISVALIDREF(r): whether a REFERENCE TO is bound (CODESYS), or a
        VAR_IN_OUT (TwinCAT: "checking the VAR_IN_OUT reference" before a
        METHOD uses it, when the block may not have been called yet)."""
        args = e.args
        if len(args) != 1 or args[0].name is not None or args[0].value is None:
            self.d.error("E041", "__ISVALIDREF takes one argument", e.pos, "__ISVALIDREF(ref)")
            return None
        a = args[0].value
        ty = self.expr(a, scope)
        if ty is None:
            return None
        in_out = isinstance(a, A.Name) and isinstance(a.sym, VarSymbol) and a.sym.section == "VAR_IN_OUT"
        if a.implicit_ref is None and not in_out:
            self.d.error(
                "E160",
                f"__ISVALIDREF needs a REFERENCE TO or a VAR_IN_OUT, not {ty}",
                a.pos,
                "an interface is 0 until assigned: test it with itf <> 0"
                if isinstance(T.resolve(ty), T.InterfaceType)
                else "for a POINTER TO or REF_TO compare it with NULL: p <> NULL",
            )
            return None
        return T.BOOL
