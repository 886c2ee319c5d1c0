"""An array element read once for the statements that follow.

``last := accs[i].Step(x); check := check + accs[i].Total;`` reads
``accs[i]`` twice: a subtraction and a subscript each time. Where nothing
can change the element between the two reads, the first read is bound to a
local before its statement (``_e7 = _a_v_accs[_i4 - 1]``) and the others
use the local. That holds for an element ``B[i]`` when:

* B is an array of this POU that no call can reach (a FUNCTION's local, or
  a PROGRAM's without actions, methods, properties or SFC steps:
  CodeGenBase._closed_program), not located, and no reference to it or
  into it is taken anywhere in the body (ADR, REF, REF=, VAR_IN_OUT, =>,
  an assignment inside an expression);
* every index is a constant or a FOR variable read from its loop local
  (which its loop's body cannot change), and lies inside the bounds, so the
  read cannot fault and may run before the rest of its statement;
* the read is part of a plain assignment, whose expressions run once where
  the statement stands.

A plain assignment into such an element binds it too: ``avg[i] := sum / 8.0;
IF avg[i] < lo THEN lo := avg[i]; END_IF`` stores ``_a_v_avg[_i4] = _e7 =
...`` and reads ``_e7`` after it (a literal it stores is read as itself).

The bound element is one of the facts (codegen_facts.py): a store into B
forgets it, and so do a loop's start and end, the join of branches that did
not all bind it, a list with labels, an assignment inside an expression.
"""

from __future__ import annotations

import re
from typing import Any

from .. import ast as A
from .. import types as T
from ..check.symbols import CallInfo
from . import ranges as R
from .codegen_facts import FACTS_MAX, FactsGen, root_name
from .codegen_locals import walk

# a stored value that later reads repeat instead of a local (a negative one
# in parentheses: -1 ** 2 is not (-1) ** 2)
_NUMBER = r"[0-9][0-9_.]*(e[+-]?[0-9]+)?"
_LITERAL = re.compile(rf"{_NUMBER}|True|False")
_NEGATIVE = re.compile(rf"-{_NUMBER}")
_BOUND = re.compile("\1(_e[0-9]+)\1 = ")


def lvalues(node: A.Node) -> list:
    """The expressions node takes a reference to or stores into besides its
    target: VAR_IN_OUT and => arguments (and a builtin's or an ENO's), the
    value of REF=, the target of an assignment inside an expression."""
    found: list = []
    if isinstance(node, A.Call) and isinstance(node.target, CallInfo):
        info = node.target
        found += [a for _, a in info.inouts] + [t for _, t, _ in info.outputs]
        if info.kind == "builtin" or info.eno is not None:
            found += list(info.args) + [info.eno]
    elif isinstance(node, A.Assign) and node.op == "REF=":
        found.append(node.value)
    elif isinstance(node, A.AssignExpr):
        found.append(node.target)
    return found


def referenced(stmts: list) -> set:
    """Ids of the variables a reference is taken to or into anywhere in
    stmts: ADR, REF, REF=, VAR_IN_OUT and => arguments, assignments inside
    expressions."""
    found: set = set()
    for node, _ in walk(stmts):
        found.update(id(sym) for sym in map(root_name, lvalues(node)) if sym is not None)
    return found


class ReuseGen(FactsGen):
    """Array elements bound to locals (the module docstring)."""

    def _reuse_key(self, e: A.Index) -> tuple | None:
        base = e.base
        if not isinstance(base, A.Name) or not self._reusable_array(base.sym):
            return None
        arr = T.resolve(base.ty)
        if not isinstance(arr, T.ArrayType) or arr.variable_length:
            return None
        keys: list = []
        for ix, dim in zip(e.indices, arr.dims):
            if isinstance(ix.const, int) and not isinstance(ix.const, bool):
                key: Any = ix.const
            elif isinstance(ix, A.Name) and id(ix.sym) in self.fn.for_locals:
                key = id(ix.sym)
            else:
                return None
            if dim is None or not R.within(self._range(ix), dim[0], dim[1]):
                return None  # it may fault: it stays where it is
            keys.append(key)
        return ("elem", id(base.sym), tuple(keys))

    def _reusable_array(self, sym: Any) -> bool:
        pou = self.fn.pou
        if pou is None or not self._own_unreferenced(sym) or not self._fact_stable(sym):
            return False
        if self.fn.referenced is None:
            self.fn.referenced = referenced(pou.node.body or [])
        return id(sym) not in self.fn.referenced

    def _index_read(self, e: A.Index) -> str:
        """An element read: a local bound before an earlier statement, or
        bound now, or read where it stands."""
        facts = self.fn.facts
        key = self._reuse_key(e) if facts is not None else None
        if key is None:
            return self._index_target(e)
        assert facts is not None
        bound = facts.get(key)
        if bound is not None:
            self._stores_read.add(bound)
            return bound
        code = self._index_target(e)
        if self.fn.bind_at != self.indent or len(facts) >= FACTS_MAX:  # not a plain assignment's own line
            return code
        local = self.tmp("e")
        self.emit(f"{local} = {code}")
        facts[key] = local
        return local

    def _bind_stored(self, target: A.Index) -> None:
        """target := value was just emitted as ``B[i] = code``: the element
        now holds what code gave, which the statements after it read from a
        local bound in the same line (``B[i] = _e7 = code``)."""
        facts = self.fn.facts
        if facts is None or target.implicit_ref is not None or len(facts) >= FACTS_MAX:
            return
        key = self._reuse_key(target)
        if key is None:
            return
        line, pos = self.out[-1]
        split = line.find(" = ")  # its index is a constant or a FOR variable: no " = " in it
        pad = "    " * self.indent
        if split < 0 or not line.startswith(pad) or line[len(pad) : len(pad) + 1] == " " or line[split - 1] != "]":
            return
        head, code = line[: split + 3], line[split + 3 :]
        if _LITERAL.fullmatch(code) or _NEGATIVE.fullmatch(code):
            facts[key] = code if code[0] != "-" else f"({code})"
            return
        local = self.tmp("e")
        self.out[-1] = (f"{head}\1{local}\1 = {code}", pos)
        self._stores_bound += 1
        facts[key] = local

    def _unbind_unread(self) -> None:
        """The module is complete: a local bound by _bind_stored stays in its
        line if a read used it, else goes (until now the local was marked in
        its line, between two \\1, as lines move and are re-indented)."""
        read = self._stores_read
        left = self._stores_bound

        def keep(m: re.Match) -> str:
            return f"{m.group(1)} = " if m.group(1) in read else ""

        for i, (text, pos) in enumerate(self.out):
            if not left:
                break
            if "\1" in text:
                self.out[i] = (_BOUND.sub(keep, text), pos)
                left -= text.count("\1") // 2
