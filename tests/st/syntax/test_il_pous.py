"""IL bodies in .st files, continued (runtime/st/syntax/il*.py): POUs and
actions written in IL called from ST, IL in textual SFC's transitions and
actions, and ST bodies that only look like IL."""

from __future__ import annotations

import pytest

from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.syntax.parser import parse_source

from .il_helpers import twins, varies

# ---------------------------------------------------------------- POUs in IL called from ST, actions

POUS_IL = """
FUNCTION Scale : REAL
VAR_INPUT raw : INT; gain : REAL; END_VAR
LD raw
INT_TO_REAL
MUL gain
ST Scale
END_FUNCTION

FUNCTION_BLOCK Debounce
VAR_INPUT in_ : BOOL; n : INT := 3; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
VAR count : INT; END_VAR
LD in_
JMPC high
LD 0
ST count
ST q
RET
high:
LD count
ADD 1
ST count
GE n
ST q
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    cycle : INT;
    d : Debounce;
    v : REAL;
    q : BOOL;
    hits : INT;
END_VAR
cycle := cycle + 1;
d(in_ := cycle MOD 6 < 4);
q := d.q;
v := Scale(cycle, 0.5);
Tally();
ACTION Tally:
    LD q
    JMPCN skip
    LD hits
    ADD 1
    ST hits
skip:
END_ACTION
END_PROGRAM
"""

POUS_ST = """
FUNCTION Scale : REAL
VAR_INPUT raw : INT; gain : REAL; END_VAR
Scale := INT_TO_REAL(raw) * gain;
END_FUNCTION

FUNCTION_BLOCK Debounce
VAR_INPUT in_ : BOOL; n : INT := 3; END_VAR
VAR_OUTPUT q : BOOL; END_VAR
VAR count : INT; END_VAR
IF NOT in_ THEN
    count := 0;
    q := FALSE;
    RETURN;
END_IF;
count := count + 1;
q := count >= n;
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    cycle : INT;
    d : Debounce;
    v : REAL;
    q : BOOL;
    hits : INT;
END_VAR
cycle := cycle + 1;
d(in_ := cycle MOD 6 < 4);
q := d.q;
v := Scale(cycle, 0.5);
Tally();
ACTION Tally:
    IF q THEN hits := hits + 1; END_IF;
END_ACTION
END_PROGRAM
"""


def test_a_function_a_function_block_and_an_action_in_il_called_from_st():
    rows = twins(POUS_IL, POUS_ST, ["q", "v", "hits", "d.count"], cycles=14)
    assert [r["q"] for r in rows][:7] == [False, False, True, False, False, False, False]
    assert rows[-1]["hits"] == 4 and rows[3]["v"] == 2.0  # q at cycles 3, 8, 9, 14


# ---------------------------------------------------------------- what stays ST


@pytest.mark.parametrize(
    "body",
    [
        "LD := 5;",  # a variable named like an operator
        "L1: x := 1;",  # a CODESYS label
        "JMP L1;\nL1: x := 2;",  # a CODESYS jump
        "IN := x;",
        "ST(x);",
    ],
)
def test_st_bodies_that_look_like_il_stay_st(body):
    src = f"PROGRAM Main\nVAR LD, IN, x : INT; st : BOOL; END_VAR\n{body}\nEND_PROGRAM\n"
    sf = parse_source(src, "main.st", DiagnosticBag())
    assert sf.lowered == []


# ---------------------------------------------------------------- textual SFC: IL in actions and transitions

SFC_HEAD = """
PROGRAM Main
VAR n, runs : INT; fast : BOOL; END_VAR
INITIAL_STEP Idle: END_STEP
"""
SFC_IL = (
    SFC_HEAD
    + """TRANSITION FROM Idle TO Run :
    LD n
    MOD 3
    EQ 0
    OR( fast
    ANDN fast
    )
END_TRANSITION
STEP Run: Count(N); END_STEP
TRANSITION FROM Run TO Idle:
    LD n
    MOD( 4
    ADD 0
    )
    EQ 3
END_TRANSITION
ACTION Count:
    LD n
    ADD 1
    ST n
    GT 5
    ST fast
    LD runs
    ADD 1
    ST runs
END_ACTION
END_PROGRAM
"""
)
SFC_ST = (
    SFC_HEAD
    + """TRANSITION FROM Idle TO Run := n MOD 3 = 0 OR (fast AND NOT fast); END_TRANSITION
STEP Run: Count(N); END_STEP
TRANSITION FROM Run TO Idle := n MOD 4 = 3; END_TRANSITION
ACTION Count:
    n := n + 1;
    fast := n > 5;
    runs := runs + 1;
END_ACTION
END_PROGRAM
"""
)


def test_il_in_textual_sfc_transitions_and_actions():
    """Beremiz writes an IL transition so: TRANSITION FROM a TO b : IL
    END_TRANSITION, the current result at its end the condition."""
    rows = twins(SFC_IL, SFC_ST, ["n", "runs", "Idle.X", "Run.X", "fast"], cycles=16)
    assert varies(rows, "Idle.X") == {"True", "False"} and rows[-1]["runs"] > 3


def test_two_pieces_never_touch_into_a_comment_opener_or_closer():
    """export-st's text is read again with its comments: '(' then '*' (or
    '*' then ')', '/' then '/') must not touch."""
    from softplc.runtime.st.syntax.il_emit import Layout

    out = Layout(1, 1)
    for text in ("(", "*x", "%I*", ")", "/", "/"):
        out.put(text, 0, 0)
    for s in (out.lines[1], out.plain[1]):
        assert not any(c in s for c in ("(*", "*)", "//")), s
