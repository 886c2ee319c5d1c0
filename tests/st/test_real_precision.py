"""REAL is single precision through and through: every operation on REALs
rounds to IEC 60559 binary32, at run time and when the compiler folds
constants; LREAL stays binary64, and REAL meeting LREAL computes in LREAL.

IEC 61131-3 ed.3 6.4.2 Table 10: REAL is 32 bits, LREAL 64, both in the
IEC 60559 (IEEE 754) formats; a PLC's FPU (CODESYS and TwinCAT on x86/ARM
single precision for REAL) rounds after each operation and overflows to
+-inf. The expected values are computed here step by step with struct,
which rounds a double to binary32 exactly as a C float cast does.
"""

from __future__ import annotations

import math
import struct

from .conftest import prog, run_st


def f32(x: float) -> float:
    """binary32 rounding of x (round to nearest even), inf beyond FLT_MAX."""
    try:
        return struct.unpack("<f", struct.pack("<f", x))[0]
    except OverflowError:
        return math.copysign(math.inf, x)


def test_each_operation_rounds_to_binary32():
    r = run_st(
        prog(
            "r : REAL; r2 : REAL; d : REAL; l : LREAL; l2 : LREAL; dl : LREAL;",
            "r := 0.1; r2 := r * 3.0; d := r * 3.0 - 0.3; l := 0.1; l2 := l * 3.0; dl := l * 3.0 - 0.3;",
        )
    )
    assert r.get("r2") == f32(f32(0.1) * 3.0) == 0.30000001192092896
    # r * 3.0 is rounded before 0.3 is subtracted: both are the binary32 0.3
    assert r.get("d") == f32(f32(f32(0.1) * 3.0) - f32(0.3)) == 0.0
    assert r.get("l2") == 0.1 * 3.0 == 0.30000000000000004
    assert r.get("dl") == 0.1 * 3.0 - 0.3 == 5.551115123125783e-17


def test_a_real_has_24_bits_and_an_lreal_53():
    r = run_st(
        prog(
            "big : REAL := 16777216.0; s : REAL; diff : REAL; gt : BOOL; i : INT; "
            "lbig : LREAL := 16777216.0; ls : LREAL; ldiff : LREAL;",
            "s := big + 1.0; diff := big + 1.0 - big; gt := big + 1.0 > big; i := REAL_TO_INT(big + 1.0 - big); "
            "ls := lbig + 1.0; ldiff := lbig + 1.0 - lbig;",
        )
    )
    assert r.get("s") == 16777216.0  # 2**24 + 1 needs 25 bits: ties to even
    assert r.get("diff") == 0.0 and r.get("gt") is False and r.get("i") == 0
    assert r.get("ls") == 16777217.0 and r.get("ldiff") == 1.0


def test_real_overflows_to_infinity_where_the_operation_overflows():
    r = run_st(
        prog(
            "a : REAL := 1.0E38; p : REAL; q : REAL; n : REAL; la : LREAL := 1.0E38; lq : LREAL; "
            "c : REAL := 1.0E38 * 10.0 / 100.0;",
            "p := a * 10.0; q := a * 10.0 / 100.0; n := -a * 10.0; lq := la * 10.0 / 100.0;",
        )
    )
    assert r.get("p") == math.inf and r.get("n") == -math.inf
    assert r.get("q") == math.inf  # inf / 100, not 1e39 / 100 (as if in double)
    assert r.get("c") == math.inf  # the folded initial value as well
    assert r.get("lq") == 1.0e37


def test_real_and_lreal_literals_differ():
    r = run_st(
        prog(
            "ne : BOOL; eq : BOOL; r : REAL := 0.1; l : LREAL := 0.1; rl : BOOL; widened : LREAL;",
            "ne := REAL#0.1 <> LREAL#0.1; eq := r = 0.1; rl := REAL_TO_LREAL(r) = l; widened := REAL#0.1;",
        )
    )
    assert r.get("ne") is True  # folded: binary32 0.1 against binary64 0.1
    assert r.get("eq") is True  # 0.1 beside a REAL is REAL#0.1
    assert r.get("rl") is False
    assert r.get("widened") == f32(0.1) == 0.10000000149011612


def test_a_real_literal_argument_is_its_binary32_value():
    src = """
FUNCTION twice : LREAL
VAR_INPUT x : LREAL; END_VAR
twice := x * 2.0;
END_FUNCTION
PROGRAM main
VAR a : LREAL; b : LREAL; END_VAR
a := twice(REAL#0.1);
b := twice(LREAL#0.1);
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("a") == f32(0.1) * 2.0 == 0.20000000298023224
    assert r.get("b") == 0.2


def test_real_function_results_are_binary32():
    r = run_st(
        prog(
            "r : REAL := 2.0; sq : REAL; s : REAL; e : REAL; l : LREAL := 2.0; lsq : LREAL;",
            "sq := SQRT(r) * SQRT(r); s := SIN(r) * 2.0; e := EXPT(r, 0.5) * EXPT(r, 0.5); lsq := SQRT(l) * SQRT(l);",
        )
    )
    root = f32(math.sqrt(2.0))
    assert r.get("sq") == f32(root * root) == 1.9999998807907104
    assert r.get("s") == f32(f32(math.sin(2.0)) * 2.0)
    assert r.get("e") == f32(f32(2.0**0.5) * f32(2.0**0.5))
    assert r.get("lsq") == math.sqrt(2.0) * math.sqrt(2.0) == 2.0000000000000004


def test_mixed_real_and_lreal_compute_in_lreal():
    r = run_st(
        prog(
            "r : REAL := 0.5; l : LREAL := 0.1; m : LREAL; third : REAL := 3.0; q : LREAL;",
            "m := r + l; q := l / third;",
        )
    )
    assert r.get("m") == 0.5 + 0.1 == 0.6  # the LREAL side is not rounded
    assert r.get("q") == 0.1 / 3.0


def test_constant_folding_is_binary32_in_a_real_context():
    # 2**-24 + 2**-50: its binary32 value is 2**-24, and 1 + 2**-24 ties to
    # even, 1.0; in double the sum is above the tie and would round up
    src = prog(
        "folded : REAL; x : REAL := 1.0; run : REAL; lfolded : LREAL;",
        "folded := 1.0 + 5.960464566356904E-8; run := x + 5.960464566356904E-8; lfolded := 1.0 + 5.960464566356904E-8;",
    )
    r = run_st(src)
    assert r.get("folded") == f32(1.0 + f32(5.960464566356904e-08)) == 1.0
    assert r.get("run") == 1.0
    assert r.get("lfolded") == 1.0 + 5.960464566356904e-08


def test_an_accumulating_sum_matches_binary32_step_by_step():
    src = prog(
        "i : INT; s : REAL; x : REAL := 0.7; w : REAL; ls : LREAL;",
        "FOR i := 1 TO 100 DO s := s + x * 0.1; ls := ls + x * 0.1; END_FOR w := s / 3.0 + 0.5;",
    )
    r = run_st(src, cycles=3)
    s = 0.0
    step = f32(f32(0.7) * f32(0.1))
    for _ in range(300):
        s = f32(s + step)
    assert r.get("s") == s
    assert r.get("w") == f32(f32(s / 3.0) + 0.5)
    ls = 0.0
    for _ in range(300):
        ls = ls + step  # REAL * REAL is a REAL; the sum is LREAL
    assert r.get("ls") == ls


def test_struct_array_and_fb_values_are_binary32():
    src = """
TYPE Pt : STRUCT x : REAL; END_STRUCT END_TYPE
FUNCTION_BLOCK Scale
VAR_INPUT v : REAL; END_VAR
VAR_OUTPUT y : REAL; END_VAR
y := v * 3.0 - 0.3;
END_FUNCTION_BLOCK
PROGRAM main
VAR p : Pt; a : ARRAY[1..2] OF REAL; fb : Scale; out : REAL; r : REAL := 0.1; END_VAR
p.x := r * 3.0 - 0.3;
a[2] := SQRT(2.0 * r * 10.0) * SQRT(2.0 * r * 10.0);
fb(v := r, y => out);
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("p.x") == 0.0
    assert r.get("a")[1] == 1.9999998807907104
    assert r.get("out") == 0.0


def test_min_max_of_an_integer_and_a_real_is_a_real():
    r = run_st(prog("i : INT := 3; r : REAL := 0.5; m : REAL; s : REAL;", "m := MAX(i, r); s := SQRT(i);"))
    assert r.get("m") == 3.0 and isinstance(r.get("m"), float)  # not the INT 3
    assert r.get("s") == f32(math.sqrt(3.0))
