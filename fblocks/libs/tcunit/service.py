"""The TcUnit service: the natives of the library (natives.py) answered for
one run of a PLC, the way TcUnit's RUN, TEST, TEST_FINISHED and asserts
behave (tcunit.org: "Introduction user guide", "API", "FAQ" 1, 2, 7).

    service = TcUnit(host)                  # host: the engine's side (below)
    engine.ctx.services[SERVICE] = service  # runtime/testing/tcunit.py does it
    ... the engine runs until service.done
    service.suites, service.log             # the results, TcUnit's messages

The host gives the engine time (now_ns), the test suites in TcUnit's order
(suites: (instance path, instance) of every block extending FB_TestSuite)
and where the test's code made a call (caller: a native of the library
is called from the library's ST; the site wanted is the test's).

RUN() calls the body of every suite not finished, the current suite set
for the TEST and assert calls its tests make; RUN_IN_SEQUENCE() one suite
at a time, the next one two cycles after the last finished (TcUnit's timer
between suites, TimeBetweenTestSuitesExecution T#0MS). The run is done
when every suite has finished: each of its tests finished or skipped.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

from softplc.runtime.st import types as T

from . import values as V
from .books import Failure, Suite

MESSAGE_MAX = 253  # TcUnit: an ADS message of 254 characters, 253 with an argument
_NAME_TOO_LONG = "...TestName too long"
_MESSAGE_TOO_LONG = "...TestMsg too long"
_FAILED_LOOKUPS = 3  # TEST_FINISHED_NAMED's messages before it is quiet


class Host(Protocol):
    def now_ns(self) -> int: ...

    def suites(self) -> list[tuple[str, Any]]: ...

    def caller(self, site: Any) -> Any: ...


@dataclass(frozen=True)
class LogLine:
    """A message TcUnit writes (to the ADS log): its level ('error', 'warning',
    'hint'), its text, and whose it is: 'assert' (a failed assert), 'result'
    (the results, the summary), 'tcunit' (TcUnit's error about the tests: a
    duplicate name, a test TEST_FINISHED_NAMED does not find), 'user'
    (TCUNIT_ADSLOGSTR)."""

    level: str
    text: str
    kind: str = "tcunit"


class TcUnit:
    """The service of one run (a fresh engine)."""

    def __init__(self, host: Host, select=None) -> None:
        self.host = host
        self.select = select  # None, or test path -> whether it runs (-k); the others are skipped
        self.suites: list[Suite] | None = None
        self.log: list[LogLine] = []
        self.runs = 0  # RUN() calls: TcUnit's cycles
        self.done = False
        self.aborted = ""  # why the run was stopped (TEST_FINISHED_NAMED of a test that is not)
        self.started_ns = 0
        self.duration_s = 0.0
        self.current: Suite | None = None
        self.name = ""  # the current test's name
        self.finished = False  # TcUnit's CurrentTestIsFinished
        self.ignore = False  # TcUnit's IgnoreCurrentTest
        self.failed_lookups = 0
        self.sequence = 0  # RUN_IN_SEQUENCE: the suite running, and the run it may start in
        self.resume_at = 0

    # ------------------------------------------------------------ the natives

    def request(self, name: str, *args: Any) -> Any:
        handler = getattr(self, "_" + name.lower().lstrip("_"))
        return handler(*args)

    def _tcunit_run(self, in_sequence: bool) -> bool:
        self.runs += 1
        if self.suites is None:
            self.started_ns = self.host.now_ns()
            self.suites = [Suite(i, path, obj) for i, (path, obj) in enumerate(self.host.suites())]
        if self.done:
            return True
        first = self.runs == 1
        if self.aborted:
            pass
        elif not in_sequence:
            for suite in self.suites:
                if not suite.all_finished(first):
                    self._call(suite, first)
        elif self.suites:
            suite = self.suites[self.sequence]
            if suite.all_finished(first):
                if self.sequence < len(self.suites) - 1:
                    self.sequence += 1
                    self.resume_at = self.runs + 2
            elif self.runs >= self.resume_at:
                self._call(suite, first)
        if self.aborted or all(s.all_finished(first) for s in self.suites):
            self._finish()
        return True

    def _call(self, suite: Suite, first: bool) -> None:
        now = self.host.now_ns()
        self.current = suite
        if suite.started_ns is None:
            suite.started_ns = now
        suite.obj()  # the suite's body: its tests
        if suite.all_finished(first):
            suite.finished_ns = self.host.now_ns()

    def _tcunit_test(self, name: str, ordered: bool, site: Any) -> bool:
        name = name.strip(" \t")
        self.name = name
        suite = self.current
        if suite is None:
            return False
        where = self.host.caller(site)
        test, self.ignore, duplicate = suite.add(name, ordered, self.runs, where)
        if duplicate:
            self.log.append(LogLine("error", duplicate))
        if test is not None and self.select is not None and not self.select(suite.at(test.name)):
            test.skipped, self.ignore = True, True  # -k: as a disabled test
        self.finished = test is not None and test.finished
        if ordered and not self.ignore:
            if test is not None and test.order == suite.running_order:
                if self.finished:
                    suite.running_order += 1
                    self.ignore = True
                    return False
            else:
                self.ignore = True
                return False
        elif ordered:
            return False
        if test is not None and test.started_ns is None:
            test.started_ns = self.host.now_ns()
        return True

    def _tcunit_finished(self, name: str, named: bool) -> bool:
        suite = self.current
        if suite is None:
            return False
        if not named:
            suite.finish(self.name, self.host.now_ns(), self.name)
            self.finished = True
            return True
        name = name.strip(" \t")
        if suite.finish(name, self.host.now_ns(), self.name):
            self.finished = True
            return True
        if self.failed_lookups < _FAILED_LOOKUPS:
            self.failed_lookups += 1
            self.log.append(LogLine("error", f"Failed to find test '{name}'"))
            self.aborted = self.aborted or f"TEST_FINISHED_NAMED('{name}'): {suite.path} has no such test"
        elif self.failed_lookups == _FAILED_LOOKUPS:
            self.failed_lookups += 1
            self.log.append(
                LogLine(
                    "error", "Excess failed attempts to mark test finished, failed. Further warnings will be suppressed"
                )
            )
        return True

    def _tcunit_is_finished(self, name: str) -> bool:
        test = self.current.test(name.strip(" \t")) if self.current is not None else None
        return test is not None and test.finished

    def _tcunit_equals(self, holds: bool, kind: str, expected, actual, message: str, site) -> bool:
        if self._ignored():
            return True
        outcome = V.typed(kind, site.types[2], expected, actual, bool(holds), message)
        return self._report(outcome, kind, message, site, arrays=False)

    def _tcunit_arrays(self, kind: str, expecteds, actuals, delta: float, message: str, site) -> bool:
        if self._ignored():
            return True
        outcome = V.arrays(kind, site.types[1], expecteds, site.types[2], actuals, delta, message)
        return self._report(outcome, kind, message, site, arrays=True)

    def _assertequals(self, expected, actual, message: str, site) -> bool:
        if self._ignored():
            return True
        outcome = V.any_equals(site.types[0], expected, site.types[1], actual, message)
        return self._report(outcome, "AssertEquals", message, site, arrays=False)

    def _tcunit_log(self, mask: int, fmt: str, arg: str) -> bool:
        # ADSLOG_MSGTYPE_ERROR 4, _WARN 2, _HINT 1 (Tc2_System)
        level = "error" if int(mask) & 0x4 else "warning" if int(mask) & 0x2 else "hint"
        self.log.append(LogLine(level, fmt.replace("%s", arg, 1), "user"))
        return True

    # ------------------------------------------------------------ asserts

    def _ignored(self) -> bool:
        return self.ignore or self.finished or self.current is None

    def _report(self, outcome: V.Outcome, kind: str, message: str, site, arrays: bool) -> bool:
        suite = self.current
        assert suite is not None
        path = suite.at(self.name)
        ledger = suite.arrays if arrays else suite.values
        if not ledger.report((*outcome.key, message, path), path, self.runs) or outcome.holds:
            return outcome.holds
        suite.fail(self.name, outcome.atype, message)
        line = failure_line(path, outcome.expected, outcome.actual, outcome.message)
        self.log.append(LogLine("error", line, "assert"))
        test = suite.test(self.name)
        if test is not None:
            where = self.host.caller(site)
            shown = outcome.message
            test.failures.append(
                Failure(where, kind, shown, outcome.expected, outcome.actual, self.host.now_ns(), line)
            )
        return False

    # ------------------------------------------------------------ the results

    def _finish(self) -> None:
        self.done = True
        now = self.host.now_ns()
        self.duration_s = (now - self.started_ns) / 1e9
        for suite in self.suites or []:
            if suite.finished_ns is None and suite.started_ns is not None:
                suite.finished_ns = now
            self.log.extend(_suite_lines(suite))
        suites = self.suites or []
        tests = sum(len(s.tests) for s in suites)
        failed = sum(s.failed for s in suites)
        for text in (
            "| ==========TESTS FINISHED RUNNING==========",
            f"| Test suites: {len(suites)}",
            f"| Tests: {tests}",
            f"| Successful tests: {tests - failed}",
            f"| Failed tests: {failed}",
            f"| Duration: {seconds(self.duration_s)}",
            "| ======================================",
        ):
            self.log.append(LogLine("error", text, "result"))


def seconds(s: float) -> str:
    """A duration as TcUnit prints it (LREAL_TO_STRING of seconds)."""
    return V.text(T.LREAL, s)


def failure_line(path: str, expected: str, actual: str, message: str) -> str:
    """TcUnit's message for a failed assert (FB_AdsAssertMessageFormatter):
    FAILED TEST 'PRG_TEST.Suite@Test', EXP: 5, ACT: 4, MSG: the message;
    no MSG part for an empty message; the path and the message shortened
    as TcUnit does to fit an ADS message of 253 characters."""
    head = f"FAILED TEST '{path}', EXP: {expected}, ACT: {actual}"
    if message:
        head += ", MSG: %s"
    if len(head) + len(message) <= MESSAGE_MAX:
        shown_head, shown = head, message
    elif len(head) > MESSAGE_MAX - len(_MESSAGE_TOO_LONG):
        shown_head, shown = head[: MESSAGE_MAX - len(_NAME_TOO_LONG)] + _NAME_TOO_LONG, ""
    else:
        shown_head = head
        shown = message[: max(0, MESSAGE_MAX - len(_MESSAGE_TOO_LONG) - len(head))] + _MESSAGE_TOO_LONG
    return shown_head.replace("%s", shown, 1) if "%s" in shown_head else shown_head


def _suite_lines(suite: Suite) -> list[LogLine]:
    """TcUnit's extended results of a suite (LogExtendedResults)."""
    out = [
        f"| Test suite ID={suite.index} '{suite.path}'",
        f"| ID={suite.index} number of tests={len(suite.tests)}, number of failed tests={suite.failed}, "
        f"duration={seconds(suite.duration_s)}",
    ]
    for t in suite.tests:
        status = "FAIL" if t.failed else "SKIP" if t.skipped else "PASS"
        out += [
            f"| Test name={t.name}",
            f"| Test class name={suite.path}",
            f"| Test status={status}, number of asserts={t.asserts}, duration={seconds(t.duration_s)}",
        ]
        if t.amessage:
            out.append(f"| Test assert message={t.amessage}")
        if t.atype:
            out.append(f"| Test assert type={t.atype}")
    return [LogLine("hint", text, "result") for text in out]
