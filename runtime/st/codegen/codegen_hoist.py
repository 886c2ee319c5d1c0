"""Integer arithmetic a FOR loop's body repeats on values it never changes,
computed once before the loop.

``FOR i := 0 TO 999 DO x := (cycle * 7 + i) MOD 1000; ...`` multiplied
``cycle * 7`` a thousand times a cycle. Before the loop starts, such an
expression is bound to a local (``_h5 = (_l_v_cycle * 7)``), which the body
reads instead. An expression is moved when:

* it is an integer ``+``, ``-`` or ``*`` (or a unary minus) whose operands
  are literals, moved expressions or variables that are Python locals of
  the body (a PROGRAM's scalar held in a local, codegen_locals.py; a
  VAR_TEMP; a FUNCTION's own variable; the variable of an enclosing FOR
  loop) which the loop's body never stores: no assignment, FOR, SET or
  RESET to them, no reference taken (ADR, REF, VAR_IN_OUT, =>). Nothing
  else can reach such a local, so its value is the same at every pass;
* its Python is plain arithmetic on names and literals (no call, no
  division): computing it early cannot fault, even when the loop does not
  run or the expression stands in a branch not taken;
* it is the largest such expression (``cycle * 7 + k``, k unchanged, moves
  whole) and the body has no labels.
"""

from __future__ import annotations

import re
from typing import Any

from .. import ast as A
from .. import types as T
from ..check.symbols import VarSymbol
from .codegen_facts import root_name
from .codegen_locals import walk
from .codegen_reuse import ReuseGen, lvalues

_OPS = frozenset(("+", "-", "*"))
# what a moved expression's Python may be: names, integer literals, parentheses, + - * & and spaces
_PLAIN = re.compile(r"[A-Za-z0-9_ ()+\-*&]+")
_CALL = re.compile(r"[A-Za-z0-9_]\s*\(")


class HoistGen(ReuseGen):
    """Loop-invariant integer arithmetic moved before its FOR loop (the module docstring)."""

    def _local_name(self, sym: Any) -> bool:
        """Whether the body reads sym from a Python local, which nothing but
        the body's own statements can change: what _read_name (codegen_exprs.py)
        gives for it is a bare name (a FOR loop's local, a PROGRAM's promoted
        scalar, a VAR_TEMP, a FUNCTION's own variable), not an attribute,
        a cell or an accessor."""
        if not isinstance(sym, VarSymbol) or sym.location is not None or T.resolve(sym.type).is_aggregate:
            return False  # (an accessor is bound, an aggregate counted, on reading: not asked)
        return self._read_name(sym).isidentifier()

    def _invariants(self, s: A.For) -> list:
        """The largest integer expressions of s's body that do not change while it runs."""
        stored = {id(s.var.sym)}  # the variables the body stores to or references, and the loop's own
        parent: dict = {}
        order: list = []
        for node, _ in walk(s.body):  # one pass: a long body is walked once per loop around it
            order.append(node)
            if isinstance(node, A.Binary):
                parent[id(node.left)] = parent[id(node.right)] = node
            elif isinstance(node, A.Unary):
                parent[id(node.operand)] = node
            elif isinstance(node, A.Label):
                return []  # a jump target
            targets = lvalues(node)
            if isinstance(node, (A.Assign, A.AssignExpr, A.SetReset)):
                targets.append(node.target)
            elif isinstance(node, A.For):
                targets.append(node.var)
            for target in targets:
                sym = root_name(target)
                if sym is not None:
                    stored.add(id(sym))
        hoisted = self.fn.hoisted
        same: dict = {}  # id(expression) -> True when it is the same at every pass
        for node in reversed(order):  # operands before their operator
            if id(node) in hoisted:
                same[id(node)] = True
            elif isinstance(node, (A.Literal, A.Name)) and node.const is not None:
                same[id(node)] = isinstance(node.const, int) and not isinstance(node.const, bool)
            elif isinstance(node, A.Name):
                same[id(node)] = id(node.sym) not in stored and self._local_name(node.sym)
            elif isinstance(node, (A.Binary, A.Unary)) and self._integer_op(node):
                operands = (node.left, node.right) if isinstance(node, A.Binary) else (node.operand,)
                same[id(node)] = all(same.get(id(o), False) for o in operands)
        found = []
        for node in order:
            if not isinstance(node, (A.Binary, A.Unary)) or not same.get(id(node)) or id(node) in hoisted:
                continue
            up = parent.get(id(node))
            if up is None or not same.get(id(up)):
                found.append(node)
        return found

    @staticmethod
    def _integer_op(node: Any) -> bool:
        if isinstance(node, A.Binary):
            if node.op not in _OPS or node.impl is not None:
                return False
        elif node.op != "-":
            return False
        if node.const is not None:
            return False  # folded already
        be = T.base_elementary(T.resolve(node.ty)) if node.ty is not None else None
        return be is not None and be.is_integer

    def _hoist(self, s: A.For) -> list:
        """Bind the body's invariant expressions to locals before the loop;
        the ids to forget once its body is emitted."""
        if not self.optimise:
            return []
        moved = []
        for node in self._invariants(s):
            lines = len(self.out)
            code = self.ex(node)
            if len(self.out) != lines or not _PLAIN.fullmatch(code) or _CALL.search(code):
                del self.out[lines:]  # (plain arithmetic emits nothing before it)
                continue
            local = self.tmp("h")
            self.emit(f"{local} = {code}")
            self.fn.hoisted[id(node)] = local
            moved.append(id(node))
        return moved
