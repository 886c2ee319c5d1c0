"""The checker's generic inputs of user-written functions.

IEC 61131-3 ed.3 leaves generic types (ANY_NUM ...) in user-declared POUs
to the implementation; CODESYS and TwinCAT accept them as inputs of a
FUNCTION. Here such an input takes an argument of any type of its family
and holds it in the family's widest type, as if the input were declared
with that type but accepting every member without a narrowing warning:

    ANY_NUM, ANY_REAL     LREAL        ANY_INT, ANY_SIGNED   LINT
    ANY_UNSIGNED          ULINT        ANY_BIT               LWORD

so a body computes with the value itself (``Scale := x * 2.0``), not with
CODESYS's __SYSTEM.AnyType (pValue, diSize, TypeClass), whose pointers
this runtime does not give a FUNCTION's inputs. A ULINT beyond LINT's range
passed to ANY_INT wraps. Other generics (ANY, ANY_ELEMENTARY, ANY_STRING,
ANY_DATE ...), a generic result, or a generic input of an FB are E012.
"""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from .checker_base import CheckerBase
from .symbols import VarSymbol

WIDEST = {
    "ANY_NUM": T.LREAL,
    "ANY_REAL": T.LREAL,
    "ANY_INT": T.LINT,
    "ANY_SIGNED": T.LINT,
    "ANY_UNSIGNED": T.ULINT,
    "ANY_BIT": T.LWORD,
}


class GenericChecks(CheckerBase):
    """Generic inputs of user FUNCTIONs."""

    def generic_input_type(self, spec: A.TypeSpec, section: str, owner_kind: str | None) -> tuple | None:
        """(family, widest type) for ``x : ANY_NUM`` in a FUNCTION's
        VAR_INPUT; None when spec is no generic type (type_of reports the
        generic types that are not allowed)."""
        if not isinstance(spec, A.NamedType):
            return None
        family = spec.name.upper()
        widest = WIDEST.get(family)
        if widest is None or section != "VAR_INPUT" or owner_kind != "FUNCTION":
            if family in T.GENERICS:
                self.d.error(
                    "E012",
                    f"generic type '{spec.name}' cannot be used here",
                    spec.pos,
                    "a FUNCTION's VAR_INPUT may be " + ", ".join(WIDEST) + "; elsewhere use a concrete type",
                )
                return (family, None)
            return None
        return (family, widest)

    def generic_argument(self, param: VarSymbol, ty: T.Type, value: A.Expr) -> None:
        """E020 unless the argument's type belongs to the input's family."""
        family = param.generic or "ANY"
        if not T.is_generic_member(ty, family) or isinstance(T.resolve(ty), T.EnumType):
            self.d.error(
                "E020",
                f"input '{param.name}' is {family}; got {ty}",
                value.pos,
                f"pass a value of a type of {family}, or convert it",
            )
