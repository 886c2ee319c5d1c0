"""Pointer arithmetic (CODESYS POINTER TO, runtime/st/check/checker_pointers.py,
codegen_pointers.py, refs.py ElemPtr/ObjPtr): a program and the values its
variables hold after the cycles run.

CODESYS ("Data Type: POINTER TO", "Operator: ADR") computes with addresses:
`p := p + SIZEOF(INT)` steps one INT, `ADR(arr) + i * SIZEOF(INT)` is the
i-th element (from 0), `p2 - p1` is a distance in bytes. Here a pointer
stays bound to the object it points into; a dereference outside that object
is a 'reference' fault at the ST location, where a PLC would read or write
another variable's memory.
"""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import diagnostics, prog, run_st


def test_a_pointer_walks_an_array_by_sizeof_steps():
    src = prog(
        "arr : ARRAY[1..5] OF INT := [1, 2, 3, 4, 5]; p : POINTER TO INT; pend : POINTER TO INT;"
        "s : INT; i : INT; q : POINTER TO INT; n : INT;",
        "p := ADR(arr); pend := ADR(arr[5]);\n"  # ADR(arr): a pointer to the first element
        "WHILE p <= pend DO s := s + p^; p := p + SIZEOF(INT); END_WHILE\n"
        "q := ADR(arr) + 2 * SIZEOF(arr[1]); q^ := 30;\n"
        "FOR i := 0 TO 4 DO q := ADR(arr) + i * SIZEOF(INT); n := n + q^; END_FOR",
    )
    r = run_st(src)
    assert (r.get("s"), r.get("arr"), r.get("n")) == (15, [1, 2, 30, 4, 5], 42)


def test_pointer_difference_and_comparison():
    src = prog(
        "arr : ARRAY[0..9] OF DINT; p : POINTER TO DINT; q : POINTER TO DINT; d : DINT; lt : BOOL; "
        "ge : BOOL; eq : BOOL; ne : BOOL;",
        "p := ADR(arr[1]); q := ADR(arr) + 7 * SIZEOF(DINT);\n"
        "d := q - p; lt := p < q; ge := p >= q;\n"
        "p := p + 6 * SIZEOF(DINT); eq := p = q; ne := p <> ADR(arr[7]);",
    )
    r = run_st(src)
    # the distance is in bytes: 6 DINTs
    assert (r.get("d"), r.get("lt"), r.get("ge"), r.get("eq"), r.get("ne")) == (24, True, False, True, False)


def test_a_pointer_steps_over_structures_and_across_rows():
    src = """
TYPE S : STRUCT a : INT; b : LREAL; END_STRUCT END_TYPE
PROGRAM main
VAR sa : ARRAY[0..2] OF S; ps : POINTER TO S; m : ARRAY[1..2, 1..3] OF INT; pm : POINTER TO INT; k : INT;
    a2 : INT; b2 : LREAL; END_VAR
ps := ADR(sa[0]); ps^.a := 1; ps := ps + SIZEOF(S); ps := ps + SIZEOF(S); ps^.a := 2; ps^.b := 2.5;
a2 := sa[2].a; b2 := sa[2].b;
pm := ADR(m[1, 3]); pm := pm + SIZEOF(INT); pm^ := 7;   (* row-major: m[2, 1] follows m[1, 3] *)
FOR k := 1 TO 6 DO pm := ADR(m) + (k - 1) * SIZEOF(INT); pm^ := pm^ + k; END_FOR
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("a2"), r.get("b2"), r.get("m")) == (2, 2.5, [[1, 2, 3], [11, 5, 6]])


def test_a_pointer_initialised_to_an_array_and_moved_back_to_its_variable():
    src = """
VAR_GLOBAL g : ARRAY[0..3] OF DINT := [10, 20, 30, 40]; END_VAR
PROGRAM main
VAR p : POINTER TO DINT := ADR(g); y : DINT; x : INT := 4; px : POINTER TO INT; z : INT; same : BOOL; END_VAR
p := p + 8; y := p^;
px := ADR(x) + 2; px := px - 2; z := px^; same := px = ADR(x);
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("y"), r.get("z"), r.get("same")) == (30, 4, True)


@pytest.mark.parametrize(
    "decls,body,message",
    [
        # past the end of its array
        ("arr : ARRAY[1..3] OF INT; p : POINTER TO INT; y : INT;", "p := ADR(arr[3]) + 2;\ny := p^;", "byte offset 6"),
        # before its start, written through
        ("arr : ARRAY[1..3] OF INT; p : POINTER TO INT;", "p := ADR(arr) - 2;\np^ := 1;", "byte offset -2"),
        # between two elements: p + 1 on a POINTER TO INT
        ("arr : ARRAY[1..3] OF INT; p : POINTER TO INT; y : INT;", "p := ADR(arr) + 1;\ny := p^;", "between"),
        # off a single variable: never the next variable's memory
        ("x : DINT; y : DINT; p : POINTER TO DINT;", "p := ADR(x) + 4;\ny := p^;", "off its variable"),
        # arithmetic on NULL
        ("p : POINTER TO INT;", "p := NULL;\np := p + 2;", "NULL"),
    ],
)
def test_a_dereference_outside_the_object_is_a_located_fault(decls, body, message):
    with pytest.raises(STFault) as err:
        run_st(prog(decls, body))
    assert err.value.kind == "reference" and (err.value.pos.file, err.value.pos.line) == ("test.st", 6)
    assert message in err.value.message


@pytest.mark.parametrize(
    "decls,body,col,words",
    [
        ("r : REF_TO INT;", "r := r + 2;", 6, "REF_TO INT allows no arithmetic"),
        ("p : POINTER TO INT;", "p := p + 1.5;", 6, "integer number of bytes"),
        ("p : POINTER TO INT;", "p := 2 - p;", 6, "minus a pointer"),
        ("p : POINTER TO INT; q : POINTER TO REAL; d : DINT;", "d := p - q;", 6, "INT and to REAL"),
        ("p : POINTER TO INT; b : BOOL;", "b := p < 3;", 6, "no pointer arithmetic"),
        # a byte view of a function block instance (its layout is the compiler's: README)
        ("f : TON; pb : POINTER TO BYTE;", "pb := ADR(f);", 7, "POINTER TO BYTE over TON"),
    ],
)
def test_pointer_errors_are_coded_and_located(decls, body, col, words):
    d = [x for x in diagnostics(prog(decls, body)) if x.severity == "error"]
    assert [(x.code, x.pos.line, x.pos.col) for x in d] == [("E161", 5, col)]
    assert words in d[0].message and d[0].hint


def test_a_pointer_to_byte_over_a_byte_array_is_no_punning():
    src = prog(
        "buf : ARRAY[0..3] OF BYTE := [1, 2, 3, 4]; pb : POINTER TO BYTE; s : INT; i : INT;",
        "pb := ADR(buf);\nFOR i := 0 TO 3 DO s := s + pb^; pb := pb + 1; END_FOR",
    )
    assert run_st(src).get("s") == 10
