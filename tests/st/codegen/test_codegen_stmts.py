"""Generated statements and stores (runtime/st/codegen/codegen_stmts.py): wrap on
store, REAL precision, string length, value copies, loops, CASE, the
watchdog."""

from __future__ import annotations

import struct

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.st.faults import STFault

from ..conftest import prog, run_st


@pytest.mark.parametrize(
    "ty,start,delta,expected",
    [
        ("SINT", 127, 1, -128),
        ("INT", 32767, 1, -32768),
        ("DINT", 2147483647, 1, -2147483648),
        ("LINT", 9223372036854775807, 1, -9223372036854775808),
        ("USINT", 255, 1, 0),
        ("UINT", 0, -1, 65535),
        ("UDINT", 4294967295, 1, 0),
        ("ULINT", 0, -1, 18446744073709551615),
        ("BYTE", 255, 1, 0),
        ("WORD", 65535, 1, 0),
        ("DWORD", 0, -1, 4294967295),
        ("LWORD", 18446744073709551615, 1, 0),
    ],
)
def test_integers_wrap_on_store(ty, start, delta, expected):
    r = run_st(prog(f"x : {ty} := {start};", f"x := x + ({delta});"))
    assert r.get("x") == expected


def test_intermediate_results_are_not_wrapped_before_the_store():
    # (a + b) / 2 with INTs: the sum is computed wide, only the store wraps
    r = run_st(prog("a : INT := 30000; b : INT := 30000; m : INT;", "m := (a + b) / 2;"))
    assert r.get("m") == 30000


def test_real_is_rounded_to_32_bits_and_lreal_is_not():
    r = run_st(
        prog(
            "r : REAL; l : LREAL; big : REAL; x : REAL := 1.0; y : REAL := 3.0; q : REAL;",
            "r := 0.1; l := 0.1; big := DINT_TO_REAL(16777217); q := x / y;",
        )
    )
    f32 = struct.unpack("<f", struct.pack("<f", 0.1))[0]
    assert r.get("r") == f32 == 0.10000000149011612
    assert r.get("l") == 0.1
    assert r.get("big") == 16777216.0
    assert r.get("q") == struct.unpack("<f", struct.pack("<f", 1 / 3))[0]


def test_string_is_truncated_to_its_declared_length():
    r = run_st(prog("s : STRING[5]; t : STRING := 'abc';", "s := CONCAT(t, 'defgh');"))
    assert r.get("s") == "abcde"


def test_structs_arrays_and_fb_instances_copy_by_value():
    src = """
TYPE Point : STRUCT x : INT; y : INT := 3; END_STRUCT END_TYPE
PROGRAM main
VAR p1, p2 : Point; a1, a2 : ARRAY[1..3] OF Point; c1, c2 : CTU; END_VAR
p1.x := 1; p2 := p1; p1.x := 99;
a1[2].y := 5; a2 := a1; a1[2].y := 6;
c1(CU := TRUE, PV := 10); c2 := c1; c1(CU := FALSE); c1(CU := TRUE);
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("p2.x") == 1 and r.get("p2.y") == 3 and r.get("p1.x") == 99
    assert r.get("a2")[1].f_y == 5 and r.get("a1")[1].f_y == 6
    assert r.get("c1.CV") == 2 and r.get("c2.CV") == 1


def test_for_loop_leaves_the_variable_past_the_end_and_exit_keeps_it():
    src = prog(
        "i : INT; j : INT; s : INT; k : INT;",
        "FOR i := 1 TO 10 BY 3 DO s := s + i; END_FOR\n"
        "FOR j := 10 TO 1 BY -1 DO IF j = 4 THEN EXIT; END_IF END_FOR\n"
        "FOR k := 5 TO 1 DO s := 1000; END_FOR",
    )
    r = run_st(src)
    assert r.get("s") == 1 + 4 + 7 + 10
    assert r.get("i") == 13 and r.get("j") == 4 and r.get("k") == 5


def test_for_loop_to_the_top_of_its_type_leaves_the_variable_wrapped():
    # the value past the end of constant bounds is computed when compiling: 128 wraps in a SINT
    src = prog(
        "b : SINT; u : USINT; n : INT;",
        "FOR b := 120 TO 127 DO n := n + 1; END_FOR\nFOR u := 250 TO 255 DO n := n + 1; END_FOR",
    )
    r = run_st(src)
    assert (r.get("b"), r.get("u"), r.get("n")) == (-128, 0, 14)


def test_arrays_and_instances_read_through_locals_see_every_store_into_them():
    # a body reads the arrays and FB instances of self it uses more than once through
    # locals: whole assignments copy into the same objects, so every read sees them
    src = prog(
        "a : ARRAY[0..2] OF INT; b : ARRAY[0..2] OF INT; p : POINTER TO ARRAY[0..2] OF INT;"
        " t1 : TON; t2 : TON; s : INT; q : BOOL;",
        "b[1] := 5; a := b; s := a[1]; b[1] := 7; s := s + a[1] * 10 + b[1] * 100;\n"
        "p := ADR(a); p^[2] := 9; s := s + a[2] * 1000;\n"
        "t2(IN := TRUE, PT := T#0ms); t1 := t2; q := t1.Q AND t2.Q;",
    )
    r = run_st(src)
    assert (r.get("s"), r.get("a"), r.get("q")) == (5 + 50 + 700 + 9000, [0, 5, 9], True)


def test_while_repeat_continue():
    src = prog(
        "i : INT; odd : INT; n : INT;",
        "WHILE i < 10 DO i := i + 1; IF i MOD 2 = 0 THEN CONTINUE; END_IF odd := odd + 1; END_WHILE\n"
        "REPEAT n := n + 1; IF n < 3 THEN CONTINUE; END_IF UNTIL n >= 5 END_REPEAT",
    )
    r = run_st(src)
    assert r.get("odd") == 5 and r.get("n") == 5


def test_case_with_lists_ranges_enums_and_else():
    src = """
TYPE Mode : (Idle, Run := 5, Fault); END_TYPE
PROGRAM main
VAR k : INT; out : ARRAY[0..6] OF INT; m : Mode := Mode#Fault; name : INT; END_VAR
FOR k := 0 TO 6 DO
  CASE k OF
    0, 1: out[k] := 1;
    2..4: out[k] := 2;
  ELSE out[k] := 9;
  END_CASE
END_FOR
CASE m OF Idle: name := 1; Run: name := 2; Fault: name := 3; END_CASE
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("out") == [1, 1, 2, 2, 2, 9, 9]
    assert r.get("name") == 3 and r.get("m") == 6


def test_subrange_violation_is_a_fault():
    src = prog("pct : INT(0..100); v : INT := 101;", "pct := 50; pct := v;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "range"


# ---------------------------------------------------------------- the watchdog on loop back-edges


def _runner(source: str, watchdog_s: float):
    r = compile_files([], texts={"w.st": source}).runner("main")
    r.ctx.watchdog_s = watchdog_s  # the watchdog counts this thread's CPU time: no host can make it late
    return r


ENDLESS = {
    "WHILE": "WHILE TRUE DO n := n + 1; END_WHILE",
    "REPEAT": "REPEAT n := n + 1; UNTIL FALSE END_REPEAT",
    "FOR": "FOR i := 0 TO 2147483647 DO n := n + 1; END_FOR",
    "FOR BY": "FOR i := 2147483647 TO 0 BY step DO n := n + 1; END_FOR",
    "FOR LINT": "FOR l := 0 TO 9223372036854775807 DO n := n + 1; END_FOR",
}


@pytest.mark.parametrize("loop", ENDLESS)
def test_the_watchdog_stops_an_endless_loop_at_the_loop(loop):
    # FOR i := 0 TO 2147483647 ran for minutes before: no check on its back-edge
    r = _runner(prog("n : DINT; i : DINT; l : LINT; step : DINT := -1;", ENDLESS[loop]), 0.02)
    with pytest.raises(STFault) as err:
        r.run(1)
    fault = err.value
    assert fault.kind == "watchdog" and "longer than 20 ms" in fault.message
    assert (fault.pos.file, fault.pos.line, fault.pos.col) == ("w.st", 5, 1)
    assert r.get("n") > 0


def test_the_watchdog_leaves_the_for_variable_at_the_pass_it_stopped():
    r = _runner(prog("n : DINT; i : DINT; l : LINT; step : DINT := -1;", ENDLESS["FOR"]), 0.02)
    with pytest.raises(STFault):
        r.run(1)
    assert r.get("i") == r.get("n") - 1 > 0  # the pass that was running, not the value before the loop


# ---------------------------------------------------------------- a fault inside a FOR loop
# The body reads the loop variable from a Python local and the variable is
# stored after the loop: a fault in a pass must still leave it at that pass,
# as the monitor shows it (CODESYS shows the index that failed).

SUM = """FUNCTION_BLOCK Sum
VAR i : INT; a : ARRAY[0..3] OF INT := [1, 2, 3, 4]; s : INT; END_VAR
s := 0;
FOR i := 0 TO 5 DO
  s := s + a[i];
END_FOR
END_FUNCTION_BLOCK
"""


def _faulted(source: str, entry: str = "main"):
    r = compile_files([], texts={"f.st": source}).runner(entry)
    with pytest.raises(STFault) as err:
        r.run(1)
    return r, err.value


def test_a_fault_in_a_for_loop_leaves_the_variable_at_the_failing_pass():
    src = prog("i : INT; a : ARRAY[0..3] OF INT := [1, 2, 3, 4]; s : INT;", "FOR i := 0 TO 5 DO s := s + a[i]; END_FOR")
    r, fault = _faulted(src)
    assert fault.kind == "bounds" and "index 4" in fault.message and fault.pos.line == 5
    assert (r.get("i"), r.get("s")) == (4, 10)


def test_in_a_function_block_too():
    r, fault = _faulted(SUM + "PROGRAM main VAR f : Sum; END_VAR f(); END_PROGRAM\n")
    assert "index 4" in fault.message and (fault.pos.file, fault.pos.line) == ("f.st", 5)
    assert (r.get("f.i"), r.get("f.s")) == (4, 10)


def test_nested_loops_leave_both_variables_at_their_pass():
    src = prog(
        "i : INT; j : INT; a : ARRAY[0..2, 0..2] OF INT;",
        "FOR i := 0 TO 2 DO FOR j := 0 TO 3 DO a[i, j] := i + j; END_FOR END_FOR",
    )
    r, _fault = _faulted(src)
    assert (r.get("i"), r.get("j")) == (0, 3)


def test_a_fault_after_a_finished_loop_leaves_its_value_after_the_end():
    src = prog("i : INT; k : INT; a : ARRAY[0..3] OF INT;", "FOR i := 0 TO 3 DO a[i] := i; END_FOR\nk := a[i];")
    r, fault = _faulted(src)
    assert fault.pos.line == 6 and r.get("i") == 4  # IEC: the first value past the end


def test_without_a_fault_the_loops_end_as_before():
    r = run_st(
        prog(
            "i : INT; j : INT; n : INT;",
            "FOR i := 1 TO 3 DO n := n + i; END_FOR\nFOR j := 1 TO 9 DO IF j = 4 THEN EXIT; END_IF END_FOR",
        )
    )
    assert (r.get("i"), r.get("j"), r.get("n")) == (4, 4, 6)


# Loops too short to check on their own, but more than LOOP_CHECK_EVERY passes
# in all: nested, or in a FUNCTION or FB called in a loop, left by EXIT or
# RETURN. In a cycle already past its deadline (a negative watchdog time) the
# first check faults, at the loop whose pass spends the shared loop budget.
PAST_THE_BUDGET = {
    "nested FOR": (
        """PROGRAM main
VAR i, j, k, n : DINT; END_VAR
FOR i := 1 TO 20 DO
  FOR j := 1 TO 20 DO
    FOR k := 1 TO 20 DO n := n + 1; END_FOR
  END_FOR
END_FOR
END_PROGRAM
""",
        (5, 5),
    ),
    "nested WHILE": (
        """PROGRAM main
VAR i, j, k, n : DINT; END_VAR
WHILE i < 20 DO i := i + 1; j := 0;
  WHILE j < 20 DO j := j + 1; k := 0;
    WHILE k < 20 DO k := k + 1; n := n + 1; END_WHILE
  END_WHILE
END_WHILE
END_PROGRAM
""",
        (5, 5),
    ),
    "nested REPEAT": (
        """PROGRAM main
VAR i, j, k, n : DINT; END_VAR
REPEAT i := i + 1; j := 0;
  REPEAT j := j + 1; k := 0;
    REPEAT k := k + 1; n := n + 1; UNTIL k >= 20 END_REPEAT
  UNTIL j >= 20 END_REPEAT
UNTIL i >= 20 END_REPEAT
END_PROGRAM
""",
        (5, 5),
    ),
    "FOR in a FUNCTION called in a FOR": (
        """FUNCTION sum_to : DINT
VAR_INPUT n : DINT; END_VAR
VAR k : DINT; END_VAR
FOR k := 1 TO n DO sum_to := sum_to + k; END_FOR
END_FUNCTION
PROGRAM main
VAR i, total : DINT; END_VAR
FOR i := 1 TO 100 DO total := total + sum_to(50); END_FOR
END_PROGRAM
""",
        (4, 1),
    ),
    "WHILE left by EXIT in an FB called in a WHILE": (
        """FUNCTION_BLOCK Tens
VAR_OUTPUT n : DINT; END_VAR
WHILE TRUE DO n := n + 1; IF n MOD 10 = 0 THEN EXIT; END_IF END_WHILE
END_FUNCTION_BLOCK
PROGRAM main
VAR c : Tens; i : DINT; END_VAR
WHILE i < 200 DO i := i + 1; c(); END_WHILE
END_PROGRAM
""",
        (3, 1),
    ),
    "WHILE left by RETURN in a FUNCTION called in a FOR": (
        """FUNCTION tens : DINT
VAR_INPUT x : DINT; END_VAR
WHILE TRUE DO tens := tens + 1; IF tens >= 10 THEN RETURN; END_IF END_WHILE
END_FUNCTION
PROGRAM main
VAR i, n : DINT; END_VAR
FOR i := 1 TO 200 DO n := n + tens(i); END_FOR
END_PROGRAM
""",
        (3, 1),
    ),
}


@pytest.mark.parametrize("case", PAST_THE_BUDGET)
def test_loops_share_one_budget_so_nesting_cannot_hide_a_long_cycle(case):
    source, where = PAST_THE_BUDGET[case]
    r = _runner(source, -1.0)
    with pytest.raises(STFault) as err:
        r.run(1)
    assert err.value.kind == "watchdog"
    assert (err.value.pos.line, err.value.pos.col) == where


def test_for_bounds_convert_to_the_loop_variables_type():
    # found by the fuzzer: a REAL bound is a W121 narrowing in CODESYS and must still run
    r = run_st(prog("i : INT; n : INT; hi : REAL := 3.6;", "FOR i := 1 TO hi DO n := n + 1; END_FOR"))
    assert r.get("n") == 4  # 3.6 rounds to 4, as REAL_TO_INT does


OWN_INPUTS = """
FUNCTION_BLOCK Doubler
VAR_INPUT i : INT; END_VAR
VAR_OUTPUT o : INT; seen : INT; END_VAR
seen := i;
i := i * 2;
o := i;
END_FUNCTION_BLOCK
FUNCTION Inc : INT
VAR_INPUT a : INT; END_VAR
a := a + 1;
Inc := a;
END_FUNCTION
PROGRAM main
VAR_INPUT p : INT; END_VAR
VAR d : Doubler; n : INT; q : INT; r : INT; END_VAR
p := p + 5;
q := p;
n := n + 1;
IF n = 1 THEN d(i := 3); ELSE d(); END_IF
r := Inc(10);
END_PROGRAM
"""


def test_an_input_assigned_inside_its_own_pou_takes_effect_at_once_and_holds():
    # CODESYS/TwinCAT (W130): the assignment writes the input itself, so the
    # POU reads its own value back in the same call (q, o, Inc); an FB's or a
    # program's input then keeps it until a call passes another (the second
    # d() passes nothing: i is still 6, 12 after the call).
    r = run_st(OWN_INPUTS, cycles=1)
    assert [d.code for d in r.program.warnings] == ["W130", "W130", "W130"]
    assert (r.get("p"), r.get("q"), r.get("d.i"), r.get("d.o"), r.get("r")) == (5, 5, 6, 6, 11)
    r.run(1)
    assert (r.get("p"), r.get("q"), r.get("d.seen"), r.get("d.i"), r.get("d.o"), r.get("r")) == (10, 10, 6, 12, 12, 11)
