"""Dialect rules of function blocks and methods met in real CODESYS and
TwinCAT code (issue 30): what each profile takes, seen from a program a user
compiles and runs."""

from __future__ import annotations

import pytest

from .conftest import codes, diagnostics, run_st

COUNTER = """
FUNCTION_BLOCK FB_Counter
VAR_INPUT
    up : BOOL;
END_VAR
VAR
    count : INT := 7;
    history : ARRAY[0..2] OF INT := [1, 2, 3];
END_VAR
VAR_TEMP
    scratch : INT;
END_VAR
IF up THEN
    count := count + 1;
END_IF
END_FUNCTION_BLOCK
"""


def _main(body: str) -> str:
    return COUNTER + f"PROGRAM main\nVAR\n    c : FB_Counter;\n    n, h : INT;\nEND_VAR\n{body}\nEND_PROGRAM\n"


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_an_instances_internal_var_is_read_from_outside_with_a_warning(profile):
    # CODESYS and TwinCAT permit read access (their static analysis flags
    # it, SA0102): the value is the instance's own
    src = _main("c(up := TRUE);\nn := c.count;\nh := c.history[2];")
    ds = diagnostics(src, profile)
    assert [(d.code, d.pos.line, d.pos.col) for d in ds] == [("W113", 23, 6), ("W113", 24, 6)]
    assert ds[0].message == "'count' is internal to FB_Counter: read from outside"
    r = run_st(src, cycles=3, profile=profile)
    assert (r.get("n"), r.get("h")) == (10, 3)


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
@pytest.mark.parametrize("write", ["c.count := 5;", "c.history[1] := 5;"])
def test_writing_it_from_outside_stays_an_error(profile, write):
    ds = diagnostics(_main(write), profile)
    assert [d.code for d in ds] == ["E013"]
    assert ds[0].message.endswith("it may be read from outside, not written")


def test_passing_it_to_a_var_in_out_is_a_write():
    src = (
        COUNTER
        + """
FUNCTION Bump : BOOL
VAR_IN_OUT v : INT; END_VAR
v := v + 1;
END_FUNCTION
PROGRAM main
VAR c : FB_Counter; END_VAR
Bump(v := c.count);
END_PROGRAM
"""
    )
    assert codes(src) == ["E013"]


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_the_strict_profiles_refuse_the_read(profile):
    ds = diagnostics(_main("n := c.count;"), profile)
    assert [d.code for d in ds] == ["E013"]
    assert "the codesys and twincat profiles let a VAR be read" in ds[0].hint


def test_a_var_temp_is_no_instance_variable_anywhere():
    assert codes(_main("n := c.scratch;"), "codesys") == ["E013"]


MODES = """
FUNCTION_BLOCK FB_Modes
VAR CONSTANT
    MODE_SLOW : INT := 1;
    MODE_FAST : INT := 2;
    DEPTH : INT := 3;
END_VAR
VAR
    n : INT;
    mode : INT := 2;
    last : INT;
END_VAR
n := n + 1;
END_FUNCTION_BLOCK
ACTION FB_Modes.Restart:
n := 0;
END_ACTION
METHOD Apply : INT
VAR
    buf : ARRAY[1..DEPTH] OF INT;
END_VAR
Restart();
CASE mode OF
    MODE_SLOW: n := 10;
    MODE_FAST: n := 20;
END_CASE
buf[DEPTH] := n;
last := buf[DEPTH];
Apply := DINT_TO_INT(UPPER_BOUND(buf, 1));
END_METHOD
PROGRAM main
VAR
    m : FB_Modes;
    bound, before, after : INT;
END_VAR
m();
m();
before := m.n;
bound := m.Apply();
after := m.n;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat", "iec"])
def test_a_method_calls_its_blocks_action_and_uses_its_constants(profile):
    # CODESYS and TwinCAT: a METHOD sees its block's actions and its VAR
    # CONSTANTs, as CASE labels and as array bounds alike
    src = MODES.replace("before := m.n;", "").replace("after := m.n;", "")
    r = run_st(src, profile=profile)
    assert r.get("bound") == 3
    r = run_st(MODES, profile="codesys")
    assert (r.get("before"), r.get("after"), r.get("m.last")) == (2, 20, 20)


def test_a_derived_blocks_method_calls_the_base_action():
    src = """
FUNCTION_BLOCK FB_Base
VAR
    n : INT;
END_VAR
n := n + 1;
END_FUNCTION_BLOCK
ACTION FB_Base.Restart:
n := 0;
END_ACTION
FUNCTION_BLOCK FB_Derived EXTENDS FB_Base
n := 5;
END_FUNCTION_BLOCK
METHOD Clear : BOOL
Restart();
Clear := n = 0;
END_METHOD
PROGRAM main
VAR
    d : FB_Derived;
    cleared : BOOL;
END_VAR
d();
cleared := d.Clear();
END_PROGRAM
"""
    assert run_st(src).get("cleared") is True


VALID_IN_OUT = """
TYPE DUT_EPS :
STRUCT
    nFlags : UDINT;
END_STRUCT
END_TYPE
FUNCTION_BLOCK FB_EPS
VAR_IN_OUT
    eps : DUT_EPS;
END_VAR
END_FUNCTION_BLOCK
METHOD setBit : BOOL
VAR_INPUT
    nBit : BYTE;
END_VAR
IF NOT __ISVALIDREF(eps) THEN
    RETURN;
END_IF
eps.nFlags := eps.nFlags OR SHL(UDINT#1, nBit);
setBit := TRUE;
END_METHOD
FUNCTION Bound : BOOL
VAR_IN_OUT
    x : INT;
END_VAR
Bound := __ISVALIDREF(x);
END_FUNCTION
PROGRAM main
VAR
    fb : FB_EPS;
    d : DUT_EPS;
    before, after, inFunction : BOOL;
    k : INT;
END_VAR
before := fb.setBit(nBit := 1);
fb(eps := d);
after := fb.setBit(nBit := 2);
inFunction := Bound(x := k);
END_PROGRAM
"""


def test_isvalidref_tells_whether_a_var_in_out_is_bound():
    # TwinCAT's own example: a METHOD checks the block's VAR_IN_OUT before it
    # uses it, since the block may not have been called yet
    r = run_st(VALID_IN_OUT)
    assert (r.get("before"), r.get("after"), r.get("d.nFlags"), r.get("inFunction")) == (False, True, 4, True)
