"""IEC semantics of generated code: the traps a CODESYS/TwinCAT engineer
knows (wrap on store, truncating division, MOD sign, REAL precision, string
length, bounds, value copies)."""
from __future__ import annotations

import struct

import pytest

from softplc.runtime.st.faults import STFault

from .conftest import run_st


def prog(decls: str, body: str) -> str:
    return f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"


@pytest.mark.parametrize("ty,start,delta,expected", [
    ("SINT", 127, 1, -128), ("INT", 32767, 1, -32768), ("DINT", 2147483647, 1, -2147483648),
    ("LINT", 9223372036854775807, 1, -9223372036854775808),
    ("USINT", 255, 1, 0), ("UINT", 0, -1, 65535), ("UDINT", 4294967295, 1, 0),
    ("ULINT", 0, -1, 18446744073709551615),
    ("BYTE", 255, 1, 0), ("WORD", 65535, 1, 0), ("DWORD", 0, -1, 4294967295),
    ("LWORD", 18446744073709551615, 1, 0),
])
def test_integers_wrap_on_store(ty, start, delta, expected):
    r = run_st(prog(f"x : {ty} := {start};", f"x := x + ({delta});"))
    assert r.get("x") == expected


def test_intermediate_results_are_not_wrapped_before_the_store():
    # (a + b) / 2 with INTs: the sum is computed wide, only the store wraps
    r = run_st(prog("a : INT := 30000; b : INT := 30000; m : INT;", "m := (a + b) / 2;"))
    assert r.get("m") == 30000


@pytest.mark.parametrize("a,b,quot,rem", [(-7, 2, -3, -1), (7, -2, -3, 1), (7, 2, 3, 1), (-7, -2, 3, -1)])
def test_integer_division_truncates_and_mod_takes_the_dividends_sign(a, b, quot, rem):
    r = run_st(prog(f"a : DINT := {a}; b : DINT := {b}; q : DINT; m : DINT;", "q := a / b; m := a MOD b;"))
    assert (r.get("q"), r.get("m")) == (quot, rem)


def test_real_is_rounded_to_32_bits_and_lreal_is_not():
    r = run_st(prog("r : REAL; l : LREAL; big : REAL; x : REAL := 1.0; y : REAL := 3.0; q : REAL;",
                    "r := 0.1; l := 0.1; big := DINT_TO_REAL(16777217); q := x / y;"))
    f32 = struct.unpack("<f", struct.pack("<f", 0.1))[0]
    assert r.get("r") == f32 == 0.10000000149011612
    assert r.get("l") == 0.1
    assert r.get("big") == 16777216.0
    assert r.get("q") == struct.unpack("<f", struct.pack("<f", 1 / 3))[0]


def test_real_division_by_zero_gives_infinity_not_a_fault():
    r = run_st(prog("a : REAL := 1.0; z : REAL; q : REAL;", "q := a / z;"))
    assert r.get("q") == float("inf")


def test_string_is_truncated_to_its_declared_length():
    r = run_st(prog("s : STRING[5]; t : STRING := 'abc';", "s := CONCAT(t, 'defgh');"))
    assert r.get("s") == "abcde"


def test_integer_division_by_zero_is_a_fault_with_the_st_location():
    src = prog("a : INT := 1; z : INT; q : INT;", "q := 5;\nq := a / z;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "division"
    assert (err.value.pos.file, err.value.pos.line) == ("test.st", 6)
    assert "test.st:6:" in str(err.value) and "division by zero" in str(err.value)


def test_array_index_out_of_bounds_is_a_fault_not_a_wraparound():
    src = prog("a : ARRAY[1..3] OF INT; i : INT := 0;", "a[i] := 7;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "bounds" and err.value.pos.line == 5
    assert "0" in err.value.message and "1..3" in err.value.message


def test_array_with_non_zero_lower_bound_and_two_dimensions():
    src = prog("a : ARRAY[-2..2, 1..3] OF INT; i : INT; j : INT; s : INT;",
               "FOR i := -2 TO 2 DO FOR j := 1 TO 3 DO a[i, j] := i * 10 + j; END_FOR END_FOR\n"
               "s := a[-2, 1] + a[2, 3];")
    r = run_st(src)
    assert r.get("s") == -19 + 23
    assert r.get("a")[0][0] == -19 and r.get("a")[4][2] == 23


def test_array_initialiser_with_repetition():
    r = run_st(prog("a : ARRAY[0..5] OF INT := [1, 2, 3(7)];", ""))
    assert r.get("a") == [1, 2, 7, 7, 7, 0]


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


def test_and_or_evaluate_both_sides_in_codesys_and_short_circuit_with_and_then():
    src = """
FUNCTION bump : BOOL
VAR_IN_OUT n : INT; END_VAR
n := n + 1; bump := TRUE;
END_FUNCTION
PROGRAM main
VAR n1 : INT; n2 : INT; f : BOOL; x : BOOL; END_VAR
x := f AND bump(n1);
x := f AND_THEN bump(n2);
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("n1") == 1  # evaluated although f is FALSE (CODESYS)
    assert r.get("n2") == 0  # AND_THEN short-circuits


def test_for_loop_leaves_the_variable_past_the_end_and_exit_keeps_it():
    src = prog("i : INT; j : INT; s : INT; k : INT;",
               "FOR i := 1 TO 10 BY 3 DO s := s + i; END_FOR\n"
               "FOR j := 10 TO 1 BY -1 DO IF j = 4 THEN EXIT; END_IF END_FOR\n"
               "FOR k := 5 TO 1 DO s := 1000; END_FOR")
    r = run_st(src)
    assert r.get("s") == 1 + 4 + 7 + 10
    assert r.get("i") == 13 and r.get("j") == 4 and r.get("k") == 5


def test_while_repeat_continue():
    src = prog("i : INT; odd : INT; n : INT;",
               "WHILE i < 10 DO i := i + 1; IF i MOD 2 = 0 THEN CONTINUE; END_IF odd := odd + 1; END_WHILE\n"
               "REPEAT n := n + 1; IF n < 3 THEN CONTINUE; END_IF UNTIL n >= 5 END_REPEAT")
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


def test_function_outputs_in_outs_and_recursion_free_calls():
    src = """
FUNCTION divmod : BOOL
VAR_INPUT a, b : DINT; END_VAR
VAR_OUTPUT q, r : DINT; END_VAR
VAR_IN_OUT calls : INT; END_VAR
q := a / b; r := a MOD b; calls := calls + 1; divmod := TRUE;
END_FUNCTION
PROGRAM main
VAR q, r : DINT; n : INT; ok : BOOL; END_VAR
ok := divmod(a := 17, b := 5, q => q, r => r, calls := n);
ok := divmod(-17, 5, n, q => q);
END_PROGRAM
"""
    r = run_st(src)
    assert (r.get("q"), r.get("r"), r.get("n"), r.get("ok")) == (-3, 2, 2, True)


def test_references_and_pointers():
    src = """
PROGRAM main
VAR x : INT := 5; r : REF_TO INT; p : POINTER TO INT; y : INT; isnull : BOOL; arr : ARRAY[1..3] OF INT; END_VAR
r := REF(x); r^ := r^ + 1;
p := ADR(arr[2]); p^ := 42;
y := x;
isnull := r = 0;
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("y") == 6 and r.get("arr") == [0, 42, 0] and r.get("isnull") is False


def test_null_reference_is_a_fault():
    src = prog("r : REF_TO INT; y : INT;", "y := r^;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "reference" and err.value.pos.line == 5


def test_bit_access_read_and_write():
    src = prog("w : WORD := 16#0F0F; i : INT; b1 : BOOL; b2 : BOOL;",
               "b1 := w.3; b2 := w.%X4; w.15 := TRUE; w.0 := FALSE; i.15 := TRUE;")
    r = run_st(src)
    assert r.get("b1") is True and r.get("b2") is False
    assert r.get("w") == 0x8F0E and r.get("i") == -32768


def test_subrange_violation_is_a_fault():
    src = prog("pct : INT(0..100); v : INT := 101;", "pct := 50; pct := v;")
    with pytest.raises(STFault) as err:
        run_st(src)
    assert err.value.kind == "range"


def test_time_arithmetic_and_clock():
    src = prog("t : TIME := T#1s; u : TIME; tod1 : TOD := TOD#23:59:59; tod2 : TOD; d : DT := DT#2024-01-01-00:00:00; "
               "d2 : DT; diff : TIME; now : TIME;",
               "u := t * 3 + T#250ms; tod2 := tod1 + T#2s; d2 := d + T#1h; diff := d2 - d; now := TIME();")
    r = run_st(src, cycles=4, cycle_time_ms=10)
    assert r.get("u") == 3250
    assert r.get("tod2") == 1000  # wraps past midnight to 00:00:01
    assert r.get("d2") - r.get("d") == 3600 and r.get("diff") == 3_600_000
    assert r.get("now") == 30  # fourth cycle at 30 ms of virtual time


def test_globals_constants_and_var_external():
    src = """
VAR_GLOBAL CONSTANT N : INT := 4; END_VAR
VAR_GLOBAL total : DINT; END_VAR
FUNCTION_BLOCK Adder
VAR_EXTERNAL total : DINT; END_VAR
VAR_INPUT x : DINT; END_VAR
total := total + x;
END_FUNCTION_BLOCK
PROGRAM main
VAR add : Adder; buf : ARRAY[1..N] OF INT; i : INT; END_VAR
FOR i := 1 TO N DO add(x := i); END_FOR
END_PROGRAM
"""
    r = run_st(src, cycles=2)
    assert r.get("total") == 20 and len(r.get("buf")) == 4


def test_function_entry_returns_its_result():
    src = "FUNCTION answer : INT\nVAR a : INT := 6; END_VAR\nanswer := a * 7;\nEND_FUNCTION\n"
    r = run_st(src, entry="answer")
    assert r.result == 42


def test_watchdog_stops_an_endless_loop():
    from softplc.runtime.program import compile_files
    prog_ = compile_files([], texts={"w.st": prog("n : DINT;", "WHILE TRUE DO n := n + 1; END_WHILE")})
    r = prog_.runner("main")
    r.ctx.watchdog_s = 0.02
    with pytest.raises(STFault) as err:
        r.run(1)
    assert err.value.kind == "watchdog" and err.value.pos.line == 5
    assert r.get("n") > 0


def test_standard_functions_accept_what_codesys_accepts():
    src = prog("i : INT := 16; r : REAL; s : DINT; w : WORD := 16#0081; n : BYTE := 1; m : INT;",
               "r := SQRT(i); s := ADD(IN1 := 1, IN2 := 2, IN3 := 3); w := ROL(w, n);"
               " m := MUX(K := 2, IN0 := 10, IN1 := 20, IN2 := 30);")
    r = run_st(src)
    assert r.get("r") == 4.0 and r.get("s") == 6 and r.get("w") == 0x0102 and r.get("m") == 30


def test_inlined_operations_keep_iec_results():
    # constant divisors, shifts and conversions are emitted inline: same results as the library
    src = prog("a : DINT := -7; q : DINT; m : DINT; w : WORD := 16#8421; s1 : WORD; s2 : WORD; r1 : WORD;"
               " r2 : WORD; b : BYTE := 16#81; sn : SINT; uw : WORD; big : WORD; lim : INT; x : INT := 500;",
               "q := a / 2; m := a MOD 2; s1 := SHL(w, 4); s2 := SHR(w, 4); r1 := ROL(w, 4); r2 := ROR(w, 20);"
               " sn := INT_TO_SINT(300); uw := INT_TO_WORD(-1); big := SHL(w, 16); b := ROL(b, 1);"
               " lim := LIMIT(0, x, 100);")
    r = run_st(src)
    assert (r.get("q"), r.get("m")) == (-3, -1)
    assert (r.get("s1"), r.get("s2"), r.get("r1"), r.get("r2")) == (0x4210, 0x0842, 0x4218, 0x1842)
    assert (r.get("sn"), r.get("uw"), r.get("big"), r.get("b"), r.get("lim")) == (44, 65535, 0, 0x03, 100)


def test_fb_instances_in_an_array_are_called_by_index():
    src = """
PROGRAM main
VAR t : ARRAY[1..3] OF TON; i : INT; done : INT; END_VAR
done := 0;
FOR i := 1 TO 3 DO
  t[i](IN := TRUE, PT := INT_TO_TIME(i * 10));
  IF t[i].Q THEN done := done + 1; END_IF
END_FOR
END_PROGRAM
"""
    r = run_st(src, cycles=3, cycle_time_ms=10)  # at the third cycle 20 ms have passed
    assert r.get("done") == 2


def test_for_bounds_convert_to_the_loop_variables_type():
    # found by the fuzzer: a REAL bound is a W121 narrowing in CODESYS and must still run
    r = run_st(prog("i : INT; n : INT; hi : REAL := 3.6;", "FOR i := 1 TO hi DO n := n + 1; END_FOR"))
    assert r.get("n") == 4  # 3.6 rounds to 4, as REAL_TO_INT does
