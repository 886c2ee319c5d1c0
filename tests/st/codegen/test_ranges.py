"""Range analysis (runtime/st/codegen/ranges.py): the interval an integer expression
of the checked AST can take, which lets generated code skip a wrap or a
bounds check."""

from __future__ import annotations

import pytest

from softplc.runtime.st import types as T
from softplc.runtime.st.codegen import ranges as R

from ..conftest import check_st, pou_body

DECLS = "b : BYTE; u : USINT; i : INT; d : DINT; w : WORD; r : REAL; k : INT; x : DINT; arr : ARRAY[1..10] OF USINT;"


def value(expr: str, decls: str = DECLS):
    """The checked expression expr, as the right side of an assignment to x."""
    checked, diags = check_st(f"PROGRAM main\nVAR\n{decls}\nEND_VAR\nx := {expr};\nEND_PROGRAM\n")
    assert [d for d in diags if d.is_error] == []
    return pou_body(checked)[0].value


@pytest.mark.parametrize(
    "expr,rng",
    [
        ("42", (42, 42)),
        ("-7", (-7, -7)),
        ("b", (0, 255)),
        ("i", (-32768, 32767)),
        ("arr[2]", (0, 255)),
        ("b + u", (0, 510)),
        ("b - u", (-255, 255)),
        ("u * 3", (0, 765)),
        ("i AND 16#0F", (0, 15)),
        ("b OR u", (0, 255)),
        ("i MOD 10", (-9, 9)),
        ("u MOD 10", (0, 9)),
        ("u / 4", (0, 63)),
        ("SHL(w, 1)", (0, 65535)),
        ("INT_TO_BYTE(d)", (0, 255)),
        ("MAX(b, u)", (0, 255)),
        ("SEL(i > 0, 3, 9)", (3, 9)),
        ("REAL_TO_INT(r)", (-32768, 32767)),
    ],
)
def test_interval_of_integer_expressions(expr, rng):
    assert R.value_range(value(expr)) == rng


@pytest.mark.parametrize("expr", ["r", "i / k", "i MOD k", "i OR k", "ABS(i)", "d / k"])
def test_unknown_ranges_are_none(expr):
    assert R.value_range(value(expr)) is None


def test_a_range_wider_than_the_target_means_the_store_wraps():
    rng = R.value_range(value("i * k - d"))
    assert rng == (-32768 * 32767 - 2147483647, 32768 * 32768 + 2147483648)
    assert not R.fits(T.DINT, rng) and R.fits(T.LINT, rng)


def test_a_variable_the_caller_knows_better_than_its_type():
    e = value("k * 2")
    k = e.left.sym
    assert R.value_range(e) == (-65536, 65534)
    assert R.value_range(e, {id(k): (1, 10)}) == (2, 20)


@pytest.mark.parametrize(
    "expr,stored",
    [
        ("i", True),
        ("arr[3]", True),
        ("5", True),
        ("i + 1", False),
        ("MAX(i, k)", True),
        ("MAX(i, k + 1)", False),
        ("SEL(i > 0, k, i)", True),
        ("ABS(i)", False),
    ],
)
def test_stored_values_have_their_types_representation(expr, stored):
    assert R.is_stored_value(value(expr)) is stored


def test_within_and_fits():
    assert R.within((0, 9), 0, 9) and not R.within((0, 10), 0, 9) and not R.within(None, 0, 9)
    assert R.fits(T.BYTE, (0, 255)) and not R.fits(T.BYTE, (-1, 3)) and R.fits(T.INT, (-5, 510))
    assert not R.fits(T.INT, None)


@pytest.mark.parametrize(
    "expr,rng",
    [
        ("t", (-(1 << 31), (1 << 31) - 1)),  # a stored TIME is a wrapped 32-bit value
        ("TIME()", (-(1 << 31), (1 << 31) - 1)),  # the task clock, wrapped to TIME
        ("TIME() - t", (-(1 << 32) + 1, (1 << 32) - 1)),  # a difference may wrap
    ],
)
def test_interval_of_time_expressions(expr, rng):
    """TON's ET := PT copies a TIME without a wrap; TIME() - start wraps."""
    got = R.value_range(value(expr, "t : TIME; x : TIME;"))
    assert got == rng
    assert R.fits(T.TIME, got) == (rng[1] - rng[0] < 1 << 32)
