"""s[i] on a STRING (profile switch string_index; checker_pointers.py
string_index, rt_bytes.StrLeaf): the i-th byte, from 0, read and written as a
BYTE (a WSTRING's i-th character as a WORD). CODESYS V3 and TwinCAT 3 accept
it (a CODESYS forum example copies `abRxBuf[i] := testString[i]` for i from
0 to LEN - 1); IEC 61131-3 has no string indexing, so the iec, matiec and
schneider profiles report E050.
"""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import diagnostics, prog, run_st

_INC = "FUNCTION inc : BOOL\nVAR_IN_OUT b : BYTE; END_VAR\nb := b + 1;\nEND_FUNCTION\n"


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_string_bytes_read_and_written_by_index(profile):
    src = prog(
        "s : STRING(10) := 'abc'; c0, c3, c10 : BYTE; i : INT; ws : WSTRING(4) := \"xy\"; w : WORD; n : INT;"
        "buf : ARRAY[0..9] OF BYTE; t : STRING(10) := 'hey';",
        "c0 := s[0]; c3 := s[3]; c10 := s[10];\n"  # past the end: the terminator and what follows read 0
        "FOR i := 0 TO 2 DO s[i] := s[i] - 32; END_FOR\n"
        "s[3] := 68; n := LEN(s);\n"  # a character at the end makes the string longer
        "ws[1] := 16#5A; w := ws[0];\n"
        "FOR i := 0 TO LEN(t) - 1 DO buf[i] := t[i]; END_FOR",
    )
    r = run_st(src, profile=profile)
    assert (r.get("c0"), r.get("c3"), r.get("c10"), r.get("s"), r.get("n")) == (97, 0, 0, "ABCD", 4)
    assert (r.get("ws"), r.get("w"), r.get("buf")[:4]) == ("xZ", 120, [104, 101, 121, 0])


def test_a_string_byte_by_reference_and_its_address():
    src = _INC + prog(
        "s : STRING(10) := 'abc'; pb : POINTER TO BYTE;",
        "pb := ADR(s[1]); pb^ := 66; pb := pb + 1; pb^ := 67;\ninc(s[0]);",
    )
    assert run_st(src).get("s") == "bBC"


def test_an_index_past_the_string_size_is_a_bounds_fault():
    src = prog("s : STRING(10); i : INT := 11; c : BYTE;", "c := s[i];")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "bounds" and err.value.pos.line == 5 and "0..10" in err.value.message


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_iec_strings_are_not_indexed(profile):
    d = [x for x in diagnostics(prog("s : STRING(10); c : BYTE;", "c := s[1];"), profile) if x.severity == "error"]
    assert [(x.code, x.pos.line, x.pos.col) for x in d] == [("E050", 5, 6)] and "codesys and twincat" in d[0].hint


def test_a_constant_index_outside_the_string_is_e051():
    d = [x for x in diagnostics(prog("s : STRING(10); c : BYTE;", "c := s[11];")) if x.severity == "error"]
    assert [(x.code, x.pos.line, x.pos.col) for x in d] == [("E051", 5, 8)]
