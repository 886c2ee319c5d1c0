#!/usr/bin/env python3
"""Benchmarks of the language's hardening (issue 31, see benchmarks/README.md).

    python benchmarks/bench_language_limits.py           # full run, about 30 s
    python benchmarks/bench_language_limits.py --quick   # smoke run, a few s

1. strings: a string-heavy scan (CONCAT, INSERT, REPLACE, LEFT, MID, DELETE
   stored into STRING[n] variables in a loop), us/cycle: what cutting every
   store at the declared length costs.
2. CASE: checking a CASE of N branches (and N duplicate labels), seconds:
   the label overlap check is sorted, not pairwise.
3. long expressions: compiling and running one expression of N operators
   (DINT +, BOOL AND and OR, REAL *, a + b * c - d ..., literals alone);
   past MAX_OPERATORS (10,000) or the checker's depth, the E-code.

Nothing here is asserted: the script prints figures measured in this run.
"""

from __future__ import annotations

import argparse
import time

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import CompileError

STRINGS = """
PROGRAM main
VAR
  a : STRING[80] := 'the quick brown fox';
  b : STRING[20] := 'jumps over';
  c : STRING[40];
  d : STRING[10];
  e : STRING[80];
  i, n : INT;
END_VAR
FOR i := 1 TO 100 DO
  c := CONCAT(a, b);
  d := INSERT(b, 'xyz', 3);
  e := REPLACE(a, b, 3, 5);
  c := LEFT(a, 12);
  d := MID(b, 4, 2);
  e := DELETE(a, 4, 1);
  e := a;
  n := n + LEN(c) + LEN(d);
END_FOR
END_PROGRAM
"""


def bench_strings(cycles: int) -> None:
    prog = compile_files([], texts={"strings.st": STRINGS})
    runner = prog.runner("main", cycle_time_ms=10)
    runner.run(5)
    best = float("inf")
    for _ in range(7):
        t0 = time.perf_counter()
        runner.run(cycles)
        best = min(best, (time.perf_counter() - t0) / cycles)
    print(f"strings: {best * 1e6:8.1f} us/cycle (700 string stores a cycle, best of 7 x {cycles} cycles)")


def case_source(n: int, duplicate: bool = False) -> str:
    labels = "\n".join(f"{0 if duplicate else k}: x := {k % 10};" for k in range(n))  # 60,000 within 1 MiB
    return f"PROGRAM main\nVAR k, x : DINT; END_VAR\nCASE k OF\n{labels}\nEND_CASE;\nEND_PROGRAM\n"


def expression_source(n: int, op: str) -> str:
    """x := a <op> a <op> ... with n operators; "mixed" is a + b * c - d ...,
    "literals" a chain of literals alone (a constant: the checker's limit)."""
    if op == "mixed":
        chain = "a" + " + b * c - d" * (n // 3) + " + a" * (n % 3)
        return f"PROGRAM main\nVAR a, b, c, d, x : DINT; END_VAR\nx := {chain};\nEND_PROGRAM\n"
    if op == "literals":
        return f"PROGRAM main\nVAR x : DINT; END_VAR\nx := {' + '.join(['1'] * (n + 1))};\nEND_PROGRAM\n"
    ty = "BOOL" if op in ("AND", "OR") else "REAL" if op == "*" else "DINT"
    return f"PROGRAM main\nVAR a, x : {ty}; END_VAR\nx := {f' {op} '.join(['a'] * (n + 1))};\nEND_PROGRAM\n"


def timed_check(name: str, text: str) -> tuple[float, int]:
    t0 = time.perf_counter()
    diags, _ = check_files([], texts={name: text})
    return time.perf_counter() - t0, sum(d.is_error for d in diags)


def bench_case(sizes: list[int]) -> None:
    for n in sizes:
        secs, errors = timed_check("case.st", case_source(n))
        dsecs, derrors = timed_check("dup.st", case_source(n, duplicate=True))
        print(f"CASE {n:6d} branches: check {secs:6.2f} s ({errors} errors)", end="; ")
        print(f"all labels 0: {dsecs:6.2f} s ({derrors} errors)")


def bench_expressions(sizes: list[int]) -> None:
    for n in sizes:
        for op in ("+", "AND", "OR", "*", "mixed", "literals"):
            t0 = time.perf_counter()
            try:
                prog = compile_files([], texts={"expr.st": expression_source(n, op)})
                prog.runner("main", cycle_time_ms=10).run(1)
                what = "compiled and ran"
            except CompileError as exc:  # a limit is a figure too
                what = ", ".join(sorted({d.code for d in exc.diagnostics if d.is_error}))
            print(f"expression of {n:5d} {op:8s}: {time.perf_counter() - t0:6.2f} s, {what}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a smoke run with small sizes")
    args = ap.parse_args()
    bench_strings(20 if args.quick else 200)
    bench_case([1000] if args.quick else [1000, 10_000, 40_000, 60_000])
    bench_expressions([1000] if args.quick else [200, 1000, 5000, 10_000, 10_001])


if __name__ == "__main__":
    main()
