"""EN/ENO on functions and function blocks (runtime/st/check/checker_eno.py,
codegen_eno.py).

IEC 61131-3 ed.3 6.6.1.6 and Table 18: when EN is FALSE at the call, the
body is not executed and ENO is reset to FALSE; otherwise ENO is set TRUE
and the body runs, which may assign ENO. What the outputs hold when ENO is
FALSE the standard leaves to the implementation; here, as in CODESYS and
TwinCAT (a box with EN/ENO: "the operations defined in the POU are not
executed") and Panasonic's FPWIN ("the function result is not changed and
the connected variables keep their values"), nothing of the call happens:
no input is passed, no output written.
"""

from __future__ import annotations

from .conftest import codes, diagnostics, prog, run_st

SCALE = """
FUNCTION Scale : INT
VAR_INPUT IN : INT; END_VAR
VAR_OUTPUT twice : INT; END_VAR
twice := IN * 2;
IF IN < 0 THEN
    ENO := FALSE;  (* the body may reset ENO (ed.3 6.6.1.6 b) *)
END_IF
Scale := IN * 10;
END_FUNCTION

FUNCTION_BLOCK Counter
VAR_INPUT step : INT; END_VAR
VAR_OUTPUT count : INT; END_VAR
count := count + step;
IF count > 100 THEN
    ENO := FALSE;
END_IF
END_FUNCTION_BLOCK
"""


def test_a_function_runs_only_under_en_and_reports_eno():
    src = SCALE + prog(
        "r1 : INT := 7; r2 : INT := 7; r3 : INT := 7; t1 : INT := 5; t2 : INT := 5;"
        "ok1 : BOOL; ok2 : BOOL := TRUE; ok3 : BOOL := TRUE; c : BOOL;",
        "r1 := Scale(EN := TRUE, IN := 3, twice => t1, ENO => ok1);\n"
        "r2 := Scale(EN := c, IN := 3, twice => t2, ENO => ok2);\n"
        "r3 := Scale(IN := -1, ENO => ok3);",
    )
    runner = run_st(src)
    # EN TRUE: the body ran, ENO is TRUE
    assert (runner.get("r1"), runner.get("t1"), runner.get("ok1")) == (30, 6, True)
    # EN FALSE: not run; the output keeps its value, the value is the result's initial value
    assert (runner.get("r2"), runner.get("t2"), runner.get("ok2")) == (0, 5, False)
    # no EN: it runs; the body set ENO FALSE
    assert (runner.get("r3"), runner.get("ok3")) == (-10, False)


def test_a_function_block_under_en_keeps_its_state_and_outputs():
    src = SCALE + prog(
        "cnt : Counter; run : BOOL; ok : BOOL; n : INT; cycles : INT; inst_eno : BOOL;",
        "cycles := cycles + 1;\n"
        "run := cycles MOD 2 = 1;  (* runs in cycles 1, 3, 5 *)\n"
        "cnt(EN := run, step := 60, count => n, ENO => ok);\n"
        "inst_eno := cnt.ENO;",
    )
    runner = run_st(src, cycles=4)
    # cycles 1 and 3 ran (60, 120: ENO FALSE from the body in cycle 3); cycle 4 did not run
    assert (runner.get("n"), runner.get("cnt.count")) == (120, 120)
    assert (runner.get("ok"), runner.get("inst_eno")) == (False, False)
    runner.run(1)  # cycle 5 runs: 180 > 100, the body resets ENO again
    assert (runner.get("n"), runner.get("ok")) == (180, False)


def test_eno_is_true_after_a_call_that_ran():
    src = SCALE + prog(
        "cnt : Counter; ok : BOOL; n : INT;",
        "cnt(EN := TRUE, step := 1, count => n, ENO => ok);",
    )
    runner = run_st(src, cycles=3)
    assert (runner.get("n"), runner.get("ok"), runner.get("cnt.ENO")) == (3, True, True)


def test_standard_functions_called_formally_take_en_and_eno():
    src = prog(
        "x : REAL := 7.0; r1 : REAL := 1.0; r2 : REAL := 1.0; ok1 : BOOL; ok2 : BOOL := TRUE;"
        "i : INT := 9; m : INT := 3; ok3 : BOOL; s : INT := 4; ok4 : BOOL := TRUE;",
        "r1 := SQRT(EN := TRUE, IN := 16.0, ENO => ok1);\n"
        "r2 := SQRT(EN := x < 0.0, IN := x, ENO => ok2);\n"
        "m := ADD(EN := TRUE, IN1 := i, IN2 := 1, ENO => ok3);\n"
        "s := MAX(EN := FALSE, IN1 := i, IN2 := 1, ENO => ok4);",
    )
    runner = run_st(src)
    assert (runner.get("r1"), runner.get("ok1")) == (4.0, True)
    # EN FALSE: not evaluated; the value is the result type's initial value
    assert (runner.get("r2"), runner.get("ok2")) == (0.0, False)
    assert (runner.get("m"), runner.get("ok3")) == (10, True)
    assert (runner.get("s"), runner.get("ok4")) == (0, False)


def test_a_declared_eno_is_the_same_enable_output():
    src = """
FUNCTION_BLOCK Limit
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT y : INT; ENO : BOOL; END_VAR
y := x;
ENO := x <= 10;
END_FUNCTION_BLOCK
""" + prog(
        "a : Limit; b : Limit; oka : BOOL; okb : BOOL := TRUE;",
        "a(x := 5, ENO => oka);\nb(EN := FALSE, x := 50, ENO => okb);",
    )
    runner = run_st(src)
    assert (runner.get("a.y"), runner.get("oka"), runner.get("b.y"), runner.get("okb")) == (5, True, 0, False)


def test_code_without_en_or_eno_is_the_plain_call():
    """A POU that never names ENO has none: no extra variable, no extra work."""
    from softplc.runtime.program import compile_files

    plain = """
FUNCTION Twice : INT
VAR_INPUT IN : INT; END_VAR
Twice := IN * 2;
END_FUNCTION
FUNCTION_BLOCK Acc
VAR_INPUT step : INT; END_VAR
VAR_OUTPUT total : INT; END_VAR
total := total + step;
END_FUNCTION_BLOCK
""" + prog("a : Acc; r : INT;", "a(step := Twice(2));\nr := a.total;")
    code = compile_files([], profile="codesys", texts={"t.st": plain})
    assert "eno" not in code.python_source.lower()
    assert run_st(plain, cycles=2).get("r") == 8


def test_en_and_eno_errors_are_coded():
    src = SCALE + prog(
        "r : INT; i : INT; cnt : Counter;",
        "r := Scale(EN := i, IN := 1);\n"
        "r := Scale(IN := 1, ENO := TRUE);\n"
        "r := ABS(EN => r, IN := 1);\n"
        "cnt(EN := TRUE, EN := FALSE);",
    )
    found = [(d.code, d.pos.line) for d in diagnostics(src)]
    assert found == [("E020", 24), ("E040", 25), ("E046", 26), ("E041", 27)]


def test_a_declared_eno_that_is_not_a_bool_output_is_e045():
    src = "FUNCTION F : INT\nVAR_INPUT ENO : INT; END_VAR\nF := ENO;\nEND_FUNCTION\n" + prog("r : INT;", "r := F(1);")
    assert codes(src) == ["E045"]
    d = diagnostics(src)[0]
    assert (d.pos.line, d.pos.col) == (2, 11)
    assert "BOOL VAR_OUTPUT" in d.message and d.hint
