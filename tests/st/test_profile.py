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
    # and its library's F_TRIG, whose memory starts FALSE
    differing = {f for f in IEC.__dataclass_fields__ if getattr(IEC, f) != getattr(MATIEC, f)}
    assert differing == {"name", "bool_from_0_1", "f_trig_first_call_edge"}
