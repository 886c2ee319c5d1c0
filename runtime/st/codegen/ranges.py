"""Range analysis: the interval an integer expression of the checked AST takes.

Interval arithmetic over the annotated AST (``Expr.ty``, ``Expr.const``,
``Call.target``): a value read from storage lies within its type; a sum of
two bounded values within the sum of the bounds; and so on. The code
generator asks before a store (``fits``: no wrap), an index (no bounds
check), a shift or an explicit conversion, and skips the wrap or check
when the answer allows; an unknown range means "do the full work". Pure
functions: nothing here changes the AST.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from .. import ast as A
from .. import types as T
from ..check.symbols import CallInfo

Range = tuple[int, int]

# Standard functions that always return a wrapped value of their type.
WRAPPING_FUNCS = ("SHL", "SHR", "ROL", "ROR")
# Standard functions whose result is one of their arguments.
_SELECTING_FUNCS = ("MIN", "MAX", "LIMIT", "SEL", "MOVE")


def _selected_args(info: CallInfo) -> list:
    """The arguments a selecting function may return (SEL's selector is not one)."""
    return info.args[1:] if info.func.name == "SEL" else info.args


def is_stored_value(e: A.Expr | None) -> bool:
    """A value read from storage already has its type's representation;
    so do MIN/MAX/LIMIT/SEL/MOVE of such values."""
    if e is None:
        return False
    if isinstance(e, (A.Name, A.Member, A.Index, A.Deref, A.Located, A.BitAccess)) or e.const is not None:
        return True
    if (
        isinstance(e, A.Call)
        and isinstance(e.target, CallInfo)
        and e.target.kind == "std"
        and e.target.func.name in _SELECTING_FUNCS
    ):
        return all(is_stored_value(a) for a in _selected_args(e.target))
    return False


def value_range(e: A.Expr | None, known: Mapping[int, Range] | None = None) -> Range | None:
    """(lowest, highest) an integer expression can have, or None if
    unknown. known: ranges the caller knows for variables beyond their type,
    by id of the VarSymbol (a FOR variable read from its loop local).
    A chain a + b + c ... is taken from its first operand on, in a loop."""
    spine: list[A.Binary] = []
    while isinstance(e, A.Binary) and _is_range_binary(e):
        spine.append(e)
        e = e.left
    rng = _value_range(e, known)
    for b in reversed(spine):
        if rng is None:
            return None
        rng = _binary_range(b.op, rng, _value_range(b.right, known))
    return rng


def _is_range_binary(e: A.Binary) -> bool:
    """Whether value_range takes e from the ranges of its operands."""
    if e.const is not None:  # a folded value, or one stored (is_stored_value)
        return False
    be = T.base_elementary(e.ty) if e.ty is not None else None
    return be is not None and (be.is_intlike or be.is_time) and be.lo is not None and be.hi is not None


def _value_range(e: A.Expr | None, known: Mapping[int, Range] | None) -> Range | None:
    if e is None:
        return None
    if isinstance(e.const, int) and not isinstance(e.const, bool):
        return (e.const, e.const)
    if isinstance(e, A.Name) and known:
        rng = known.get(id(e.sym))
        if rng is not None:
            return rng
    be = T.base_elementary(e.ty) if e.ty is not None else None
    # TIME and the dates are wrapped ints too (ranges of their stored values)
    if be is None or not (be.is_intlike or be.is_time) or be.lo is None or be.hi is None:
        return None
    if is_stored_value(e) and not isinstance(e, A.Call):
        return (be.lo, be.hi)
    if isinstance(e, A.Binary):
        return value_range(e, known)
    if isinstance(e, A.Call) and isinstance(e.target, CallInfo) and e.target.kind == "method":
        return (be.lo, be.hi)  # the method's result variable, stored in its type
    if isinstance(e, A.Call) and isinstance(e.target, CallInfo) and e.target.kind == "builtin":
        if e.target.func in ("TIME", "LTIME"):
            return (be.lo, be.hi)  # the task clock, wrapped to its type (program/context.py)
    if isinstance(e, A.Call) and isinstance(e.target, CallInfo) and e.target.kind == "operator":
        return value_range(e.target.args[0], known)  # ADD(a, b) is a + b
    if isinstance(e, A.Call) and isinstance(e.target, CallInfo) and e.target.kind == "std":
        name = e.target.func.name
        if name in WRAPPING_FUNCS or ("_TO_" in name and "BCD" not in name):
            return (be.lo, be.hi)  # these always return a wrapped value of their type
        if name in _SELECTING_FUNCS:
            rs = [value_range(a, known) for a in _selected_args(e.target)]
            if all(r is not None for r in rs):
                return (min(r[0] for r in rs if r is not None), max(r[1] for r in rs if r is not None))
    return None


def _binary_range(op: str, lr: Range | None, rr: Range | None) -> Range | None:
    if lr is None or rr is None:
        return None
    if op == "+":
        return (lr[0] + rr[0], lr[1] + rr[1])
    if op == "-":
        return (lr[0] - rr[1], lr[1] - rr[0])
    if op == "*":
        ps = [a * b for a in lr for b in rr]
        return (min(ps), max(ps))
    if op == "AND":
        nonneg = [r for r in (lr, rr) if r[0] >= 0]
        return (0, min(r[1] for r in nonneg)) if nonneg else None
    if op in ("OR", "XOR") and lr[0] >= 0 and rr[0] >= 0:
        return (0, (1 << max(lr[1], rr[1]).bit_length()) - 1)
    if op == "MOD" and rr[0] == rr[1] and rr[0] > 0:
        # the remainder has the dividend's sign and is smaller than the divisor
        return (0 if lr[0] >= 0 else -(rr[0] - 1), rr[0] - 1)
    if op == "/" and rr[0] == rr[1] and rr[0] > 0 and lr[0] >= 0:
        return (lr[0] // rr[0], lr[1] // rr[0])
    return None


# where `x op c` is TRUE: what it adds to c for the lowest and the highest value of x
_BOUNDS = {">=": (0, None), ">": (1, None), "<=": (None, 0), "<": (None, -1), "=": (0, 0)}
_MIRROR = {">=": "<=", ">": "<", "<=": ">=", "<": ">", "=": "="}


def narrowings(cond: A.Expr, current: Callable[[Any], Range | None]) -> dict:
    """The ranges variables have where cond is TRUE: i >= 8, 8 <= i,
    i < n AND i > 0 narrow the range of i. current(sym): the range of a
    variable that may be narrowed, None for one that may not. Returns
    id(sym) -> (sym, range); a comparison no value can meet is left out
    (the branch never runs)."""
    out: dict = {}
    todo = [cond]
    while todo:
        c = todo.pop()
        if not isinstance(c, A.Binary):
            continue
        if c.op in ("AND", "AND_THEN") and T.base_elementary(c.ty) is T.BOOL:
            todo.append(c.right)
            todo.append(c.left)
            continue
        op, var, const = c.op, c.left, c.right
        if not isinstance(var, A.Name):
            op, var, const = _MIRROR.get(op, ""), c.right, c.left
        k = const.const
        if op not in _BOUNDS or not isinstance(var, A.Name) or not isinstance(k, int) or isinstance(k, bool):
            continue
        rng = out[id(var.sym)][1] if id(var.sym) in out else current(var.sym)
        if rng is None:
            continue
        dlo, dhi = _BOUNDS[op]
        lo = rng[0] if dlo is None else max(rng[0], k + dlo)
        hi = rng[1] if dhi is None else min(rng[1], k + dhi)
        if lo <= hi:
            out[id(var.sym)] = (var.sym, (lo, hi))
    return out


def within(rng: Range | None, lo: int, hi: int) -> bool:
    """Whether a known range lies inside lo..hi."""
    return rng is not None and lo <= rng[0] and rng[1] <= hi


def fits(t: T.ElementaryType, rng: Range | None) -> bool:
    """Whether every value of a known range is a value of integer type t
    (a store into t needs no wrap)."""
    return t.lo is not None and t.hi is not None and within(rng, t.lo, t.hi)
