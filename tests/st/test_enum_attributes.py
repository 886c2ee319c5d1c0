"""{attribute 'qualified_only'} and {attribute 'strict'} before an
enumeration's TYPE (CODESYS, TwinCAT; checker_exprs.py, checker_operators.py,
conversions.py), RuSTy-style: a program and its values, or the diagnostics.

CODESYS "Attribute 'qualified_only'": the values of the enumeration can only
be written with the type name (``Color.Red``). "Attribute 'strict'" (CODESYS,
TwinCAT): arithmetic on the enumeration's values, and assigning it a
constant or variable of another type, are compile errors; without it, an
enumeration is its base integer type there (TwinCAT adds both attributes to
every new enumeration). IEC 61131-3 enumerated values are no numbers (ed.3
6.4.4.3): every enumeration is strict in the iec, matiec and schneider
profiles."""

from __future__ import annotations

import pytest

from .conftest import diagnostics, run_st

QUALIFIED = """{attribute 'qualified_only'}
TYPE Color : (Red, Green, Blue); END_TYPE
PROGRAM main
VAR c : Color; n : INT; END_VAR
c := Color.Green;
CASE c OF
    Color.Red: n := 1;
    Color#Green: n := 2;
END_CASE
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_qualified_only_takes_type_dot_value_and_a_bare_value_is_e018(profile):
    assert run_st(QUALIFIED, cycles=1, profile=profile).get("n") == 2
    src = QUALIFIED.replace("c := Color.Green;", "c := Green;")
    [d] = diagnostics(src, profile)
    assert (d.code, d.pos.line, d.pos.col) == ("E018", 5, 6)
    assert d.message == "'Green' is a value of the enumeration Color, which is qualified_only"
    assert d.hint == "write Color.Green ({attribute 'qualified_only'} before its TYPE)"


LOOSE = """TYPE Mode : (Off, Slow := 10, Fast := 20); END_TYPE
PROGRAM main
VAR m : Mode := Mode.Slow; next_m : Mode; n : INT; faster : BOOL; END_VAR
n := m + 5;
next_m := n + 5;
faster := next_m > 15;
END_PROGRAM
"""


def test_without_strict_codesys_computes_with_an_enumeration_as_its_integer():
    r = run_st(LOOSE, cycles=1)
    assert (r.get("n"), r.get("next_m"), r.get("faster")) == (15, 20, True)
    # an integer into the enumeration is accepted with a warning
    [d] = diagnostics(LOOSE)
    assert (d.code, d.pos.line) == ("W151", 5)
    assert d.message == "INT into the enumeration Mode in the assignment: the value may be none of its enumerators"


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_strict_makes_arithmetic_and_integers_errors_with_the_attribute_named(profile):
    src = "{attribute 'strict'}\n" + LOOSE
    found = [(d.code, d.pos.line, d.hint) for d in diagnostics(src, profile)]
    assert found == [
        ("E023", 5, "Mode is {attribute 'strict'}: no arithmetic on its values"),
        ("E020", 6, "Mode is {attribute 'strict'}: use an enumerator of Mode, e.g. Mode#Off"),
        ("E020", 7, "convert one side so both have the same type"),
    ]


@pytest.mark.parametrize("profile", ["iec", "matiec"])
def test_every_enumeration_is_strict_in_iec(profile):
    assert [d.code for d in diagnostics(LOOSE, profile)] == ["E023", "E020", "E020"]
