"""The dialect profiles (runtime/st/profile.py): what each one decides, seen
from a program a user compiles and runs with it."""

from __future__ import annotations

import pytest

from softplc.runtime.st.profile import IEC, MATIEC, PROFILES, get_profile

from .conftest import codes, prog, run_st


def test_every_profile_can_be_named_in_any_case():
    assert list(PROFILES) == ["iec", "matiec", "codesys", "twincat", "schneider"]
    assert get_profile("MatIEC") is MATIEC
    with pytest.raises(KeyError, match="choose one of iec, matiec, codesys, twincat, schneider"):
        get_profile("openplc")


def test_matiec_runs_a_program():
    # OpenPLC / Beremiz code: a counter with a typed literal, as MatIEC compiles it
    src = prog("n : INT; total : DINT;", "n := n + INT#1;\ntotal := total + INT_TO_DINT(n);")
    r = run_st(src, cycles=4, profile="matiec")
    assert (r.get("n"), r.get("total")) == (4, 10)


@pytest.mark.parametrize("profile", ["iec", "matiec"])
def test_matiec_types_strictly_as_iec(profile):
    # MatIEC converts nothing implicitly that loses data (DINT -> INT is
    # E021, as in IEC 61131-3 ed.3 Fig. 11) and keeps AND/OR/XOR for ANY_BIT
    # (the standard bitwise functions take ANY_BIT); CODESYS warns about the
    # first and accepts both.
    narrowing = prog("big : DINT := 5; small : INT;", "small := big;")
    assert codes(narrowing, profile) == ["E021"]
    assert codes(narrowing, "codesys") == ["W121"]
    bit_ops = prog("a : INT := 6; b : INT := 3; c : INT;", "c := a AND b;")
    assert codes(bit_ops, profile) == ["E023"]
    assert codes(bit_ops, "codesys") == []


def test_matiec_differs_from_iec_only_where_it_says_so():
    # MatIEC is strict IEC but for 0 and 1 as BOOL literals, which its
    # grammar takes as the standard's does (the iec profile is stricter),
    # and for what its compiler accepts beyond the standard (the OSCAT port
    # to Beremiz leans on each): a POU writing its own inputs, ed.3's type
    # names as variables, an FB's in-out kept as the instance's copy, TRUNC
    # typed by its context, and its library's F_TRIG, whose memory starts FALSE
    differing = {f for f in IEC.__dataclass_fields__ if getattr(IEC, f) != getattr(MATIEC, f)}
    assert differing == {
        "name",
        "bool_from_0_1",
        "own_input_assignment",
        "ed3_type_names_reserved",
        "fb_in_out_copied",
        "trunc_from_context",
        "f_trig_first_call_edge",
    }


ED2_NAMES = """
FUNCTION LTIME_TO_UTC : UDINT
VAR_INPUT
    LTIME : UDINT;
    OFFSET : INT;
END_VAR
LTIME_TO_UTC := LTIME - INT_TO_UDINT(OFFSET * 60);
END_FUNCTION
FUNCTION_BLOCK Local
VAR_INPUT UDT : UDINT; END_VAR
VAR_OUTPUT LDT : UDINT; CHAR : INT; END_VAR
VAR lt : LTIME; END_VAR
LDT := UDT + 3600;
CHAR := 5;
lt := LTIME();
END_FUNCTION_BLOCK
PROGRAM Main
VAR f : Local; u : UDINT; c : INT; END_VAR
f(UDT := 100);
u := LTIME_TO_UTC(LTIME := f.LDT, OFFSET := 60);
c := f.CHAR;
END_PROGRAM
"""


def test_matiec_takes_the_names_of_ed3_types_as_variables():
    # OSCAT's port to Beremiz: LTIME_TO_UTC has an input LTIME, another
    # function a variable LDT; MatIEC reads ed.2, which has neither type
    r = run_st(ED2_NAMES, cycles=1, profile="matiec")
    assert (r.get("u"), r.get("c"), r.get("f.LDT")) == (100, 5, 3700)
    ds = codes(ED2_NAMES, "codesys")
    assert ds == ["E011", "E010", "E011", "E011", "E010", "E010", "E040", "E013", "E013"]


def test_a_global_named_as_an_ed3_type_is_refused_in_matiec_too():
    # it would hide LTIME() from every POU, the standard blocks' included
    src = "VAR_GLOBAL LTIME : UDINT; END_VAR\n" + prog("x : INT;", "x := 1;")
    assert codes(src, "matiec") == ["E011"]


IN_OUT_COPIED = """
FUNCTION_BLOCK Ramp
VAR_INPUT up : BOOL; END_VAR
VAR_IN_OUT rmp : INT; pt : ARRAY[1..3] OF INT; END_VAR
IF up THEN rmp := rmp + 1; ELSE rmp := rmp - 1; END_IF;
pt[1] := pt[1] + 10;
END_FUNCTION_BLOCK
PROGRAM Main
VAR r : Ramp; out : INT := 5; seen : INT; last : INT; n : INT;
    a : ARRAY[1..3] OF INT; b : ARRAY[1..3] OF INT; END_VAR
r(up := TRUE, rmp := out, pt := a);  (* copied in, and back out into out, a *)
seen := r.rmp;                       (* the instance's copy, read from outside *)
r.rmp := 100;                        (* and written *)
r(up := FALSE);                      (* not connected: the body works on the copy *)
last := r.rmp;
n := r.pt[1];
r.pt := b;
r();
b := r.pt;
END_PROGRAM
"""


def test_matiec_keeps_an_fb_in_out_as_the_instances_copy():
    # MatIEC's C holds an FB's VAR_IN_OUT in the instance, sets it before the
    # call and reads it back after; OSCAT's port leans on it: `rmp(..., rmp
    # := out); out := rmp.RMP;` and `fb.pt := pt; fb(); pt := fb.pt;`
    r = run_st(IN_OUT_COPIED, cycles=1, profile="matiec")
    assert (r.get("out"), r.get("seen"), r.get("last")) == (6, 6, 99)
    assert r.get("a") == [10, 0, 0] and r.get("n") == 20 and r.get("b") == [10, 0, 0]
    r.run(1)  # the next cycle copies out (6) in again: 7, and a[1] 20
    assert (r.get("out"), r.get("a")[0], r.get("n")) == (7, 20, 30)


def test_elsewhere_an_fb_in_out_is_a_reference_bound_at_each_call():
    assert codes(IN_OUT_COPIED, "codesys") == [
        "E013",
        "E013",
        "E042",
        "E042",
        "E013",
        "E013",
        "E013",
        "E042",
        "E042",
        "E013",
    ]


TRUNC_IN_CONTEXT = prog(
    "i : INT; low : INT := 2; high : INT := 10; r : REAL := 0.75; b : BYTE; s : SINT; d : DINT; ok : BOOL;",
    """i := TRUNC(r * INT_TO_REAL(high - low + 1)) + low;
b := INT_TO_BYTE(TRUNC(r * 255.0));
s := TRUNC(r * -10.0);
d := TRUNC(r * 1.0E6);
ok := TRUNC(r * 10.0) > low;""",
)


def test_matiec_types_trunc_by_its_context():
    # OSCAT's RDM2 and RANGE_TO_BYTE as ported to Beremiz: MatIEC declares
    # TRUNC once per integer type and picks the one the context wants
    r = run_st(TRUNC_IN_CONTEXT, cycles=1, profile="matiec")
    assert (r.get("i"), r.get("b"), r.get("s"), r.get("d"), r.get("ok")) == (8, 191, -7, 750000, True)
    # elsewhere TRUNC is a DINT: storing it into an INT narrows
    assert codes(TRUNC_IN_CONTEXT, "iec") == ["E021", "E021", "E021"]
    assert codes(TRUNC_IN_CONTEXT, "codesys") == ["W121", "W121", "W121"]
