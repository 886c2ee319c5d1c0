"""TcUnit's texts (fblocks/libs/tcunit/values.py, service.failure_line):
values as TcUnit prints them, and its failure line cut to the 253
characters of an ADS message the way TcUnit's verifier expects it
(FB_AdjustAssertFailureMessageToMax253CharLengthTest)."""

from __future__ import annotations

import pytest

from softplc.fblocks.libs.tcunit.service import failure_line
from softplc.fblocks.libs.tcunit.values import any_equals, text
from softplc.runtime.st import types as T

LONG_NAME = "PRG_TEST." + "LongInstanceName" * 10


@pytest.mark.parametrize(
    "ty, value, shown",
    [
        (T.BOOL, True, "TRUE"),
        (T.BYTE, 0x0A, "0x0A"),
        (T.LWORD, 0x0123456789ABCDEF, "0x0123456789ABCDEF"),
        (T.SINT, -128, "-128"),
        (T.REAL, 24.0, "24.0"),
        (T.LREAL, 1234567.89, "1234567.89"),
        (T.TIME, 0, "T#0ms"),
        (T.TIME, -1, "T#49d17h2m47s295ms"),  # TwinCAT's TIME is unsigned
        (T.LTIME, -1, "LTIME#213503d23h34m33s709ms551us615ns"),
        (T.ELEMENTARY["DATE"], 831_340_800, "D#1996-05-06"),
        (T.ELEMENTARY["TOD"], 56_190_123, "TOD#15:36:30.123"),
        (T.StringType(80), "as it is", "as it is"),
    ],
)
def test_values_as_tcunit_prints_them(ty, value, shown):
    assert text(ty, value) == shown


def test_a_failure_line_fits_253_characters_as_tcunit_cuts_it():
    head = f"FAILED TEST '{LONG_NAME}@T', EXP: 1, ACT: 2"
    assert failure_line(f"{LONG_NAME}@T", "1", "2", "short") == f"{head}, MSG: short"
    # the format ('..., MSG: %s') and the message in 253: the message cut, marked
    cut = failure_line(f"{LONG_NAME}@T", "1", "2", "m" * 200)
    assert cut.startswith(f"{head}, MSG: mmm") and cut.endswith("m...TestMsg too long")
    assert len(cut) == 253 - len("%s")
    # a test instance path too long for a message at all: cut, marked, no message
    longer = f"{LONG_NAME}{'X' * 80}@T"
    assert failure_line(longer, "1", "2", "m") == (
        f"FAILED TEST '{longer}', EXP: 1, ACT: 2, MSG: %s"[:233] + "...TestName too long"
    )


def test_any_of_one_elementary_type_compares_as_its_typed_assert():
    holds = any_equals(T.REAL, float("nan"), T.REAL, 1.0, "m")
    assert holds.holds  # as TcUnit: AssertEquals_REAL with Delta 0.0 holds for NaN (ABS(NaN) > 0.0 is FALSE)
    o = any_equals(T.WORD, 0xABCD, T.WORD, 0x0123, "m")
    assert (o.holds, o.atype, o.expected, o.actual) == (False, "WORD", "0xABCD", "0x0123")
    o = any_equals(T.INT, 1, T.DINT, 1, "m")
    assert (o.holds, o.expected, o.actual) == (False, "(Type class = INT)", "(Type class = DINT)")
