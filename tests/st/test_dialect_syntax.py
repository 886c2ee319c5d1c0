"""Dialect rules of the syntax met in real CODESYS and TwinCAT code (issue
30): what each profile takes, seen from a program a user compiles and runs."""

from __future__ import annotations

import pytest

from .conftest import codes, prog, run_st


def test_doubled_underscores_in_numbers_are_twincats():
    # a TwinCAT library writes its largest LINT as 16#7f_ff_ff_ff__ff_ff_ff_ff
    src = prog(
        "big : LINT := 16#7f_ff_ff_ff__ff_ff_ff_ff; n : DINT;",
        "n := 1__000 + DINT#2__0;",
    )
    for profile in ("codesys", "twincat"):
        r = run_st(src, profile=profile)
        assert (r.get("big"), r.get("n")) == (2**63 - 1, 1020)
    for profile in ("iec", "matiec", "schneider"):
        assert codes(src, profile) == ["E003"] * 3


@pytest.mark.parametrize("literal", ["10_", "16#_FF", "1_.5"])
def test_an_underscore_still_stands_between_digits(literal):
    assert "E003" in codes(prog("n : LREAL;", f"n := {literal};"), "twincat")


HEADERS_WITH_SEMICOLONS = """
FUNCTION_BLOCK FB_Counter;
VAR
    n : INT;
END_VAR
n := n + 1;
END_FUNCTION_BLOCK
METHOD PUBLIC Count : INT;
Count := n;
END_METHOD
METHOD INTERNAL Scaled : INT;
VAR_INPUT
    k : INT;
END_VAR
Scaled := n * k;
END_METHOD
PROPERTY Twice : INT;
GET
    Twice := 2 * n;
END_GET
END_PROPERTY
FUNCTION Plus1 : INT;
VAR_INPUT
    x : INT;
END_VAR
Plus1 := x + 1;
END_FUNCTION
PROGRAM main;
VAR
    c : FB_Counter;
    a, b, t, p : INT;
END_VAR
c();
a := c.Count();
b := c.Scaled(k := 10);
t := c.Twice;
p := Plus1(a);
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_a_pou_header_may_end_with_a_semicolon(profile):
    # TwinCAT writes `METHOD PUBLIC Close : HRESULT;` in its .TcPOU
    # declarations; the semicolon changes nothing
    r = run_st(HEADERS_WITH_SEMICOLONS, cycles=2, profile=profile)
    assert [r.get(v) for v in ("a", "b", "t", "p")] == [2, 20, 4, 3]


ASSIGNED_VALUES = """
TYPE ST_P :
STRUCT
    x : INT;
END_STRUCT
END_TYPE
FUNCTION Count : INT
VAR_INPUT
    limit : INT;
END_VAR
VAR
    i : INT;
END_VAR
WHILE (i := i + 1) < limit DO
    Count := Count + 1;
END_WHILE
END_FUNCTION
PROGRAM main
VAR
    i, hits, c, g : INT;
    s : ST_P;
    arr : ARRAY[0..2] OF INT;
    b : SINT;
END_VAR
IF (i := i + 1) = 3 THEN
    hits := 1;
END_IF
c := Count(limit := 5);
IF (s.x := s.x + 2) > 3 AND (arr[1] := arr[1] + 5) > 0 THEN
    hits := hits + 10;
END_IF
g := (b := b + 100);
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_an_assignment_in_parentheses_is_a_value(profile):
    # CODESYS "Assignment as expression": the target is assigned when the
    # expression is evaluated (every time a WHILE tests it, both sides of
    # AND as CODESYS evaluates them), the value is what was stored
    r = run_st(ASSIGNED_VALUES, cycles=3, profile=profile)
    assert (r.get("i"), r.get("hits"), r.get("c")) == (3, 11, 4)
    assert (r.get("s.x"), r.get("arr")[1]) == (6, 15)
    assert (r.get("b"), r.get("g")) == (44, 44)  # 100, -56 (wrapped), 44: the SINT stored


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_elsewhere_an_assignment_is_a_statement(profile):
    assert codes(ASSIGNED_VALUES, profile) == ["E032"] * 5


def test_an_aggregate_assignment_is_no_value():
    src = prog("a, b, c : ARRAY[0..1] OF INT;", "c := (a := b);")
    assert codes(src) == ["E032"]


DOCUMENTED_CHAINS = """
PROGRAM main
VAR
    i, a, b, c, n, neg : INT;
    r1, r2 : REAL;
    flag, same : BOOL;
    s : SINT;
    short : STRING(3);
END_VAR
a := b := c + 9;
r1 := r2 := c;
IF flag := (i = 1) THEN
    n := n + 1;
END_IF
IF (s := s + 100) < 0 THEN
    neg := neg + 1;
END_IF
same := (short := 'abcdef') = 'abc';
i := i + 1;
c := c + 1;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_the_documented_assignments_as_values(profile):
    # CODESYS "ExST Assignment as an Expression" (and Beckhoff Infosys, TC3
    # PLC, "ExST assignment as expression"): a := b := c + 9 gives both the
    # value; IF b := (i = 1) THEN assigns b, then tests it. The value used is
    # what the target holds: a SINT's 100 + 100 compares as -56, a
    # STRING(3) as 'abc'
    r = run_st(DOCUMENTED_CHAINS, cycles=3, profile=profile)
    assert (r.get("a"), r.get("b"), r.get("r1"), r.get("r2")) == (11, 11, 2.0, 2.0)
    assert (r.get("flag"), r.get("n")) == (False, 1)  # TRUE in the 2nd cycle only
    assert (r.get("s"), r.get("neg")) == (44, 1)  # 100, -56, 44: negative once
    assert (r.get("short"), r.get("same")) == ("abc", True)


def test_a_chain_keeps_each_assignments_type_rules():
    # "nVarInt := fVarReal1 := nVarInt; (* incorrect assignment, the data
    # types do not match *)": the REAL stored in an INT draws what n := r
    # draws (W121 under codesys, an implicit narrowing)
    decls = "n : INT; r : REAL;"
    assert codes(prog(decls, "n := r := n;")) == codes(prog(decls, "n := r;")) == ["W121"]
    assert codes(prog("n : INT; r : REAL;", "r := n := 3;")) == []
    assert codes(prog("n : INT; b : BOOL;", "IF b := n THEN n := 0; END_IF"))[0] == "E020"


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_elsewhere_a_chain_is_no_assignment(profile):
    assert codes(DOCUMENTED_CHAINS, profile) == ["E032"] * 5


RUSTY_ACTIONS = """
FUNCTION_BLOCK fb
VAR_INPUT
    x : INT;
END_VAR
VAR_OUTPUT
    y : INT;
END_VAR
y := y + x;
END_FUNCTION_BLOCK

ACTIONS
    ACTION act
        y := y + 100;
    END_ACTION
END_ACTIONS

ACTIONS fb
    ACTION act2
        y := y * 2;
    END_ACTION
    ACTION act4
        y := y - 1;
    END_ACTION
END_ACTIONS

ACTION fb.act3
    y := 0;
END_ACTION

PROGRAM main
VAR
    f : fb;
    r1, r2, r3 : INT;
    actions : INT;
END_VAR
f(x := 1);
f.act();
r1 := f.y;
f.act2();
f.act4();
r2 := f.y;
f.act3();
r3 := f.y;
actions := actions + 1;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["iec", "matiec", "codesys", "twincat", "schneider"])
def test_rustys_actions_container_holds_a_pous_actions(profile):
    # RuSTy ("POUs", Action): ACTIONS right below the POU (its actions),
    # ACTIONS fb (fb's), ACTION fb.act3 (as CODESYS exports). Every profile
    # takes the container: no dialect spells anything else so, and `actions`
    # stays a name where no name follows it
    r = run_st(RUSTY_ACTIONS, cycles=2, profile=profile)
    # cycle 1: 1, 101, 202, 201, 0; cycle 2: 1, 101, ...
    assert [r.get(v) for v in ("r1", "r2", "r3", "actions")] == [101, 201, 0, 2]


def test_an_actions_container_names_its_pou():
    stray = "ACTIONS\n ACTION a\n  ;\n END_ACTION\nEND_ACTIONS\n" + prog("n : INT;", "n := 1;")
    assert codes(stray) == ["E047"]  # nothing above it
    other = RUSTY_ACTIONS.replace("ACTION act4", "ACTION main.act4")
    assert codes(other) == ["E047"]  # ACTIONS fb holds fb's actions
