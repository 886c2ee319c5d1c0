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
