"""build_exprs.py: literals, direct addresses and expressions in the AST."""

from __future__ import annotations

import pytest

from softplc.runtime.st import ast

from .parse_helpers import body, errors, expr, show, span

# ---------------------------------------------------------------- literals in the AST


@pytest.mark.parametrize(
    "text, kind, value, type_name",
    [
        ("16#FF", "int", 255, None),
        ("2#1010_1010", "int", 170, None),
        ("8#17", "int", 15, None),
        ("1_000", "int", 1000, None),
        ("INT#5", "int", 5, "INT"),
        ("INT#16#FF", "int", 255, "INT"),
        ("INT#-5", "int", -5, "INT"),
        ("REAL#1.5", "real", 1.5, "REAL"),
        ("BOOL#1", "bool", True, "BOOL"),
        ("1.0E-3", "real", 0.001, None),
        ("1.5e3", "real", 1500.0, None),
        ("TRUE", "bool", True, None),
        ("false", "bool", False, None),
        ("'it$'s'", "string", "it's", None),
        ("'$''", "string", "'", None),
        ('"$00C4"', "wstring", "Ä", None),
        ("T#1h2m3s4ms", "time", 3_723_004_000_000, None),
        ("TIME#1.5s", "time", 1_500_000_000, None),
        ("T#-5s", "time", -5_000_000_000, None),
        ("t#100us", "time", 100_000, None),
        ("LT#5ns", "ltime", 5, None),
        ("LTIME#1d", "ltime", 86_400 * 10**9, None),
        ("D#2024-01-02", "date", 1_704_153_600 * 10**9, None),
        ("DATE#1970-01-01", "date", 0, None),
        ("TOD#12:30:15.5", "tod", 45_015_500_000_000, None),
        ("TIME_OF_DAY#00:00:01", "tod", 10**9, None),
        ("DT#2008-09-04-07:50:32", "dt", 1_220_514_632 * 10**9, None),
        ("DATE_AND_TIME#1970-01-01-00:00:00.25", "dt", 250_000_000, None),
        ("LDATE#1970-01-02", "ldate", 86_400 * 10**9, None),
        ("LTOD#00:00:02", "ltod", 2 * 10**9, None),
        ("LDT#1970-01-01-00:00:03", "ldt", 3 * 10**9, None),
    ],
)
def test_literals(text, kind, value, type_name):
    lit = expr(text)
    assert isinstance(lit, ast.Literal)
    assert (lit.kind, lit.value, lit.type_name, lit.c_hex) == (kind, value, type_name, False)
    assert span(lit) == (1, 6, 1, 6 + len(text))


def test_c_style_hex_is_marked():
    lit = expr("0x00032007")
    assert (lit.kind, lit.value, lit.c_hex) == ("int", 0x32007, True)


def test_a_negative_number_is_a_negation_but_a_typed_one_is_a_literal():
    neg = expr("-5")
    assert isinstance(neg, ast.Unary) and neg.op == "-" and neg.operand.value == 5
    assert expr("INT#-5").value == -5


def test_enumeration_values_and_schneider_addresses():
    assert show(expr("Color#Red")) == "Color#Red"
    assert isinstance(expr("Color#Red"), ast.EnumLiteral)
    assert expr("ADR#0.1.SYS").parts == ("0", "1", "SYS")


# ---------------------------------------------------------------- direct addresses


@pytest.mark.parametrize(
    "text, area, size, indices, bit, table",
    [
        ("%I0.1", "I", "", (0, 1), None, None),
        ("%IX0.0", "I", "X", (0, 0), None, None),
        ("%QX1.2", "Q", "X", (1, 2), None, None),
        ("%IW3", "I", "W", (3,), None, None),
        ("%QW4", "Q", "W", (4,), None, None),
        ("%MB2", "M", "B", (2,), None, None),
        ("%MW3250", "M", "W", (3250,), None, None),
        ("%MD3200", "M", "D", (3200,), None, None),
        ("%ML1", "M", "L", (1,), None, None),
        ("%M100", "M", "", (100,), None, None),
        ("%MX0.3", "M", "X", (0, 3), None, None),
        ("%mw3250:x0", "M", "W", (3250,), 0, None),
        ("%MW3250:X0", "M", "W", (3250,), 0, None),
        ("%MW3250:4", "M", "W", (3250,), None, 4),
        ("%IW1.2.3", "I", "W", (1, 2, 3), None, None),
    ],
)
def test_located_addresses(text, area, size, indices, bit, table):
    loc = expr(text)
    assert isinstance(loc, ast.Located)
    assert loc.addr == ast.LocatedAddress(area, size, indices, bit, table, text)


def test_an_address_before_assign_is_not_a_table():
    [a] = body("%MD3200:= 0x00032007;")
    assert a.target.addr.text == "%MD3200" and a.target.addr.table is None
    assert a.value.value == 0x32007


def test_set_and_reset_statements_and_names_called_set():
    stmts = body("SET %M100; RESET q.x; Set := TRUE; Reset := Set; rs(SET := a, RESET1 := b); y := rs.RESET;")
    assert [type(s).__name__ for s in stmts] == ["SetReset", "SetReset", "Assign", "Assign", "CallStmt", "Assign"]
    assert (stmts[0].kind, show(stmts[0].target)) == ("SET", "%M100")
    assert (stmts[1].kind, show(stmts[1].target)) == ("RESET", "q.x")
    assert show(stmts[2].target) == "Set" and show(stmts[3].value) == "Set"
    assert show(stmts[4].call) == "rs(SET := a, RESET1 := b)"
    assert show(stmts[5].value) == "rs.RESET"


# ---------------------------------------------------------------- expressions


@pytest.mark.parametrize(
    "text, tree",
    [
        ("a OR b AND c", "(OR a (AND b c))"),
        ("a OR b XOR c", "(OR a (XOR b c))"),
        ("a XOR b AND c", "(XOR a (AND b c))"),
        ("a AND b = c", "(AND a (= b c))"),
        ("a = b < c", "(= a (< b c))"),
        ("a <> b >= c", "(<> a (>= b c))"),
        ("a < b + c", "(< a (+ b c))"),
        ("a + b * c", "(+ a (* b c))"),
        ("a - b - c", "(- (- a b) c)"),
        ("a / b MOD c", "(MOD (/ a b) c)"),
        ("a * b ** c", "(* a (** b c))"),
        ("a ** b ** c", "(** (** a b) c)"),
        ("-a ** 2", "(** (- a) 2)"),
        ("NOT a AND b", "(AND (NOT a) b)"),
        ("NOT (a AND b)", "(NOT (AND a b))"),
        ("a & b", "(AND a b)"),
        ("a AND_THEN b OR_ELSE c", "(OR_ELSE (AND_THEN a b) c)"),
        ("(a + b) * c", "(* (+ a b) c)"),
        ("- -a", "(- (- a))"),
        ("+a", "(+ a)"),
        ("a <= b", "(<= a b)"),
        ("a > -1", "(> a (- 1))"),
    ],
)
def test_precedence(text, tree):
    assert show(expr(text)) == tree


@pytest.mark.parametrize(
    "text, tree",
    [
        ("w.3", "w.%X3"),
        ("w.%X3", "w.%X3"),
        ("a.b.0", "a.b.%X0"),
        ("a.0.1", "a.%X0.%X1"),
        ("a.b[i, j + 1]^.c(1)", "a.b[i, (+ j 1)]^.c(1)"),
        ("p^^", "p^^"),
        ("m[1][2]", "m[1][2]"),
        ("REF(x)", "REF(x)"),
        ("ADR(x) + SIZEOF(x)", "(+ ADR(x) SIZEOF(x))"),
        ("f()", "f()"),
        ("f(g(1), 2)", "f(g(1), 2)"),
    ],
)
def test_postfix_chains(text, tree):
    assert show(expr(text)) == tree


def test_call_arguments():
    [s] = body("fb(IN := x, PT := T#1s, Q => y, ET => , NOT Done => z);")
    call = s.call
    assert show(call) == "fb(IN := x, PT := 1000000000, Q => y, ET =>, NOT Done => z)"
    et = call.args[3]
    assert (et.name, et.value, et.output) == ("ET", None, True)
    assert call.args[4].negated and call.args[4].output


def test_call_statement_on_a_member():
    [s] = body("inst.sub.fb();")
    assert isinstance(s, ast.CallStmt) and show(s.call.callee) == "inst.sub.fb" and s.call.args == []


def test_positions_of_expressions():
    a = expr("alpha + 16#FF * (b)")
    assert span(a) == (1, 6, 1, 25)
    assert span(a.left) == (1, 6, 1, 11)
    assert span(a.right) == (1, 14, 1, 25)
    assert span(a.right.left) == (1, 14, 1, 19)
    call = expr("f(1,\n  x := 2)")
    assert span(call) == (1, 6, 2, 10)
    assert span(call.args[1]) == (2, 3, 2, 9)


def test_invalid_literals_are_located():
    diags = errors("x := T#5x + 2#102 + D#2024-13-01 + 'a$Qb' + 16#_1;")
    assert [(d.code, d.pos.col) for d in diags] == [("E003", 6), ("E003", 13), ("E003", 21), ("E003", 36), ("E003", 45)]
    assert "digit '2' is not valid in base 2" in diags[1].message


# ---------------------------------------------------------------- argument lists


def test_a_trailing_comma_is_read_and_kept_where_it_is():
    # The parser takes F(a := 1,) in every profile and notes the comma; the
    # checker decides by the profile (checker_base.trailing_comma).
    [stmt] = body("x := f(a := 1, b := 2 ,);")
    assert show(stmt.value) == "f(a := 1, b := 2)"
    p = stmt.value.trailing_comma
    assert (p.line, p.col, p.end_line, p.end_col) == (1, 23, 1, 24)
    [stmt] = body("x := f(a := 1, b := 2);")
    assert stmt.value.trailing_comma is None


@pytest.mark.parametrize("text", ["x := f(,);", "x := f(1,,);", "x := f(1,, 2);"])
def test_a_comma_alone_or_twice_is_still_a_syntax_error(text):
    assert [d.code for d in errors(text)][:1] == ["E001"]
