"""IEC semantics end to end, where no one module of the compiler is the
subject: bit access, time arithmetic and the clock, globals and
VAR_EXTERNAL, a FUNCTION as entry, what standard functions accept. The
traps a CODESYS/TwinCAT engineer knows (wrap on store, truncating division,
MOD sign, REAL precision, bounds, value copies) are tested with the code
generator's parts (test_codegen_*.py)."""

from __future__ import annotations

from .conftest import prog, run_st


def test_bit_access_read_and_write():
    src = prog(
        "w : WORD := 16#0F0F; i : INT; b1 : BOOL; b2 : BOOL;",
        "b1 := w.3; b2 := w.%X4; w.15 := TRUE; w.0 := FALSE; i.15 := TRUE;",
    )
    r = run_st(src)
    assert r.get("b1") is True and r.get("b2") is False
    assert r.get("w") == 0x8F0E and r.get("i") == -32768


def test_time_arithmetic_and_clock():
    src = prog(
        "t : TIME := T#1s; u : TIME; tod1 : TOD := TOD#23:59:59; tod2 : TOD; d : DT := DT#2024-01-01-00:00:00; "
        "d2 : DT; diff : TIME; now : TIME;",
        "u := t * 3 + T#250ms; tod2 := tod1 + T#2s; d2 := d + T#1h; diff := d2 - d; now := TIME();",
    )
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


def test_standard_functions_accept_what_codesys_accepts():
    src = prog(
        "i : INT := 16; r : REAL; s : DINT; w : WORD := 16#0081; n : BYTE := 1; m : INT;",
        "r := SQRT(i); s := ADD(IN1 := 1, IN2 := 2, IN3 := 3); w := ROL(w, n);"
        " m := MUX(K := 2, IN0 := 10, IN1 := 20, IN2 := 30);",
    )
    r = run_st(src)
    assert r.get("r") == 4.0 and r.get("s") == 6 and r.get("w") == 0x0102 and r.get("m") == 30
