""" "Did you mean" hints (runtime/st/hints.py): the same names difflib
picked, and one search per unknown name however often it is used."""

from __future__ import annotations

import difflib

import pytest

from softplc.runtime.st import hints
from softplc.runtime.st.hints import NameIndex

from .conftest import diagnostics


def _difflib(key: str, names: list, cutoff: float) -> str | None:
    """The hint as the checker computed it before the index."""
    close = difflib.get_close_matches(key, [n.upper() for n in names], n=1, cutoff=cutoff)
    return next(n for n in names if n.upper() == close[0]) if close else None


NAMES = [
    "Motor_Speed", "MotorSpeed", "motor_speeds", "Valve1", "Valve2", "Valve12", "bStart", "bStop",
    "nCount", "nCounter", "FB_Alarm", "FB_AlarmList", "ST_Axis", "E_State", "CONCAT", "LIMIT", "a", "ab",
]  # fmt: skip


@pytest.mark.parametrize(
    "key",
    ["MOTOR_SPEEDS", "MOTORSPED", "VALVE", "VALVE21", "BSTRAT", "NCOUNTR", "FB_ALARMLST", "ST_AXES", "CONCT",
     "LIMITS", "A", "B", "XYZ", "", "FB_ALARM", "MOTOR_SPEED_SETPOINT_FILTERED"],
)  # fmt: skip
@pytest.mark.parametrize("cutoff", [0.6, 0.75])
def test_the_index_picks_what_difflib_picked(key, cutoff):
    assert NameIndex(NAMES).closest(key, cutoff) == _difflib(key, NAMES, cutoff)


def test_ties_go_to_the_larger_name_and_the_first_spelling():
    names = ["Pump_B", "Pump_A", "PUMP_a"]
    assert NameIndex(names).closest("PUMP_C", 0.75) == _difflib("PUMP_C", names, 0.75) == "Pump_B"
    assert NameIndex(names).closest("PUMP_AA", 0.75) == "Pump_A"  # declared first of the two spellings


def test_a_repeated_unknown_name_is_searched_once_and_hinted_every_time():
    uses = "\n".join("total := total + nSpeedd;" for _ in range(40))
    src = f"PROGRAM main\nVAR total : INT; nSpeed : INT; nPressure : INT; END_VAR\n{uses}\nEND_PROGRAM\n"
    before = hints.SEARCHES
    found = [d for d in diagnostics(src) if d.code == "E010"]
    assert hints.SEARCHES - before == 1
    assert len(found) == 40
    assert {d.hint for d in found} == {"did you mean 'nSpeed'?"}


def test_the_checker_hints_as_before():
    src = (
        "FUNCTION_BLOCK FB_Conveyor\nVAR_INPUT bRun : BOOL; END_VAR\nEND_FUNCTION_BLOCK\n"
        "PROGRAM main\nVAR fbConveyor : FB_Convyor; rLevel : REAL; x : REAL; END_VAR\n"
        "x := rLvel;\nx := LIMT(0.0, x, 1.0);\nx := rTotallyElse;\nEND_PROGRAM\n"
    )
    found = {d.message: d.hint for d in diagnostics(src) if d.is_error}
    assert found["unknown type 'FB_Convyor'"] == "did you mean 'FB_CONVEYOR'?"  # (types are listed UPPER)
    assert found["unknown name 'rLvel'"] == "did you mean 'rLevel'?"
    assert [h for m, h in found.items() if "LIMT" in m] == ["did you mean 'LIMIT'?"]
    assert found["unknown name 'rTotallyElse'"] == "declare it in a VAR block"
