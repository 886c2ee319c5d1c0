"""Integer arithmetic a FOR loop repeats on values it never changes,
computed once before the loop (runtime/st/codegen/codegen_hoist.py). Each
test gives the loop a reason to see a new value (a store, a nested loop, a
reference, a call) and checks the result against the plain generator's
(CodeGenBase.optimise off) and the value worked out by hand."""

from __future__ import annotations

import pytest

from softplc.runtime import cache
from softplc.runtime.program import compile_files

from ..conftest import plain_codegen, prog, run_st

DECLS = "i, j, k, m, x, y : DINT; d : DINT := 0; go : BOOL := TRUE; a : ARRAY[0..9] OF DINT;"


def _body(text: str) -> str:
    src = compile_files([], texts={"test.st": text}).python_source
    return src[src.index("class P_main") :]


def test_a_product_the_loop_never_changes_is_computed_once_before_it():
    text = prog(DECLS, "k := 3; FOR i := 0 TO 9 DO x := x + (k * 7 + i) MOD 10; END_FOR")
    body = _body(text)
    [moved] = [line.strip() for line in body.splitlines() if line.strip().startswith("_h")]
    local = moved.split(" = ")[0]
    assert "* 7" in moved and body.count(local) == 2  # bound before the loop, read in it
    assert body.index(moved) < body.index("for _i")
    assert run_st(text).get("x") == sum((21 + i) % 10 for i in range(10))


@pytest.mark.parametrize(
    "body,x",
    [
        ("k := 3; FOR i := 0 TO 2 DO x := x + k * 2; k := k + 1; END_FOR", 6 + 8 + 10),  # stored in the loop
        ("k := 3; FOR i := 0 TO 2 DO x := x + k * 2; IF go THEN k := 0; END_IF END_FOR", 6),
        ("k := 1; FOR i := 0 TO 2 DO x := x + k * 2; FOR j := 0 TO 1 DO k := k + 1; END_FOR END_FOR", 2 + 6 + 10),
        ("k := 1; FOR i := 0 TO 2 DO x := x + k * 2; FOR k := 5 TO 6 DO END_FOR END_FOR", 2 + 14 + 14),
        ("k := 1; FOR i := 0 TO 2 DO x := x + k * 2; Bump(v := k); END_FOR", 2 + 4 + 6),  # VAR_IN_OUT
        ("k := 1; FOR i := 0 TO 2 DO x := x + k * 2; y := (k := k + 2); END_FOR", 2 + 6 + 10),  # inside an expression
        (
            "FOR i := 0 TO 2 DO FOR j := 0 TO 2 DO x := x + i * 10 + j; END_FOR END_FOR",
            3 * (0 + 10 + 20) + 3 * (0 + 1 + 2),
        ),  # the outer's i
        ("FOR i := 0 TO 2 DO x := x + i * 2; END_FOR", 6),  # its own variable
        ("k := 3; FOR i := 1 TO 0 DO x := k * 3; END_FOR", 0),  # a loop that does not run
        ("k := 3; FOR i := 0 TO 2 DO IF d <> 0 THEN x := x + 100 / d; END_IF x := x + k - 1; END_FOR", 6),  # no / moved
    ],
)
def test_a_loop_sees_what_changes_the_values_it_reads(body, x):
    text = f"""
FUNCTION Bump : BOOL
VAR_IN_OUT v : DINT; END_VAR
v := v + 1;
Bump := TRUE;
END_FUNCTION
PROGRAM main
VAR {DECLS} END_VAR
{body}
END_PROGRAM
"""
    assert run_st(text).get("x") == x
    with plain_codegen(), cache.disabled():
        runner = compile_files([], texts={"test.st": text}).runner("main")
    runner.run(1)
    assert runner.get("x") == x


def test_a_functions_own_variables_and_inputs_move_too():
    text = """
FUNCTION Sum : DINT
VAR_INPUT n, m : DINT; END_VAR
VAR i : DINT; s : DINT; END_VAR
FOR i := 1 TO n DO s := s + i * (m * m - 1); END_FOR
Sum := s;
END_FUNCTION
PROGRAM main
VAR r : DINT; END_VAR
r := Sum(n := 4, m := 3);
END_PROGRAM
"""
    src = compile_files([], texts={"test.st": text}).python_source
    function = src[src.index("def F_sum") : src.index("class P_main")]
    assert "_h" in function
    assert run_st(text).get("r") == (1 + 2 + 3 + 4) * 8
