"""What variables occupy (runtime/st/check/checker_storage.py): no type contains
itself, and the variables stay within the element limits."""

from __future__ import annotations

import pytest

from softplc.runtime.st.limits import MAX_TOTAL_ELEMENTS, MAX_VAR_ELEMENTS

from ...test_cli import softplc
from ..conftest import diagnostics

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


# ---------------------------------------------------------------- sizes


def test_a_variable_of_more_elements_than_the_limit_is_e054_at_its_declaration():
    # 4 million two-field points: 4M * (2 + 1) elements
    src = (
        "TYPE Point : STRUCT x : REAL; y : REAL; END_STRUCT END_TYPE\n"
        "FUNCTION_BLOCK Track\nVAR pts : ARRAY[1..4000000] OF Point; END_VAR\nEND_FUNCTION_BLOCK\n"
        "PROGRAM main\nVAR\n    ok : ARRAY[1..3000000] OF Point;\n    t : Track;\nEND_VAR\nEND_PROGRAM\n"
    )
    found = [(d.code, d.pos.line, d.pos.col, d.message) for d in diagnostics(src)]
    assert found == [
        ("E054", 3, 5, f"'pts' has 12,000,000 elements; one variable may have {MAX_VAR_ELEMENTS:,}"),
        ("E054", 8, 5, f"'t' has 12,000,001 elements; one variable may have {MAX_VAR_ELEMENTS:,}"),
    ]


def test_all_variables_together_pass_the_total_limit_at_the_one_that_crosses_it():
    half = MAX_TOTAL_ELEMENTS // 4
    src = (
        f"VAR_GLOBAL g : ARRAY[1..{half}] OF LREAL; END_VAR\n"
        f"FUNCTION f : INT\nVAR tmp : ARRAY[1..{half}] OF DINT; END_VAR\nf := 0;\nEND_FUNCTION\n"
        f"PROGRAM main\nVAR\n    a : ARRAY[1..{half}] OF INT;\n    b : ARRAY[1..{half}] OF INT;\n"
        "    c : INT;\nEND_VAR\nEND_PROGRAM\n"
    )
    [d] = diagnostics(src)
    assert (d.code, d.pos.line) == ("E055", 9)
    assert d.message.startswith(f"the variables have more than {MAX_TOTAL_ELEMENTS:,} elements together (")
    assert d.message.endswith(" up to 'b')")
