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
