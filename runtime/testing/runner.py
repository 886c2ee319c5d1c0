"""Running ST tests: one fresh engine per test, in virtual time, with the
configured plant (its tasks, drivers and simulated devices) and the test
FUNCTION_BLOCK in a task of its own after the plant's tasks.

    suite = TestSuite.load("io_config/default.toml", ["st_programs/tests/test_default_plant.st"])
    for case in suite.tests:
        result = suite.run(case, timeout_ns=60_000_000_000)

A test ends at the end of the cycle in which it calls TEST_FINISHED() or
an assertion fails (every failure of that cycle is reported), when a
runtime fault stops a task, or at the timeout (engine time).
"""

from __future__ import annotations

import logging
import re
from dataclasses import dataclass, field
from pathlib import Path

from ..config import (
    DEFAULT_PAUSE_NS,
    PRIORITY_MAX,
    PlcConfig,
    ProgramInstance,
    TaskConfig,
    config_from_dict,
    default_watchdog_ns,
)
from ..config import load_config as _load_config
from ..engine.build import build_engine
from ..plugin.registry import registry
from ..program import compile_files
from ..program.shipped import shipped_named
from ..st.faults import STFault
from .discover import TestCase, discover
from .natives import NATIVES, SERVICE, Failure, Recorder, Simulated

DEFAULT_TIMEOUT_NS = 60_000_000_000  # st_pytest_plugin.py has it too
DEFAULT_INTERVAL_NS = 10_000_000

PASSED, FAILED, ERROR, SKIPPED = "passed", "failed", "error", "skipped"  # (SKIPPED: a disabled TcUnit test)


@dataclass
class TestResult:
    __test__ = False  # not a pytest class
    case: TestCase
    outcome: str  # PASSED, FAILED (an assertion or the timeout), ERROR (a runtime fault, the plant), SKIPPED
    time_ns: int  # engine time when it ended
    failures: list[Failure] = field(default_factory=list)
    error: str = ""  # the timeout or the fault, when there is no failed assertion
    asserts: int = 0
    wall_s: float = 0.0

    def describe(self) -> str:
        """The lines a report shows under a failed test."""
        parts = [f.describe() for f in self.failures]
        if self.error:
            parts.append(self.error)
        return "\n".join(parts)


_TCUNIT = re.compile(r"\bFB_TestSuite\b", re.IGNORECASE)


def _names_tcunit(files: list) -> bool:
    """Whether a test file declares TcUnit test suites (names FB_TestSuite):
    then it is compiled with the TcUnit library, whose TEST_FINISHED() is
    TcUnit's, not the ST tests' (natives.py)."""
    for f in files:
        try:
            if _TCUNIT.search(Path(f).read_text(encoding="utf-8", errors="replace")):
                return True
        except OSError:
            pass  # (the compiler says it cannot read it)
    return False


def _no_plant(files: list) -> PlcConfig:
    """The configuration of tests run without one: the test files, no
    buses; a PROGRAM the files declare runs in the default task."""
    return config_from_dict({"plc": {"programs": [str(Path(f).resolve()) for f in files]}})


class TestSuite:
    """The test files compiled with the configuration's programs (once),
    and the tests they declare."""

    __test__ = False  # not a pytest class

    def __init__(self, config: PlcConfig, files: list) -> None:
        self.config = config
        self.files = [str(f) for f in files]
        mine = {Path(f).resolve() for f in self.files}
        plant = [p for p in config.programs if Path(p).resolve() not in mine]
        libraries = tuple(config.libraries)
        tcunit = shipped_named("TcUnit")  # TcUnit's test suites are tests too (tcunit.py)
        if tcunit is not None and _names_tcunit(self.files):
            if all(lib.namespace.upper() != tcunit.namespace.upper() for lib in libraries):
                libraries += (tcunit,)
        self.program = compile_files(plant + self.files, profile=config.profile, natives=NATIVES, libraries=libraries)
        self.tests = discover(self.program, self.files)
        intervals = [t.interval_ns for t in config.tasks if t.interval_ns]
        self.interval_ns = min(intervals, default=DEFAULT_INTERVAL_NS)

    @classmethod
    def load(cls, config: str | Path | None, files: list) -> TestSuite:
        """ConfigError for the configuration, CompileError for the ST files."""
        return cls(_load_config(Path(config)) if config else _no_plant(files), files)

    def tcunit_tasks(self) -> tuple:
        """The task that runs the PROGRAMs of the test files (TcUnit's
        PRG_TEST) beside a configured plant's tasks; none without [[task]]
        tables (every PROGRAM is in the default task then)."""
        if not self.config.tasks:
            return ()
        tasked = {inst.program.upper() for t in self.config.tasks for inst in t.programs}
        mine = [
            info
            for info in self.program.checked.pous
            if info.kind == "PROGRAM" and not info.library and info.node.pos.file in self.files
        ]
        calls = [
            ProgramInstance(i.name, i.name, f"{i.node.pos.file}: {i.name}")
            for i in mine
            if i.name.upper() not in tasked
        ]
        if not calls:
            return ()
        task = TaskConfig(
            name="TcUnit",
            interval_ns=self.interval_ns,
            pause_ns=DEFAULT_PAUSE_NS,
            priority=PRIORITY_MAX,
            watchdog_ns=default_watchdog_ns(self.interval_ns),
            sensitivity=1,
            programs=calls,
            key="TcUnit",
        )
        return (task,)

    def _task(self, case: TestCase) -> TaskConfig:
        return TaskConfig(
            name=f"test {case.name}",
            interval_ns=self.interval_ns,
            pause_ns=DEFAULT_PAUSE_NS,
            priority=PRIORITY_MAX,  # after every task of the plant at the same tick
            watchdog_ns=default_watchdog_ns(self.interval_ns),
            sensitivity=1,
            programs=[ProgramInstance(case.name, case.name, f"{case.file}: {case.name}")],
            key=f"test {case.name}",
        )

    def _simulated(self, engine) -> dict:
        return simulated(self.config, engine)

    def run(self, case: TestCase, timeout_ns: int = DEFAULT_TIMEOUT_NS) -> TestResult:
        """Run one test in a fresh engine (cold start, no retain file).
        timeout_ns: for a test without a timeout of its own."""
        import time

        if case.timeout_ns is not None:
            timeout_ns = case.timeout_ns

        started = time.perf_counter()
        engine = build_engine(
            self.config,
            virtual_time=True,
            start_mode="cold",
            program=self.program,
            extra_tasks=(self._task(case),),
            retain=False,
        )
        recorder = Recorder(engine.clock, self._simulated(engine))
        engine.ctx.services[SERVICE] = recorder

        def watch(engine) -> None:
            if recorder.finished or recorder.failures or engine.faults:
                engine.request_stop()

        engine.after_tick.append(watch)
        quiet_ = quiet()
        start_fault = None
        try:
            with quiet_:
                engine.start()
                engine.run(duration_ns=timeout_ns)
        except STFault as e:  # an initial value of the plant or the test
            start_fault = f"initial values: {e}"
        finally:
            with quiet_:
                engine.stop()
        result = TestResult(case, PASSED, engine.now_ns(), list(recorder.failures), asserts=recorder.asserts)
        if start_fault is not None:
            result.outcome, result.error = ERROR, start_fault
        elif recorder.failures:
            result.outcome = FAILED
        elif engine.faults:
            result.outcome = ERROR
            result.error = "; ".join(str(f) for f in engine.faults)
        elif not recorder.finished:
            result.outcome = FAILED
            result.error = f"timed out after {timeout_ns / 1e9:g} s of engine time without TEST_FINISHED()"
        result.wall_s = time.perf_counter() - started
        return result


def quiet() -> _Quiet:
    """A context in which the plant's log below ERROR is not shown."""
    return _Quiet()


class _Quiet:
    """The plant's log below ERROR is not a test's output (a simulated
    device unplugged on purpose is logged as a warning)."""

    def __enter__(self) -> None:
        self.log = logging.getLogger("softplc")
        self.level = self.log.level
        self.log.setLevel(max(self.level, logging.ERROR))

    def __exit__(self, *exc) -> None:
        self.log.setLevel(self.level)


def simulated(config: PlcConfig, engine) -> dict:
    """The engine's simulated devices, with their devices' faults (SIM_FAULT):
    what a Recorder needs (a test's, a sweep's scenario's)."""
    if not config.sims:
        return {}  # (the registry is not loaded for a plant without them)
    types = registry().sim_types()
    out = {}
    for sim in config.sims:
        simulator = engine.simulators.get(sim.name)
        device = types.get(sim.type)
        if simulator is not None and device is not None:
            faults = {f.name: f for f in device.sim_faults}
            out[sim.name.upper()] = Simulated(sim.name, simulator, faults)
    return out
