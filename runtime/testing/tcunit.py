"""TcUnit's tests under ``softplc test``: a program (PRG_TEST, MAIN) that
calls TcUnit.RUN() every cycle, with test suites (instances of blocks that
EXTEND TcUnit.FB_TestSuite) among its variables, run in virtual time until
TcUnit reports every test finished, or the timeout.

    run = run_tcunit(config, program, timeout_ns)   # a fresh engine
    run.results     # a TestResult per test (runner.py): PASS/FAIL/SKIP, each
                    # failed assert with its file:line and both values
    run.log         # TcUnit's messages (FAILED TEST '...', EXP: 5, ACT: 4, MSG: ...)

The library (fblocks/libs/tcunit) keeps TcUnit's books in its service
(service.py); this module binds it on the engine with what it needs of the
engine: the clock, the suites found in the program instances (in the order
TcUnit registers them: declaration order), and where the test's code made
a call (the innermost frame of generated code outside the library, mapped
to its ST statement by the program's line maps, as runtime faults are).
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, field
from itertools import product

from ...fblocks.libs.tcunit.natives import SERVICE
from ...fblocks.libs.tcunit.service import LogLine, TcUnit
from ..engine.build import build_engine
from ..program.shipped import shipped_named
from ..st import types as T
from ..st.faults import STFault
from ..st.native import CallSite
from .discover import TestCase
from .natives import Failure
from .runner import ERROR, FAILED, PASSED, SKIPPED, TestResult, quiet

LIBRARY = "TcUnit"
SUITE = "FB_TESTSUITE"
# A TcUnit run's cycles may be long: RUN() calls every suite's tests in
# each cycle (TwinCAT counts such a cycle as an overrun and goes on; TcUnit's
# FAQ 7: RUN_IN_SEQUENCE for fewer). Its tasks' watchdog (CPU time of a
# cycle, in virtual time) is at least this, enough for an endless loop.
WATCHDOG_NS = 10_000_000_000


def tcunit_library():
    """The TcUnit library softplc ships, as the compiler takes it."""
    return shipped_named(LIBRARY)


def uses_tcunit(program) -> bool:
    """Whether program declares test suites: blocks extending TcUnit's FB_TestSuite."""
    return any(_extends_suite(info) for info in program.checked.pous if not info.library)


def _extends_suite(info) -> bool:
    base = info.base
    while base is not None:
        if base.name.upper() == SUITE and base.library:
            return True
        base = base.base
    return False


@dataclass
class TcUnitRun:
    """What one run gives: the results, TcUnit's messages, the errors of
    the run itself (the timeout; TcUnit's errors about the tests, such as a
    duplicate name), the number of suites and the engine time it took."""

    results: list[TestResult] = field(default_factory=list)
    log: list[LogLine] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    suites: int = 0
    ran: bool = False  # whether a program called TcUnit.RUN()
    time_ns: int = 0
    wall_s: float = 0.0


class _Host:
    """The engine's side of the TcUnit service (service.Host)."""

    def __init__(self, engine, library_files: frozenset) -> None:
        self.engine = engine
        self.library_files = library_files

    def now_ns(self) -> int:
        return self.engine.now_ns()

    def suites(self) -> list:
        ns = self.engine.ns
        info = next((i for i in self.engine.program.checked.pous if i.name.upper() == SUITE and i.library), None)
        cls = ns.get(info.pyname) if info is not None else None
        if cls is None:
            return []
        found: list = []
        seen: set = set()
        _walk(ns["_G"], "", cls, found, seen)
        for name, _info, obj in self.engine.instances.values():
            if obj is not None:
                _walk(obj, name, cls, found, seen)
        return found

    def caller(self, site):
        """site when the test's code made the call, else the statement of the
        innermost generated frame that is not the library's."""
        if site is not None and site.file not in self.library_files:
            return site
        linemaps = self.engine.program.linemaps
        frame = sys._getframe(1)
        while frame is not None:
            lines = linemaps.get(frame.f_code.co_filename)
            pos = lines.get(frame.f_lineno) if lines is not None else None
            if pos is not None and pos.file not in self.library_files:
                return CallSite(pos.file, pos.line, pos.col)
            frame = frame.f_back
        return site


def _walk(obj, path: str, cls, found: list, seen: set) -> None:
    """The instances of cls inside obj, by their ST paths, in declaration order."""
    if id(obj) in seen:
        return
    seen.add(id(obj))
    for name, attr, ty, section in getattr(type(obj), "_VARS_", ()):
        if section in ("VAR_IN_OUT", "VAR_EXTERNAL") or isinstance(T.resolve(ty), (T.RefType, T.InterfaceType)):
            continue
        value = getattr(obj, attr, None)
        where = f"{path}.{name}" if path else name
        _value(value, where, T.resolve(ty), cls, found, seen)


def _value(value, where: str, ty, cls, found: list, seen: set) -> None:
    if isinstance(value, list) and isinstance(ty, T.ArrayType):  # suites in an array: arr[1], m[1,2]
        dims = [d if d is not None else (0, 0) for d in ty.dims]
        items = value
        for _ in dims[1:]:
            items = [x for row in items for x in row]
        for at, item in zip(product(*(range(lo, hi + 1) for lo, hi in dims)), items):
            _value(item, f"{where}[{','.join(map(str, at))}]", T.resolve(ty.elem), cls, found, seen)
        return
    if getattr(type(value), "_VARS_", None) is None:
        return
    if isinstance(value, cls):
        found.append((where, value))
    _walk(value, where, cls, found, seen)


def run_tcunit(config, program, timeout_ns: int, select=None, extra_tasks: tuple = ()) -> TcUnitRun:
    """Run program's tasks (config's) in a fresh engine in virtual time
    until TcUnit reports every suite finished, a runtime fault stops a task,
    or timeout_ns of engine time; select(path 'PRG_TEST.Suite@Test') picks
    the tests that run (-k), the others are skipped; extra_tasks run beside
    config's (the test files' PROGRAMs next to a configured plant)."""
    started = time.perf_counter()
    engine = build_engine(
        config, virtual_time=True, start_mode="cold", program=program, extra_tasks=extra_tasks, retain=False
    )
    library = tcunit_library()
    files = frozenset(str(f) for f in library.files()) if library is not None else frozenset()
    service = TcUnit(_Host(engine, files), select)
    engine.ctx.services[SERVICE] = service
    for task in engine.tasks:
        if task.watchdog_ns is not None and task.watchdog_ns < WATCHDOG_NS:
            task.watchdog_ns = WATCHDOG_NS
            task.budget_s = WATCHDOG_NS * task.sensitivity / 1e9
    tasks = [*config.tasks, *extra_tasks]
    window = max((t.interval_ns for t in tasks if t.interval_ns), default=10_000_000)

    def watch(engine) -> None:
        if service.done or engine.faults or (service.runs == 0 and engine.now_ns() >= window):
            engine.request_stop()

    engine.after_tick.append(watch)
    out = TcUnitRun()
    fault = ""
    try:
        with quiet():
            engine.start()
            engine.run(duration_ns=timeout_ns)
    except STFault as e:
        fault = f"initial values: {e}"
    finally:
        with quiet():
            engine.stop()
    if engine.faults:
        fault = "; ".join(str(f) for f in engine.faults)
    out.ran = service.runs > 0
    out.suites = len(service.suites or [])
    out.log = list(service.log)
    out.time_ns = engine.now_ns()
    out.wall_s = time.perf_counter() - started
    out.results = _results(service, select, fault, timeout_ns, out.time_ns)
    out.errors = [line.text for line in service.log if line.level == "error" and line.kind == "tcunit"]
    if service.aborted:
        out.errors.append(f"TcUnit stopped the run: {service.aborted}")
    if fault:
        out.errors.append(fault)
    elif out.ran and not service.done:
        out.errors.append(f"timed out after {timeout_ns / 1e9:g} s of engine time: a test never called TEST_FINISHED()")
    return out


def _results(service: TcUnit, select, fault: str, timeout_ns: int, end_ns: int) -> list[TestResult]:
    out = []
    for suite in service.suites or []:
        for t in suite.tests:
            path = suite.at(t.name)
            if select is not None and not select(path):
                continue
            site = t.site
            case = TestCase(t.name, site.file if site else "", site.line if site else 0, classname=suite.path)
            failures = [
                Failure(f.site, f.function, f.message, f.expected, f.actual, f.time_ns, detail=f.line)
                for f in t.failures
            ]
            started = t.started_ns if t.started_ns is not None else end_ns
            took = (t.finished_ns if t.finished_ns is not None else end_ns) - started
            result = TestResult(case, PASSED, took, failures)  # engine time from TEST() to TEST_FINISHED()
            result.asserts = t.asserts
            if t.skipped:
                result.outcome = SKIPPED
            elif t.failed or failures:
                result.outcome = FAILED
            elif not t.finished:
                result.outcome = ERROR if fault else FAILED
                result.error = (
                    fault
                    or (service.aborted and f"not finished when TcUnit stopped the run ({service.aborted})")
                    or f"timed out after {timeout_ns / 1e9:g} s of engine time without TEST_FINISHED()"
                )
            out.append(result)
    return out
