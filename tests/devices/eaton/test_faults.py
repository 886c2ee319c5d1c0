"""The Eaton PowerXL faults (faults.py, Tabelle 11) against the manual's own
numbers (manual 002, shared/manuals/002_a23ab2a6587941cb.txt; "L<n>" is a
line of that file; digest shared/digests/002_eaton_modbus.md).

Every expected value below is copied from the manual (or, where a test says
so, from the digest's derived examples); none is computed by the code under
test.
"""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import faults as eaton_faults
from softplc.runtime.devices.eaton.registers import Family

DA1, DB1, DC1, DE1 = Family.DA1, Family.DB1, Family.DC1, Family.DE1


# ---------------------------------------------------------------------------
# Faults (Tabelle 11, L854-916)
# ---------------------------------------------------------------------------

MANUAL_FAULT_NUMBERS = (
    0,
    1,
    2,
    3,
    4,
    5,
    6,
    7,
    8,
    9,
    10,
    11,
    12,
    13,
    14,
    15,
    16,
    17,
    18,
    19,
    20,
    21,
    22,
    23,
    24,
    25,
    26,
    29,
    30,
    31,
    32,
    33,
    34,
    35,
    40,
    41,
    42,
    43,
    44,
    49,
    50,
    51,
    52,
    53,
    60,
    61,
    70,
    71,
    72,
    73,
    74,
)


def test_fault_numbers_are_those_of_the_table():
    assert tuple(sorted(eaton_faults.FAULTS)) == MANUAL_FAULT_NUMBERS


@pytest.mark.parametrize(
    "code, words, display",
    [
        (0, "No fault", "no-Flt"),  # L859
        (3, "Overcurrent", "O-I"),  # L862
        (6, "overvoltage", "O-Volt"),  # L865
        (7, "undervoltage", "U-Volt"),  # L866
        (14, "supply phase", "P-LOSS"),  # L873
        (50, "Modbus telegram", "SC-F01"),  # L906
        (51, "CANopen telegram", "SC-F02"),  # L907
        (74, "table overflow", "PLC-05"),  # L916
    ],
)
def test_fault_texts(code, words, display):
    assert words.lower() in eaton_faults.fault_text(code).lower()
    assert eaton_faults.fault_display(code) == display


@pytest.mark.parametrize("code", [27, 28, 36, 45, 54, 62, 75, 255])
def test_numbers_missing_from_the_table_are_unknown(code):
    assert eaton_faults.fault_text(code) == f"unknown fault number {code}"
    assert eaton_faults.fault_display(code) == ""


def test_fault_families_as_printed():
    assert eaton_faults.FAULTS[1].families == {DA1, DB1, DC1, DE1}  # L860
    assert eaton_faults.FAULTS[19].families == {DA1, DB1, DC1}  # L878
    assert eaton_faults.FAULTS[24].families == {DA1}  # L890
    assert eaton_faults.FAULTS[50].families == {DA1, DB1, DC1}  # L906 (no DE1, A20)
    assert DC1 in eaton_faults.FAULTS[15].families  # L874 names DC1 in its text (A20)


def test_comm_loss_fault_is_the_modbus_timeout():
    assert eaton_faults.COMM_LOSS_FAULT == 50
    assert "Modbus" in eaton_faults.fault_text(eaton_faults.COMM_LOSS_FAULT)
