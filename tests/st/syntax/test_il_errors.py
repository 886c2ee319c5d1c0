"""IL that is wrong: each problem is a coded diagnostic at the IL's line and
column (E190-E198 of st/syntax/il_parse.py and il_lower.py, E002/E004 as in ST),
never a traceback; what the checker and the runtime say about lowered IL
points at the IL too."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.faults import STFault
from softplc.runtime.st.limits import MAX_OPERATORS

HEAD = """PROGRAM Main
VAR
    a, b, c, x, y : BOOL;
    n, k : INT;
    t : TON;
END_VAR
"""
FIRST = HEAD.count("\n") + 1  # the line of the body's first instruction


def diagnostics(body: str, profile: str = "codesys") -> list:
    diags, _ = check_files([], profile, texts={"main.st": HEAD + body + "END_PROGRAM\n"})
    return [(d.code, d.pos.line - FIRST + 1, d.pos.col) for d in diags if d.is_error]


@pytest.mark.parametrize(
    "body, expected",
    [
        # E190: not an operator, an operator with a modifier it does not take, ST in IL
        ("LD a\nIF b\nST a\n", [("E190", 2, 1)]),
        ("LD n\n   5\nST n\n", [("E190", 2, 4)]),
        ("LD n\nADDN 1\nST n\n", [("E190", 2, 1)]),
        ("LD a\nx := b;\n", [("E190", 2, 1)]),
        ("LD n\nLD(\n", [("E190", 2, 3)]),
        # E191: an operand missing
        ("LD n\nADD\nST n\n", [("E191", 2, 1)]),
        ("LD a\n  JMPC\n", [("E191", 2, 3)]),
        ("LD a\nCLK\n", [("E191", 2, 1)]),
        # E192: an operand, or more, where none or one goes
        ("LD a\nNOT b\nST a\n", [("E192", 2, 5)]),
        ("LD a\nRETC x\n", [("E192", 2, 6)]),
        ("LD a, b\nST x\n", [("E192", 1, 5)]),
        ("LD a\nAND( b\n) c\nST x\n", [("E192", 3, 3)]),  # only the reading problem
        # E193: parentheses that do not match
        ("LD a\nAND b\n)\nST x\n", [("E193", 3, 1)]),
        ("LD a\nAND( b\nOR c\nST x\n", [("E193", 2, 1)]),
        ("LD n\nCAL t(IN := a,\n PT := T#1s\n", [("E193", 2, 6)]),
        # E194: the current result undefined where it is read
        ("AND a\nST x\n", [("E194", 1, 1)]),
        ("LD a\nJMP end\nST x\nend: LD b\nST y\n", [("E194", 3, 1)]),
        ("LD a\nJMPC l1\nLD b\nl1:\nS x\n", [("E195", 4, 1)]),
        ("LD a\nJMPC l1\nLD b\nJMP l2\nl1: LD c\nl2: CAL t\nST x\n", [("E194", 7, 1)]),
        ("LD a\nAND(\nOR b\n)\nST x\n", [("E194", 3, 1)]),
        ("LD n\nNOSUCH 1\n", []),  # a function call: the checker's (E041-ish) below
        # E196: not inside parentheses
        ("LD a\nAND( b\nS x\n)\nST x\n", [("E196", 3, 1)]),
        ("LD a\nAND( b\nin1: OR c\n)\nST x\n", [("E196", 3, 1)]),
        # E197: the current result changed under it, or read again after a call
        ("LD x\nR x\nST y\n", [("E197", 3, 1)]),
        ("LD n\nMAX k\nGT 3\nS x\nST y\n", [("E197", 5, 1)]),
        # E198: operands, labels, arguments
        ("LD n\nST 5\n", [("E198", 2, 4)]),
        ("LD a.\nST x\n", [("E198", 1, 5)]),
        ("LD a\nJMP 5\n", [("E198", 2, 5)]),
        ("LD END_IF\nST x\n", [("E198", 1, 4)]),
        ("LD a\nCAL t(IN := , PT := T#1s)\n", [("E198", 2, 13)]),
        ("LD a\nCAL t(IN := a PT := T#1s)\n", [("E198", 2, 15)]),
        ("LD n\nST k[1\n", [("E198", 2, 5)]),
        ("IF: LD a\nST x\n", [("E198", 1, 1)]),
        # E199 is a transition's (test_a_transition_in_il_computes_a_condition_only)
        # characters and strings, as in ST
        ("LD a\nAND b @\nST x\n", [("E002", 2, 7)]),
        ("LD 'abc\nST x\n", [("E004", 1, 4)]),
    ],
)
def test_each_il_problem_is_a_coded_diagnostic_at_its_line_and_column(body, expected):
    got = diagnostics(body)
    if body.startswith("LD n\nNOSUCH"):
        assert [(code, line, col) for code, line, col in got][:1] and got[0][1:] == (2, 1)
        return
    assert got == expected


def test_a_body_with_a_problem_reports_only_its_own():
    """Every line that does not read is reported; then the body is left out:
    no diagnostic of the lowering or the checker follows (ST nope)."""
    assert diagnostics("LD a\nAND( b\nST nope\nADD\nS\n") == [("E191", 4, 1), ("E191", 5, 1)]
    assert diagnostics("AND a\nOR b\n)\nST nope\n") == [("E194", 1, 1)]


def test_the_checker_points_at_the_il_it_checks():
    """The target of ST is written before the value in ST, but an error in
    it is at the IL's ST; an operand's, at the operand."""
    got = diagnostics("LD n\nADD 1\nST nope\nLD a\nAND       c\nOR  nada\nST x\nLD n\n  AND a\nST y\n")
    assert got == [("E010", 3, 4), ("E010", 6, 5), ("E020", 9, 3)]  # E020: INT AND BOOL, at the AND


def test_a_division_by_zero_faults_at_the_div_line():
    src = HEAD + "LD 100\nADD n\nDIV k\nST n\n" + "END_PROGRAM\n"
    r = compile_files([], texts={"main.st": src}).runner("Main")
    with pytest.raises(STFault) as err:
        r.run(1)
    assert err.value.kind == "division"
    assert (err.value.pos.line, err.value.pos.file) == (FIRST + 2, "main.st")


def test_a_bounds_fault_in_an_operand_faults_at_its_line():
    src = """PROGRAM Main
VAR arr : ARRAY[1..3] OF INT; i : INT; s : INT; END_VAR
LD i
ADD 1
ST i
LD s
ADD arr[i]
ST s
END_PROGRAM
"""
    r = compile_files([], texts={"main.st": src}).runner("Main")
    r.run(3)
    with pytest.raises(STFault) as err:
        r.run(1)
    assert err.value.kind == "bounds" and err.value.pos.line == 7


def test_a_chain_of_a_thousand_il_operators_runs():
    """A thousand IL operators make a thousand-operator ST expression: it
    compiles (it was E006) and adds up; past MAX_OPERATORS it is E006 at the
    IL's first line, as the same in ST."""
    adds = 999
    src = HEAD.replace("n, k : INT;", "n, k : DINT;") + "LD n\n" + "ADD 3\n" * adds + "ST n\nEND_PROGRAM\n"
    r = compile_files([], texts={"main.st": src}).runner("Main")
    r.run(2)
    assert r.get("n") == 2 * 3 * adds
    got = diagnostics("LD n\n" + "ADD 1\n" * (MAX_OPERATORS + 1) + "ST n\n")
    assert [code for code, _line, _col in got] == ["E006"]


@pytest.mark.parametrize("profile", ["iec", "matiec"])
def test_jmp_in_il_is_no_e159_in_profiles_without_jumps_in_st(profile):
    assert diagnostics("LD a\nJMPC skip\nLD b\nST x\nskip: LD c\nJMPCN skip\n", profile) == []


def test_softplc_check_exits_1_on_il_errors(tmp_path):
    f = tmp_path / "bad.st"
    f.write_text(HEAD + "LD a\nAND( b\nIF c\n)\nST\nEND_PROGRAM\n")
    env = dict(os.environ, PYTHONIOENCODING="utf-8")
    proc = subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", "check", str(f)],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        env=env,
        timeout=120,
    )
    assert proc.returncode == 1, proc.stderr + proc.stdout
    out = proc.stdout + proc.stderr
    assert f"bad.st:{FIRST + 2}:1: error E190" in out and f"bad.st:{FIRST + 4}:1: error E191" in out
    assert "Traceback" not in out


def test_a_transition_in_il_computes_a_condition_only():
    src = """PROGRAM Main
VAR n : INT; x : BOOL; END_VAR
INITIAL_STEP Idle: END_STEP
TRANSITION FROM Idle TO Run :
    LD n
    JMPC Idle
END_TRANSITION
STEP Run: END_STEP
TRANSITION FROM Run TO Idle :
    LD n
    AND(
END_TRANSITION
END_PROGRAM
"""
    diags, _ = check_files([], texts={"main.st": src})
    assert [(d.code, d.pos.line, d.pos.col) for d in diags if d.is_error] == [("E199", 6, 5), ("E193", 11, 5)]
