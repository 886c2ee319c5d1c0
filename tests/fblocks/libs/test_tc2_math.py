"""Tc2_Math (fblocks/libs/tc2_math): the rounding and modulo functions of
LREAL. Values from the Beckhoff Information System pages "TwinCAT 3 PLC
Lib: Tc2_Math" (FLOOR, CEIL, LTRUNC: the table "Example results of various
rounding functions"; FRAC, LMOD, MODABS, MODTURNS: their examples)."""

from __future__ import annotations

import pytest

from .conftest import run

XS = [0, 0.4, 0.5, 0.6, 1, 1.4, 1.5, 1.6, 1.78, -1.78, -1.6, -1.5, -1.4, -1, -0.6, -0.5, -0.4]
TABLE = {  # "Example results of various rounding functions"
    "FLOOR": [0, 0, 0, 0, 1, 1, 1, 1, 1, -2, -2, -2, -2, -1, -1, -1, -1],
    "CEIL": [0, 1, 1, 1, 1, 2, 2, 2, 2, -1, -1, -1, -1, -1, 0, 0, 0],
    "LTRUNC": [0, 0, 0, 0, 1, 1, 1, 1, 1, -1, -1, -1, -1, -1, 0, 0, 0],
}


@pytest.mark.parametrize("fn", sorted(TABLE))
def test_the_rounding_functions_give_the_documented_table(fn):
    n = len(XS)
    src = f"""
    PROGRAM Main
    VAR x : ARRAY[1..{n}] OF LREAL := [{", ".join(str(float(v)) for v in XS)}];
        y : ARRAY[1..{n}] OF LREAL; i : INT; END_VAR
    FOR i := 1 TO {n} DO y[i] := {fn}(x[i]); END_FOR
    END_PROGRAM
    """
    assert run(src, "Tc2_Math").get("y") == TABLE[fn]


def test_rounding_is_not_limited_to_the_range_of_an_integer():
    # "The resulting number is of type LREAL and is therefore not limited to the value range of
    # integer variables": FLOOR(2.8) = 2, FLOOR(-2.8) = -3, LTRUNC(-2.8) = -2, FRAC(-2.8) = -0.8
    src = """
    PROGRAM Main
    VAR a, b, c, d, e, f, g : LREAL; END_VAR
    a := FLOOR(2.8); b := FLOOR(-2.8); c := LTRUNC(-2.8); d := FRAC(2.8); e := FRAC(-2.8);
    f := FLOOR(-1.0E20 - 0.5); g := CEIL(lr_in := 1.0E17 + 16.0);
    END_PROGRAM
    """
    r = run(src, "Tc2_Math")
    assert [r.get(n) for n in "abc"] == [2.0, -3.0, -2.0]
    assert (r.get("d"), r.get("e")) == (pytest.approx(0.8), pytest.approx(-0.8))
    assert (r.get("f"), r.get("g")) == (-1.0e20, 1.0e17 + 16.0)  # beyond LINT, and no fraction left


def test_modulo_functions_give_the_documented_examples():
    # LMOD(400.56, 360) = 40.56, LMOD(-400.56, 360) = -40.56; MODABS(400.56, 360) = 40.56,
    # MODABS(-400.56, 360) = 319.44; MODTURNS(800.56, 360) = 2, MODTURNS(-400.56, 360) = -2
    src = """
    PROGRAM Main
    VAR l1, l2, a1, a2, back : LREAL; t1, t2 : DINT; END_VAR
    l1 := LMOD(400.56, 360); l2 := LMOD(lr_Value := -400.56, lr_Arg := 360);
    a1 := MODABS(400.56, 360); a2 := MODABS(lr_val := -400.56, lr_mod := 360);
    t1 := MODTURNS(800.56, 360); t2 := MODTURNS(-400.56, 360);
    back := t2 * 360.0 + a2;     (* the position: whole turns and the place in the range *)
    END_PROGRAM
    """
    r = run(src, "Tc2_Math")
    assert [r.get(n) for n in ("l1", "l2", "a1", "a2", "back")] == pytest.approx(
        [40.56, -40.56, 40.56, 319.44, -400.56]
    )
    assert (r.get("t1"), r.get("t2")) == (2, -2)


def test_the_library_version_and_qualified_names():
    src = """
    PROGRAM Main VAR v : ARRAY[1..4] OF UINT; f : LREAL; END_VAR
    v[1] := F_GetVersionTcMath(1); v[2] := F_GetVersionTcMath(2); v[3] := F_GetVersionTcMath(3);
    v[4] := F_GetVersionTcMath(9);
    f := Tc2_Math.FLOOR(-0.5);
    END_PROGRAM
    """
    r = run(src, "Tc2_Math")
    assert (r.get("v"), r.get("f")) == ([3, 3, 1, 0], -1.0)
