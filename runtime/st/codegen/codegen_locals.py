"""A PROGRAM's scalars in Python locals while its body runs.

A local is one fast load; ``self.v_x`` is an attribute lookup, and a store
into it another. A PROGRAM whose variables nothing but its own body can
reach (CodeGenBase._closed_program: no actions, methods, properties or SFC
steps; no reference taken; not located) reads each elementary variable its
body uses more than once into a local when the body starts, works on the
local, and stores it back in a ``finally``, so a RETURN, a fault or the
watchdog still leaves every variable stored, as the monitor, retain and
the next cycle expect::

    _l_v_check = self.v_check
    try:
        for _i4 in _r5:
            _l_v_check = _l_v_check + ...
    finally:
        self.v_check = _l_v_check

Nothing outside the body can tell: between cycles (where surfaces read,
write and force, and online change carries values) every variable is in
its slot, and while the body runs no other code can name them.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from .. import ast as A
from .. import types as T
from ..check.symbols import VarSymbol
from .codegen_base import CodeGenBase

_SKIP = frozenset(("pos", "ty", "const", "sym", "pragmas", "qualifier", "flexible", "implicit_ref", "impl", "via"))
_FIELDS: dict[type, tuple] = {}


def walk(stmts: list) -> Iterator[tuple[A.Node, bool]]:
    """Every node of stmts (statements and their expressions; not the
    checker's annotations), with whether it lies inside a loop. A loop over
    the tree: a chain of operators may be 10,000 long."""
    todo: list = [(s, False) for s in stmts]
    while todo:
        node, in_loop = todo.pop()
        if isinstance(node, (list, tuple)):
            todo.extend((n, in_loop) for n in node)
            continue
        if not isinstance(node, A.Node):
            continue
        yield node, in_loop
        in_loop = in_loop or isinstance(node, (A.For, A.While, A.Repeat))
        fields = _FIELDS.get(node.__class__)
        if fields is None:
            fields = _FIELDS[node.__class__] = tuple(
                f
                for f in node.__dataclass_fields__
                if f not in _SKIP and not (f == "target" and isinstance(node, A.Call))
            )
        for f in fields:
            value = getattr(node, f)
            if isinstance(value, (A.Node, list, tuple)):
                todo.append((value, in_loop))


def uses(stmts: list) -> dict:
    """id(VarSymbol) -> [sym, uses] of the names in stmts; a use inside a
    loop counts twice (it runs many times)."""
    found: dict = {}
    for node, in_loop in walk(stmts):
        if node.__class__ is A.Name and isinstance(node.sym, VarSymbol):
            entry = found.setdefault(id(node.sym), [node.sym, 0])
            entry[1] += 2 if in_loop else 1
    return found


def _leaves(stmt: A.Stmt) -> bool:
    """Whether a statement may leave the body or go elsewhere in it
    (RETURN, JMP, a label)."""
    return any(isinstance(node, (A.Return, A.Jump, A.Label)) for node, _ in walk([stmt]))


def stored_first(stmts: list, sym: VarSymbol) -> bool:
    """Whether the body stores sym (`F := ...`) before anything can read
    it or return it: the statements before that store neither name sym
    nor leave the body (a fault before it returns nothing)."""
    for s in stmts:
        if isinstance(s, A.Assign) and s.op == ":=" and isinstance(s.target, A.Name) and s.target.sym is sym:
            return id(sym) not in uses([s.value])
        if id(sym) in uses([s]) or _leaves(s):
            return False
    return False


class LocalsGen(CodeGenBase):
    """The program's scalars in locals (the module docstring)."""

    def _promotable(self, sym: Any) -> bool:
        """An elementary variable of the program's own, in a slot of self
        (a VAR_TEMP that no reference reaches is a Python local already)."""
        return (
            self._own_unreferenced(sym)
            and sym.section != "VAR_TEMP"
            and not sym.constant
            and T.base_elementary(sym.type) is not None
            and not T.resolve(sym.type).is_aggregate
        )

    def _locals_begin(self, stmts: list) -> list:
        """Before a PROGRAM's body: its scalars read into locals and a try
        opened; returns them (for _locals_end)."""
        pou = self.fn.pou
        if not self.optimise or pou is None or not self._closed_program(pou):
            return []
        syms = [sym for sym, n in uses(stmts).values() if n > 1 and self._promotable(sym)]
        if not syms:
            return []
        syms.sort(key=lambda s: s.pyname)
        for sym in syms:
            self.emit(f"_l_{sym.pyname} = {self.fn.self_name}.{sym.pyname}")
        self.emit("try:")
        self.indent += 1
        self.fn.promoted = {id(sym): f"_l_{sym.pyname}" for sym in syms}
        return syms

    def _locals_end(self, syms: list) -> None:
        """After the body: every local stored back, however the body ends."""
        if not syms:
            return
        stored = self.fn.promoted_stored
        self.fn.promoted = {}
        self.indent -= 1
        self.emit("finally:")
        self.indent += 1
        back = [sym for sym in syms if id(sym) in stored]
        for sym in back:
            self.emit(f"{self.fn.self_name}.{sym.pyname} = _l_{sym.pyname}")
        if not back:
            self.emit("pass")
        self.indent -= 1
