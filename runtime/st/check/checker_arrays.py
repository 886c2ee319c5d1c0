"""The checker's variable-length arrays: LOWER_BOUND and UPPER_BOUND.

IEC 61131-3 ed.3 6.5.4 (Table 15, variable-length arrays) and CODESYS
("Array with variable length"): an ``ARRAY[*]`` VAR_IN_OUT takes an array
of any bounds with its element type and number of dimensions, and
``LOWER_BOUND(arr, dim)`` / ``UPPER_BOUND(arr, dim)`` give the bounds of
dimension dim (1 = the first) as a DINT. dim is a constant; for an array of
fixed bounds the result is a constant too.
"""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from .checker_base import CheckerBase, Scope
from .symbols import CallInfo

BOUND_FUNCTIONS = ("LOWER_BOUND", "UPPER_BOUND")


class ArrayChecks(CheckerBase):
    """LOWER_BOUND and UPPER_BOUND."""

    def bound_call(self, e: A.Call, key: str, scope: Scope) -> T.Type | None:
        args = list(e.args)
        usage = f"{key}(array, dimension), e.g. {key}(arr, 1)"
        if len(args) != 2 or any(a.name is not None or a.value is None for a in args):
            self.d.error("E041", f"{key} takes two arguments", e.pos, usage)
            self._check_args_loosely(e, scope)
            return None
        arr, dim = args[0].value, args[1].value
        assert arr is not None and dim is not None  # checked above
        aty = self.expr(arr, scope)
        self.expr(dim, scope)
        if aty is None:
            return None
        at = T.resolve(aty)
        if not isinstance(at, T.ArrayType):
            self.d.error("E057", f"{key} needs an array, not {aty}", arr.pos, usage)
            return None
        n = dim.const
        if not isinstance(n, int) or isinstance(n, bool) or not 1 <= n <= len(at.dims):
            self.d.error(
                "E057",
                f"{key}: the dimension must be a constant 1..{len(at.dims)} for {at.name}",
                dim.pos,
                usage,
            )
            return None
        e.target = CallInfo("builtin", func=key, args=[arr, dim])
        bounds = at.dims[n - 1]
        if bounds is not None:
            e.const = bounds[0] if key == "LOWER_BOUND" else bounds[1]
        return T.DINT
