"""rt_timedate.py: time and date arithmetic."""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import RangeFault
from softplc.runtime.st.rtlib import rt_timedate as r

# ---------------------------------------------------------------- time and date arithmetic

DAY = 19724 * 86_400  # D#2024-01-02


def test_time_arithmetic():
    assert r.ADD_TIME(1000, 500) == 1500
    assert r.SUB_TIME(1000, 1500) == -500
    assert r.ADD_TIME(2**31 - 1, 1) == -(2**31)  # wraps like DINT
    assert r.MUL_TIME(1500, 3) == 4500
    assert r.MUL_TIME(1000, 1.5) == 1500
    assert r.MUL_TIME(3, 0.5) == 2  # 1.5 ms rounds away from zero
    assert r.DIV_TIME(10, 4) == 2  # integer divisor truncates
    assert r.DIV_TIME(-10, 4) == -2
    assert r.DIV_TIME(10, 4.0) == 3  # real divisor rounds
    with pytest.raises(ZeroDivisionError):
        r.DIV_TIME(10, 0)
    with pytest.raises(ZeroDivisionError):
        r.DIV_TIME(10, 0.0)
    assert r.ADD_LTIME(1, 2) == 3
    assert r.MUL_LTIME(10**9, 2) == 2 * 10**9
    assert r.DIV_LTIME(10**9, 3) == 333_333_333


def test_tod_arithmetic_wraps_at_midnight():
    assert r.ADD_TOD_TIME(86_399_999, 1) == 0  # TOD#23:59:59.999 + T#1ms
    assert r.ADD_TOD_TIME(3_600_000, 1_800_000) == 5_400_000
    assert r.SUB_TOD_TIME(1_000, 2_000) == 86_399_000
    assert r.SUB_TOD_TOD(3_600_000, 7_200_000) == -3_600_000
    assert r.ADD_LTOD_LTIME(86_400 * 10**9 - 1, 2) == 1
    assert r.SUB_LTOD_LTIME(0, 1) == 86_400 * 10**9 - 1
    assert r.SUB_LTOD_LTOD(5, 7) == -2


def test_dt_arithmetic():
    assert r.ADD_DT_TIME(DAY, 1500) == DAY + 1  # DT has whole seconds
    assert r.ADD_DT_TIME(DAY, -1500) == DAY - 2  # floor
    assert r.SUB_DT_TIME(DAY, 1000) == DAY - 1
    assert r.SUB_DT_DT(DAY + 60, DAY) == 60_000
    assert r.SUB_DATE_DATE(DAY + 86_400, DAY) == 86_400_000
    assert r.SUB_DATE_DATE(DAY + 25 * 86_400, DAY) == 25 * 86_400_000 - 2**32  # TIME wraps
    assert r.ADD_LDT_LTIME(5, 7) == 12
    assert r.SUB_LDT_LTIME(5, 7) == 2**64 - 2
    assert r.SUB_LDT_LDT(5, 7) == -2
    assert r.SUB_LDATE_LDATE(86_400 * 10**9, 0) == 86_400 * 10**9


def test_concat_and_day_of_week():
    assert r.CONCAT_DATE_TOD(DAY, 45_015_500) == DAY + 45_015
    assert r.CONCAT_LDATE_LTOD(DAY * 10**9, 5) == DAY * 10**9 + 5
    assert r.CONCAT_DATE(2024, 1, 2) == DAY
    assert r.CONCAT_DATE(2106, 2, 7) == 49_710 * 86_400  # the last day DATE holds
    assert r.CONCAT_TOD(12, 30, 15, 500) == 45_015_500
    assert r.CONCAT_TOD(23, 59, 59, 999) == 86_399_999
    assert r.CONCAT_LTOD(0, 0, 1, 1) == 1_001_000_000
    assert r.CONCAT_DT(2024, 1, 2, 12, 30, 15, 999) == DAY + 45_015
    assert r.CONCAT_DT(2106, 2, 7, 6, 28, 15, 0) == 2**32 - 1
    assert r.CONCAT_LDT(2024, 1, 2, 0, 0, 1, 5) == (DAY + 1) * 10**9 + 5_000_000
    assert r.DAY_OF_WEEK(0) == 4  # 1970-01-01 was a Thursday
    assert r.DAY_OF_WEEK(DAY) == 2  # 2024-01-02 was a Tuesday
    assert r.DAY_OF_WEEK(DAY + 5 * 86_400) == 0  # Sunday


@pytest.mark.parametrize(
    "fn, args, message",
    [
        ("CONCAT_DATE", (2024, 13, 1), "CONCAT_DATE: 2024-13-01 is not a date"),
        ("CONCAT_DATE", (2023, 2, 29), "CONCAT_DATE: 2023-02-29 is not a date"),
        ("CONCAT_DATE", (1969, 12, 31), "CONCAT_DATE: 1969-12-31 is outside 1970-01-01 .. 2106-02-07"),
        ("CONCAT_DATE", (2106, 2, 8), "CONCAT_DATE: 2106-02-08 is outside 1970-01-01 .. 2106-02-07"),
        ("CONCAT_TOD", (24, 0, 0, 1), "CONCAT_TOD: 24:00:00.001 is not a time of day"),
        ("CONCAT_LTOD", (0, 60, 0, 0), "CONCAT_LTOD: 00:60:00.000 is not a time of day"),
        ("CONCAT_DT", (2024, 1, 2, 0, 0, 0, 1000), "CONCAT_DT: 00:00:00.1000 is not a time of day"),
        ("CONCAT_DT", (2106, 2, 7, 6, 28, 16, 0), "CONCAT_DT: 2106-02-07-06:28:16 is beyond DT"),
        ("CONCAT_LDT", (2024, 2, 30, 0, 0, 0, 0), "CONCAT_LDT: 2024-02-30 is not a date"),
    ],
)
def test_concat_of_no_date_or_time_is_a_range_fault(fn, args, message):
    """IEC 61131-3 ed.3 Table 37 leaves an impossible date open; here it is
    a runtime fault (RangeFault: faults.py locates it at the ST call)."""
    with pytest.raises(RangeFault) as info:
        getattr(r, fn)(*args)
    assert (info.value.kind, str(info.value)) == ("range", message)
