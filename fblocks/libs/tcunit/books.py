"""TcUnit's books: the test suites, their tests, and the asserts already
reported, kept as TcUnit keeps them (tcunit.org: "Introduction user guide",
"FAQ" 1, 2, 6, 7; the messages as TcUnit's verifier project expects them).

A test is known by its name in its suite (TEST('name') the first time); a
name called again in the same cycle of the suite is a duplicate: TcUnit
says so once ("Test with name 'X' already exists in test suite 'Y'") and
ignores the duplicate's asserts. A name starting with DISABLED_ (any case)
is a skipped test. A test's first failed assert gives its assertion type
and message; every failed assert is reported once: an assert identical to
one already made (the same expected and actual values, message and test)
in the suite's last cycle with asserts is reported again only when the
cycle makes more of them (a test asserting the same thing every cycle
reports it once).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

DISABLED = "disabled_"


@dataclass
class Failure:
    """One failed assert: where the test's code calls it (file:line:column),
    the assert, the message as TcUnit prints it, both values, the engine
    time and TcUnit's own line."""

    site: Any
    function: str
    message: str
    expected: str
    actual: str
    time_ns: int
    line: str


@dataclass
class Test:
    name: str
    order: int = 0  # TEST_ORDERED's place in its suite (1, 2 ...); 0 for TEST
    skipped: bool = False
    finished: bool = False
    failed: bool = False
    atype: str = ""  # TcUnit's assertion type of the first failed assert
    amessage: str = ""  # and its message (the first that is not empty)
    asserts: int = 0  # set when it finishes, as TcUnit counts them
    started_ns: int | None = None
    finished_ns: int | None = None
    last_cycle: int = -1
    duplicate_reported: bool = False
    site: Any = None  # where TEST() is first called for it
    failures: list = field(default_factory=list)

    @property
    def duration_s(self) -> float:
        if self.started_ns is None or self.finished_ns is None:
            return 0.0
        return (self.finished_ns - self.started_ns) / 1e9


class Ledger:
    """The asserts a suite reported (TcUnit's FB_AssertResultStatic, one for
    the asserts of values and one for those of arrays): which were new,
    and the test each counts for."""

    def __init__(self) -> None:
        self.counts: dict = {}  # key -> [made in the last cycle with asserts, made in this one]
        self.cycle = -1
        self.reported: dict = {}  # test path -> asserts reported

    def report(self, key: tuple, path: str, cycle: int) -> bool:
        """Whether this assert is new (to report); counts it for the test at path."""
        if cycle != self.cycle:
            self.cycle = cycle
            for k in [k for k, c in self.counts.items() if c[1] == 0]:
                del self.counts[k]  # made in neither cycle: as new next time (TcUnit frees its slot)
            for c in self.counts.values():
                c[0], c[1] = c[1], 0
        c = self.counts.setdefault(key, [0, 0])
        c[1] += 1
        if c[1] <= c[0]:
            return False
        self.reported[path] = self.reported.get(path, 0) + 1
        return True


class Suite:
    """A test suite: an instance of a block that EXTENDS FB_TestSuite, its
    instance path (PRG_TEST.fbSum_Test) and its tests in the order declared."""

    def __init__(self, index: int, path: str, obj: Any) -> None:
        self.index = index  # TcUnit's ID
        self.path = path
        self.obj = obj
        self.tests: list[Test] = []
        self.started_ns: int | None = None
        self.finished_ns: int | None = None
        self.ordered = 0  # tests declared by TEST_ORDERED
        self.running_order = 1  # the TEST_ORDERED test whose turn it is
        self.values = Ledger()
        self.arrays = Ledger()

    def test(self, name: str) -> Test | None:
        return next((t for t in self.tests if t.name == name), None)

    def all_finished(self, first_cycle: bool) -> bool:
        """TcUnit's AreAllTestsFinished: every test finished or skipped; a
        suite without tests once it ran a cycle after the first."""
        if self.tests:
            return all(t.finished or t.skipped for t in self.tests)
        return not first_cycle and self.started_ns is not None

    def add(self, name: str, ordered: bool, cycle: int, site: Any) -> tuple[Test | None, bool, str]:
        """TEST/TEST_ORDERED of name in cycle: (the test, or None for a
        skipped one; whether its asserts are ignored; TcUnit's message for a
        duplicate, or '')."""
        ignore, message = False, ""
        skipped = name.lower().startswith(DISABLED)
        if skipped:
            name = name[len(DISABLED) :]
        same = [t for t in self.tests if t.name == name]
        for t in same:
            if t.last_cycle == cycle:
                ignore = True
                if not t.duplicate_reported:
                    t.duplicate_reported = True
                    message = f"Test with name '{name}' already exists in test suite '{self.path}'"
            t.last_cycle = cycle
        if not same:
            t = Test(name, skipped=skipped, last_cycle=cycle, site=site)
            if ordered:
                self.ordered += 1
                t.order = self.ordered
            self.tests.append(t)
        if skipped:
            return None, True, message
        return self.test(name), ignore, message

    def finish(self, name: str, now_ns: int, current: str) -> bool:
        """TEST_FINISHED of the test of that name: whether the suite has it.
        Its asserts are counted as TcUnit does, by the current test's path
        (for TEST_FINISHED_NAMED, the test being called)."""
        t = self.test(name)
        if t is None:
            return False
        if not t.finished:
            t.finished, t.finished_ns = True, now_ns
        reported = self.values.reported.get(self.at(current), 0) + self.arrays.reported.get(self.at(current), 0)
        if reported:
            t.asserts = reported
        return True

    def fail(self, name: str, atype: str, message: str) -> None:
        for t in self.tests:
            if t.name == name:
                t.failed = True
                t.atype = t.atype or atype
                t.amessage = t.amessage or message

    def at(self, name: str) -> str:
        """TcUnit's test instance path: PRG_TEST.Suite@Test."""
        return f"{self.path}@{name}"

    @property
    def duration_s(self) -> float:
        if self.started_ns is None or self.finished_ns is None:
            return 0.0
        return (self.finished_ns - self.started_ns) / 1e9

    @property
    def failed(self) -> int:
        return sum(t.failed for t in self.tests)
