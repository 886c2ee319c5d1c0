"""The STRING/WSTRING length oracle (issue 31: `h := CONCAT(h, 'abc')`
grew past its STRING[10] every cycle): random string functions stored into
variables, a STRUCT field and an array element of random declared lengths
compile, run one cycle and hold exactly what the reference (string_ops.py,
Python slicing; a WSTRING's UTF-16 units) gives, never more than their
declared length, and LEN of each is the reference's."""

from __future__ import annotations

from hypothesis import given

from softplc.runtime.program import compile_files

from .string_ops import NAMES, TARGETS, cases, expected, length, source
from .support import bounded, fuzz, long, short


def _check(case) -> str:
    src = source(case)
    with bounded("a string program"):
        runner = compile_files([], texts={"strings.st": src}).runner("Main")
        runner.run(1)
    want = expected(case)
    for target in TARGETS:
        got = runner.get("arr")[1] if target == "arr[2]" else runner.get(target)
        assert length(got, case.wide) <= case.lengths[target], f"{target} longer than declared:\n{src}"
        assert got == want[target], f"{target}: {got!r}, the reference {want[target]!r}\n{src}"
    for name in NAMES:
        assert runner.get(f"len_{name}") == want[f"len_{name}"], f"LEN({name})\n{src}"
    return "wide" if case.wide else "narrow"


@short(15)
@given(cases())
def test_string_functions_hold_the_reference_within_the_declared_length(case):
    _check(case)


@fuzz
def test_long_string_functions(tally, shard):
    counts = tally("st")

    @long("st", 0.05, shard, per_example=6)
    @given(cases())
    def run(case):
        counts.add(_check(case))

    run()
