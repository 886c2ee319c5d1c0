"""IL bodies in .st files, continued (runtime/st/syntax/il*.py): calls of
functions and function blocks in every form, jumps, returns, the current
result across a label (POUs and actions written in IL, IL in textual SFC:
test_il_pous.py)."""

from __future__ import annotations

import pytest

from softplc.runtime.program import check_files

from .il_helpers import twins, varies

CALLS_IL = """
FUNCTION Twice : INT
VAR_INPUT v : INT; END_VAR
LD v
MUL 2
ST Twice
END_FUNCTION

PROGRAM Main
VAR
    n : INT;
    big, lim, dbl, cv, chosen : INT;
    r : REAL;
    ok : BOOL;
END_VAR
LD n
ADD 1
ST n
LD n
MAX 4
MIN 9
ST big
LIMIT(
    MN := 2,
    IN := n,
    MX := 6
)
ST lim
LD n
Twice
Twice
ST dbl
LD n
INT_TO_REAL
DIV 4.0
ST r
REAL_TO_INT
ST cv
LD n
GT 5
SEL 10, 20
ST chosen
LD n
MOD 2
EQ 0
ST ok
END_PROGRAM
"""

CALLS_ST = """
FUNCTION Twice : INT
VAR_INPUT v : INT; END_VAR
Twice := v * 2;
END_FUNCTION

PROGRAM Main
VAR
    n : INT;
    big, lim, dbl, cv, chosen : INT;
    r : REAL;
    ok : BOOL;
END_VAR
n := n + 1;
big := MIN(MAX(n, 4), 9);
lim := LIMIT(MN := 2, IN := n, MX := 6);
dbl := Twice(Twice(n));
r := INT_TO_REAL(n) / 4.0;
cv := REAL_TO_INT(r);
chosen := SEL(n > 5, 10, 20);
ok := n MOD 2 = 0;
END_PROGRAM
"""


def test_function_calls_take_the_current_result_first():
    rows = twins(CALLS_IL, CALLS_ST, ["big", "lim", "dbl", "cv", "chosen", "ok", "r"], cycles=11)
    assert [r["lim"] for r in rows][:7] == [2, 2, 3, 4, 5, 6, 6]
    assert rows[2]["dbl"] == 12 and rows[0]["chosen"] == 10 and rows[9]["chosen"] == 20


FBS_HEAD = """
FUNCTION_BLOCK Acc
VAR_INPUT step : INT; END_VAR
VAR_OUTPUT total : INT; END_VAR
{acc}
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    n : INT;
    trig : R_TRIG;
    ctr : CTU;
    tmr : TON;
    ff : SR;
    rs1 : RS;
    acc : Acc;
    edges, q, done, ffq, rsq, big : BOOL;
    cv, total, m : INT;
    et : TIME;
END_VAR
"""

FBS_IL = (
    FBS_HEAD.format(acc="LD total\nADD step\nST total")
    + """
LD n
ADD 1
ST n
MOD 3
EQ 0
CLK trig
LD trig.Q
ST edges
LD 3
PV ctr
LD edges
CU ctr
LD ctr.CV
ST cv
LD n
GT 3
ST q
IN tmr
LD T#30ms
PT tmr
LD tmr.Q
ST done
LD tmr.ET
ST et
LD n
GE 4
S1 ff
LD n
GE 8
R ff
LD ff.Q1
ST ffq
LD n
EQ 2
S rs1
LD n
EQ 6
R1 rs1
LD rs1.Q1
ST rsq
CAL acc(step := n)
LD acc.total
ST total
LD 2
ST acc.step
LD n
GT 5
CALC acc
LD n
LE 5
CALCN acc(step := 100)
LD acc.total
MAX total, 10
ST m
GT 40
ST big
END_PROGRAM
"""
)

FBS_ST = (
    FBS_HEAD.format(acc="total := total + step;")
    + """
n := n + 1;
trig(CLK := n MOD 3 = 0);
edges := trig.Q;
ctr(PV := 3);
ctr(CU := edges);
cv := ctr.CV;
q := n > 3;
tmr(IN := q);
tmr(PT := T#30ms);
done := tmr.Q;
et := tmr.ET;
ff(S1 := n >= 4);
ff(R := n >= 8);
ffq := ff.Q1;
rs1(S := n = 2);
rs1(R1 := n = 6);
rsq := rs1.Q1;
acc(step := n);
total := acc.total;
acc.step := 2;
IF n > 5 THEN acc(); END_IF;
IF NOT (n <= 5) THEN acc(step := 100); END_IF;
m := MAX(acc.total, total, 10);
big := m > 40;
END_PROGRAM
"""
)


def test_function_block_calls_in_every_form():
    names = ["edges", "cv", "ctr.Q", "done", "et", "ffq", "rsq", "total", "acc.total", "m", "big"]
    rows = twins(FBS_IL, FBS_ST, names, cycles=12)
    for name in ("edges", "done", "ffq", "rsq", "big"):
        assert varies(rows, name) == {"True", "False"}, name
    assert rows[-1]["cv"] == 4 and rows[-1]["ctr.Q"] is True  # edges at n = 3, 6, 9, 12


# ---------------------------------------------------------------- jumps and returns

JUMPS_IL = """
FUNCTION Clamp : INT
VAR_INPUT v, lo, hi : INT; END_VAR
    LD v
    ST Clamp
    LT lo
    JMPCN notlow
    LD lo
    ST Clamp
    RET
notlow:
    LD v
    GT hi
    RETCN
    LD hi
    ST Clamp
END_FUNCTION

FUNCTION SumTo : DINT
VAR_INPUT n : INT; END_VAR
VAR i : INT; END_VAR
    LD 0
    ST SumTo
    ST i
again: LD i
    GE n
    RETC
    LD i
    ADD 1
    ST i
    ADD SumTo
    ST SumTo
    JMP again
END_FUNCTION

PROGRAM Main
VAR
    n : INT;
    out, c : INT;
    s : DINT;
    k : INT;
END_VAR
    LD n
    ADD 1
    ST n
    GT 5
    JMPC big
    LD n
    MUL 10
    JMP store
big: LD -1
store: ST out
    LD n
    Clamp 2, 4
    ST c
    LD n
    SumTo
    ST s
    LD 0
    ST k
count:
    LD k
    ADD 1
    ST k
    LT n
    JMPC count
END_PROGRAM
"""

JUMPS_ST = """
FUNCTION Clamp : INT
VAR_INPUT v, lo, hi : INT; END_VAR
Clamp := LIMIT(lo, v, hi);
END_FUNCTION

FUNCTION SumTo : DINT
VAR_INPUT n : INT; END_VAR
VAR i : INT; END_VAR
SumTo := 0;
FOR i := 1 TO n DO SumTo := SumTo + i; END_FOR;
END_FUNCTION

PROGRAM Main
VAR
    n : INT;
    out, c : INT;
    s : DINT;
    k : INT;
END_VAR
n := n + 1;
IF n > 5 THEN out := -1; ELSE out := n * 10; END_IF;
c := Clamp(n, 2, 4);
s := SumTo(n);
k := 0;
REPEAT k := k + 1; UNTIL k >= n END_REPEAT;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "matiec", "iec"])
def test_jumps_forward_and_backward_and_returns(profile):
    """Loops that terminate, conditional returns; and JMP, which ST has not
    in iec and matiec, is IL's own there (SourceFile.lowered)."""
    rows = twins(JUMPS_IL, JUMPS_ST, ["out", "c", "s", "k"], cycles=8, profile=profile)
    assert [r["out"] for r in rows][:6] == [10, 20, 30, 40, 50, -1]
    assert rows[-1]["s"] == 36 and rows[-1]["k"] == 8 and [r["c"] for r in rows][:5] == [2, 2, 3, 4, 4]


def test_jmp_in_st_is_still_refused_in_iec():
    src = "PROGRAM Main\nVAR n : INT; END_VAR\nagain: n := n + 1;\nIF n < 3 THEN JMP again; END_IF;\nEND_PROGRAM\n"
    diags, _ = check_files([], "iec", texts={"main.st": src})
    assert [d.code for d in diags if d.is_error] == ["E159"]


# The current result crosses a label (Beremiz's example counter, and the
# stack of IEC 61131-3 Annex F): the code after the label, ending in ST, is
# written on each way in.
CROSS_IL = """
FUNCTION_BLOCK Counter
VAR_INPUT Reset : BOOL; END_VAR
VAR_OUTPUT Out : INT; END_VAR
VAR Cnt : INT; Start : INT := 7; END_VAR
LD Reset
JMPC reset_it
LD Cnt
ADD 1
JMP done
reset_it:
LD Start
done:
ST Cnt
ST Out
END_FUNCTION_BLOCK

FUNCTION_BLOCK Pick
VAR_INPUT sel : INT; END_VAR
VAR_OUTPUT v : INT; flag : BOOL; END_VAR
LD sel
EQ 1
JMPC one
LD sel
EQ 2
JMPCN other
LD 20
JMP out
one: LD 10
JMP out
other: LD sel
MUL 100
out: ADD 1
ST v
LD sel
GT 1
JMPC yes
LD FALSE
JMP set
yes: LD TRUE
set: ST flag
END_FUNCTION_BLOCK

PROGRAM Main
VAR n : INT; c : Counter; p : Pick; cv, pv : INT; pf : BOOL; END_VAR
LD n
ADD 1
ST n
EQ 5
ST c.Reset
CAL c
LD c.Out
ST cv
LD n
MOD 4
ST p.sel
CAL p
LD p.v
ST pv
LD p.flag
ST pf
END_PROGRAM
"""

CROSS_ST = """
FUNCTION_BLOCK Counter
VAR_INPUT Reset : BOOL; END_VAR
VAR_OUTPUT Out : INT; END_VAR
VAR Cnt : INT; Start : INT := 7; END_VAR
IF Reset THEN Cnt := Start; ELSE Cnt := Cnt + 1; END_IF;
Out := Cnt;
END_FUNCTION_BLOCK

FUNCTION_BLOCK Pick
VAR_INPUT sel : INT; END_VAR
VAR_OUTPUT v : INT; flag : BOOL; END_VAR
CASE sel OF
    1: v := 11;
    2: v := 21;
ELSE
    v := sel * 100 + 1;
END_CASE;
flag := sel > 1;
END_FUNCTION_BLOCK

PROGRAM Main
VAR n : INT; c : Counter; p : Pick; cv, pv : INT; pf : BOOL; END_VAR
n := n + 1;
c.Reset := n = 5;
c();
cv := c.Out;
p.sel := n MOD 4;
p();
pv := p.v;
pf := p.flag;
END_PROGRAM
"""


def test_the_current_result_crosses_a_label_into_code_ending_with_st():
    rows = twins(CROSS_IL, CROSS_ST, ["cv", "pv", "pf"], cycles=9)
    assert [r["cv"] for r in rows] == [1, 2, 3, 4, 7, 8, 9, 10, 11]
    assert [r["pv"] for r in rows][:4] == [11, 21, 301, 1]
