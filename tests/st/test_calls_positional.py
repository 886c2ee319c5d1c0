"""Non-formal (positional) calls that include outputs (runtime/st/check/checker_calls.py
_positional_params): a program and the values its variables hold after a cycle.

IEC 61131-3 ed.3 6.6.1.4.2: a non-formal call lists its arguments in the order
the parameters are declared, EN and ENO left out; TwinCAT 3 ("Userdefined
Functions"): "The order of declaration is significant. It is used for
nonformal calls." An output given positionally is the variable it is written
to, as `name => variable` would be.
"""

from __future__ import annotations

from .conftest import diagnostics, prog, run_st

_F = """
FUNCTION f : INT
VAR_INPUT a : INT; END_VAR
VAR_OUTPUT q : INT; END_VAR
VAR_IN_OUT io : INT; END_VAR
q := a * 2; io := io + 1; f := a + 1;
END_FUNCTION
"""


def test_a_standard_split_function_called_without_names():
    src = prog(
        "h, m, s, ms : INT; y, mo, d : INT;",
        "SPLIT_TOD(TOD#13:45:12.345, h, m, s, ms);\nSPLIT_DATE(D#2024-02-29, y, mo, d);",
    )
    r = run_st(src)
    assert [r.get(n) for n in ("h", "m", "s", "ms", "y", "mo", "d")] == [13, 45, 12, 345, 2024, 2, 29]


def test_outputs_and_in_outs_bind_in_declaration_order():
    # declared: a (input), q (output), io (in-out)
    src = _F + prog("r : INT; x : INT; y : INT := 7;", "r := f(5, x, y);")
    r = run_st(src)
    assert (r.get("r"), r.get("x"), r.get("y")) == (6, 10, 8)


def test_a_call_with_only_inputs_and_in_outs_skips_the_outputs():
    # as before: no more positional arguments than inputs and in-outs bind those alone
    src = _F + prog("r : INT; y : INT := 7;", "r := f(5, y);")
    r = run_st(src)
    assert (r.get("r"), r.get("y")) == (6, 8)


def test_a_function_block_called_without_names_writes_its_outputs():
    # TON's declaration order: IN, PT, then Q, ET
    src = prog("t : TON; q : BOOL; et : TIME;", "t(TRUE, T#50ms, q, et);")
    r = run_st(src, cycles=6)
    assert (r.get("q"), r.get("et")) == (True, 50)


def test_a_positional_output_needs_a_variable():
    d = [x for x in diagnostics(_F + prog("r : INT; y : INT;", "r := f(5, 3, y);")) if x.severity == "error"]
    assert [(x.code, x.pos.line, x.pos.col) for x in d] == [("E031", 12, 11)]


def test_too_many_positional_arguments_counts_the_outputs():
    d = [x for x in diagnostics(_F + prog("r, x, y : INT;", "r := f(5, x, y, 1);")) if x.severity == "error"]
    assert [x.code for x in d] == ["E041"] and "takes 3" in d[0].message
