"""Generated calls (runtime/st/codegen/codegen_calls.py): FUNCTION outputs and
in-outs, inlined standard functions, FB instances by index."""

from __future__ import annotations

from ..conftest import prog, run_st


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


def test_inlined_operations_keep_iec_results():
    # constant divisors, shifts and conversions are emitted inline: same results as the library
    src = prog(
        "a : DINT := -7; q : DINT; m : DINT; w : WORD := 16#8421; s1 : WORD; s2 : WORD; r1 : WORD;"
        " r2 : WORD; b : BYTE := 16#81; sn : SINT; uw : WORD; big : WORD; lim : INT; x : INT := 500;",
        "q := a / 2; m := a MOD 2; s1 := SHL(w, 4); s2 := SHR(w, 4); r1 := ROL(w, 4); r2 := ROR(w, 20);"
        " sn := INT_TO_SINT(300); uw := INT_TO_WORD(-1); big := SHL(w, 16); b := ROL(b, 1);"
        " lim := LIMIT(0, x, 100);",
    )
    r = run_st(src)
    assert (r.get("q"), r.get("m")) == (-3, -1)
    assert (r.get("s1"), r.get("s2"), r.get("r1"), r.get("r2")) == (0x4210, 0x0842, 0x4218, 0x1842)
    assert (r.get("sn"), r.get("uw"), r.get("big"), r.get("b"), r.get("lim")) == (44, 65535, 0, 0x03, 100)


def test_shifts_that_stay_in_the_width_and_bit_reads_of_negative_values():
    # SHL(WORD#1, j) and SHL(w AND 16#F, 12) cannot leave the WORD (emitted without a mask);
    # SHL(w AND 16#1F, 12) can; a bit of a negative INT or LINT is its two's complement bit
    src = prog(
        "w : WORD := 16#ABDD; j : INT; packed : WORD; lo : WORD; cut : WORD; i : INT := -2; l : LINT := -1;"
        " bits : WORD; top : BOOL; b0 : BOOL;",
        "FOR j := 0 TO 15 DO IF j MOD 3 = 0 THEN packed := packed OR SHL(WORD#1, j); END_IF END_FOR\n"
        "lo := SHL(w AND 16#000F, 12); cut := SHL(w AND 16#001F, 12);\n"
        "FOR j := 0 TO 15 DO IF i.15 AND NOT i.0 THEN bits := bits OR SHL(WORD#1, j); END_IF END_FOR\n"
        "top := l.63; b0 := i.1;",
    )
    r = run_st(src)
    assert r.get("packed") == sum(1 << j for j in range(0, 16, 3))
    assert (r.get("lo"), r.get("cut")) == (0xD000, 0xD000)
    assert (r.get("bits"), r.get("top"), r.get("b0")) == (0xFFFF, True, True)


def test_fb_calls_of_variables_elements_members_and_in_outs_run_the_instances_own_body():
    # an instance built from its declared type is called through its class; one reached
    # through a VAR_IN_OUT may be of a derived block and runs that block's body
    src = """
FUNCTION_BLOCK FB_Base
VAR_INPUT x : INT; END_VAR
VAR_OUTPUT y : INT; END_VAR
y := x + 1;
END_FUNCTION_BLOCK
FUNCTION_BLOCK FB_Twice EXTENDS FB_Base
y := x * 2;
END_FUNCTION_BLOCK
TYPE Holder : STRUCT inner : FB_Base; END_STRUCT END_TYPE
FUNCTION_BLOCK FB_Caller
VAR_IN_OUT fb : FB_Base; END_VAR
fb(x := 10);
END_FUNCTION_BLOCK
PROGRAM main
VAR b : FB_Base; d : FB_Twice; arr : ARRAY[1..2] OF FB_Base; h : Holder; c : FB_Caller; r : ARRAY[1..5] OF INT; END_VAR
b(x := 1); r[1] := b.y;
arr[2](x := 2); r[2] := arr[2].y;
h.inner(x := 3); r[3] := h.inner.y;
d(x := 4); r[4] := d.y;
c(fb := d); r[5] := d.y;
END_PROGRAM
"""
    r = run_st(src)
    assert r.get("r") == [2, 3, 4, 8, 20]


def test_limit_with_mn_above_mx_gives_mx_inline_folded_and_in_the_library():
    # IEC 61131-3 Table 28: LIMIT(MN, IN, MX) = MIN(MAX(IN, MN), MX), so MN > MX gives MX.
    # The inlined form gave MN, the folded constant and the library function MX.
    src = prog(
        "mn : INT := 10; x : INT := 5; mx : INT := 0; v : INT; c : INT; r : REAL; lo : REAL := 2.5;",
        "v := LIMIT(mn, x, mx); c := LIMIT(10, 5, 0); r := LIMIT(lo, 9.0, 1.5);",
    )
    r = run_st(src)
    assert (r.get("v"), r.get("c"), r.get("r")) == (0, 0, 1.5)


def test_a_real_literal_into_an_integer_parameter_is_that_integer():
    # MAX(1.5, n) with n an INT: T is INT (W121 in codesys), 1.5 converts to 2 as LREAL_TO_INT
    # rounds; it went into max() as 1.5 and the INT then held a float (a fault at the next AND)
    src = prog(
        "n : INT := 1; lim : INT; low : INT; w : WORD; k : DINT := 7;",
        "lim := MAX(1.5, n); low := MIN(k, 2.5); w := INT_TO_WORD(lim) AND 16#FF;",
    )
    r = run_st(src, cycles=2)
    assert (r.get("lim"), r.get("low"), r.get("w")) == (2, 3, 2)  # 2.5 -> 3, as LREAL_TO_DINT rounds
    assert isinstance(r.get("lim"), int) and isinstance(r.get("low"), int)


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


# ---------------------------------------------------------------- natives with their call site


def test_a_site_native_gets_its_values_in_the_common_type_and_where_it_is_called():
    from softplc.runtime.program import compile_files
    from softplc.runtime.st import types as T
    from softplc.runtime.st.native import ANY_ELEMENTARY, STRING, CallSite, NativeFunction, Param

    calls = []

    class Service:
        def request(self, name, *args):
            calls.append((name, *args))
            return True

    probe = NativeFunction(
        "PROBE_SITE",
        (Param("a", ANY_ELEMENTARY, same="T"), Param("b", ANY_ELEMENTARY, same="T"), Param("m", STRING)),
        service="probe",
        fallback=Service(),
        usage="PROBE_SITE(a, b, 'm')",
        site=True,
    )
    source = prog("r : REAL := 2.5; ok : BOOL;", "ok := PROBE_SITE(1, r, 'one');\n    PROBE_SITE(r, r, 'two');")
    program = compile_files([], texts={"site.st": source}, natives=(probe,))
    runner = program.runner("main")
    runner.run(1)
    (n1, a1, b1, m1, site1), (_n2, *_v, site2) = calls
    assert (n1, a1, b1, m1) == ("PROBE_SITE", 1.0, 2.5, "one")
    assert isinstance(a1, float)  # the literal 1 was passed as a REAL
    assert site1 == CallSite("site.st", 5, 7, (T.REAL, T.REAL, site1.types[2]))
    assert (site2.line, site2.col) == (6, 5)
    assert runner.get("ok") is True


def test_without_the_declaration_the_name_is_an_unknown_function():
    from ..conftest import diagnostics

    found = diagnostics(prog("ok : BOOL;", "ok := PROBE_SITE(1, 2, 'x');"))
    assert [(d.code, d.pos.line) for d in found if d.is_error] == [("E043", 5)]


def test_calls_with_a_trailing_comma_run_as_without_in_twincat():
    src = """
FUNCTION add : INT
VAR_INPUT a : INT; b : INT; END_VAR
add := a + b;
END_FUNCTION
PROGRAM main
VAR r : INT; s : INT; t : TON; q : BOOL; END_VAR
r := add(a := 1, b := 2,);
s := add(40, 2,);
t(IN := TRUE, PT := T#20ms, Q => q,);
END_PROGRAM
"""
    r = run_st(src, cycles=3, profile="twincat")
    assert (r.get("r"), r.get("s"), r.get("t.PT"), r.get("q")) == (3, 42, 20, True)
