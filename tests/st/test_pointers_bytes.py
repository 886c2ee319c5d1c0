"""Byte pointers into strings (st/rtlib/rt_bytes.py, refs.BytePtr): a program and
the values its variables hold after a cycle.

CODESYS keeps a STRING(n) in n+1 bytes, its characters and a terminating 0
("Data Type: STRING"), a WSTRING(n) in 2(n+1) (UTF-16); OSCAT BASIC walks
them through `POINTER TO BYTE` and `POINTER TO ARRAY[1..255] OF BYTE` taken
with ADR ("Operator: ADR"). Here writing 0 ends the string, a byte past its
end reads 0, and a byte beyond its n+1 is a 'reference' fault (where a PLC
would reach the next variable's memory).
"""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import prog, run_st

# as OSCAT's UPPERCASE: the result string, walked through an array pointer
_UPPER = """
FUNCTION upper1 : STRING(20)
VAR_INPUT s : STRING(20); END_VAR
VAR pt : POINTER TO ARRAY[1..255] OF BYTE; i : INT; END_VAR
upper1 := s;
pt := ADR(upper1);
i := 1;
WHILE pt^[i] <> 0 DO
    IF pt^[i] >= 97 AND pt^[i] <= 122 THEN pt^[i] := pt^[i] - 32; END_IF
    i := i + 1;
END_WHILE
END_FUNCTION
"""

# as OSCAT's BYTE_TO_STRB: filled from the end, the terminator first
_BIN8 = """
FUNCTION bin8 : STRING(8)
VAR_INPUT x : BYTE; END_VAR
VAR pt : POINTER TO BYTE; v : BYTE; i : INT; END_VAR
v := x;
pt := ADR(bin8) + 8;
pt^ := 0;
FOR i := 1 TO 8 DO
    pt := pt - 1;
    pt^ := BYTE#48 + (v AND 1);
    v := SHR(v, 1);
END_FOR
END_FUNCTION
"""


def test_an_array_pointer_reads_the_characters_and_the_terminating_zero():
    src = prog(
        "str : STRING(10) := 'abc'; pt : POINTER TO ARRAY[1..255] OF BYTE; c1, c3, c4, c11 : BYTE;",
        "pt := ADR(str);\nc1 := pt^[1]; c3 := pt^[3]; c4 := pt^[4]; c11 := pt^[11];",
    )
    r = run_st(src)
    # 'a', 'c', the terminator, and the last of STRING(10)'s 11 bytes
    assert (r.get("c1"), r.get("c3"), r.get("c4"), r.get("c11")) == (97, 99, 0, 0)


def test_writing_bytes_changes_extends_and_ends_the_string():
    src = prog(
        "str : STRING(10) := 'abc'; pb : POINTER TO BYTE; pt : POINTER TO ARRAY[1..255] OF BYTE; i : INT := 2;"
        "s1 : STRING(10); s2 : STRING(10); s3 : STRING(10); n : INT;",
        "pb := ADR(str) + i - 1; pb^ := pb^ - 32; s1 := str;\n"  # OSCAT's pb^ := pb^ + 32 on one character
        "pt := ADR(str); pt^[4] := 100; pt^[5] := 0; s2 := str;\n"  # a character at the end: one longer
        "pt^[2] := 0; s3 := str; n := LEN(str);",  # 0 ends the string
    )
    r = run_st(src)
    assert (r.get("s1"), r.get("s2"), r.get("s3"), r.get("n")) == ("aBc", "aBcd", "a", 1)


def test_oscat_style_functions_over_their_result_string():
    src = _UPPER + _BIN8 + prog("u : STRING(20); b : STRING(8);", "u := upper1('hello, world');\nb := bin8(16#A5);")
    r = run_st(src)
    assert (r.get("u"), r.get("b")) == ("HELLO, WORLD", "10100101")


def test_char_and_wchar_pointers_and_a_word_pointer_over_a_wstring():
    src = prog(
        "s : STRING(5) := 'xyz'; pc : POINTER TO CHAR; c : CHAR;"
        'ws : WSTRING(5) := "AB"; pw : POINTER TO WORD; pwc : POINTER TO ARRAY[0..5] OF WCHAR; w1 : WORD; wc : WCHAR;',
        "pc := ADR(s) + 2; c := pc^; pc^ := CHAR#'Z';\n"
        "pw := ADR(ws) + 2; w1 := pw^; pw := pw + 2; pw^ := 16#43;\n"  # WSTRING: 2 bytes a character
        'pwc := ADR(ws); wc := pwc^[0]; pwc^[3] := WCHAR#"D";',
    )
    r = run_st(src)
    assert (r.get("c"), r.get("s"), r.get("w1"), r.get("wc"), r.get("ws")) == (122, "xyZ", 66, 65, "ABCD")


def test_a_byte_loop_copies_a_string_as_memcpy_would():
    # OSCAT copies memory with loops over POINTER TO BYTE
    src = prog(
        "src : STRING(10) := 'copy me'; dst : STRING(10); ps : POINTER TO BYTE; pd : POINTER TO BYTE; i : INT;",
        "ps := ADR(src); pd := ADR(dst);\n"
        "FOR i := 1 TO LEN(src) + 1 DO pd^ := ps^; ps := ps + 1; pd := pd + 1; END_FOR",
    )
    assert run_st(src).get("dst") == "copy me"


@pytest.mark.parametrize(
    "body,message",
    [
        # STRING(10) is 11 bytes: the 12th is another variable's on a PLC
        ("pt := ADR(str); c := pt^[12];", "byte offset 11 in 11 bytes"),
        ("pb := ADR(str) - 1; pb^ := 1;", "byte offset -1"),
        # the 11th byte is the terminator of the longest string: it takes 0 only
        ("pt := ADR(str); pt^[11] := 65;", "terminating 0 of a STRING(10)"),
    ],
)
def test_outside_the_string_is_a_located_fault(body, message):
    decls = "str : STRING(10) := 'abc'; pt : POINTER TO ARRAY[1..255] OF BYTE; pb : POINTER TO BYTE; c : BYTE;"
    with pytest.raises(STFault) as err:
        run_st(prog(decls, body))
    assert err.value.kind == "reference" and err.value.pos.line == 5
    assert message in err.value.message


def test_oscat_buffer_functions_take_any_array_through_a_large_byte_array_pointer():
    # OSCAT BASIC's _BUFFER_* and _STRING_TO_BUFFER declare PT : POINTER TO ARRAY[0..32767]
    # OF BYTE and are passed ADR(buffer) of whatever size; SIZE keeps them inside it
    src = """
FUNCTION buffer_clear : BOOL
VAR_INPUT PT : POINTER TO BYTE; SIZE : UINT; END_VAR
VAR p : POINTER TO BYTE; k : UINT; END_VAR
p := PT;
FOR k := 1 TO SIZE DO p^ := 0; p := p + 1; END_FOR
buffer_clear := TRUE;
END_FUNCTION
FUNCTION string_to_buffer : INT
VAR_INPUT str : STRING(255); PT : POINTER TO ARRAY[0..32767] OF BYTE; pos : INT; size : UINT; END_VAR
VAR ps : POINTER TO BYTE; i : INT; stop : INT; END_VAR
ps := ADR(str);
stop := MIN(pos + LEN(str), UINT_TO_INT(size)) - 1;
FOR i := pos TO stop DO PT^[i] := ps^; ps := ps + 1; END_FOR
string_to_buffer := i;
END_FUNCTION
PROGRAM main
VAR buf : ARRAY[0..9] OF BYTE := [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]; ok : BOOL; n : INT;
    w : ARRAY[0..3] OF WORD := [1, 2, 3, 4]; END_VAR
ok := buffer_clear(ADR(buf), 4);
n := string_to_buffer('AB', ADR(buf), 5, SIZEOF(buf));
ok := buffer_clear(ADR(w), SIZEOF(w) - 2);
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("buf"), r.get("n"), r.get("w")) == ([0, 0, 0, 0, 5, 65, 66, 8, 9, 10], 7, [0, 0, 0, 4])


def test_the_array_a_byte_view_points_to_is_copied_whole():
    # p^ of a POINTER TO ARRAY[0..3] OF BYTE is those 4 bytes, copied in and out as an array
    src = prog(
        "s : STRING(10) := 'abc'; pt : POINTER TO ARRAY[0..3] OF BYTE; a : ARRAY[0..3] OF BYTE;",
        "pt := ADR(s);\na := pt^; a[1] := 66; a[3] := 0; pt^ := a;",
    )
    r = run_st(src)
    assert (r.get("a"), r.get("s")) == ([97, 66, 99, 0], "aBc")
