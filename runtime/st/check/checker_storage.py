"""The checker's storage: what the variables occupy.

No STRUCT or FUNCTION_BLOCK may contain itself, directly or through other
types and arrays (E014: its instance would never end being built), and
the variables stay within the element limits of limits.py (E054 for one
variable, E055 for all of them together), so that building them takes a
bounded time and memory.
"""

from __future__ import annotations

from .. import types as T
from ..limits import MAX_TOTAL_ELEMENTS, MAX_VAR_ELEMENTS
from .checker_base import CheckerBase

# The sections whose variables an instance holds itself (VAR_IN_OUT and
# VAR_EXTERNAL refer to storage elsewhere).
_HELD = ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_TEMP", "VAR_STAT")


def _parts(t: T.Type) -> list:
    """(member name, its type) of each member of a STRUCT or FB type that
    holds storage of its own."""
    if isinstance(t, T.StructType):
        return [(f.name, f.type) for f in t.fields.values() if f.type is not None]
    if isinstance(t, T.FBType) and t.pou is not None:
        return [(v.name, v.type) for v in t.pou.vars.values() if v.section in _HELD and v.type is not None]
    return []


def _holders(ty: T.Type) -> list:
    """The STRUCT and FB types a value of type ty is made of at its top
    level: itself, or its elements' type (through arrays and aliases)."""
    t = T.resolve(ty)
    while isinstance(t, T.ArrayType):
        t = T.resolve(t.elem)
    return [t] if isinstance(t, (T.StructType, T.FBType)) else []


class StorageChecks(CheckerBase):
    """Types that contain themselves; the size limits."""

    def _check_containment(self) -> None:
        """E014 for each STRUCT or FB that contains itself, naming the
        members that close the cycle; the member that closes it is cut."""
        structs = [self.types.get(k) for k in self.type_decls]  # in declaration order
        types = [t for t in structs if isinstance(t, T.StructType)]
        types += [p.fbtype for p in self.pous.values() if p.fbtype is not None]
        done: set = set()
        for start in types:
            if id(start) in done:
                continue
            # depth-first, with the path of (type, member name, member type) that led here
            path: list = []
            on_path: set = set()
            self._walk(start, path, on_path, done)

    def _walk(self, t: T.Type, path: list, on_path: set, done: set) -> None:
        on_path.add(id(t))
        for name, member_ty in _parts(t):
            for inner in _holders(member_ty):
                if id(inner) in on_path:
                    self._report_cycle(path + [(t, name, member_ty)], inner)
                    self._cut(t, name)
                elif id(inner) not in done:
                    path.append((t, name, member_ty))
                    self._walk(inner, path, on_path, done)
                    path.pop()
        on_path.discard(id(t))
        done.add(id(t))

    def _report_cycle(self, path: list, closing: T.Type) -> None:
        start = next(i for i, (t, _n, _m) in enumerate(path) if t is closing)
        cycle = path[start:]
        steps = ", ".join(f"{t.name}.{name} is {member_ty}" for t, name, member_ty in cycle)
        kind = "STRUCT" if isinstance(closing, T.StructType) else "FUNCTION_BLOCK"
        pos = self._member_at(closing, cycle[0][1])
        self.d.error(
            "E014",
            f"{kind} '{closing.name}' contains itself: {steps}",
            pos,
            "an instance would never end being built; hold the inner one by REF_TO instead",
        )

    def _member_at(self, t: T.Type, name: str):
        """Where the member name of the STRUCT or FB t is declared."""
        if isinstance(t, T.FBType):
            return t.pou.vars[name.upper()].pos
        decl = self.type_decls[t.name.upper()]
        return next((m.pos for m in decl.spec.members if m.name.upper() == name.upper()), decl.pos)

    @staticmethod
    def _cut(t: T.Type, name: str) -> None:
        """A STRUCT field's type is forgotten, as an unknown one is (its
        uses report nothing more); an FB's variable stays: the walks over
        FB variables (sizes, codegen) do not run or keep a visited set."""
        if isinstance(t, T.StructType):
            t.fields[name.upper()].type = None

    # ------------------------------------------------------------ sizes

    def _check_sizes(self) -> None:
        """E054 for a variable with more elements than MAX_VAR_ELEMENTS;
        E055 where the globals and the variables of the PROGRAMs and
        FUNCTIONs together pass MAX_TOTAL_ELEMENTS (FB instances count
        where they are declared)."""
        memo: dict = {}
        total = 0
        over = False
        owners = [None] + list(self.pous.values())
        for owner in owners:
            syms = self.globals.values() if owner is None else owner.vars.values()
            for sym in syms:
                if owner is not None and (sym.section not in _HELD or sym.owner is not owner):
                    continue
                n = _elements(sym.type, memo)
                if n > MAX_VAR_ELEMENTS:
                    self.d.error(
                        "E054",
                        f"'{sym.name}' has {n:,} elements; one variable may have {MAX_VAR_ELEMENTS:,}",
                        sym.pos,
                        "make it smaller, or split it into several variables",
                    )
                    continue
                if owner is not None and owner.kind == "FUNCTION_BLOCK":
                    continue  # counted in the instances
                total += n
                if total > MAX_TOTAL_ELEMENTS and not over:
                    over = True
                    self.d.error(
                        "E055",
                        f"the variables have more than {MAX_TOTAL_ELEMENTS:,} elements together "
                        f"({total:,} up to '{sym.name}')",
                        sym.pos,
                        "make the largest arrays smaller",
                    )


def _elements(ty: T.Type, memo: dict) -> int:
    """How many elements a value of type ty holds (limits.py): one per
    elementary value, and one more per STRUCT or FB instance."""
    t = T.resolve(ty)
    if isinstance(t, T.ArrayType):
        if t.variable_length:
            return 1  # a VAR_IN_OUT: a reference to an array held elsewhere
        n = 1
        for lo, hi in t.dims:
            n *= hi - lo + 1
        return n * _elements(t.elem, memo)
    if not isinstance(t, (T.StructType, T.FBType)):
        return 1
    key = id(t)
    if key not in memo:
        memo[key] = 1  # while counting: a cycle (reported) counts once
        memo[key] = 1 + sum(_elements(m, memo) for _name, m in _parts(t))
    return memo[key]
