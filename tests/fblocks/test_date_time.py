"""The date and time functions from ST: SPLIT_DATE, SPLIT_TOD, SPLIT_DT
(fblocks/iec/date_time.st), CONCAT_DATE, CONCAT_TOD, CONCAT_DT,
CONCAT_DATE_TOD and DAY_OF_WEEK (fblocks/iec/functions.py), IEC 61131-3
ed.3 Table 36 and 37, and IS_VALID_BCD."""

from __future__ import annotations

import datetime

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.st.faults import STFault

from .st_bench import Bench

_FIELDS = "y mo d h mi s ms".split()
_DECLS = "y, mo, d, h, mi, s, ms : INT;"


def test_split_date_tod_and_dt_give_the_calendar_fields():
    b = Bench(
        f"{_DECLS} ty, tmo, td : DINT; th, tmi, ts, tms : INT; dy, dmo, dd, dh, dmi, ds, dms : INT;",
        "SPLIT_DATE(IN := D#2024-02-29, YEAR => y, MONTH => mo, DAY => d);\n"
        "SPLIT_TOD(IN := TOD#13:45:12.345, HOUR => th, MINUTE => tmi, SECOND => ts, MILLISECOND => tms);\n"
        "SPLIT_DT(IN := DT#2106-02-07-06:28:15, YEAR => dy, MONTH => dmo, DAY => dd,\n"
        "         HOUR => dh, MINUTE => dmi, SECOND => ds, MILLISECOND => dms);\n"
        "SPLIT_DATE(D#1970-01-01, YEAR => ty, MONTH => tmo, DAY => td);",  # INT outputs into DINTs
    )
    b.step()
    assert [b[n] for n in ("y", "mo", "d")] == [2024, 2, 29]
    assert [b[n] for n in ("th", "tmi", "ts", "tms")] == [13, 45, 12, 345]
    # the last second DT holds; DT counts whole seconds, so no milliseconds
    assert [b[n] for n in ("dy", "dmo", "dd", "dh", "dmi", "ds", "dms")] == [2106, 2, 7, 6, 28, 15, 0]
    assert [b[n] for n in ("ty", "tmo", "td")] == [1970, 1, 1]


def test_split_date_undoes_concat_date_over_the_range_of_date():
    """Every 7th day from 1970-01-01 to 2106-02-07, and the days around
    leap days (2000 is a leap year, 2100 is not)."""
    b = Bench(
        "n : UDINT; day : DATE; y, m, d : INT; bad : DINT; first_bad : DATE; checked : DINT;",
        "FOR n := 0 TO 49710 BY 7 DO\n"
        "    day := UDINT_TO_DATE(n * 86400);\n"
        "    SPLIT_DATE(IN := day, YEAR => y, MONTH => m, DAY => d);\n"
        "    IF CONCAT_DATE(y, m, d) <> day THEN bad := bad + 1; first_bad := day; END_IF\n"
        "    checked := checked + 1;\n"
        "END_FOR",
    )
    b.step()
    assert (b["bad"], b["checked"]) == (0, 7102)
    edges = ["1972-02-29", "1972-03-01", "1999-12-31", "2000-02-29", "2000-03-01", "2100-02-28", "2100-03-01"]
    for text in edges:
        day = datetime.date.fromisoformat(text)
        b2 = Bench(_DECLS, f"SPLIT_DATE(IN := D#{text}, YEAR => y, MONTH => mo, DAY => d);")
        b2.step()
        assert (b2["y"], b2["mo"], b2["d"]) == (day.year, day.month, day.day)


def test_concat_functions_and_day_of_week():
    b = Bench(
        "a, b, c, dtod, e, w, bcd : BOOL; dow : INT; sunday : INT;",
        "a := CONCAT_DATE(2024, 2, 29) = D#2024-02-29;\n"
        "b := CONCAT_TOD(HOUR := 13, MINUTE := 45, SECOND := 12, MILLISECOND := 345) = TOD#13:45:12.345;\n"
        "c := CONCAT_DT(2024, 2, 29, 13, 45, 12, 999) = DT#2024-02-29-13:45:12;\n"  # DT: whole seconds
        "dtod := CONCAT_DATE_TOD(D#2024-02-29, TOD#13:45:12) = DT#2024-02-29-13:45:12;\n"
        "dow := DAY_OF_WEEK(D#2024-02-29);\n"
        "sunday := DAY_OF_WEEK(IN := CONCAT_DATE(YEAR := 2024, MONTH := 3, DAY := 3));",
    )
    b.step()
    assert (b["a"], b["b"], b["c"], b["dtod"]) == (True, True, True, True)
    assert (b["dow"], b["sunday"]) == (4, 0)  # IEC: 0 = Sunday; 2024-02-29 was a Thursday


@pytest.mark.parametrize(
    "call, message",
    [
        ("CONCAT_DATE(2024, m, 30)", "CONCAT_DATE: 2024-02-30 is not a date"),
        ("DT_TO_DATE(CONCAT_DT(2024, m, 1, 24, 0, 0, 0))", "CONCAT_DT: 24:00:00.000 is not a time of day"),
    ],
)
def test_an_impossible_date_is_a_runtime_fault_at_the_call(call, message):
    decls = "VAR day : DATE; m : INT := 2; reached : BOOL; END_VAR"
    src = f"PROGRAM main\n{decls}\nreached := TRUE;\n  day := {call};\nEND_PROGRAM\n"
    runner = compile_files([], texts={"dates.st": src}).runner("main")
    with pytest.raises(STFault) as info:
        runner.run(1)
    fault = info.value
    assert (fault.kind, fault.message) == ("range", message)
    assert (fault.pos.file, fault.pos.line, fault.pos.col) == ("dates.st", 4, 3)
    assert str(fault).startswith("dates.st:4:3: runtime fault: ")
    assert runner.get("reached") is True


def test_the_split_functions_are_compiled_only_into_programs_that_name_one():
    def pous(body: str) -> set:
        src = f"PROGRAM main\nVAR d : DATE; y, m, dd : INT; END_VAR\n{body}\nEND_PROGRAM\n"
        return {p.name for p in compile_files([], texts={"t.st": src}).checked.pous}

    assert not {"SPLIT_DATE", "SPLIT_TOD", "SPLIT_DT"} & pous("d := CONCAT_DATE(2024, 1, 1);")
    assert {"SPLIT_DATE", "SPLIT_TOD", "SPLIT_DT"} <= pous("SPLIT_DATE(d, YEAR => y, MONTH => m, DAY => dd);")


def test_is_valid_bcd():
    """Each 4-bit digit of the bit string is 0..9."""
    b = Bench(
        "r1, r2, r3, r4, r5, r6, r7 : BOOL; w : WORD := 16#1234;",
        "r1 := IS_VALID_BCD(BYTE#16#99);\nr2 := IS_VALID_BCD(BYTE#16#9A);\nr3 := IS_VALID_BCD(w);\n"
        "r4 := IS_VALID_BCD(WORD#16#12A4);\nr5 := IS_VALID_BCD(DWORD#16#99999999);\n"
        "r6 := IS_VALID_BCD(IN := DWORD#16#F0000000);\nr7 := IS_VALID_BCD(LWORD#16#9876543210987654);",
    )
    b.step()
    assert [b[f"r{i}"] for i in range(1, 8)] == [True, False, True, False, True, False, True]


def test_the_l_variants_split_and_concat_to_the_millisecond():
    """SPLIT_LDATE, SPLIT_LTOD, SPLIT_LDT and CONCAT_LDATE, CONCAT_DATE_LTOD
    (IEC 61131-3 ed.3 Table 37; the L-types count nanoseconds, to 2554)."""
    b = Bench(
        f"{_DECLS} ly, lmo, ld : INT; th, tmi, ts, tms : INT; dy, dmo, dd, dh, dmi, ds, dms : INT;"
        "back : LDATE; stamp : LDT; same : BOOL;",
        "SPLIT_LDATE(IN := LDATE#2400-02-29, YEAR => ly, MONTH => lmo, DAY => ld);\n"
        "SPLIT_LTOD(IN := LTOD#23:59:59.999999, HOUR => th, MINUTE => tmi, SECOND => ts, MILLISECOND => tms);\n"
        "SPLIT_LDT(IN := LDT#2554-07-21-23:34:33.709, YEAR => dy, MONTH => dmo, DAY => dd,\n"
        "          HOUR => dh, MINUTE => dmi, SECOND => ds, MILLISECOND => dms);\n"
        "back := CONCAT_LDATE(2400, 2, 29);\n"
        "same := back = LDATE#2400-02-29;\n"
        "stamp := CONCAT_DATE_LTOD(D#2024-05-01, LTOD#12:00:00.5);",
    )
    b.step()
    assert [b[n] for n in ("ly", "lmo", "ld")] == [2400, 2, 29]
    assert [b[n] for n in ("th", "tmi", "ts", "tms")] == [23, 59, 59, 999]
    assert [b[n] for n in ("dy", "dmo", "dd", "dh", "dmi", "ds", "dms")] == [2554, 7, 21, 23, 34, 33, 709]
    assert b["same"] is True
    stamp = datetime.datetime(2024, 5, 1, 12, 0, 0, 500000, tzinfo=datetime.UTC)
    assert b["stamp"] == int(stamp.timestamp()) * 1_000_000_000 + 500_000_000
