"""lexer.py: comments, keywords and names (through the parser)."""

from __future__ import annotations

import pytest

from softplc.runtime.st import ast
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.limits import MAX_COMMENT_DEPTH
from softplc.runtime.st.profile import PROFILES
from softplc.runtime.st.syntax.parser import parse_source

from ..conftest import prog, run_st
from .parse_helpers import body, errors, expr, ok, parse, show, span

# ---------------------------------------------------------------- lexical


def test_keywords_are_case_insensitive_and_names_keep_their_spelling():
    sf = ok("program Main\nvAr MyVar : int; END_var\nif MyVar = 1 tHeN MyVar := 2; End_If\nend_PROGRAM\n")
    [pou] = sf.decls
    assert (pou.kind, pou.name) == ("PROGRAM", "Main")
    [decl] = pou.var_blocks[0].decls
    assert decl.name == "MyVar" and decl.type.name == "int"
    [stmt] = pou.body
    assert isinstance(stmt, ast.If) and show(stmt.branches[0][0]) == "(= MyVar 1)"


def test_identifiers_may_start_with_an_underscore():
    [a] = body("_x := a_b_1 + _;")
    assert show(a.target) == "_x" and show(a.value) == "(+ a_b_1 _)"


def test_keyword_prefixes_are_names():
    assert show(expr("END_IFx + IFa + ORb + TOTAL")) == "(+ (+ (+ END_IFx IFa) ORb) TOTAL)"


def test_comments_nest_and_all_three_styles_are_skipped():
    src = """(* outer (* inner *) still comment *)
x := 1; // line comment with (* inside
(* y := 2; *) z := 3; /* block
comment (* not nested here */ w := 4;
"""
    stmts = body(src)
    assert [show(s.target) for s in stmts] == ["x", "z", "w"]
    assert span(stmts[2].target) == (4, 31, 4, 32)  # positions survive the comments


def test_comment_markers_inside_strings_are_text():
    stmts = body("x := '(* not a comment *)'; y := '// nor {this}'; z := \"/* no */\";")
    assert [s.value.value for s in stmts] == ["(* not a comment *)", "// nor {this}", "/* no */"]


@pytest.mark.parametrize(
    "src, line, col, what",
    [
        ("x := 1;\n(* open (* nested *)\ny := 2;", 2, 1, "'(*' is never closed"),
        ("x := 1; /* open", 1, 9, "'/*' is never closed"),
        ("{attribute 'x'\nx := 1;", 1, 1, "'{' is never closed"),
    ],
)
def test_unterminated_comments_and_pragmas(src, line, col, what):
    [d] = errors(src)
    assert (d.code, d.pos.line, d.pos.col) == ("E004", line, col) and what in d.message


def test_stray_comment_close():
    [d] = errors("x := 1; *) y := 2;")
    assert (d.code, d.pos.col) == ("E001", 9) and "'*)'" in d.message


# ---------------------------------------------------------------- comment nesting


def test_comments_nest_up_to_the_limit_and_deeper_is_e008_where_it_starts():
    ok("(*" * MAX_COMMENT_DEPTH + " deep " + "*)" * MAX_COMMENT_DEPTH + "\nx := 1;")
    text = "x := 1;\n  " + "(*" * (MAX_COMMENT_DEPTH + 1) + "*)" * (MAX_COMMENT_DEPTH + 1) + "\ny := 2;"
    sf, diags = parse(text)
    [d] = diags
    assert (d.code, d.pos.line, d.pos.col) == ("E008", 2, 3 + 2 * MAX_COMMENT_DEPTH)
    assert d.message == f"comments nested too deeply (more than {MAX_COMMENT_DEPTH} levels)"
    # the comment still ends at its own '*)': the statements around it are read
    assert [s.target.name for s in sf.decls[0].body] == ["x", "y"]


# ---------------------------------------------------------------- nesting by profile


def parse_as(text: str, profile: str) -> tuple:
    diags = DiagnosticBag()
    sf = parse_source(text, "test.st", diags, PROFILES[profile])
    return sf, diags.items


NESTING = prog("x : INT; y : INT;", "x := 1;\n(* off: (* y := 5; *) x := 2; *)\ny := y + 1;")


@pytest.mark.parametrize("profile", ["codesys", "twincat", "schneider"])
def test_nesting_profiles_read_the_whole_comment(profile):
    # CODESYS and TwinCAT: (* (* *) *) is one comment (their static analysis
    # rule SA0163 flags such nested comments), so x := 2 is commented out.
    r = run_st(NESTING, profile=profile)
    assert (r.get("x"), r.get("y")) == (1, 1)


@pytest.mark.parametrize("profile", ["iec", "matiec"])
def test_without_nesting_the_first_close_ends_the_comment(profile):
    # IEC 61131-3 ed.2 2.1.5 and MatIEC: comments do not nest. The comment
    # ends after 'y := 5; *)', so x := 2 is a statement and the last '*)' is
    # stray: an error that says why.
    _, diags = parse_as(NESTING, profile)
    [d] = diags
    assert (d.code, d.pos.line, d.pos.col) == ("E001", 6, 31)
    assert d.message == "'*)' without a matching '(*'"
    assert d.hint == (
        "(* *) comments do not nest in this profile: the comment at line 6 ended at its first '*)'; "
        "they nest in codesys, twincat and schneider"
    )
    # without the stray '*)' the program runs, and x := 2 with it
    r = run_st(NESTING.replace(" *)\ny", "\ny"), profile=profile)
    assert (r.get("x"), r.get("y")) == (2, 1)


def test_without_nesting_an_inner_open_is_text():
    # "(* a (* b *)" is a whole comment in IEC; in CODESYS it is still open
    src = "x := 1; (* a (* b *)\ny := 2;"
    [pou] = parse_as(src, "iec")[0].decls
    assert [show(s.target) for s in pou.body] == ["x", "y"] and parse_as(src, "iec")[1] == []
    [d] = parse_as(src, "codesys")[1]
    assert (d.code, d.pos.line, d.pos.col) == ("E004", 1, 9)
    assert d.hint == (
        "(* *) comments nest in this profile: every '(*' inside needs its own '*)'; "
        "in iec and matiec (no nesting) it would end at line 1"
    )


def test_an_unclosed_comment_is_e004_at_its_start_in_every_profile():
    src = "x := 1;\n(* never closed\ny := 2;"
    for profile in PROFILES:
        [d] = parse_as(src, profile)[1]
        assert (d.code, d.pos.line, d.pos.col) == ("E004", 2, 1), profile
        assert "'(*' is never closed" in d.message
    assert parse_as(src, "iec")[1][0].hint == "close it with '*)'"
    assert "would end" not in parse_as(src, "codesys")[1][0].hint  # no '*)' anywhere: nothing to add


def test_without_nesting_there_is_no_depth_limit():
    text = "(*" * (MAX_COMMENT_DEPTH + 1) + " *)\nx := 1;"
    sf, diags = parse_as(text, "iec")
    assert diags == [] and [s.target.name for s in sf.decls[0].body] == ["x"]


# ---------------------------------------------------------------- operator keywords as functions


def test_operator_keywords_before_a_parenthesis_are_functions_where_an_operand_stands():
    """IEC 61131-3 ed.3 Table 29-31: AND, OR, XOR, NOT and MOD are also
    functions (AND(a, b, c)). After an operand they stay operators."""
    assert show(expr("AND(a, b, c) OR NOT (x) AND y MOD(3)")) == "(OR AND(a, b, c) (AND (NOT x) (MOD y 3)))"
    assert show(expr("a AND (b) XOR MOD(7, 3)")) == "(XOR (AND a b) MOD(7, 3))"
    assert show(expr("(a) OR\n(b) OR x[1] AND (c) OR p^ XOR (d)")) == "(OR (OR (OR a b) (AND x[1] c)) (XOR p^ d))"
    assert show(expr("NOT(IN := w) AND NOT b")) == "(AND NOT(IN := w) (NOT b))"
    [stmt] = body("XOR(IN1 := a, IN2 := b);")
    assert isinstance(stmt, ast.CallStmt) and show(stmt.call) == "XOR(IN1 := a, IN2 := b)"
