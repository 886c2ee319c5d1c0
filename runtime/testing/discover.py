"""Which POUs of the test files are tests.

A test is a FUNCTION_BLOCK of a test file whose name starts with TEST_
(any case), or that carries the pragma {attribute 'test'} (CODESYS style,
between its name and its first declaration). {attribute 'timeout' := '20s'}
there gives it its own timeout in engine time (T#20s works too). It is instantiated once per
test run and called every cycle of its own task until it calls
TEST_FINISHED(), an assertion fails, or the timeout passes.
"""

from __future__ import annotations

import fnmatch
import re
from dataclasses import dataclass
from pathlib import Path

from ..durations import EXAMPLES, parse_duration_ns

_ATTRIBUTE = re.compile(r"attribute\s+'test'\s*$", re.IGNORECASE)
_TIMEOUT = re.compile(r"attribute\s+'timeout'\s*:=\s*'([^']*)'\s*$", re.IGNORECASE)


class TestError(ValueError):
    """A test's declaration is wrong (its timeout); the message says where."""

    __test__ = False  # not a pytest class


@dataclass(frozen=True)
class TestCase:
    __test__ = False  # not a pytest class
    name: str  # the FUNCTION_BLOCK, as declared
    file: str  # the test file, as given
    line: int
    timeout_ns: int | None = None  # its own, from {attribute 'timeout' := '...'}
    classname: str | None = None  # a TcUnit test's suite (PRG_TEST.fbSum_Test)

    @property
    def suite(self) -> str:
        """The JUnit classname: the file's stem, or a TcUnit test's suite."""
        return self.classname or Path(self.file).stem


def _is_test(pou) -> bool:
    return pou.name.upper().startswith("TEST_") or any(_ATTRIBUTE.match(str(p)) for p in pou.pragmas)


def _timeout(pou) -> int | None:
    for pragma in pou.pragmas:
        m = _TIMEOUT.match(str(pragma))
        if m:
            ns = parse_duration_ns(m.group(1))
            if ns is None or ns <= 0:
                raise TestError(
                    f"{pou.pos}: {pou.name}: timeout {m.group(1)!r} is not a positive duration (examples: {EXAMPLES})"
                )
            return ns
    return None


def discover(program, files: list) -> list[TestCase]:
    """The tests the files declare, in file then declaration order.
    TestError for a wrong timeout attribute."""
    wanted = [str(f) for f in files]
    found = [
        TestCase(info.name, info.node.pos.file, info.node.pos.line, _timeout(info.node))
        for info in program.checked.pous
        if info.kind == "FUNCTION_BLOCK" and not info.library and info.node.pos.file in wanted and _is_test(info.node)
    ]
    return sorted(found, key=lambda t: (wanted.index(t.file), t.line))


def select(tests: list[TestCase], pattern: str | None) -> list[TestCase]:
    """-k: a case-insensitive part of the name, or a glob (TEST_Motor*)."""
    if not pattern:
        return tests
    p = pattern.upper()
    if any(c in p for c in "*?["):
        return [t for t in tests if fnmatch.fnmatchcase(t.name.upper(), p)]
    return [t for t in tests if p in t.name.upper()]
