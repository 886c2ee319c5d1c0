"""Dialect rules of types met in real CODESYS and TwinCAT code (issue 30):
what each profile takes, seen from a program a user compiles and runs."""

from __future__ import annotations

import pytest

from .conftest import codes, run_st

QUALIFIED_DEFAULT = """
{attribute 'qualified_only'}
{attribute 'strict'}
TYPE E_Mode :
(
    NONE := 0,
    AUTO := 1,
    MANUAL := 2
) := MANUAL;
END_TYPE
{attribute 'qualified_only'}
TYPE E_State : (IDLE, RUN, STOPPED) INT := RUN;
END_TYPE
PROGRAM main
VAR
    m : E_Mode;
    s : E_State;
    isManual, isRunning : BOOL;
END_VAR
isManual := m = E_Mode.MANUAL;
isRunning := s = E_State.RUN;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_a_qualified_only_enumeration_names_its_default_bare_in_its_type(profile):
    # TwinCAT's DUT editor writes `) := NONE;` under {attribute 'qualified_only'}
    r = run_st(QUALIFIED_DEFAULT, profile=profile)
    assert (r.get("isManual"), r.get("isRunning")) == (True, True)


def test_elsewhere_its_values_stay_qualified():
    assert codes(QUALIFIED_DEFAULT.replace("m = E_Mode.MANUAL", "m = MANUAL")) == ["E018"]
