"""The dialect profiles (runtime/st/profile.py): what each one decides, seen
from a program a user compiles and runs with it."""

from __future__ import annotations

import pytest

from softplc.runtime.st.profile import IEC, MATIEC, PROFILES, get_profile

from .conftest import codes, prog, run_st


def test_every_profile_can_be_named_in_any_case():
    assert list(PROFILES) == ["iec", "matiec", "codesys", "twincat", "schneider"]
    assert get_profile("MatIEC") is MATIEC
    with pytest.raises(KeyError, match="choose one of iec, matiec, codesys, twincat, schneider"):
        get_profile("openplc")


def test_matiec_runs_a_program():
    # OpenPLC / Beremiz code: a counter with a typed literal, as MatIEC compiles it
    src = prog("n : INT; total : DINT;", "n := n + INT#1;\ntotal := total + INT_TO_DINT(n);")
    r = run_st(src, cycles=4, profile="matiec")
    assert (r.get("n"), r.get("total")) == (4, 10)


@pytest.mark.parametrize("profile", ["iec", "matiec"])
def test_matiec_types_strictly_as_iec(profile):
    # MatIEC converts nothing implicitly that loses data (DINT -> INT is
    # E021, as in IEC 61131-3 ed.3 Fig. 11) and keeps AND/OR/XOR for ANY_BIT
    # (the standard bitwise functions take ANY_BIT); CODESYS warns about the
    # first and accepts both.
    narrowing = prog("big : DINT := 5; small : INT;", "small := big;")
    assert codes(narrowing, profile) == ["E021"]
    assert codes(narrowing, "codesys") == ["W121"]
    bit_ops = prog("a : INT := 6; b : INT := 3; c : INT;", "c := a AND b;")
    assert codes(bit_ops, profile) == ["E023"]
    assert codes(bit_ops, "codesys") == []


def test_matiec_differs_from_iec_only_where_it_says_so():
    # MatIEC is strict IEC but for 0 and 1 as BOOL literals, which its
    # grammar takes as the standard's does (the iec profile is stricter),
    # and for what its compiler accepts beyond the standard (the OSCAT port
    # to Beremiz leans on each): a POU writing its own inputs, ed.3's type
    # names as variables
    differing = {f for f in IEC.__dataclass_fields__ if getattr(IEC, f) != getattr(MATIEC, f)}
    assert differing == {"name", "bool_from_0_1", "own_input_assignment", "ed3_type_names_reserved"}


ED2_NAMES = """
FUNCTION LTIME_TO_UTC : UDINT
VAR_INPUT
    LTIME : UDINT;
    OFFSET : INT;
END_VAR
LTIME_TO_UTC := LTIME - INT_TO_UDINT(OFFSET * 60);
END_FUNCTION
FUNCTION_BLOCK Local
VAR_INPUT UDT : UDINT; END_VAR
VAR_OUTPUT LDT : UDINT; CHAR : INT; END_VAR
VAR lt : LTIME; END_VAR
LDT := UDT + 3600;
CHAR := 5;
lt := LTIME();
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Local; u : UDINT; c : INT; END_VAR
f(UDT := 100);
u := LTIME_TO_UTC(LTIME := f.LDT, OFFSET := 60);
c := f.CHAR;
END_PROGRAM
"""


def test_matiec_takes_the_names_of_ed3_types_as_variables():
    # OSCAT's port to Beremiz: LTIME_TO_UTC has an input LTIME, another
    # function a variable LDT; MatIEC reads ed.2, which has neither type
    r = run_st(ED2_NAMES, cycles=1, profile="matiec")
    assert (r.get("u"), r.get("c"), r.get("f.LDT")) == (100, 5, 3700)
    ds = codes(ED2_NAMES, "codesys")
    assert ds == ["E011", "E010", "E011", "E011", "E010", "E010", "E040", "E013", "E013"]


def test_a_global_named_as_an_ed3_type_is_refused_in_matiec_too():
    # it would hide LTIME() from every POU, the standard blocks' included
    src = "VAR_GLOBAL LTIME : UDINT; END_VAR\n" + prog("x : INT;", "x := 1;")
    assert codes(src, "matiec") == ["E011"]
