"""build_stmts.py: statements in the AST."""

from __future__ import annotations

from softplc.runtime.st import ast

from .parse_helpers import body, show, span

# ---------------------------------------------------------------- statements


def test_assignment_operators():
    stmts = body("a := 1; b S= c; b R= d; p REF= x;")
    assert [s.op for s in stmts] == [":=", "S=", "R=", "REF="]


def test_if_elsif_else():
    [s] = body("IF a THEN x := 1; ELSIF b THEN x := 2; ELSIF c THEN ; ELSE x := 3; y := 4; END_IF")
    assert [show(c) for c, _ in s.branches] == ["a", "b", "c"]
    assert [len(b) for _, b in s.branches] == [1, 1, 0]
    assert len(s.else_body) == 2
    [s2] = body("IF a THEN END_IF;")
    assert s2.else_body is None and s2.branches[0][1] == []
    [s3] = body("IF a THEN x := 1; ELSE END_IF")
    assert s3.else_body == []


def test_trailing_semicolons_after_end_keywords_are_optional():
    with_semis = body("IF a THEN x := 1; END_IF; FOR i := 1 TO 2 DO END_FOR; ;;")
    without = body("IF a THEN x := 1; END_IF FOR i := 1 TO 2 DO END_FOR")
    assert [type(s) for s in with_semis] == [type(s) for s in without] == [ast.If, ast.For]


def test_case_labels():
    [s] = body("""CASE sel OF
    1, 2: x := 1;
    3..5, -7, -10..-8: x := 2;
    Color#Red, Green: x := 3;
    Color.Blue, MAX_VAL..MAX_VAL + 1: x := 4;
    16#10, (N + 1): ;
    TRUE: x := 5; y := 6;
ELSE
    x := 0;
END_CASE""")
    labels = [[show(lab) for lab in b.labels] for b in s.branches]
    assert labels == [
        ["1", "2"],
        ["3..5", "(- 7)", "(- 10)..(- 8)"],
        ["Color#Red", "Green"],
        ["Color.Blue", "MAX_VAL..(+ MAX_VAL 1)"],
        ["16", "(+ N 1)"],
        ["True"],
    ]
    assert [len(b.body) for b in s.branches] == [1, 1, 1, 1, 0, 2]
    assert len(s.else_body) == 1
    assert isinstance(s.branches[1].labels[0], ast.CaseRange)


def test_case_without_else_and_a_label_after_a_call():
    [s] = body("CASE n OF 1: f(); two: g(); END_CASE")
    assert s.else_body is None and [show(b.labels[0]) for b in s.branches] == ["1", "two"]


def test_loops_and_jumps():
    stmts = body("""FOR i := 10 TO 1 BY -2 DO IF i = 5 THEN EXIT; END_IF; CONTINUE; END_FOR
FOR j := 1 TO n DO END_FOR
WHILE x < 10 DO x := x + 1; END_WHILE
REPEAT x := x - 1; UNTIL x <= 0 END_REPEAT
REPEAT UNTIL TRUE; END_REPEAT
RETURN;""")
    f1, f2, w, r1, r2, ret = stmts
    assert isinstance(f1.var, ast.Name) and f1.var.name == "i"
    assert show(f1.start) == "10" and show(f1.end) == "1" and show(f1.step) == "(- 2)"
    assert isinstance(f1.body[0].branches[0][1][0], ast.Exit) and isinstance(f1.body[1], ast.Continue)
    assert f2.step is None and f2.body == []
    assert show(w.cond) == "(< x 10)" and len(w.body) == 1
    assert show(r1.cond) == "(<= x 0)" and len(r1.body) == 1
    assert r2.body == []
    assert isinstance(ret, ast.Return)


def test_empty_statements_leave_nothing():
    assert body(";;x := 1;;;") and len(body(";;x := 1;;;")) == 1


def test_statement_positions():
    [s] = body("\n  IF a THEN\n    x := 1;\n  END_IF;")
    assert span(s) == (2, 3, 4, 9)
    assert span(s.branches[0][1][0]) == (3, 5, 3, 11)
