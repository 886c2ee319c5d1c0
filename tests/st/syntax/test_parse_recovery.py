"""parse_recovery.py: syntax errors are reported where they are, with a
hint, and the parse goes on."""

from __future__ import annotations

from softplc.runtime.st import ast

from .parse_helpers import errors, parse, show

# ---------------------------------------------------------------- syntax errors


def test_three_separate_errors_give_three_diagnostics():
    src = """PROGRAM p
VAR
    a : INT
    b : INT;
END_VAR
a := 1 +;
IF a > 0 THEN
    b := 2
END_IF;
END_PROGRAM
"""
    sf, diags = parse(src)
    assert [(d.code, d.pos.line) for d in diags] == [("E001", 3), ("E001", 6), ("E001", 8)]
    missing = diags[0]
    assert missing.message == "missing ';' before 'b'" and missing.hint == "missing ';' after the declaration?"
    assert diags[2].hint == "missing ';' after the statement?"
    assert (missing.pos.line, missing.pos.col) == (3, 12)  # right after INT
    assert (diags[1].pos.col, diags[1].hint) == (9, "an expression (a value or a variable) is missing here")
    # What could be parsed is still there.
    [pou] = sf.decls
    assert [d.name for d in pou.var_blocks[0].decls] == ["a", "b"]
    assert isinstance(pou.body[-1], ast.If)


def test_missing_end_if_names_the_if():
    sf, [d] = parse("PROGRAM p\nIF a THEN\n  x := 1;\ny := 2;\nEND_PROGRAM\n")
    assert (d.code, d.pos.line) == ("E001", 5)
    assert "END_IF expected to close the IF at line 2" in d.message
    [pou] = sf.decls
    [if_] = pou.body
    assert [show(s.target) for s in if_.branches[0][1]] == ["x", "y"]  # each once: LALR's early reductions undone
    [d] = errors("PROGRAM p\nIF a THEN\n  x := 1;\n")
    assert d.message == "unexpected end of file" and d.hint == "END_IF expected to close the IF at line 2"


def test_each_pou_gets_its_own_error_and_survives():
    sf, diags = parse("""FUNCTION_BLOCK A
VAR x : INT; END_VAR
x := ;
END_FUNCTION_BLOCK
PROGRAM B
VAR y : INT END_VAR
y := 1;
END_PROGRAM
FUNCTION C : INT
C := 1 +* 2;
END_FUNCTION
""")
    assert [(d.code, d.pos.line) for d in diags] == [("E001", 3), ("E001", 6), ("E001", 10)]
    assert [p.name for p in sf.decls] == ["A", "B", "C"]
    assert sf.decls[1].body[0].value.value == 1


def test_garbage_between_pous_is_one_error():
    sf, [d] = parse(
        "PROGRAM a\nx := 1;\nEND_PROGRAM\ngarbage here; more := garbage;\n"
        "x := 1;\nFUNCTION f : INT\nf := 1;\nEND_FUNCTION\n"
    )
    assert (d.code, d.pos.line, d.pos.col) == ("E001", 4, 1) and d.hint.startswith("outside a POU")
    assert [p.name for p in sf.decls] == ["a", "f"]


def test_var_block_after_statements():
    sf, [d] = parse("PROGRAM p\nx := 1;\nVAR y : INT; END_VAR\ny := 2;\nEND_PROGRAM")
    assert (d.code, d.pos.line, d.message) == ("E005", 3, "VAR block after the statements")
    assert len(sf.decls[0].body) == 2


def test_mismatched_end_keyword():
    [d] = errors("WHILE a DO\n  x := 1;\nEND_FOR\n")
    assert "END_FOR" in d.message and d.hint == "END_WHILE expected to close the WHILE at line 1"


def test_equals_instead_of_assign():
    sf, [d] = parse("x = 5;\ny := 1;")
    assert (d.code, d.pos.line, d.pos.col) == ("E001", 1, 3)
    assert d.hint == "':=' assigns, '=' compares"
    assert len(sf.decls[0].body) == 2  # parsed on as an assignment


def test_duplicate_else_and_elsif_after_else():
    [d] = errors("IF a THEN x := 1; ELSE x := 2; ELSE x := 3; END_IF")
    assert (d.code, d.message, d.pos.col) == ("E005", "duplicate ELSE", 32)
    [d] = errors("IF a THEN x := 1;\nELSE x := 2;\nELSIF b THEN x := 3;\nEND_IF")
    assert (d.code, d.message, d.pos.line) == ("E005", "ELSIF after ELSE", 3)


def test_jumps_and_labels_parse_and_a_jump_to_a_number_is_refused_clearly():
    assert errors("x := 1;\nJMP done;\ndone: x := 2;\n") == []
    # CODESYS C0114 "Invalid destination 0 for 'JMP'"
    [d] = errors("x := 1;\nJMP 0;\nx := 2;\n")
    assert (d.code, d.message, d.pos.line, d.pos.col) == ("E001", "JMP needs a label", 2, 1)


def test_misspelt_keyword_gets_a_suggestion():
    [d] = errors("IF a THEN x := 1;\nELSEIF b THEN x := 2;\nEND_IF")
    assert d.hint == "did you mean ELSIF?"
    [d] = errors("FUNCTION_BLOCK f\nVAR_INPUTS x : INT; END_VAR\nEND_FUNCTION_BLOCK")
    assert d.hint == "did you mean VAR_INPUT?"


def test_a_method_left_open_is_closed_by_its_block():
    sf, diags = parse("FUNCTION_BLOCK f\nMETHOD m : INT\nm := 1;\nEND_FUNCTION_BLOCK\n")
    assert [(d.code, d.pos.line) for d in diags] == [("E001", 4)]
    assert diags[0].hint == "END_METHOD expected to close the METHOD at line 2"


def test_an_expression_alone_is_not_a_statement():
    [d] = errors("x;")
    assert d.code == "E001" and "not a statement" in d.message


def test_missing_brackets_and_commas():
    diags = errors("x := (1 + 2;\ny := f(a b);\nz := a[1;\n")
    assert [d.message for d in diags] == ["missing ')' before ';'", "missing ',' before 'b'", "missing ']' before ';'"]


def test_error_positions_point_into_the_text():
    src = "PROGRAM p\nVAR x : INT; END_VAR\nx := (1 + ;\nIF x THEN\nEND_PROGRAM"
    for d in errors(src):
        lines = src.split("\n")
        assert 1 <= d.pos.line <= len(lines) and 1 <= d.pos.col <= len(lines[d.pos.line - 1]) + 1
