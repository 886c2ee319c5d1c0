"""Facts: what the statements before tell of an integer variable's value.

After ``running := 0`` the variable holds 0; after ``IF t1.Q THEN running :=
running + 1; END_IF`` it holds 0 or 1; inside ``ELSIF CV < 32767 THEN`` the
counter is at most 32766. The generator keeps such ranges along the code of
a body (``FnState.facts``: id of the VarSymbol -> (lowest, highest)) and
range analysis (ranges.py) reads them, so ``running := running + 1`` stores
without a wrap and ``a[i]`` after ``i := 3`` reads without a bounds check.

A fact is only ever kept for a variable no one else can write while the body
runs: an integer of this POU itself, not located (AT %M...), not global, not
reached by a reference (REF, ADR, VAR_IN_OUT, =>: ``address_taken``). Of those,
what a call can still reach:

* a FUNCTION's or METHOD's variables and a body's VAR_TEMP are Python locals
  no call can reach, nor can anything reach a PROGRAM's without actions,
  methods, properties or SFC steps (no other POU names a program's
  variables, and a program is called only by its task): their facts survive
  every call;
* an FB's own variables can be reached by a call that has a reference to the
  instance (THIS, an interface, a REFERENCE TO), or by one of its methods:
  any call that may run user code (a FUNCTION, an FB, a method, a property,
  a standard function taking a pointer) forgets them, and so does a store
  through anything but a plain name.

Where control flow joins, the ranges are joined (IF, CASE: the union over
the ways in); a loop forgets every fact before it starts and after it ends
(its body may run again with what it stored); a statement list with labels
(JMP) keeps none. A store forgets the target's fact; an assignment whose
value's range is known and fits states a new one. An assignment inside an
expression (``(x := v)``) forgets all.
"""

from __future__ import annotations

from typing import Any

from .. import ast as A
from .. import types as T
from ..check.symbols import CallInfo, PropertyInfo, VarSymbol
from . import ranges as R
from .codegen_base import CodeGenBase
from .codegen_locals import walk


def root_name(e: Any) -> Any:
    """The variable an lvalue is part of (a[i].x.3: a), or None."""
    while isinstance(e, (A.Index, A.Member, A.BitAccess)):
        e = e.base
    return e.sym if isinstance(e, A.Name) else None


#: a statement's expressions call code that may write variables / assign inside an expression
CALLS, ASSIGNS = 1, 2

#: at most this many facts at a time: a branch copies them, and a long body
#: with thousands of assignments would copy thousands at every IF (forgetting
#: a fact is always safe, it only keeps a wrap or a check)
FACTS_MAX = 48


def _pure_call(info: Any) -> bool:
    """Whether a call runs no user code and writes nothing: an operator,
    a builtin, a standard function with no pointer or output."""
    if not isinstance(info, CallInfo) or info.eno is not None or info.outputs or info.inouts:
        return False
    if info.kind in ("operator", "builtin"):
        return True
    return info.kind == "std" and not any(a is not None and T.resolve(a.ty).is_ref for a in info.args)


#: the nodes effects() knows; another (AssignExpr, or one it does not know) is assumed to call and assign
_KNOWN = (
    A.Binary,
    A.Unary,
    A.Name,
    A.Member,
    A.Call,
    A.Arg,
    A.Index,
    A.BitAccess,
    A.Deref,
    A.Literal,
    A.EnumLiteral,
    A.Located,
)


def effects(exprs: list) -> int:
    """CALLS and ASSIGNS found in expressions."""
    found = 0
    for node, _ in walk([e for e in exprs if e is not None]):
        if isinstance(node, A.Call):
            if not _pure_call(node.target):
                found |= CALLS
        elif isinstance(node, (A.Name, A.Member)) and isinstance(node.sym, PropertyInfo):
            found |= CALLS  # a getter or setter runs
        elif not isinstance(node, _KNOWN):
            return found | ASSIGNS | CALLS
    return found


def join(first: dict, *others: dict) -> dict:
    """What holds after any of the ways in: each range widened over all of
    them; a variable without a fact on one way has none; an array element
    bound to a local (codegen_reuse.py) stays bound where every way bound it
    to the same local."""
    out: dict = {}
    for key, value in first.items():
        if isinstance(value, str):
            if all(other.get(key) == value for other in others):
                out[key] = value
            continue
        lo, hi = value
        for other in others:
            rng = other.get(key)
            if rng is None:
                break
            lo, hi = min(lo, rng[0]), max(hi, rng[1])
        else:
            out[key] = (lo, hi)
    return out


class FactsGen(CodeGenBase):
    """Facts along a body (the module docstring)."""

    def _fact_var(self, sym: Any) -> T.ElementaryType | None:
        """The integer type of a variable that may carry facts here, or None."""
        if not self._own_unreferenced(sym):
            return None
        be = T.base_elementary(sym.type)
        if be is None or not (be.is_intlike or be.is_time) or be.lo is None or be.hi is None:
            return None
        return be

    def _fact_stable(self, sym: VarSymbol) -> bool:
        """Whether no call can reach the variable (the module docstring)."""
        pou = self.fn.pou
        assert pou is not None  # _fact_var said yes
        if pou.kind == "FUNCTION" or self._temp_local(sym):
            return True
        return self._closed_program(pou)

    def _facts_before(self, exprs: list, narrows: bool = False) -> int:
        """Forget what the expressions of the statement about to be emitted
        may change; their effects (narrows: asked for a condition that may
        narrow, else only when there are facts to forget)."""
        facts = self.fn.facts
        if facts is None:
            return CALLS | ASSIGNS
        if not facts and not narrows:
            return 0
        found = effects(exprs)
        if found & ASSIGNS:
            facts.clear()
        elif found & CALLS:
            self._facts_forget_reachable()
        return found

    def _facts_forget_reachable(self) -> None:
        facts = self.fn.facts
        if facts:
            for key in self.fn.fact_reachable:
                facts.pop(key, None)

    def _facts_stored(self, target: A.Expr) -> None:
        """A store to target is emitted: the old fact goes."""
        facts = self.fn.facts
        if not facts:
            return
        if isinstance(target, A.Name) and target.implicit_ref is None:
            facts.pop(id(target.sym), None)
            self._facts_forget_array(target.sym)
        elif not isinstance(target, A.BitAccess):  # a bit's store stores its base next
            self._facts_forget_array(root_name(target))
            self._facts_forget_reachable()
            if target.implicit_ref is not None:
                facts.clear()

    def _facts_forget_array(self, sym: Any) -> None:
        """A store into the variable sym: its elements bound to locals go (codegen_reuse.py)."""
        facts = self.fn.facts
        if facts and sym is not None:
            for key in [k for k in facts if isinstance(k, tuple) and k[1] == id(sym)]:
                del facts[key]

    def _fact_range(self, target: A.Expr, value: A.Expr) -> R.Range | None:
        """The range target := value stores without a wrap, if that can be
        a fact (asked before the store is emitted)."""
        if self.fn.facts is None or not isinstance(target, A.Name) or target.implicit_ref is not None:
            return None
        be = self._fact_var(target.sym)
        if be is None or T.base_elementary(value.ty) is not be:
            return None
        rng = self._range(value)
        return rng if R.fits(be, rng) else None

    def _fact_set(self, sym: VarSymbol, rng: R.Range) -> None:
        facts = self.fn.facts
        if facts is None or (len(facts) >= FACTS_MAX and id(sym) not in facts):
            return
        facts[id(sym)] = rng
        if not self._fact_stable(sym):
            self.fn.fact_reachable.add(id(sym))

    def _fact_narrowable(self, sym: Any, found: int) -> R.Range | None:
        """The range a condition may narrow: a FOR variable's, or a fact's
        (the type's when none) if the condition runs no code."""
        rng = self.fn.loop_ranges.get(id(sym))
        if rng is not None or found or self.fn.facts is None:
            return rng
        be = self._fact_var(sym)
        if be is None:
            return None
        return self.fn.facts.get(id(sym), (be.lo, be.hi))

    def _facts_narrow(self, cond: A.Expr, found: int) -> None:
        """Enter a branch where cond is TRUE: FOR variables and facts narrowed."""
        narrowed = R.narrowings(cond, lambda sym: self._fact_narrowable(sym, found))
        if not narrowed:
            return
        loops = self.fn.loop_ranges = dict(self.fn.loop_ranges)
        for sym, rng in narrowed.values():
            if id(sym) in loops:
                loops[id(sym)] = rng
            else:
                self._fact_set(sym, rng)

    def _facts_branches(self, pre: dict | None, exits: list, exhaustive: bool) -> None:
        """After IF or CASE: the join of the branches' ends (and of pre when
        no branch may run)."""
        if pre is None or self.fn.facts is None:
            return
        self.fn.facts = join(*exits, *(() if exhaustive and exits else (pre,)))

    def _facts_enter_branch(self, pre: dict | None) -> None:
        if pre is not None and self.fn.facts is not None:
            self.fn.facts = dict(pre)

    def _facts_loop(self) -> None:
        """A loop starts or ends: what was known no longer is."""
        if self.fn.facts is not None:
            self.fn.facts = {}

    def _facts_copy(self) -> dict | None:
        facts = self.fn.facts
        return None if facts is None else dict(facts)
