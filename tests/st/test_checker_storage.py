"""What variables occupy (runtime/st/checker_storage.py): no type contains
itself, and the variables stay within the element limits."""

from __future__ import annotations

import pytest

from ..test_cli import softplc
from .conftest import diagnostics

# ---------------------------------------------------------------- types that contain themselves


@pytest.mark.parametrize(
    "types,message,line",
    [
        ("S : STRUCT a : INT; me : S; END_STRUCT;", "STRUCT 'S' contains itself: S.me is S", 2),
        (
            "A : STRUCT b : B; END_STRUCT;\nB : STRUCT arr : ARRAY[0..1] OF A; END_STRUCT;",
            "STRUCT 'A' contains itself: A.b is B, B.arr is ARRAY[0..1] OF A",
            2,
        ),
    ],
    ids=["directly", "through-a-struct-and-an-array"],
)
def test_a_struct_that_contains_itself_is_an_error_naming_the_cycle(types, message, line):
    src = f"TYPE\n{types}\nEND_TYPE\nPROGRAM main\nVAR s : INT; END_VAR\nEND_PROGRAM\n"
    found = [(d.code, d.message, d.pos.line) for d in diagnostics(src)]
    assert found == [("E014", message, line)]


def test_a_cycle_through_a_named_array_type_is_reported_once_with_its_chain():
    src = (
        "TYPE\nRow : ARRAY[1..2] OF S;\nS : STRUCT rows : ARRAY[1..3] OF Row; END_STRUCT;\nEND_TYPE\n"
        "PROGRAM main\nVAR s : S; END_VAR\nEND_PROGRAM\n"
    )
    found = [(d.code, d.message, d.pos.line) for d in diagnostics(src)]
    assert found == [("E012", "type 'Row' is defined in terms of itself: Row -> S -> Row", 2)]


def test_a_function_block_that_contains_itself_through_a_struct_is_an_error():
    src = (
        "TYPE Pair : STRUCT left : Node; END_STRUCT END_TYPE\n"
        "FUNCTION_BLOCK Node\nVAR_OUTPUT p : Pair; END_VAR\nEND_FUNCTION_BLOCK\n"
        "PROGRAM main\nVAR n : Node; END_VAR\nn();\nEND_PROGRAM\n"
    )
    assert [(d.code, d.message) for d in diagnostics(src)] == [
        ("E014", "STRUCT 'Pair' contains itself: Pair.left is Node, Node.p is Pair")
    ]


def test_references_in_out_parameters_and_shared_types_are_no_cycle():
    src = (
        "TYPE Item : STRUCT next : REF_TO Item; v : INT; END_STRUCT;\n"
        "Two : STRUCT a : Item; b : Item; END_STRUCT; END_TYPE\n"
        "FUNCTION_BLOCK Walker\nVAR_IN_OUT other : Walker; END_VAR\nEND_FUNCTION_BLOCK\n"
        "PROGRAM main\nVAR t : Two; END_VAR\nt.a.next := REF(t.b);\nEND_PROGRAM\n"
    )
    assert diagnostics(src) == []


def test_a_self_containing_struct_through_the_command_line_is_diagnostic_e014(tmp_path):
    path = tmp_path / "cycle.st"
    path.write_text("TYPE S : STRUCT me : S; END_STRUCT END_TYPE\nPROGRAM main\nVAR s : S; END_VAR\nEND_PROGRAM\n")
    for command in ("check", "compile", "exec"):
        proc = softplc(command, path)
        assert proc.returncode == 1, proc.stderr
        assert f"{path}:1:17: error E014: STRUCT 'S' contains itself: S.me is S" in proc.stderr
        assert "Traceback" not in proc.stderr
