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

from . import ast as A

# (codegen_stmts.CASE_CHAIN: a CASE of more branches is a tree of ifs)
CASE_CHAIN = 64

SAFE_BLOCKS = 12  # 20 refused
# An IF's ELSIFs are an elif chain, as deep for the compiler as nested IFs
# (4,000 are refused), and a CASE's branches up to CASE_CHAIN: nodes and
# such branches in each other.
SAFE_CHAIN = 300
SAFE_DEPTH = 40  # the shallowest refused shape found: 24 (21 nested REPEATs, 21 blocks); else 74

_LOOPS = (A.For, A.While, A.Repeat)
_SKIPPED = frozenset(("pos", "ty", "const", "implicit_ref", "sym", "pragmas"))
_FIELDS: dict = {}


def _fields(cls: type) -> tuple:
    names = _FIELDS.get(cls)
    if names is None:
        names = tuple(n for c in cls.__mro__ for n in getattr(c, "__slots__", ()) if n not in _SKIPPED)
        _FIELDS[cls] = names
    return names


def too_deep(
    files: list, depth_limit: int = SAFE_DEPTH, block_limit: int = SAFE_BLOCKS, chain_limit: int = SAFE_CHAIN
) -> bool:
    """Whether a node of the files lies more than depth_limit nodes deep,
    inside more than block_limit loops and labelled statement lists, or
    more than chain_limit nodes and IF and CASE branches deep (the walk
    stops at the first that does)."""
    stack: list = [(sf, 0, 0, 0) for sf in files]
    while stack:
        obj, depth, blocks, chain = stack.pop()
        if isinstance(obj, A.Node):
            depth += 1
            chain += 1
            if isinstance(obj, _LOOPS):
                blocks += 1
            elif isinstance(obj, A.If):
                chain += len(obj.branches)
            elif isinstance(obj, A.Case):
                chain += min(len(obj.branches), CASE_CHAIN)
            if depth > depth_limit or blocks > block_limit or chain > chain_limit:
                return True
            for name in _fields(type(obj)):
                value = getattr(obj, name, None)
                if isinstance(value, (A.Node, list, tuple, dict)):
                    stack.append((value, depth, blocks, chain))
            continue
        values = obj.values() if isinstance(obj, dict) else obj
        if isinstance(obj, list) and any(isinstance(v, A.Label) for v in values):
            blocks += 1
            if blocks > block_limit:
                return True
        for value in values:
            if isinstance(value, (A.Node, list, tuple, dict)):
                stack.append((value, depth, blocks, chain))
    return False
