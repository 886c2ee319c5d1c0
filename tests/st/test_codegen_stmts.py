"""Generated statements and stores (runtime/st/codegen_stmts.py): wrap on
store, REAL precision, string length, value copies, loops, CASE, the
watchdog."""

from __future__ import annotations

import struct

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import prog, run_st


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


def test_watchdog_stops_an_endless_loop():
    from softplc.runtime.program import compile_files

    prog_ = compile_files([], texts={"w.st": prog("n : DINT;", "WHILE TRUE DO n := n + 1; END_WHILE")})
    r = prog_.runner("main")
    r.ctx.watchdog_s = 0.02
    with pytest.raises(STFault) as err:
        r.run(1)
    assert err.value.kind == "watchdog" and err.value.pos.line == 5
    assert r.get("n") > 0


def test_for_bounds_convert_to_the_loop_variables_type():
    # found by the fuzzer: a REAL bound is a W121 narrowing in CODESYS and must still run
    r = run_st(prog("i : INT; n : INT; hi : REAL := 3.6;", "FOR i := 1 TO hi DO n := n + 1; END_FOR"))
    assert r.get("n") == 4  # 3.6 rounds to 4, as REAL_TO_INT does
