"""The syntax tree's nodes (runtime/st/ast.py): one __repr__ for all of
them, written as a dataclass would write it (what a developer sees in a
debugger, a failing assertion or a log)."""

from __future__ import annotations

from softplc.runtime.st import ast as A


def test_a_node_shows_its_fields_as_a_dataclass_would():
    pos = A.Pos("main.st", 3, 5, 3, 9)
    node = A.Assign(A.Name("x", pos=pos), A.Name("y", pos=pos), pos=pos)
    node.target.sym = object()  # checker annotations are not shown
    assert repr(node.target) == f"Name(pos={pos!r}, name='x', qualifier=None)"
    assert repr(node) == (f"Assign(pos={pos!r}, pragmas=[], target={node.target!r}, value={node.value!r}, op=':=')")


def test_a_node_that_holds_itself_is_shown_once():
    call = A.Call(A.Name("f"), [])
    call.args.append(call)
    assert "Call(pos=" in repr(call) and "..." in repr(call)
