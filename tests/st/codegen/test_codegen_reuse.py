"""An array element read once for the statements that follow
(runtime/st/codegen/codegen_reuse.py). Each test changes the element
between two reads in a way the generator must see (a store, a reference
into the array, a call that reaches it, a branch, a loop); the second
read must give the new value."""

from __future__ import annotations

import pytest

from softplc.runtime.program import compile_files

from ..conftest import prog, run_st

DECLS = "a : ARRAY[1..3] OF INT := [1, 2, 3]; i, k, x, y : INT; go : BOOL := TRUE;"


def test_an_element_read_twice_in_a_loop_is_read_once():
    text = prog(DECLS, "FOR i := 1 TO 3 DO x := x + a[i]; y := y + a[i] * 10; END_FOR")
    src = compile_files([], texts={"test.st": text}).python_source
    body = src[src.index("class P_main") :]
    assert body.count("_a_v_a[_i") + body.count("self.v_a[_i") == 1
    r = run_st(text)
    assert (r.get("x"), r.get("y")) == (6, 60)


@pytest.mark.parametrize(
    "body,y",
    [
        ("FOR i := 2 TO 2 DO x := a[i]; a[i] := 50; y := a[i]; END_FOR", 50),  # a store
        ("FOR i := 2 TO 2 DO x := a[i]; a := b; y := a[i]; END_FOR", 7),  # the whole array
        ("x := a[2]; IF go THEN a[2] := 50; END_IF y := a[2];", 50),  # in a branch
        ("x := a[2]; IF go THEN x := a[2]; a[2] := 50; x := a[2]; END_IF y := a[2];", 50),
        ("x := a[2]; CASE k OF 0: a[2] := 50; END_CASE y := a[2];", 50),
        # bound before the loop, stored in it
        ("x := a[2]; WHILE k < 2 DO y := a[2]; a[2] := a[2] + 1; k := k + 1; END_WHILE", 3),
        ("x := a[2]; p := ADR(a[2]); p^ := 50; y := a[2];", 50),  # a pointer into it
        ("x := a[2]; Fill(v := a[2]); y := a[2];", 50),  # VAR_IN_OUT
        ("x := a[2]; y := (a[2] := 25) + a[2];", 50),  # an assignment inside an expression
        ("x := a[2]; t(IN := TRUE, Q => f[2]); x := a[2]; IF f[2] THEN y := 50; END_IF", 50),  # =>
        # stored, then read (from the store, until something changes it again); clamped in
        # branches: what each branch stored, or what was stored before
        ("a[2] := 70; IF a[2] > 50 THEN a[2] := 50; ELSIF a[2] < 0 THEN a[2] := -1; END_IF y := a[2];", 50),
        ("a[2] := -7; IF a[2] > 50 THEN a[2] := 50; ELSIF a[2] < 0 THEN a[2] := -1; END_IF y := a[2];", -1),
        ("a[2] := 7; IF a[2] > 50 THEN a[2] := 50; ELSIF a[2] < 0 THEN a[2] := -1; END_IF y := a[2];", 7),
        ("a[2] := -3; y := a[2] ** 2;", 9),  # a negative literal stored: (-3) ** 2
        ("a[2] := -3; y := -a[2];", 3),
        ("FOR i := 1 TO 3 DO a[i] := i; a[2] := 9; x := x + a[i]; END_FOR y := x;", 1 + 9 + 3),  # i = 2: a[2]
        ("FOR i := 1 TO 3 DO a[i] := i; k := 2; a[k] := 9; x := x + a[i]; END_FOR y := x;", 1 + 9 + 3),
        ("a[2] := 5; x := a[2]; Fill(v := a[2]); y := a[2] + x;", 55),  # VAR_IN_OUT
        ("a[2] := 5; WHILE k < 2 DO a[2] := a[2] + 1; k := k + 1; END_WHILE y := a[2];", 7),
        ("a[2] := 5; a := b; y := a[2];", 7),  # the whole array
        ("FOR i := 1 TO 3 DO a[i] := 100 * i; a[i] := a[i] + 1; y := y + a[i]; END_FOR", 603),
    ],
)
def test_an_element_changed_between_two_reads_is_read_again(body, y):
    text = f"""
FUNCTION Fill : BOOL
VAR_IN_OUT v : INT; END_VAR
v := 50;
Fill := TRUE;
END_FUNCTION
FUNCTION_BLOCK Pulse
VAR_INPUT IN : BOOL; END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
Q := IN;
END_FUNCTION_BLOCK
PROGRAM main
VAR {DECLS} b : ARRAY[1..3] OF INT := [5, 7, 9]; p : POINTER TO INT; f : ARRAY[1..3] OF BOOL; t : Pulse; END_VAR
{body}
END_PROGRAM
"""
    assert run_st(text).get("y") == y


def test_an_action_that_stores_into_the_array_is_seen():
    text = """
PROGRAM main
VAR a : ARRAY[1..3] OF INT; x, y : INT; END_VAR
x := a[2];
Fill();
y := a[2];
END_PROGRAM
ACTION main.Fill:
a[2] := 50;
END_ACTION
"""
    assert run_st(text).get("y") == 50


def test_an_element_stored_is_read_from_the_store_by_the_statements_after_it():
    text = prog(
        "a : ARRAY[1..3] OF REAL; lo, hi : REAL; i : INT;",
        "FOR i := 1 TO 3 DO a[i] := INT_TO_REAL(i) / 4.0; IF a[i] < 0.5 THEN lo := a[i]; END_IF hi := a[i]; END_FOR",
    )
    src = compile_files([], texts={"test.st": text}).python_source
    body = src[src.index("class P_main") :]
    [store] = [line.strip() for line in body.splitlines() if "v_a[_i" in line]
    local = store.split(" = ")[1]
    assert local.startswith("_e") and body.count(local) == 4  # bound, compared, then read twice
    r = run_st(text)
    assert (r.get("lo"), r.get("hi")) == (0.25, 0.75)
