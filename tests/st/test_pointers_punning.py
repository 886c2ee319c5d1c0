"""Byte views of numbers, arrays and structures (st/rtlib/rt_bytes.py): a POINTER
TO BYTE, WORD, DWORD ... over a value of another type reads and writes its
bytes as x86 CODESYS lays them out, little-endian, IEEE 754 for REAL and
LREAL, structures padded as st/sizes.py says (CODESYS "Attribute:
pack_mode", 8-byte mode). OSCAT BASIC reads a REAL's bits this way
(`pt : POINTER TO DWORD; pt := ADR(x); REAL_TO_DW := pt^;`).
"""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import diagnostics, prog, run_st


def test_the_bytes_of_a_dword_little_endian_read_and_written():
    src = prog(
        "d : DWORD := 16#11223344; pb : POINTER TO BYTE; pa : POINTER TO ARRAY[0..3] OF BYTE;"
        "b0, b3 : BYTE; pw : POINTER TO ARRAY[0..1] OF WORD; w0, w1 : WORD;",
        "pb := ADR(d); b0 := pb^; pa := ADR(d); b3 := pa^[3];\n"
        "pw := ADR(d); w0 := pw^[0]; w1 := pw^[1]; pw^[1] := 16#AABB; pb^ := 16#FF;",
    )
    r = run_st(src)
    assert (r.get("b0"), r.get("b3"), r.get("w0"), r.get("w1")) == (0x44, 0x11, 0x3344, 0x1122)
    assert r.get("d") == 0xAABB33FF


def test_a_real_and_an_lreal_seen_through_integer_pointers():
    src = prog(
        "r : REAL := 1.0; l : LREAL := -2.0; pd : POINTER TO DWORD; pl : POINTER TO LWORD; pr : POINTER TO REAL;"
        "dw : DWORD; lw : LWORD; i : DINT := -1; pi : POINTER TO ARRAY[0..1] OF INT; lo, hi : INT; x : DWORD;",
        "pd := ADR(r); dw := pd^; pl := ADR(l); lw := pl^;\n"
        "pi := ADR(i); lo := pi^[0]; hi := pi^[1];\n"  # signed halves of a signed DINT
        "x := 16#40490FDB; pr := ADR(x); r := pr^;",  # and back: a DWORD's bits as a REAL
    )
    r = run_st(src)
    assert (r.get("dw"), r.get("lw")) == (0x3F800000, 0xC000000000000000)
    assert (r.get("lo"), r.get("hi")) == (-1, -1)
    assert r.get("r") == pytest.approx(3.1415927, abs=1e-6)


def test_a_byte_pointer_walks_an_int_array_and_a_structure_with_padding():
    src = """
TYPE S : STRUCT b1 : BYTE; i : DINT; b2 : BYTE; n : INT; END_STRUCT END_TYPE
FUNCTION sum_bytes : UDINT
VAR_INPUT p : POINTER TO BYTE; n : UDINT; END_VAR
VAR q : POINTER TO BYTE; k : UDINT; END_VAR
q := p;
FOR k := 1 TO n DO sum_bytes := sum_bytes + q^; q := q + 1; END_FOR
END_FUNCTION
PROGRAM main
VAR s : S; pb : POINTER TO BYTE := ADR(s); k : ARRAY[0..2] OF BYTE;
    arr : ARRAY[0..1] OF INT := [16#0102, -2]; tot : UDINT; tot2 : UDINT; same : BOOL; END_VAR
s.b1 := 1; s.i := 16#01020304; s.b2 := 5; s.n := -1;
k[0] := pb^; pb := pb + 1; k[1] := pb^; pb := pb + 3; k[2] := pb^;  (* b1, padding, i's low byte *)
pb^ := 9;
tot := sum_bytes(ADR(s), SIZEOF(s));
tot2 := sum_bytes(ADR(arr), SIZEOF(arr));
pb := ADR(arr); pb := pb + 2; same := pb = ADR(arr[1]);
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("k"), r.get("s.i")) == ([1, 0, 4], 0x01020309)
    # 1 + 0 0 0 + 09 03 02 01 + 5 + 0 + FF FF ; 02 01 FE FF
    assert (r.get("tot"), r.get("tot2"), r.get("same")) == (531, 512, True)


def test_a_byte_view_past_its_variable_is_a_located_fault():
    src = prog("d : DWORD; pb : POINTER TO BYTE; b : BYTE;", "pb := ADR(d) + 4;\nb := pb^;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "reference" and err.value.pos.line == 6 and "byte offset 4 in 4 bytes" in err.value.message


@pytest.mark.parametrize(
    "decls,body,words",
    [
        ("f : TON; pw : POINTER TO WORD;", "pw := ADR(f);", "POINTER TO WORD over TON"),
        ("pp : POINTER TO INT; pb : POINTER TO BYTE;", "pb := ADR(pp);", "over POINTER TO INT"),
    ],
)
def test_a_byte_view_of_what_has_no_fixed_bytes_is_e161(decls, body, words):
    d = [x for x in diagnostics(prog(decls, body)) if x.severity == "error"]
    assert [(x.code, x.pos.line, x.pos.col) for x in d] == [("E161", 5, 7)]
    assert words in d[0].message and d[0].hint


def test_a_field_pointer_steps_to_the_next_field_of_its_structure():
    # CODESYS lays a STRUCT out field after field (st/sizes.py): ADR(s.a) + SIZEOF(s.a) is s.b
    src = """
TYPE S : STRUCT a : INT; b : INT; c : DINT; r : REAL; END_STRUCT END_TYPE
PROGRAM main
VAR s : S; p : POINTER TO INT; x, y : INT; same : BOOL; d : DINT; pr : POINTER TO REAL; rv : REAL; END_VAR
s.a := 1; s.b := 2; s.c := 70000; s.r := 2.5;
p := ADR(s.a); x := p^; p := p + SIZEOF(s.a); y := p^; p^ := 20;
same := p = ADR(s.b); d := ADR(s.b) - ADR(s.a);
pr := ADR(s.r); rv := pr^; pr^ := rv * 2.0;
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("x"), r.get("y"), r.get("same"), r.get("d")) == (1, 2, True, 2)
    assert (r.get("s.b"), r.get("s.r")) == (20, 5.0)
