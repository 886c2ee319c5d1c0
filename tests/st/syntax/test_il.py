"""IL bodies in .st files (runtime/st/syntax/il.py, il_parse.py, il_lower.py): each
program written in IL runs, cycle after cycle in virtual time, as the same
logic written by hand in ST: the operators, their modifiers and
parentheses (calls, jumps and the rest: test_il_flow.py)."""

from __future__ import annotations

from softplc.runtime.st.diagnostics import DiagnosticBag

from .il_helpers import twins, varies

BOOL_VARS = """
VAR
    n : INT;
    a, b, c, d : BOOL;
    x1, x2, x3, x4, x5, x6, x7 : BOOL;
END_VAR
"""

BOOL_IL = f"""PROGRAM Main{BOOL_VARS}
LD n
MOD 2
EQ 0
ST a
LD n
MOD 3
EQ 0
ST b
LD n
GT 4
ST c
LDN a
ST d
LD a
AND b
OR( c
ANDN d
)
ST x1
LD a
XOR( b
OR( c
AND d
)
)
STN x2
LD a
ANDN(
LD b
ORN c
)
ST x3
LD a
& b
&N c
ST x4
LD a
XORN b
S x5
LD c
R x5
LD b
NOT
ST x6
ORN a
ST x7
LD n
ADD 1
ST n
END_PROGRAM
"""

BOOL_ST = f"""PROGRAM Main{BOOL_VARS}
a := n MOD 2 = 0;
b := n MOD 3 = 0;
c := n > 4;
d := NOT a;
x1 := (a AND b) OR (c AND NOT d);
x2 := NOT (a XOR (b OR (c AND d)));
x3 := a AND NOT (b OR NOT c);
x4 := a AND b AND NOT c;
IF a XOR NOT b THEN x5 := TRUE; END_IF;
IF c THEN x5 := FALSE; END_IF;
x6 := NOT b;
x7 := x6 OR NOT a;
n := n + 1;
END_PROGRAM
"""


def test_boolean_operators_with_modifiers_and_nested_parentheses():
    names = ["a", "b", "c", "d", "x1", "x2", "x3", "x4", "x5", "x6", "x7"]
    rows = twins(BOOL_IL, BOOL_ST, names, cycles=12)
    assert all(varies(rows, n) == {"True", "False"} for n in names)


ARITH_VARS = """
VAR
    i : INT := 3;
    k1, k2, k3, k4 : INT;
    r : REAL;
    t : TIME;
    w : WORD := 16#F0F0;
    m : WORD;
    c1, c2, c3, c4, c5, c6 : BOOL;
    s : STRING[20];
    li : LINT;
END_VAR
"""

ARITH_IL = f"""PROGRAM Main{ARITH_VARS}
LD i
ADD( 3
MUL 2
)
SUB 1
ST k1
LD i
DIV 2
MOD( 5
SUB 2
)
ST k2
LD -7
MUL INT#2
ADD i
ST k3
LD 2.5
MUL 2
ADD( r
DIV 4.0
)
ST r
LD T#1s
ADD T#500ms
SUB( T#100ms
MUL i
)
ST t
LD w
AND 16#FF00
XOR 2#1010
ST m
LD i
GE 4
ST c1
LD i
LE 6
ST c2
LD i
NE 5
ST c3
LD i
LT( k3
ADD 10
)
ST c4
LD m
EQ 16#F00A
ST c5
LD 'pump'
ST s
LD LINT#1
ST li
LD i
GT 7
JMPC wrap
LD i
ADD 1
ST i
RET
wrap:
LD 3
ST i
LDN c5
ST c6
END_PROGRAM
"""

ARITH_ST = f"""PROGRAM Main{ARITH_VARS}
k1 := i + 3 * 2 - 1;
k2 := (i / 2) MOD (5 - 2);
k3 := -7 * INT#2 + i;
r := 2.5 * 2 + r / 4.0;
t := T#1s + T#500ms - T#100ms * i;
m := (w AND 16#FF00) XOR 2#1010;
c1 := i >= 4;
c2 := i <= 6;
c3 := i <> 5;
c4 := i < k3 + 10;
c5 := m = 16#F00A;
s := 'pump';
li := LINT#1;
IF i > 7 THEN
    i := 3;
    c6 := NOT c5;
ELSE
    i := i + 1;
END_IF;
END_PROGRAM
"""


def test_arithmetic_comparisons_and_typed_literals():
    names = ["i", "k1", "k2", "k3", "r", "t", "m", "c1", "c2", "c3", "c4", "c5", "c6", "s", "li"]
    rows = twins(ARITH_IL, ARITH_ST, names, cycles=10)
    assert rows[0]["k1"] == 3 + 6 - 1 and rows[0]["s"] == "pump"
    assert varies(rows, "c1") == {"True", "False"} and len(varies(rows, "t")) > 3


MORE_VARS = """
VAR
    n : INT;
    a, b, c : BOOL;
    y1, y2, y3, y4, y5, y6, y7, y8, y9 : BOOL;
    k1, k2 : INT;
    down : CTD;
    zero : BOOL;
END_VAR
"""

MORE_IL = f"""PROGRAM Main{MORE_VARS}
LD n
ADD 1
ST n
MOD 2
EQ 1
ST a
LD n
MOD 3
NE 0
ST b
LD n
LT 6
ST c
LD a
ORN( b
XORN c
)
ST y1
LD b
XORN( a
&N c
)
ST y2
LD a
&( b
OR c
)
ST y3
LD c
&N( a
)
ST y4
LD n
MUL( n
SUB 1
)
DIV( 2
)
ST k1
LD 100
DIV( n
ADD 1
)
ST k2
GT( n
MUL 3
)
ST y5
LD k1
GE( k2
)
ST y6
LD k1
EQ( n
MUL 2
)
ST y7
LD k2
NE( 10
)
ST y8
LD n
LE( 4
)
ST y9
LD 4
PV down
LD n
MOD 2
EQ 0
CD down
LD down.Q
ST zero
END_PROGRAM
"""

MORE_ST = f"""PROGRAM Main{MORE_VARS}
n := n + 1;
a := n MOD 2 = 1;
b := n MOD 3 <> 0;
c := n < 6;
y1 := a OR NOT (b XOR NOT c);
y2 := b XOR NOT (a AND NOT c);
y3 := a AND (b OR c);
y4 := c AND NOT a;
k1 := (n * (n - 1)) / 2;
k2 := 100 / (n + 1);
y5 := k2 > n * 3;
y6 := k1 >= k2;
y7 := k1 = n * 2;
y8 := k2 <> 10;
y9 := n <= 4;
down(PV := 4);
down(CD := n MOD 2 = 0);
zero := down.Q;
END_PROGRAM
"""


def test_the_other_parenthesised_forms_and_cd():
    """ORN( XORN( &( &N( MUL( DIV( GT( GE( EQ( NE( LE(, and CD."""
    names = ["y1", "y2", "y3", "y4", "y5", "y6", "y7", "y8", "y9", "k1", "k2", "zero", "down.CV"]
    rows = twins(MORE_IL, MORE_ST, names, cycles=12)
    for name in ("y1", "y2", "y4", "y5", "y6", "y9"):
        assert varies(rows, name) == {"True", "False"}, name
    assert [r["down.CV"] for r in rows][:4] == [0, -1, -1, -2] and rows[4]["k1"] == 10


# ---------------------------------------------------------------- calls


def test_a_file_without_il_is_left_as_it_is():
    from softplc.runtime.st.syntax.il import lower_il
    from softplc.runtime.st.syntax.st_grammar import grammar

    diags = DiagnosticBag()
    text, ranges, where = lower_il(BOOL_ST, "main.st", diags, grammar().lexer)
    assert (text, ranges, where, diags.items) == (BOOL_ST, [], {}, [])
