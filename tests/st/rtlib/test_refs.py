"""References: REF_TO / NULL in every position, reference initialisers in
arrays and structs, and the CODESYS REFERENCE TO (runtime/st/check/checker_refs.py,
codegen_exprs.py). Each test is a program and the values its variables hold
after the cycles run.

Semantics: IEC 61131-3 ed. 3, 6.4.4.10 (REF_TO, REF(), ^, NULL); CODESYS
"Data Type: REFERENCE TO", "Assignment Operator: REF=", "Operator:
__ISVALIDREF" (the same in TwinCAT 3, "REFERENCE").
"""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from ..conftest import codes, diagnostics, prog, run_st

# ---------------------------------------------------------------- REF_TO and NULL


def test_references_start_in_an_array_initialiser():
    # A variable's own initial value may take references (IEC: REF() of a
    # variable is a valid initial value); so may the elements of its array.
    src = prog(
        "x : INT; y : INT; rs : ARRAY[1..2] OF REF_TO INT := [REF(x), REF(y)];"
        "m : ARRAY[0..1, 0..1] OF REF_TO INT := [REF(x), NULL, NULL, REF(y)];",
        "rs[2]^ := 3; m[0, 0]^ := m[0, 0]^ + 4;",
    )
    r = run_st(src)
    assert (r.get("x"), r.get("y")) == (4, 3)


def test_references_start_in_a_struct_initialiser_of_the_variable():
    src = """
TYPE S : STRUCT r : REF_TO INT; n : INT; END_STRUCT END_TYPE
PROGRAM main
VAR x : INT; y : INT; s : S := (r := REF(x), n := 1); sa : ARRAY[1..2] OF S := [(r := REF(y)), (r := REF(x))]; END_VAR
s.r^ := 5; sa[1].r^ := sa[2].r^ + s.n;
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("x"), r.get("y")) == (5, 6)


def test_a_struct_type_field_still_starts_null():
    # the TYPE's own default cannot know which variable: E024 (README)
    src = """
VAR_GLOBAL g : INT; END_VAR
TYPE S : STRUCT r : REF_TO INT := REF(g); END_STRUCT END_TYPE
PROGRAM main
VAR s : S; END_VAR
END_PROGRAM
"""
    assert "E024" in codes(src)


def test_null_with_references_in_sel_and_move():
    # NULL has the type of the reference it meets (IEC 6.4.4.10.2)
    src = prog(
        "x : INT; r : REF_TO INT; a : BOOL; b : BOOL; c : BOOL;",
        "r := SEL(TRUE, NULL, REF(x)); a := r = REF(x); r := MOVE(NULL); b := r = NULL; c := NULL = NULL;",
    )
    r = run_st(src)
    assert (r.get("a"), r.get("b"), r.get("c")) == (True, True, True)


def test_a_function_block_is_called_through_a_reference():
    src = """
FUNCTION_BLOCK cnt
VAR_INPUT inc : INT := 1; END_VAR
VAR_OUTPUT n : INT; END_VAR
n := n + inc;
END_FUNCTION_BLOCK
PROGRAM main
VAR c : cnt; rc : REF_TO cnt; y : INT; END_VAR
rc := REF(c); rc^(inc := 2); rc^(); y := rc^.n;
END_PROGRAM
"""
    assert run_st(src, cycles=2).get("y") == 8


def test_ref_assign_of_a_function_local_compiles_and_runs():
    # REF= of a FUNCTION's local used to crash the code generator
    src = """
FUNCTION f : INT
VAR x : INT := 3; r : REF_TO INT; END_VAR
r REF= x; r^ := 8; f := x;
END_FUNCTION
PROGRAM main
VAR y : INT; END_VAR
y := f();
END_PROGRAM
"""
    assert run_st(src).get("y") == 8


def test_null_in_every_position():
    src = """
TYPE PR : REF_TO INT := NULL; END_TYPE
TYPE S : STRUCT r : REF_TO INT; n : INT; END_STRUCT END_TYPE
FUNCTION isnull : BOOL
VAR_INPUT r : REF_TO INT := NULL; END_VAR
isnull := r = NULL;
END_FUNCTION
PROGRAM main
VAR x : INT; r : REF_TO INT; q : PR; s : S := (r := NULL, n := 2); p : POINTER TO INT;
    a : ARRAY[1..8] OF BOOL; END_VAR
a[1] := NULL = r; a[2] := q = NULL; a[3] := s.r = NULL; a[4] := isnull();
p := ADR(x); a[5] := p <> 0; a[6] := 0 <> p; a[7] := isnull(NULL); a[8] := isnull(REF(x));
END_PROGRAM
"""
    assert run_st(src).get("a") == [True, True, True, True, True, True, True, False]


# ---------------------------------------------------------------- REFERENCE TO (CODESYS)


def test_reference_to_is_dereferenced_implicitly_and_bound_with_ref_assign():
    # CODESYS: "ref := value" writes the value where ref points; "ref REF= x"
    # binds it; reading ref reads x.
    src = prog(
        "x : INT := 1; y : INT := 10; r : REFERENCE TO INT; r2 : REFERENCE TO INT; v : BOOL; w : BOOL; z : INT;",
        "v := __ISVALIDREF(r);\n"
        "r REF= x; r := r + 1; w := __ISVALIDREF(r);\n"
        "r2 REF= y; r := r2; r2 REF= r; r2 := r2 * 5; z := r;",
    )
    r = run_st(src)
    # r := r2 copies y's value into x (both dereferenced); r2 REF= r binds r2 to x
    assert (r.get("x"), r.get("y"), r.get("v"), r.get("w"), r.get("z")) == (50, 10, False, True, 50)


def test_reference_to_as_input_in_out_struct_field_and_function_input():
    # a call binds a REFERENCE TO input to the variable passed (CODESYS)
    src = """
TYPE S : STRUCT a : INT; r : REFERENCE TO INT; END_STRUCT END_TYPE
FUNCTION_BLOCK fb
VAR_INPUT ri : REFERENCE TO INT; END_VAR
VAR_IN_OUT rio : REFERENCE TO INT; END_VAR
VAR_OUTPUT ok : BOOL; END_VAR
ok := __ISVALIDREF(ri);
IF ok THEN ri := ri + 10; END_IF
rio := rio * 2;
END_FUNCTION_BLOCK
FUNCTION twice : INT
VAR_INPUT r : REFERENCE TO INT; END_VAR
r := r * 2; twice := r;
END_FUNCTION
PROGRAM main
VAR x : INT := 1; y : INT := 3; s : S; f : fb; t : INT; z : INT := 5; rs : REFERENCE TO S; q : INT; END_VAR
s.r REF= y; s.r := s.r + x;
f(ri := x, rio := y);
t := twice(z);
rs REF= s; rs.a := 9; q := s.a;
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("x"), r.get("y"), r.get("t"), r.get("z"), r.get("q")) == (11, 8, 10, 10, 9)


def test_reference_to_bound_in_its_declaration():
    src = """
VAR_GLOBAL g : INT; gr : REFERENCE TO INT := g; END_VAR
TYPE S : STRUCT r : REFERENCE TO INT; END_STRUCT END_TYPE
PROGRAM main
VAR x : INT; arr : ARRAY[1..2] OF INT; r : REFERENCE TO INT := arr[2]; s : S := (r := x); END_VAR
r := 7; s.r := 3; gr := 2;
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("x"), r.get("arr"), r.get("g")) == (3, [0, 7], 2)


def test_reference_to_a_function_block_and_a_bool():
    src = """
FUNCTION_BLOCK cnt
VAR_INPUT inc : INT := 1; END_VAR
VAR_OUTPUT n : INT; END_VAR
n := n + inc;
END_FUNCTION_BLOCK
PROGRAM main
VAR c : cnt; rc : REFERENCE TO cnt; y : INT; b : BOOL; rb : REFERENCE TO BOOL; END_VAR
rc REF= c; rc(inc := 2); rc(); y := rc.n;
rb REF= b; rb := TRUE; rb := NOT rb; SET rb;
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("y"), r.get("b")) == (4, True)


def test_an_unbound_reference_to_is_a_runtime_fault_at_its_use():
    src = prog("r : REFERENCE TO INT; y : INT;", "y := 1;\ny := r;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "reference" and (err.value.pos.file, err.value.pos.line) == ("test.st", 6)
    assert "unbound REFERENCE TO" in err.value.message


def test_ref_assign_null_unbinds_a_reference_to():
    src = prog(
        "x : INT; r : REFERENCE TO INT; a : BOOL; b : BOOL;",
        "r REF= x; a := __ISVALIDREF(r); r REF= 0; b := __ISVALIDREF(r);",
    )
    r = run_st(src)
    assert (r.get("a"), r.get("b")) == (True, False)


@pytest.mark.parametrize(
    "decls,body,code,line,col",
    [
        # CODESYS: no ARRAY OF, POINTER TO or REFERENCE TO a reference type
        ("a : ARRAY[1..2] OF REFERENCE TO INT;", "", "E160", 3, 20),
        ("p : POINTER TO REFERENCE TO INT;", "", "E160", 3, 16),
        ("r : REFERENCE TO REFERENCE TO INT;", "", "E160", 3, 18),
        ("r : REFERENCE TO INT;", "r REF= 5;", "E031", 5, 8),
        ("r : REFERENCE TO INT; y : INT;", "r REF= y + 1;", "E031", 5, 8),
        ("r : REFERENCE TO INT; y : REAL;", "r REF= y;", "E020", 5, 8),
        ("r : REFERENCE TO INT; y : INT;", "y REF= r;", "E020", 5, 1),
        ("r : REF_TO INT; b : BOOL;", "b := __ISVALIDREF(r);", "E160", 5, 19),
    ],
)
def test_reference_to_errors_are_coded_and_located(decls, body, code, line, col):
    d = [x for x in diagnostics(prog(decls, body)) if x.severity == "error"]
    assert [(x.code, x.pos.line, x.pos.col) for x in d] == [(code, line, col)]
    assert d[0].hint


def test_a_reference_input_needs_a_variable_of_its_type():
    src = """
FUNCTION_BLOCK fb
VAR_INPUT ri : REFERENCE TO INT; END_VAR
END_FUNCTION_BLOCK
PROGRAM main
VAR f : fb; r : REAL; END_VAR
f(ri := r); f(ri := 3);
END_PROGRAM
"""
    assert codes(src) == ["E020", "E031"]
