"""How deeply a parsed file nests: what decides whether `softplc check`
must generate and compile the Python to report everything.

The back end adds one diagnostic of its own, E006 when CPython's compiler
refuses the generated module: 20 statically nested blocks (the generated
code has one per FOR, WHILE and REPEAT, and one per statement list with a
label), 100 levels of indentation, 200 nested brackets, its recursion
limit. A file whose loops and labelled lists nest at most SAFE_BLOCKS deep
and whose nodes (statements, expressions, types, initialisers) nest at
most SAFE_DEPTH deep is far from each (tests/st/test_nesting.py measures
the shallowest shapes that reach one), so a check of such files skips the
back end.
"""

from __future__ import annotations

from .. import ast as A
from .codegen_stmts import CASE_CHAIN  # (a CASE of more branches is a tree of ifs, not an elif chain)

# Loops and labelled statement lists in each other: 20 are refused.
SAFE_BLOCKS = 12
# Nodes in each other: the shallowest refused shape, 21 REPEATs in each
# other, is 24 deep (and past SAFE_BLOCKS); without loops, 70 indices in
# each other, 74 deep.
SAFE_DEPTH = 40
# An IF's ELSIFs are an elif chain, as deep for the compiler as nested IFs
# (about 3,000 are refused), and a CASE's branches up to CASE_CHAIN: nodes
# and such branches in each other.
SAFE_CHAIN = 300

_SKIPPED = frozenset(("pos", "ty", "const", "implicit_ref", "sym", "pragmas"))
_LEAF, _SEQ, _MAP, _NODE, _LOOP, _IF, _CASE = range(7)
#: class -> (what it is, the fields to walk of a node)
_INFO: dict[type, tuple] = {}


def _info(cls: type) -> tuple:
    info = _INFO.get(cls)
    if info is None:
        if issubclass(cls, A.Node):
            fields = tuple(n for c in cls.__mro__ for n in getattr(c, "__slots__", ()) if n not in _SKIPPED)
            kind = (
                _LOOP
                if issubclass(cls, (A.For, A.While, A.Repeat))
                else _IF
                if issubclass(cls, A.If)
                else _CASE
                if issubclass(cls, A.Case)
                else _NODE
            )
            info = (kind, fields)
        elif issubclass(cls, (list, tuple)):
            info = (_SEQ, ())
        elif issubclass(cls, dict):
            info = (_MAP, ())
        else:
            info = (_LEAF, ())
        _INFO[cls] = info
    return info


def too_deep(
    files: list, depth_limit: int = SAFE_DEPTH, block_limit: int = SAFE_BLOCKS, chain_limit: int = SAFE_CHAIN
) -> bool:
    """Whether a node of the files lies more than depth_limit nodes deep,
    inside more than block_limit loops and labelled statement lists, or
    more than chain_limit nodes and IF and CASE branches deep (the walk
    stops at the first that does)."""
    stack: list = [(sf, 0, 0, 0) for sf in files]
    pop, push, info_of, label = stack.pop, stack.append, _INFO.get, A.Label
    while stack:
        obj, depth, blocks, chain = pop()
        kind, fields = info_of(type(obj)) or _info(type(obj))
        if kind >= _NODE:
            depth += 1
            chain += 1
            if kind == _LOOP:
                blocks += 1
            elif kind == _IF:
                chain += len(obj.branches)
            elif kind == _CASE:
                chain += min(len(obj.branches), CASE_CHAIN)
            if depth > depth_limit or blocks > block_limit or chain > chain_limit:
                return True
            for name in fields:
                value = getattr(obj, name, None)
                if (info_of(type(value)) or _info(type(value)))[0] != _LEAF:
                    push((value, depth, blocks, chain))
            continue
        if kind == _LEAF:
            continue
        values = obj.values() if kind == _MAP else obj
        if kind == _SEQ and type(obj) is not tuple and label in map(type, values):
            blocks += 1
            if blocks > block_limit:
                return True
        for value in values:
            if (info_of(type(value)) or _info(type(value)))[0] != _LEAF:
                push((value, depth, blocks, chain))
    return False
