"""The ST parser: source text -> ast.SourceFile, with positions, and coded
diagnostics instead of exceptions."""
from __future__ import annotations

import random
import threading
from pathlib import Path

import pytest

from softplc.runtime.st import ast
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.parser import MAX_ERRORS, parse_source

REPO = Path(__file__).resolve().parents[2]


# ---------------------------------------------------------------- helpers

def parse(text: str, path: str = "test.st"):
    diags = DiagnosticBag()
    sf = parse_source(text, path, diags)
    return sf, diags.items


def ok(text: str, path: str = "test.st") -> ast.SourceFile:
    sf, diags = parse(text, path)
    assert not [d for d in diags if d.is_error], "\n".join(d.format() for d in diags)
    return sf


def body(text: str) -> list:
    """The statements of a file of bare statements."""
    [pou] = ok(text).decls
    return pou.body


def expr(text: str):
    [stmt] = body(f"x := {text};")
    return stmt.value


def errors(text: str) -> list:
    return [d for d in parse(text)[1] if d.is_error]


def show(e) -> str:
    """A compact, unambiguous rendering of an expression."""
    if isinstance(e, ast.Binary):
        return f"({e.op} {show(e.left)} {show(e.right)})"
    if isinstance(e, ast.Unary):
        return f"({e.op} {show(e.operand)})"
    if isinstance(e, ast.Name):
        return e.name
    if isinstance(e, ast.Literal):
        return repr(e.value)
    if isinstance(e, ast.Member):
        return f"{show(e.base)}.{e.name}"
    if isinstance(e, ast.BitAccess):
        return f"{show(e.base)}.%X{show(e.bit)}"
    if isinstance(e, ast.Index):
        return f"{show(e.base)}[{', '.join(show(i) for i in e.indices)}]"
    if isinstance(e, ast.Deref):
        return f"{show(e.base)}^"
    if isinstance(e, ast.Call):
        return f"{show(e.callee)}({', '.join(show(a) for a in e.args)})"
    if isinstance(e, ast.Arg):
        value = "" if e.value is None else show(e.value)
        if e.name is None:
            return value
        return f"{'NOT ' if e.negated else ''}{e.name}{' => ' if e.output else ' := '}{value}".rstrip()
    if isinstance(e, ast.Located):
        return e.addr.text
    if isinstance(e, ast.EnumLiteral):
        return f"{e.type_name}#{e.value_name}"
    if isinstance(e, ast.SchneiderAddress):
        return "ADR#" + ".".join(e.parts)
    if isinstance(e, ast.CaseRange):
        return f"{show(e.lo)}..{show(e.hi)}"
    raise AssertionError(f"no rendering for {e!r}")


def span(node) -> tuple:
    p = node.pos
    return p.line, p.col, p.end_line, p.end_col


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


def test_pragmas_attach_to_the_item_that_follows():
    sf = ok("""{attribute 'qualified_only'}
VAR_GLOBAL
    {attribute 'hide'} g : INT;
END_VAR
TYPE
    {attribute 'strict'} Color : (Red, Green);
END_TYPE
{attribute 'call_after_init'}
FUNCTION_BLOCK Fb
{attribute 'header'}
VAR x : INT; END_VAR
{warning 'check this'}
x := 1;
{text after everything}
END_FUNCTION_BLOCK
""")
    gvl, color, fb = sf.decls
    assert gvl.pragmas == ["attribute 'qualified_only'"]
    assert gvl.decls[0].pragmas == ["attribute 'hide'"]
    assert color.pragmas == ["attribute 'strict'"]
    assert fb.pragmas == ["attribute 'call_after_init'", "attribute 'header'"]
    assert fb.body[0].pragmas == ["warning 'check this'"]
    assert not fb.external


def test_external_pragma_marks_a_declaration_only_pou():
    sf = ok("""{external}
FUNCTION_BLOCK NativeFb
VAR_INPUT IN : BOOL; END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
END_FUNCTION_BLOCK
FUNCTION Native : INT
{external}
VAR_INPUT a : INT; END_VAR
END_FUNCTION
FUNCTION_BLOCK Empty
END_FUNCTION_BLOCK
""")
    fb, fn, empty = sf.decls
    assert fb.external and fb.body == [] and fb.pragmas == ["external"]
    assert fn.external and fn.body == []
    assert not empty.external and empty.body == [] and empty.var_blocks == []


# ---------------------------------------------------------------- literals in the AST

@pytest.mark.parametrize("text, kind, value, type_name", [
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
])
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

@pytest.mark.parametrize("text, area, size, indices, bit, table", [
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
])
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

@pytest.mark.parametrize("text, tree", [
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
])
def test_precedence(text, tree):
    assert show(expr(text)) == tree


@pytest.mark.parametrize("text, tree", [
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
])
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
    assert labels == [["1", "2"], ["3..5", "(- 7)", "(- 10)..(- 8)"], ["Color#Red", "Green"],
                      ["Color.Blue", "MAX_VAL..(+ MAX_VAL 1)"], ["16", "(+ N 1)"], ["True"]]
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


# ---------------------------------------------------------------- declarations

def test_var_blocks_and_qualifiers():
    [pou] = ok("""FUNCTION_BLOCK Fb
VAR_INPUT a, b, c : INT := 0; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
VAR_IN_OUT io : ARRAY[*] OF INT; END_VAR
VAR RETAIN PERSISTENT r : DINT; END_VAR
VAR PERSISTENT p : DINT; END_VAR
VAR CONSTANT k : INT := 3; END_VAR
VAR_TEMP t : INT; END_VAR
VAR_STAT s : INT; END_VAR
VAR_EXTERNAL e : INT; END_VAR
VAR_GLOBAL g : INT; END_VAR
VAR NON_RETAIN n : INT; END_VAR
END_FUNCTION_BLOCK""").decls
    kinds = [(b.kind, b.constant, b.retain, b.persistent) for b in pou.var_blocks]
    assert kinds == [("VAR_INPUT", False, False, False), ("VAR_OUTPUT", False, False, False),
                     ("VAR_IN_OUT", False, False, False), ("VAR", False, True, True),
                     ("VAR", False, False, True), ("VAR", True, False, False), ("VAR_TEMP", False, False, False),
                     ("VAR_STAT", False, False, False), ("VAR_EXTERNAL", False, False, False),
                     ("VAR_GLOBAL", False, False, False), ("VAR", False, False, False)]
    a, b, c = pou.var_blocks[0].decls
    assert [d.name for d in (a, b, c)] == ["a", "b", "c"]
    assert all(d.init.value == 0 for d in (a, b, c))
    assert a.type is b.type  # one type node shared by the names of one declaration
    assert span(b) == (2, 14, 2, 29)
    assert pou.var_blocks[2].decls[0].type.ranges == [None]


def test_located_variables():
    [pou] = ok("""PROGRAM p
VAR
    start AT %IX0.0 : BOOL;
    AT %QW1 : WORD;
    AT %MW3250:X0 : BOOL;
    word AT %MW3250 : WORD := 16#00FF;
END_VAR
END_PROGRAM""").decls
    start, unnamed, bit, word = pou.var_blocks[0].decls
    assert start.location == ast.LocatedAddress("I", "X", (0, 0), None, None, "%IX0.0")
    # An unnamed located variable is named after its address (no identifier has '__').
    assert unnamed.name == "__at_QW1" and unnamed.location.text == "%QW1"
    assert bit.name == "__at_MW3250_X0" and bit.location.bit == 0
    assert word.init.value == 255


def test_types():
    sf = ok("""TYPE
    Color : (Red, Green := 5, Blue) := Green;
    Codes : (A, B) DINT;
    Mode : INT (Off := 0, On := 1);
    Percent : INT(0..100);
    Speed : REAL := 1.0;
    Name : STRING[80];
    Wide : WSTRING(10);
    Short : STRING;
    Point : STRUCT
        x, y : REAL;
        tags : ARRAY[1..N + 1, 0..3] OF STRING(20);
        sub : STRUCT_B;
    END_STRUCT;
    Grid : ARRAY[1..2] OF ARRAY[-1..1] OF Point;
    PInt : REF_TO INT;
    Raw : POINTER TO BYTE;
    Plain : STRUCT a : INT; END_STRUCT
END_TYPE""")
    t = {d.name: d for d in sf.decls}
    assert len(sf.decls) == 13
    color = t["Color"]
    assert [(n, v.value if v else None) for n, v, _ in color.spec.values] == [("Red", None), ("Green", 5), ("Blue", None)]
    assert color.spec.base is None and show(color.init) == "Green"
    assert t["Codes"].spec.base.name == "DINT" and [v[0] for v in t["Codes"].spec.values] == ["A", "B"]
    assert t["Mode"].spec.base.name == "INT" and [v[1].value for v in t["Mode"].spec.values] == [0, 1]
    pct = t["Percent"].spec
    assert isinstance(pct, ast.SubrangeTypeSpec) and (pct.base.name, pct.lo.value, pct.hi.value) == ("INT", 0, 100)
    assert isinstance(t["Speed"].spec, ast.NamedType) and t["Speed"].init.value == 1.0
    assert (t["Name"].spec.wide, t["Name"].spec.length.value) == (False, 80)
    assert (t["Wide"].spec.wide, t["Wide"].spec.length.value) == (True, 10)
    assert t["Short"].spec.length is None
    point = t["Point"].spec
    assert [m.name for m in point.members] == ["x", "y", "tags", "sub"]
    tags = point.members[2].type
    assert [(show(lo), show(hi)) for lo, hi in tags.ranges] == [("1", "(+ N 1)"), ("0", "3")]
    assert tags.elem.length.value == 20
    grid = t["Grid"].spec
    assert isinstance(grid.elem, ast.ArrayTypeSpec) and show(grid.elem.ranges[0][0]) == "(- 1)"
    assert grid.elem.elem.name == "Point"
    assert isinstance(t["PInt"].spec, ast.RefTypeSpec) and not t["PInt"].spec.pointer
    assert t["PInt"].spec.target.name == "INT"
    assert t["Raw"].spec.pointer and t["Raw"].spec.target.name == "BYTE"


def test_initialisers():
    [pou] = ok("""PROGRAM p
VAR
    a : ARRAY[1..5] OF INT := [1, 2, 3(0)];
    b : ARRAY[1..10] OF REAL := [10(1.5)];
    c : ARRAY[1..3] OF INT := [2(), 7];
    d : Point := (x := 1.0, y := -2.0);
    e : Line := (p1 := (x := 1), tags := [1, 2], name := 'n');
    f : ARRAY[1..2] OF Point := [(x := 1), (x := 2)];
    g : ARRAY[1..2, 1..2] OF INT := [[1, 2], [3, 4]];
    h : INT := (1 + 2) * 3;
    i : Color := Color#Red;
END_VAR
END_PROGRAM""").decls
    d = {v.name: v.init for v in pou.var_blocks[0].decls}
    assert [(c and c.value, show(v)) for c, v in d["a"].items] == [(None, "1"), (None, "2"), (3, "0")]
    assert [(c.value, v.value) for c, v in d["b"].items] == [(10, 1.5)]
    assert d["c"].items[0][0].value == 2 and d["c"].items[0][1] is None
    assert [(n, show(v)) for n, v, _ in d["d"].fields] == [("x", "1.0"), ("y", "(- 2.0)")]
    e = d["e"].fields
    assert isinstance(e[0][1], ast.StructInit) and isinstance(e[1][1], ast.ArrayInit)
    assert all(isinstance(v, ast.StructInit) for _, v in d["f"].items)
    assert all(isinstance(v, ast.ArrayInit) for _, v in d["g"].items)
    assert show(d["h"]) == "(* (+ 1 2) 3)"
    assert show(d["i"]) == "Color#Red"
    assert span(d["d"]) == (6, 18, 6, 39)


def test_pous():
    sf = ok("""FUNCTION Add : INT
VAR_INPUT a, b : INT; END_VAR
Add := a + b;
END_FUNCTION
FUNCTION NoResult
VAR_INPUT a : INT; END_VAR
;
END_FUNCTION
FUNCTION Text : STRING[20]
Text := 'x';
END_FUNCTION
FUNCTION_BLOCK Timer
VAR_INPUT IN : BOOL; END_VAR
END_FUNCTION_BLOCK
PROGRAM Main
VAR t : Timer; END_VAR
t(IN := TRUE);
END_PROGRAM;
""")
    add, noresult, text, timer, main = sf.decls
    assert (add.kind, add.name, add.return_type.name) == ("FUNCTION", "Add", "INT")
    assert noresult.return_type is None and noresult.body == []
    assert text.return_type.length.value == 20
    assert (timer.kind, main.kind) == ("FUNCTION_BLOCK", "PROGRAM")
    assert span(add) == (1, 1, 4, 13)
    assert span(main) == (15, 1, 18, 12)


def test_extends_and_implements_are_parsed_and_ignored_with_a_warning():
    sf, diags = parse("FUNCTION_BLOCK B EXTENDS A IMPLEMENTS I1, Lib.I2\nVAR x : INT; END_VAR\nEND_FUNCTION_BLOCK")
    [fb] = sf.decls
    assert fb.name == "B" and len(fb.var_blocks) == 1
    assert [(d.code, d.severity) for d in diags] == [("W101", "warning"), ("W101", "warning")]


def test_global_variable_lists_and_type_blocks_stand_alone():
    sf = ok("VAR_GLOBAL CONSTANT N : INT := 10; END_VAR\nVAR_GLOBAL x : INT; END_VAR\nTYPE T : INT; END_TYPE\n")
    g1, g2, t = sf.decls
    assert isinstance(g1, ast.VarBlock) and g1.kind == "VAR_GLOBAL" and g1.constant
    assert isinstance(g2, ast.VarBlock) and isinstance(t, ast.TypeDecl)
    sf, diags = parse("VAR x : INT; END_VAR\nVAR_CONFIG a.b AT %QX0.0 : BOOL; END_VAR\nTYPE T : INT; END_TYPE")
    assert [(d.code, d.pos.line) for d in diags] == [("E005", 1), ("E005", 2)]
    assert "outside a POU" in diags[0].message
    # Reported and left out: later stages only see what can stand.
    assert [type(x) for x in sf.decls] == [ast.TypeDecl]


def test_qualified_names_only_in_var_config():
    sf = ok("CONFIGURATION c\nVAR_CONFIG inst.x AT %QX1.0 : BOOL; END_VAR\nEND_CONFIGURATION")
    assert sf.decls[0].var_blocks[0].decls[0].name == "inst.x"
    sf, [d] = parse("PROGRAM p VAR a.b : INT; c : INT; END_VAR END_PROGRAM")
    assert d.code == "E005" and "'a.b'" in d.message
    assert [v.name for v in sf.decls[0].var_blocks[0].decls] == ["c"]
    sf, [d] = parse("TYPE S : STRUCT a.b : INT; c : INT; END_STRUCT END_TYPE")
    assert d.code == "E005" and [m.name for m in sf.decls[0].spec.members] == ["c"]


def test_configuration():
    sf = ok("""CONFIGURATION Plant
    VAR_GLOBAL speed : REAL; END_VAR
    RESOURCE Cpu ON PLC
        TASK Fast(INTERVAL := T#10ms, PRIORITY := 1);
        TASK Slow (interval := T#100ms, PRIORITY := 5, SINGLE := trigger);
        PROGRAM Line1 WITH Fast : Conveyor(Speed := speed, Done => ok);
        PROGRAM RETAIN Log : Logger;
    END_RESOURCE
    RESOURCE Spare
        PROGRAM Idle WITH Slow : Nothing;
    END_RESOURCE
END_CONFIGURATION
CONFIGURATION Small
    TASK T1(INTERVAL := T#1s);
    PROGRAM P WITH T1 : Main;
END_CONFIGURATION""")
    plant, small = sf.decls
    assert plant.name == "Plant" and plant.var_blocks[0].decls[0].name == "speed"
    cpu, spare = plant.resources
    assert (cpu.name, cpu.on, spare.on) == ("Cpu", "PLC", None)
    fast, slow = cpu.tasks
    assert fast.name == "Fast" and fast.params["INTERVAL"].value == 10_000_000 and fast.params["PRIORITY"].value == 1
    assert set(slow.params) == {"INTERVAL", "PRIORITY", "SINGLE"}
    line1, log = cpu.programs
    assert (line1.name, line1.task, line1.type_name, line1.retain) == ("Line1", "Fast", "Conveyor", False)
    assert [show(a) for a in line1.args] == ["Speed := speed", "Done => ok"]
    assert (log.name, log.task, log.type_name, log.retain, log.args) == ("Log", None, "Logger", True, [])
    # Without RESOURCE: one implicit resource named after the configuration.
    [res] = small.resources
    assert (res.name, res.on, [t.name for t in res.tasks], [p.name for p in res.programs]) == \
        ("Small", None, ["T1"], ["P"])


# ---------------------------------------------------------------- files of bare statements

@pytest.mark.parametrize("path, name", [
    ("ltmr/write_sdo.st", "write_sdo"), ("write-sdo.st", "write_sdo"), ("000 first.st", "_000_first"),
    ("<string>", "string"), ("---.st", "main"),
])
def test_bare_statements_become_a_program_named_after_the_file(path, name):
    sf = ok("x := 1;\ny := 2;", path)
    [pou] = sf.decls
    assert (pou.kind, pou.name, len(pou.body)) == ("PROGRAM", name, 2)
    assert span(pou) == (1, 1, 2, 7)


def _check_sdo_program(sf: ast.SourceFile, name: str, md: int, mw_value: int, mw_table: int, m_cmd: int,
                       call: str):
    [pou] = sf.decls
    assert (pou.kind, pou.name, pou.var_blocks) == ("PROGRAM", name, [])
    *first, cond_if = pou.body
    assert isinstance(first[0], ast.Assign) and show(first[0].target) == f"%MD{md}"
    assert first[0].value.c_hex and first[0].value.kind == "int"
    [(cond, stmts)] = cond_if.branches
    assert show(cond) == f"(AND %M{m_cmd} (NOT %MW{mw_table}:X0))"
    assert cond.right.operand.addr.bit == 0 and cond.right.operand.addr.indices == (mw_table,)
    timeout, call_stmt, reset = stmts
    assert show(timeout.target) == f"%MW{mw_table + 3}" and timeout.value.value == 2
    c = call_stmt.call
    assert show(c.callee) == call and len(c.args) == 6
    assert all(a.name is None and not a.output for a in c.args)
    adr, sdo, var, node, value, table = (a.value for a in c.args)
    assert isinstance(adr, ast.SchneiderAddress) and adr.parts == ("0", "1", "SYS")
    assert (sdo.kind, sdo.value) == ("string", "SDO")
    assert var.addr == ast.LocatedAddress("M", "D", (md,), None, None, f"%MD{md}")
    assert (node.kind, node.value) == ("int", 40)
    assert value.addr == ast.LocatedAddress("M", "W", (mw_value,), None, 1, f"%MW{mw_value}:1")
    assert table.addr == ast.LocatedAddress("M", "W", (mw_table,), None, 4, f"%MW{mw_table}:4")
    assert isinstance(reset, ast.SetReset) and reset.kind == "RESET" and show(reset.target) == f"%M{m_cmd}"
    assert cond_if.else_body is None


def test_ltmr_write_sdo_example_verbatim():
    path = REPO / "st_programs" / "ltmr_write_sdo.st"
    sf = ok(path.read_text(encoding="utf-8"), str(path))
    _check_sdo_program(sf, "ltmr_write_sdo", 3200, 3202, 3250, 100, "WRITE_VAR")
    [pou] = sf.decls
    assert pou.body[0].value.value == 0x00032007
    assert show(pou.body[1].target) == "%MW3202" and pou.body[1].value.value == 50
    assert span(pou.body[2]) == (12, 1, 16, 7)  # the IF, from IF to END_IF


def test_ltmr_read_sdo_example_verbatim():
    path = REPO / "st_programs" / "ltmr_read_sdo.st"
    sf = ok(path.read_text(encoding="utf-8"), str(path))
    _check_sdo_program(sf, "ltmr_read_sdo", 3220, 3222, 3260, 101, "READ_VAR")
    assert sf.decls[0].body[0].value.value == 0x00032004


def test_the_fixtures_are_the_manual_text():
    manual = (REPO.parent / "shared" / "manuals" / "000_97161f374cfc3d02.txt")
    if not manual.exists():
        pytest.skip("the manuals are not beside the project")
    lines = manual.read_text(encoding="utf-8").splitlines(keepends=True)
    assert "".join(lines[997:1013]) == (REPO / "st_programs" / "ltmr_write_sdo.st").read_text(encoding="utf-8")
    assert "".join(lines[1020:1035]) == (REPO / "st_programs" / "ltmr_read_sdo.st").read_text(encoding="utf-8")


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
    sf, [d] = parse("PROGRAM a\nx := 1;\nEND_PROGRAM\ngarbage here; more := garbage;\n"
                    "x := 1;\nFUNCTION f : INT\nf := 1;\nEND_FUNCTION\n")
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


def test_jumps_and_labels_are_refused_clearly():
    diags = errors("x := 1;\nJMP done;\ndone: x := 2;\n")
    assert [(d.code, d.pos.line) for d in diags] == [("E001", 2), ("E001", 3)]
    assert all(d.hint == "JMP and labels are not supported; use a loop or CASE" for d in diags)


def test_misspelt_keyword_gets_a_suggestion():
    [d] = errors("IF a THEN x := 1;\nELSEIF b THEN x := 2;\nEND_IF")
    assert d.hint == "did you mean ELSIF?"
    [d] = errors("FUNCTION_BLOCK f\nVAR_INPUTS x : INT; END_VAR\nEND_FUNCTION_BLOCK")
    assert d.hint == "did you mean VAR_INPUT?"


def test_methods_are_refused_and_skipped():
    sf, [d] = parse("FUNCTION_BLOCK f\nMETHOD m : INT\nm := 1;\nEND_METHOD\nEND_FUNCTION_BLOCK\n")
    assert d.code == "E001" and d.message == "METHOD: methods are not supported" and d.pos.line == 2
    assert sf.decls[0].name == "f"


def test_an_expression_alone_is_not_a_statement():
    [d] = errors("x;")
    assert d.code == "E001" and "not a statement" in d.message


def test_missing_brackets_and_commas():
    diags = errors("x := (1 + 2;\ny := f(a b);\nz := a[1;\n")
    assert [d.message for d in diags] == ["missing ')' before ';'", "missing ',' before 'b'", "missing ']' before ';'"]


def test_lexical_errors():
    diags = errors("x := 1 § 2;\nw := größe;\ns := 'open\nt := 5;\n")
    assert [(d.code, d.pos.line, d.pos.col) for d in diags] == [("E002", 1, 8), ("E002", 2, 8), ("E004", 3, 6)]
    assert diags[1].hint == "identifiers may only use ASCII letters, digits and '_'"
    [d] = errors("x := %Z1;")
    assert d.code == "E002" and d.message == "invalid direct address"


@pytest.mark.parametrize("src, line, col, what", [
    ("x := 1;\n(* open (* nested *)\ny := 2;", 2, 1, "'(*' is never closed"),
    ("x := 1; /* open", 1, 9, "'/*' is never closed"),
    ("{attribute 'x'\nx := 1;", 1, 1, "'{' is never closed"),
])
def test_unterminated_comments_and_pragmas(src, line, col, what):
    [d] = errors(src)
    assert (d.code, d.pos.line, d.pos.col) == ("E004", line, col) and what in d.message


def test_stray_comment_close():
    [d] = errors("x := 1; *) y := 2;")
    assert (d.code, d.pos.col) == ("E001", 9) and "'*)'" in d.message


def test_invalid_literals_are_located():
    diags = errors("x := T#5x + 2#102 + D#2024-13-01 + 'a$Qb' + 16#_1;")
    assert [(d.code, d.pos.col) for d in diags] == [("E003", 6), ("E003", 13), ("E003", 21), ("E003", 36),
                                                    ("E003", 45)]
    assert "digit '2' is not valid in base 2" in diags[1].message


def test_too_many_errors_stop_the_parse():
    sf, diags = parse("x := ;\n" * (MAX_ERRORS + 50))
    assert len(diags) == MAX_ERRORS + 1 and "too many errors" in diags[-1].message
    assert sf.decls == []


def test_error_positions_point_into_the_text():
    src = "PROGRAM p\nVAR x : INT; END_VAR\nx := (1 + ;\nIF x THEN\nEND_PROGRAM"
    for d in errors(src):
        lines = src.split("\n")
        assert 1 <= d.pos.line <= len(lines) and 1 <= d.pos.col <= len(lines[d.pos.line - 1]) + 1


# ---------------------------------------------------------------- hostile input

@pytest.mark.parametrize("src", [
    "", " \n\t ", "\x00" * 100, "x := 1;\x00", "\ufeffPROGRAM p END_PROGRAM", "(*", "*)", "'", '"', "{", "}",
    "%", "#", "T#", "16#", "x := \ud800;", "😀" * 50, ")))]]];;;:=:=", "END_IF END_PROGRAM END_VAR",
    "PROGRAM", "IF TRUE THEN " * 200, "[" * 5000, "(" * 10000, "x := " + "(" * 10000 + "1" + ")" * 10000 + ";",
    "x := " + "-" * 10000 + "1;", "x := " + " + ".join(["a"] * 5000) + ";", "x := " + "f(" * 3000 + ")" * 3000,
    "CASE x OF " * 500, "a" * 100_000, "'" + "x" * 100_000, "(* " * 5000 + "*)" * 5000,
])
def test_hostile_input_gives_diagnostics_not_exceptions(src):
    sf, diags = parse(src)
    assert isinstance(sf, ast.SourceFile)
    assert all(d.code[0] in "EW" and d.code != "E009" for d in diags), [d.format() for d in diags]


def test_deep_nesting_is_refused_with_a_diagnostic():
    [d] = errors("x := " + "(" * 10000 + "1" + ")" * 10000 + ";")
    assert d.code == "E005" and d.message == "nesting too deep"
    [d] = errors("x := " + " + ".join(["a"] * 2000) + ";")
    assert d.code == "E005" and "expression too long" in d.message
    ok("x := " + "(" * 50 + "1" + ")" * 50 + ";")  # but reasonable depth is fine
    ok("IF a THEN " * 30 + "x := 1;" + " END_IF" * 30)


def test_random_bytes():
    rng = random.Random(1234)
    for _ in range(200):
        data = bytes(rng.getrandbits(8) for _ in range(rng.randint(1, 400)))
        sf, diags = parse(data.decode("latin-1"))
        assert all(d.code != "E009" for d in diags)


def test_random_token_soup():
    rng = random.Random(99)
    words = ["IF ", "THEN ", "ELSE ", "END_IF", "CASE ", "OF ", "END_CASE", "VAR ", "END_VAR", "PROGRAM ",
             "END_PROGRAM", "FUNCTION_BLOCK ", "FOR ", "TO ", "DO ", "END_FOR", "TYPE ", "STRUCT ", "(*", "*)",
             "x", "1", ":=", ";", ":", "(", ")", "[", "]", ",", ".", "..", "T#1s", "16#F", "%MW1", "'s'",
             " ", "\n", "+", "=", "=>", "^", "#", "SET ", "AT "]
    for _ in range(300):
        src = "".join(rng.choice(words) for _ in range(rng.randint(1, 80)))
        sf, diags = parse(src)
        assert all(d.code != "E009" for d in diags), src


def test_arbitrary_text_property():
    hypothesis = pytest.importorskip("hypothesis")
    from hypothesis import given, settings, strategies as st

    @settings(max_examples=150, deadline=None, derandomize=True, database=None)
    @given(st.text(max_size=300))
    def never_raises(text):
        sf, diags = parse(text)
        assert all(d.code != "E009" for d in diags)

    never_raises()


def test_parses_in_threads_do_not_mix():
    sources = {f"t{i}.st": f"PROGRAM P{i}\nx{i} := {i};\nEND_PROGRAM\n" * 50 for i in range(4)}
    results = {}

    def work(path):
        results[path] = parse(sources[path], path)

    threads = [threading.Thread(target=work, args=(p,)) for p in sources]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for i in range(4):
        sf, diags = results[f"t{i}.st"]
        assert not diags and len(sf.decls) == 50
        assert all(p.name == f"P{i}" and p.pos.file == f"t{i}.st" for p in sf.decls)
