"""The checker's variables (runtime/st/check/checker_decls.py): declarations and
their initial values."""

from __future__ import annotations

from ..conftest import codes, diagnostics, prog, run_st


def test_retain_where_nothing_can_be_kept_is_a_warning():
    src = (
        "FUNCTION F : INT\nVAR RETAIN t : INT; END_VAR\nF := t;\nEND_FUNCTION\n"
        "PROGRAM main\nVAR RETAIN\n    kept : INT;\n    x AT %MW4 : INT;\nEND_VAR\n"
        "VAR_TEMP PERSISTENT\n    tmp : INT;\nEND_VAR\nkept := F() + x + tmp;\nEND_PROGRAM\n"
    )
    found = [(d.code, d.pos.line, d.message.split(",")[0]) for d in diagnostics(src)]
    assert found == [
        ("W111", 2, "RETAIN has no effect on t"),
        ("W111", 8, "RETAIN has no effect on x"),
        ("W111", 11, "PERSISTENT has no effect on tmp"),
    ]


def test_external_globals_array_initialisers_and_in_outs():
    src = (
        "PROGRAM main\nVAR_EXTERNAL g : INT; END_VAR\n"
        "VAR a : ARRAY[1..2] OF INT := [1, 2, 3]; p : INT := q; END_VAR\nEND_PROGRAM\n"
        "FUNCTION_BLOCK F\nVAR_IN_OUT io : INT := 1; END_VAR\nEND_FUNCTION_BLOCK\n"
    )
    assert [(d.code, d.message, d.pos.line) for d in diagnostics(src)] == [
        ("E010", "VAR_EXTERNAL 'g' has no VAR_GLOBAL", 2),
        ("E052", "3 initial values for 'a', which has 2 elements", 3),
        ("E010", "unknown name 'q'", 3),
        ("E024", "a VAR_IN_OUT cannot have an initial value", 6),
    ]


def test_a_constant_sizes_the_arrays_declared_after_it():
    src = "PROGRAM main\nVAR CONSTANT n : INT := 3; END_VAR\nVAR a : ARRAY[1..n] OF INT; END_VAR\nEND_PROGRAM\n"
    assert codes(src) == []
    assert codes(prog("n : INT := 3; a : ARRAY[1..n] OF INT;", "")) == ["E025"]


def test_a_reference_starts_at_a_variable_at_a_fixed_place_or_at_null():
    src = (
        "TYPE S : STRUCT r : REF_TO INT := REF(gx); END_STRUCT END_TYPE\n"
        "VAR_GLOBAL gx : INT; END_VAR\n"
        "FUNCTION F : INT\nVAR_INPUT r : REF_TO INT := REF(gx); END_VAR\nF := 1;\nEND_FUNCTION\n"
        "PROGRAM main\nVAR i : INT; a : ARRAY[1..3] OF INT;\n"
        "r1 : REF_TO INT := REF(a[i]);\nr2 : REF_TO INT := r1;\n"
        "r3 : REF_TO INT := NULL; r4 : REF_TO INT := 0; r5 : REF_TO INT := REF(a[3]);\nEND_VAR\nEND_PROGRAM\n"
    )
    assert [(d.code, d.pos.line, d.message) for d in diagnostics(src)] == [
        ("E024", 1, "'S.r' cannot start with a reference"),
        ("E024", 4, "'r' cannot start with a reference"),
        ("E024", 9, "the initial value of 'r1' is not a reference to a variable at a fixed place"),
        ("E024", 10, "the initial value of 'r2' is not a reference to a variable at a fixed place"),
    ]


def test_a_huge_repetition_count_is_counted_not_built():
    [d] = diagnostics(prog("a : ARRAY[0..9] OF INT := [1, 10000000000000000(0)];", ""))
    assert (d.code, d.pos.line, d.pos.col) == ("E052", 3, 27)
    assert d.message == "10,000,000,000,000,001 initial values for 'a', which has 10 elements"


def test_an_elementary_type_name_is_no_variable_name():
    """Found by tests/fuzz: a global named TIME hid the standard function
    TIME() from the library's timers, whose errors then pointed into files
    the user did not write. It is an IEC keyword: the declaration is the error."""
    src = "VAR_GLOBAL TIME : INT; END_VAR\n" + prog("x : INT;", "x := 1;")
    found = diagnostics(src)
    assert [d.code for d in found] == ["E011"]
    assert found[0].pos.file == "test.st" and found[0].pos.line == 1
    assert "'TIME' is the name of an elementary type" in found[0].message
    assert codes(prog("int : INT; Date : DINT;", "")) == ["E011", "E011"]
    assert codes(prog("time_1 : INT; ton1 : TON;", "")) == []


INPUT_CONSTANT = """
FUNCTION_BLOCK Every
VAR_INPUT CONSTANT
    N : UINT;
    OFS : UINT := 1;
END_VAR
VAR_OUTPUT Q : BOOL; END_VAR
VAR cnt : UINT; END_VAR
cnt := cnt + 1;
Q := cnt MOD N = OFS;
END_FUNCTION_BLOCK
PROGRAM main
VAR e : Every; hits : INT; END_VAR
e(N := 3);
IF e.Q THEN hits := hits + 1; END_IF;
END_PROGRAM
"""


def test_a_var_input_constant_is_the_calls_value_not_a_constant():
    # CODESYS's VAR_INPUT CONSTANT (OSCAT's SCHEDULER_2): read-only in the
    # block, given by the call; N's declared value (0) is no constant to
    # fold: MOD N is no division by zero
    r = run_st(INPUT_CONSTANT, cycles=9)
    assert r.get("hits") == 3  # cycles 1, 4, 7
    written = INPUT_CONSTANT.replace("cnt := cnt + 1;", "cnt := cnt + 1;\nN := 2;")
    assert codes(written) == ["E030"]
