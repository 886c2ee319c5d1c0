"""Fuzzing the ST front end, pathological nesting: deep parentheses, IFs,
types and initialisers end in a diagnostic (or compile and compute), never
in a RecursionError or a hang."""

from __future__ import annotations

import pytest

hypothesis = pytest.importorskip("hypothesis")

from softplc.runtime.program import compile_files  # noqa: E402

from .fuzz_support import FILE, check_and_maybe_run  # noqa: E402

# ---------------------------------------------------------------- pathological nesting


def _prog(body: str, decls: str = "x : DINT;") -> str:
    return f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"


@pytest.mark.parametrize("depth", [50, 5000])
def test_deeply_nested_parentheses(depth):
    src = _prog(f"x := {'(' * depth}1{')' * depth};")
    diags = check_and_maybe_run("codesys", src, cycles=1)
    if depth >= 5000:
        assert [d for d in diags if d.is_error], "5000 levels should be refused with a diagnostic"


@pytest.mark.parametrize("depth", [2000])
def test_deeply_nested_ifs(depth):
    body = "IF x < 10 THEN x := x + 1;\n" * depth + "END_IF;\n" * depth
    diags = check_and_maybe_run("codesys", _prog(body), cycles=1)
    assert [d for d in diags if d.is_error]


# Shapes the ST front end may accept but whose straightforward Python
# translation exceeds a CPython limit: 20 statically nested loops
# ("too many statically nested blocks"), 100 indentation levels, 200 nested
# brackets in one expression, the compiler's recursion limit. The compiler
# must refuse them with a diagnostic or generate code that Python accepts.
def _nested(open_: str, close: str, n: int) -> str:
    return open_ * n + close * n


BEYOND_PYTHON_LIMITS = {
    "21 nested WHILE": lambda: _nested("WHILE x < 0 DO\n", "END_WHILE\n", 21),
    "21 nested REPEAT": lambda: _nested("REPEAT\n", "UNTIL TRUE END_REPEAT\n", 21),
    "21 nested FOR": lambda: (
        "".join(f"FOR i{k} := 1 TO 1 DO\n" for k in range(21)) + "x := x + 1;\n" + "END_FOR\n" * 21
    ),
    "25 mixed loops": lambda: _nested("WHILE x < 0 DO\nREPEAT\n", "UNTIL TRUE END_REPEAT\nEND_WHILE\n", 13),
    "98 nested IF": lambda: _nested("IF x < 1000 THEN x := x + 1;\n", "END_IF;\n", 98),
    "98 nested CASE": lambda: _nested("CASE x OF 0..1000: x := x + 1;\n", "END_CASE\n", 98),
    "98 nested IF/ELSE": lambda: _nested("IF x > 1000 THEN x := 0; ELSE\n", "END_IF;\n", 98),
    "200 unary minus": lambda: f"x := {'-' * 200}x;",
    "200 spaced unary minus": lambda: f"x := {'- ' * 200}x;",
    "210 NOT": lambda: f"b := {'NOT ' * 210}b;",
    "200-term sum": lambda: "x := " + " + ".join(["x"] * 200) + ";",
    "200-term difference": lambda: "x := " + " - ".join(["x"] * 200) + ";",
    "210-term AND": lambda: "b := " + " AND ".join(["b"] * 210) + ";",
    "210-term power": lambda: "r := " + " ** ".join(["r"] * 210) + ";",
    "200 nested sums": lambda: "x := " + "(x + " * 200 + "x" + ")" * 200 + ";",
    "200 nested ABS": lambda: f"x := {'ABS(' * 200}x{')' * 200};",
    "110 nested indices": lambda: f"x := {'a[' * 110}1{']' * 110};",
    "4000 ELSIF": lambda: "IF x = 0 THEN x := 1;\n" + "ELSIF x = 1 THEN x := 2;\n" * 4000 + "END_IF",
}
_LIMIT_DECLS = "x : DINT; b : BOOL; r : LREAL := 1.0; a : ARRAY[1..2] OF DINT := [1, 1]; " + " ".join(
    f"i{k} : INT;" for k in range(21)
)


@pytest.mark.parametrize("shape", list(BEYOND_PYTHON_LIMITS))
def test_programs_beyond_cpython_compiler_limits(shape):
    check_and_maybe_run("codesys", _prog(BEYOND_PYTHON_LIMITS[shape](), _LIMIT_DECLS), cycles=1)


@pytest.mark.parametrize(
    "body,var,expected",
    [
        ("".join(f"FOR i{k} := 1 TO 1 DO\n" for k in range(18)) + "x := x + 1;\n" + "END_FOR\n" * 18, "x", 1),
        (_nested("WHILE x < 1 DO\n", "x := x + 1; END_WHILE\n", 18), "x", 18),
        (_nested("IF x < 1000 THEN x := x + 1;\n", "END_IF;\n", 60), "x", 60),
        ("x := 2; x := " + " + ".join(["x"] * 150) + ";", "x", 300),
        ("x := 3; x := " + "-" * 100 + "x;", "x", 3),
        ("b := " + "NOT " * 101 + "b;", "b", True),
        (
            "x := 7; IF x = 0 THEN x := 1;\n"
            + "".join(f"ELSIF x = {k} THEN x := {k * 10};\n" for k in range(1, 1000))
            + "END_IF",
            "x",
            70,
        ),
    ],
    ids=["18 FOR", "18 WHILE", "60 IF", "150-term sum", "100 minus", "101 NOT", "1000 ELSIF"],
)
def test_deep_but_reasonable_programs_still_compile_and_compute(body, var, expected):
    diags = check_and_maybe_run("codesys", _prog(body, _LIMIT_DECLS), cycles=1)
    assert not [d for d in diags if d.is_error], [d.format() for d in diags]
    r = compile_files([], texts={FILE: _prog(body, _LIMIT_DECLS)}).runner("main")
    r.run(1)
    assert r.get(var) == expected


@pytest.mark.parametrize(
    "build",
    [
        lambda n: f"x := {'-' * n}1;",  # unary chain
        lambda n: f"x := {'NOT ' * n}TRUE;",
        lambda n: "x := " + " + ".join(["1"] * n) + ";",  # long flat (left-assoc) chain
        lambda n: "x := 2" + " ** 1" * n + ";",
        lambda n: "WHILE x < 0 DO\n" * n + "END_WHILE\n" * n,
        lambda n: "CASE x OF 1:\n" * n + "END_CASE\n" * n,
        lambda n: "FOR x := 1 TO 2 DO\n" * n + "END_FOR\n" * n,
        lambda n: "REPEAT\n" * n + "UNTIL TRUE END_REPEAT\n" * n,
        lambda n: f"x := {'ABS(' * n}1{')' * n};",  # nested calls
        lambda n: "x := a" + "[1]" * n + ";",
        lambda n: "x := a" + "^" * n + ";",
        lambda n: "x := s" + ".f" * n + ";",
        lambda n: "(*" * n + "*)" * n,  # nested comments
        lambda n: "(" * n,  # never closed
        lambda n: "IF TRUE THEN " * n,  # never closed
        lambda n: "x := " + "[" * n,
    ],
    ids=[
        "neg",
        "not",
        "sum",
        "pow",
        "while",
        "case",
        "for",
        "repeat",
        "calls",
        "index",
        "deref",
        "member",
        "comments",
        "open-parens",
        "open-ifs",
        "open-brackets",
    ],
)
def test_other_pathological_shapes(build):
    check_and_maybe_run("codesys", _prog(build(3000)), cycles=1)


def test_deep_nesting_of_types_and_initialisers():
    n = 2000
    decls = f"a : {'ARRAY[1..1] OF ' * n}INT; b : ARRAY[1..1] OF INT := {'[' * n}1{']' * n}; c : {'REF_TO ' * n}INT;"
    check_and_maybe_run("codesys", _prog("x := 1;", decls), cycles=1)


def test_many_declarations_and_statements():
    decls = "".join(f"v{i} : INT := {i % 100};\n" for i in range(3000))
    body = "".join(f"v{i} := v{i - 1} + 1;\n" for i in range(1, 3000))
    r = compile_files([], texts={FILE: _prog(body, decls)}).runner("main")
    r.run(1)
    assert r.get("v2999") == 2999


def test_huge_literals_and_lines():
    src = _prog("x := " + "9" * 5000 + ";\ns := '" + "a" * 100_000 + "';\n", "x : DINT; s : STRING[255];")
    diags = check_and_maybe_run("codesys", src, cycles=1)
    assert [d for d in diags if d.is_error]  # 9999... does not fit a DINT
