"""Partial access of bit strings and integers: x.%X0, x.%B0, x.%W1,
x.%D0, x.%L0 (runtime/st/check/checker_exprs.py, codegen_exprs.py,
codegen_stmts.py).

IEC 61131-3 ed.3 6.5.3 and Table 16 (CODESYS and TwinCAT alike): the
parts are numbered from the least significant, %X bits, %B bytes, %W words,
%D double words, %L long words; a part is read as the bit string of its
size and written without touching the other bits. A part beyond the type
is a compile-time error.
"""

from __future__ import annotations

from .conftest import diagnostics, prog, run_st


def test_reading_the_parts_of_a_double_word():
    src = prog(
        "d : DWORD := 16#12345678; b0 : BYTE; b3 : BYTE; w1 : WORD; x4 : BOOL; l : LWORD := 16#1122334455667788;"
        "d1 : DWORD; i : DINT := -2; wi : WORD;",
        "b0 := d.%B0;\nb3 := d.%B3;\nw1 := d.%W1;\nx4 := d.%X4;\nd1 := l.%D1;\nwi := i.%W0;",
    )
    r = run_st(src)
    assert (r.get("b0"), r.get("b3"), r.get("w1"), r.get("x4")) == (0x78, 0x12, 0x1234, True)
    assert (r.get("d1"), r.get("wi")) == (0x11223344, 0xFFFE)  # parts are unsigned bit strings


def test_writing_a_part_keeps_the_other_bits():
    src = prog(
        "d : DWORD := 16#12345678; i : INT := 0; l : LINT; s : SINT;",
        "d.%B1 := 16#AB;\nd.%W1 := 16#CAFE;\ni.%B1 := 16#80;\nl.%D1 := 16#FFFFFFFF;\ns.%X7 := TRUE;",
    )
    r = run_st(src)
    assert r.get("d") == 0xCAFEAB78
    assert r.get("i") == -32768  # the high byte of an INT holds its sign
    assert r.get("l") == -(1 << 32)
    assert r.get("s") == -128


def test_a_part_beyond_the_type_is_e056_at_compile_time():
    src = prog(
        "w : WORD; b : BYTE; r : REAL; x : BYTE;",
        "x := w.%B2;\nx := b.%W0;\nw.%D0 := 1;\nx := r.%B0;",
    )
    found = [(d.code, d.pos.line, d.pos.col) for d in diagnostics(src)]
    assert found == [("E056", 5, 10), ("E056", 6, 10), ("E056", 7, 5), ("E053", 8, 6)]
    e = diagnostics(src)[0]
    assert e.message == "WORD has no %B2: it is 16 bits, %B0..%B1"
    assert e.hint == "a WORD holds %X0..%X15, %B0..%B1"


def test_an_output_bound_to_a_bit_or_a_part_writes_through_it():
    """=> w.3 and => d.%B1 for outputs of functions, standard functions' ENO
    and FB outputs (found while adding EN/ENO: it stopped the compiler)."""
    src = """
FUNCTION F : INT
VAR_INPUT a : INT; END_VAR
VAR_OUTPUT o : BOOL; b : BYTE; END_VAR
o := TRUE;
b := 16#AB;
F := a;
END_FUNCTION

FUNCTION Local : WORD
VAR w : WORD; i : INT; END_VAR
i := F(a := 1, o => w.1, b => w.%B1);
Local := w;
END_FUNCTION
""" + prog(
        "w : WORD; x : REAL := 4.0; r : REAL; i : INT; lw : WORD; t : TON;",
        "r := SQRT(EN := TRUE, IN := x, ENO => w.3);\n"
        "i := F(a := 1, ENO => w.%X4);\n"
        "i := F(a := 1, o => w.5);\n"
        "t(EN := FALSE, IN := TRUE, PT := T#1s, ENO => w.6);\n"
        "lw := Local();",
    )
    r = run_st(src)
    assert (r.get("w"), r.get("lw")) == (8 + 16 + 32, 0xAB02)
