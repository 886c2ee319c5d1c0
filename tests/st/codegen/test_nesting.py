"""How deeply a file nests (runtime/st/codegen/nesting.py), which decides whether
`softplc check` runs the back end: the shallowest shapes CPython's compiler
refuses are past the safe limits, the deepest shapes within them compile,
and a check skips the back end only within them."""

from __future__ import annotations

import pytest

from softplc.runtime.program import compile as compile_mod
from softplc.runtime.program import compile_files
from softplc.runtime.program.compile import check_files
from softplc.runtime.st.codegen import nesting
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.profile import get_profile
from softplc.runtime.st.syntax.parser import parse_source


def _prog(body: str) -> str:
    return (
        "FUNCTION F : DINT VAR_INPUT a : DINT; END_VAR F := a; END_FUNCTION\n"
        "PROGRAM main\nVAR\nx : DINT; b : BOOL; a : ARRAY[1..2] OF DINT := [1, 1];\n"
        + " ".join(f"i{k} : INT;" for k in range(30))
        + "\nEND_VAR\n"
        + body
        + "\nEND_PROGRAM\n"
    )


def _labelled_whiles(n: int) -> str:
    """n WHILEs in each other, each body with a label (two Python blocks a level)."""
    opening = "".join(f"WHILE x < 0 DO\nl{k}: x := x + 1; IF x > 5 THEN JMP l{k}; END_IF;\n" for k in range(n))
    return opening + "END_WHILE\n" * n


def _elsifs(n: int) -> str:
    return "IF x = 0 THEN x := 1;\n" + "ELSIF x = 1 THEN x := 2;\n" * n + "END_IF;\n"


# The shallowest shapes the back end refuses (E006 from Python's compiler), measured.
REFUSED = {
    "21 nested REPEAT": "REPEAT\n" * 21 + "UNTIL TRUE END_REPEAT\n" * 21,
    "21 nested FOR": "".join(f"FOR i{k} := 1 TO 1 DO\n" for k in range(21)) + "x := 1;\n" + "END_FOR\n" * 21,
    "11 labelled WHILE": _labelled_whiles(11),
    "70 nested indices": f"x := {'a[' * 70}1{']' * 70};",
    "51 nested calls": f"x := {'F(a := ' * 51}x{')' * 51};",
    "3,000 ELSIF": _elsifs(3000),
}

# The deepest shapes within the limits: the back end takes them.
WITHIN = {
    "12 nested REPEAT": "REPEAT\n" * 12 + "UNTIL TRUE END_REPEAT\n" * 12,
    "6 labelled WHILE": _labelled_whiles(6),
    "34 nested indices": f"x := {'a[' * 34}1{']' * 34};",
    "17 nested calls": f"x := {'F(a := ' * 17}x{')' * 17};",
    "290 ELSIF": _elsifs(290),
}


def _parsed(body: str) -> list:
    return [parse_source(_prog(body), "m.st", DiagnosticBag(), get_profile("codesys"))]


@pytest.mark.parametrize("shape", list(REFUSED))
def test_what_python_refuses_is_too_deep_and_check_reports_it(shape):
    assert nesting.too_deep(_parsed(REFUSED[shape]))
    diags, _ = check_files([], texts={"m.st": _prog(REFUSED[shape])})
    assert [d.code for d in diags if d.is_error] == ["E006"]


@pytest.mark.parametrize("shape", list(WITHIN))
def test_what_is_within_the_limits_compiles(shape):
    assert not nesting.too_deep(_parsed(WITHIN[shape]))
    compile_files([], texts={"m.st": _prog(WITHIN[shape])})  # raises CompileError on E006


def test_a_check_skips_the_back_end_within_the_limits_only(monkeypatch):
    calls = []
    back_end = compile_mod._back_end
    monkeypatch.setattr(compile_mod, "_back_end", lambda *a: calls.append(1) or back_end(*a))
    assert check_files([], texts={"m.st": _prog(WITHIN["12 nested REPEAT"])})[0] == []
    assert calls == []
    assert check_files([], texts={"m.st": _prog(REFUSED["21 nested REPEAT"])})[0]
    assert calls == [1]
