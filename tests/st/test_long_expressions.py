"""Expressions of thousands of operators (issue 31: the README promised more
than 1,000 operators in one expression; 198 integer ones were E006).

Each chain runs in virtual time and ends with the value the same
computation gives in Python, worked out here from the operands with IEC
semantics (DINT wraps, REAL is rounded to binary32 after every operation,
integer division truncates toward zero); what is still over a limit is a
coded E006 at the file, line and column, never a traceback or exit 4."""

from __future__ import annotations

import struct

import pytest

from softplc.runtime.st.limits import MAX_OPERATORS

from .conftest import run_st
from .test_hostile_language import no_traceback, softplc

N = 1000


def dint(v: int) -> int:
    return (v + (1 << 31)) % (1 << 32) - (1 << 31)


def f32(v: float) -> float:
    return struct.unpack("<f", struct.pack("<f", v))[0]


def idiv(a: int, b: int) -> int:
    q = abs(a) // abs(b)
    return q if (a < 0) == (b < 0) else -q


def program(decls: str, expr: str, target: str = "x") -> str:
    return f"PROGRAM Main\nVAR\n{decls}\nEND_VAR\n{target} := {expr};\nEND_PROGRAM\n"


def test_a_dint_chain_of_1000_operators_wraps_as_python_computes_it():
    values = [2_000_000_011, -7, 123_456_789, 3, -1_999_999_999]  # the sum passes DINT's range
    names = [f"v{k}" for k in range(len(values))]
    decls = "\n".join(f"{n} : DINT := {v};" for n, v in zip(names, values))
    ops = ["+" if k % 3 else "-" for k in range(N)]
    operands = [k % len(values) for k in range(N + 1)]
    expr = names[operands[0]] + "".join(f" {op} {names[i]}" for op, i in zip(ops, operands[1:]))
    want = values[operands[0]]
    for op, i in zip(ops, operands[1:]):
        want = dint(want + values[i] if op == "+" else want - values[i])
    assert expr.count(" + ") + expr.count(" - ") == N
    assert run_st(program(decls + "\nx : DINT;", expr), entry="Main").get("x") == want


def test_a_mixed_precedence_chain_of_1000_operators_keeps_iec_division():
    """a + b * c - d / e ...: each * and / binds first, / truncates toward
    zero on a negative dividend, the + and - go left to right."""
    a, b, c, d, e = 17, -5, 3, -1001, 7
    decls = f"a : DINT := {a}; b : DINT := {b}; c : DINT := {c}; d : DINT := {d}; e : DINT := {e}; x : DINT;"
    expr = "a" + " + b * c - d / e" * (N // 4)
    want = a
    for _ in range(N // 4):
        want = want + b * c - idiv(d, e)
    assert run_st(program(decls, expr), entry="Main").get("x") == dint(want)


def test_a_bool_chain_of_1000_and_or_xor_follows_iec_precedence():
    """AND binds before XOR before OR (IEC 61131-3 Table 71), as & ^ | do in
    Python; the chain mixes all three over four variables."""
    values = {"p": True, "q": False, "r": True, "s": False}
    decls = "p : BOOL := TRUE; q : BOOL := FALSE; r : BOOL := TRUE; s : BOOL := FALSE; x : BOOL;"
    ops = [("AND", "&"), ("OR", "|"), ("XOR", "^"), ("AND", "&"), ("XOR", "^")]
    names = list(values)
    st, py = ["p"], ["p"]
    for k in range(N):
        st_op, py_op = ops[k % len(ops)]
        name = names[(k * 3 + 1) % len(names)]
        st.append(f" {st_op} {name}")
        py.append(f" {py_op} {name}")
    want = bool(eval("".join(py), {}, dict(values)))  # the same text with Python's operators
    got = run_st(program(decls, "".join(st)), entry="Main").get("x")
    assert got is want
    # the same chain with every variable flipped
    flipped = program(decls.replace("TRUE", "T_").replace("FALSE", "TRUE").replace("T_", "FALSE"), "".join(st))
    want_flipped = bool(eval("".join(py), {}, {k: not v for k, v in values.items()}))
    assert run_st(flipped, entry="Main").get("x") is want_flipped


def test_a_chain_of_1000_ands_follows_its_one_changing_operand():
    """z flips every cycle (z := NOT z before the chain): the AND of 1,000
    operands is z's value of that cycle."""
    operands = ["c"] * (N + 1)
    operands[N // 2] = "z"
    src = (
        "PROGRAM Main\nVAR c : BOOL := TRUE; z : BOOL; b : BOOL; END_VAR\n"
        f"z := NOT z;\nb := {' AND '.join(operands)};\nEND_PROGRAM\n"
    )
    runner = run_st(src, entry="Main")
    z = True
    for _ in range(3):
        assert runner.get("b") is all({"c": True, "z": z}[o] for o in operands)
        runner.run(1)
        z = not z


def test_a_real_chain_of_1000_operators_is_rounded_after_every_operation():
    """r := r * 1.0001 + r * 1.0001 ...: binary32 after every * and +, over
    three cycles (each starts from the last one's r)."""
    decls = "r : REAL := 0.1;"
    expr = " + ".join(["r * 1.0001"] * (N // 2))
    runner = run_st(program(decls, expr, target="r"), cycles=3, entry="Main")
    r, k = f32(0.1), f32(1.0001)
    for _ in range(3):
        acc = f32(r * k)
        for _ in range(N // 2 - 1):
            acc = f32(acc + f32(r * k))
        r = acc
    assert runner.get("r") == r


def test_a_chain_in_a_condition_and_a_call_argument():
    """A long chain where an expression is nested in something else: an IF
    condition and an argument of a function (the temporaries of the chain
    must not break either)."""
    decls = "a : INT := 3; x : DINT; y : DINT;"
    chain = " + ".join(["a"] * (N + 1))
    src = (
        "PROGRAM Main\nVAR\n" + decls + "\nEND_VAR\n"
        f"IF {chain} > 3000 THEN x := 1; ELSE x := 2; END_IF;\n"
        f"y := ABS(-({chain}) - ({chain}));\nEND_PROGRAM\n"
    )
    runner = run_st(src, entry="Main")
    assert runner.get("x") == (1 if 3 * (N + 1) > 3000 else 2)
    assert runner.get("y") == 2 * 3 * (N + 1)


def test_the_limit_of_operators_compiles_and_one_more_is_a_coded_e006(tmp_path):
    ok = tmp_path / "ok.st"
    ok.write_text(program("a : LINT := 1; x : LINT;", " + ".join(["a"] * (MAX_OPERATORS + 1))))
    proc = softplc("check", ok)
    no_traceback(proc)
    assert proc.returncode == 0, proc.stderr
    over = tmp_path / "over.st"
    over.write_text(program("a : LINT := 1; x : LINT;", " + ".join(["a"] * (MAX_OPERATORS + 2))))
    proc = softplc("check", over)
    no_traceback(proc)
    assert proc.returncode == 1
    assert f"over.st:5:6: error E006: expression too long (more than {MAX_OPERATORS:,} operators)" in proc.stderr


@pytest.mark.parametrize(
    ("expr", "message"),
    [
        ("(" * N + "a" + " + a)" * N, "more than 300 levels of the parser"),
        ("a + (" * N + "a" + ")" * N, "more than 300 levels of the parser"),
        (" + ".join(["1"] * (N + 1)), "nested too deeply for the checker"),
    ],
    ids=["left-nested", "right-nested", "literals"],
)
def test_nesting_past_the_limit_is_a_coded_e006(tmp_path, expr, message):
    path = tmp_path / "deep.st"
    path.write_text(program("a : DINT := 1; x : DINT;", expr))
    proc = softplc("check", path)
    no_traceback(proc)
    assert proc.returncode == 1
    assert "deep.st:5:" in proc.stderr and "error E006" in proc.stderr and message in proc.stderr
    assert "RecursionError" not in proc.stderr
