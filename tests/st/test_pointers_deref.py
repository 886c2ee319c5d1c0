"""Dereferencing a pointer-valued expression (grammar.lark deref_postfix,
build_exprs.py paren_deref): `(p + 2)^`, `(ps + SIZEOF(S))^.b` and a
function's result `g(p)^`, as CODESYS allows ("Data Type: POINTER TO": the
dereference operator ^ applies to any pointer-valued operand)."""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import diagnostics, run_st

_SRC = """
TYPE S : STRUCT a : INT; b : INT; END_STRUCT END_TYPE
FUNCTION next2 : POINTER TO INT
VAR_INPUT p : POINTER TO INT; END_VAR
next2 := p + SIZEOF(INT);
END_FUNCTION
PROGRAM main
VAR arr : ARRAY[0..3] OF INT := [1, 2, 3, 4]; p : POINTER TO INT; a, b, c, d : INT; k : INT := 2;
    sa : ARRAY[0..1] OF S; ps : POINTER TO S; pp : POINTER TO POINTER TO INT; END_VAR
p := ADR(arr);
a := (p + 2 * SIZEOF(INT))^ * 10;
b := next2(p)^ + next2(next2(p))^;
ps := ADR(sa); sa[1].b := 7; c := (ps + SIZEOF(S))^.b;
pp := ADR(p); d := (pp)^^ + (pp^ + 6)^;
CASE k OF  (* a CASE label in parentheses still reads as a label *)
(1): k := 0;
(2): k := 9;
END_CASE
END_PROGRAM
"""


def test_a_parenthesised_pointer_expression_and_a_function_result_are_dereferenced():
    r = run_st(_SRC)
    assert (r.get("a"), r.get("b"), r.get("c"), r.get("d"), r.get("k")) == (30, 5, 7, 5, 9)


def test_a_dereferenced_expression_outside_its_array_is_a_located_fault():
    src = _SRC.replace("a := (p + 2 * SIZEOF(INT))^ * 10;", "a := (p + 8)^;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "reference" and err.value.pos.line == 11


def test_a_dereferenced_non_pointer_is_an_error():
    src = "PROGRAM main\nVAR x : INT; y : INT; END_VAR\ny := (x + 1)^;\nEND_PROGRAM\n"
    d = [x for x in diagnostics(src) if x.severity == "error"]
    assert [(x.code, x.pos.line, x.pos.col) for x in d] == [("E020", 3, 6)] and "needs a REF_TO or POINTER TO" in d[
        0
    ].message
