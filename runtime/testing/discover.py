"""Which POUs of the test files are tests.

A test is a FUNCTION_BLOCK of a test file whose name starts with TEST_
(any case), or that carries the pragma {attribute 'test'} (CODESYS style,
between its name and its first declaration). It is instantiated once per
test run and called every cycle of its own task until it calls
TEST_FINISHED(), an assertion fails, or the timeout passes.
"""

from __future__ import annotations

import fnmatch
import re
from dataclasses import dataclass
from pathlib import Path

_ATTRIBUTE = re.compile(r"attribute\s+'test'\s*$", re.IGNORECASE)


@dataclass(frozen=True)
class TestCase:
    __test__ = False  # not a pytest class
    name: str  # the FUNCTION_BLOCK, as declared
    file: str  # the test file, as given
    line: int

    @property
    def suite(self) -> str:
        """The JUnit classname: the file's stem."""
        return Path(self.file).stem


def _is_test(pou) -> bool:
    return pou.name.upper().startswith("TEST_") or any(_ATTRIBUTE.match(str(p)) for p in pou.pragmas)


def discover(program, files: list) -> list[TestCase]:
    """The tests the files declare, in file then declaration order."""
    wanted = [str(f) for f in files]
    found = [
        TestCase(info.name, info.node.pos.file, info.node.pos.line)
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
