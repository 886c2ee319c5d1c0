"""``softplc test``: run the ST tests of FILES against the plant of CONFIG,
and the TcUnit test suites of FILES or of a PROJECT; print a line per test
and a summary, write JUnit XML.

Exit codes: 0 every test passed, 1 a test failed (an assertion, the timeout
or a runtime fault; for TcUnit also an error TcUnit reports about the tests,
such as a duplicate test name), 2 the configuration, the ST files or the
options are wrong, or no test was found.
"""

from __future__ import annotations

import fnmatch
import sys
from pathlib import Path

from .runner import ERROR, FAILED, PASSED, SKIPPED

EXIT_PASSED, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
WORDS = {PASSED: "PASS", FAILED: "FAIL", ERROR: "ERROR", SKIPPED: "SKIP"}
NO_TESTS = (
    "a test is a FUNCTION_BLOCK named TEST_... or with {attribute 'test'}, "
    "or a TcUnit test suite: a FUNCTION_BLOCK that EXTENDS TcUnit.FB_TestSuite"
)


def _err(text: str) -> None:
    sys.stderr.write(text + "\n")


def split_arguments(paths: tuple) -> tuple:
    """(CONFIG or None, ST files): a first argument ending in .toml is the configuration."""
    items = [str(p) for p in paths]
    if items and items[0].lower().endswith(".toml"):
        return items[0], items[1:]
    return None, items


def timeouts(tests: list, timeout_ns: int) -> str:
    """The header's word on the timeouts: --timeout's, and those of the
    tests that have one of their own ({attribute 'timeout'}), which go first."""
    own = sorted({case.timeout_ns for case in tests if case.timeout_ns is not None})
    if not own:
        return f"timeout {timeout_ns / 1e9:g} s"
    shown = ", ".join(f"{ns / 1e9:g} s" for ns in own[:5]) + (", ..." if len(own) > 5 else "")
    mine = sum(1 for case in tests if case.timeout_ns is not None)
    if mine == len(tests):
        return f"each test's own timeout ({shown})"
    return f"timeout {timeout_ns / 1e9:g} s, {mine} of their own ({shown})"


def selector(pattern: str | None):
    """-k for TcUnit's tests: a case-insensitive part of 'PRG_TEST.Suite@Test',
    or a glob; None without -k."""
    if not pattern:
        return None
    p = pattern.upper()
    if any(c in p for c in "*?["):
        return lambda path: fnmatch.fnmatchcase(path.upper(), p) or fnmatch.fnmatchcase(path.split("@")[-1].upper(), p)
    return lambda path: p in path.upper()


def run_tests(
    paths: tuple,
    *,
    junit: str | None,
    pattern: str | None,
    timeout_ns: int,
    report_compile_errors,
    config_label: str | None = None,
) -> int:
    """softplc test of [CONFIG] FILE...: the exit code. config_label: how
    the header names CONFIG (the default plant's path is a package's)."""
    from ..collector import collector_off
    from ..config import ConfigError
    from ..engine.scan import EngineError
    from ..engine.tasks import TaskSetupError
    from ..plugin.driver import DriverError
    from ..st.diagnostics import CompileError
    from .discover import TestError, select
    from .runner import TestSuite
    from .tcunit import run_tcunit, uses_tcunit

    config, files = split_arguments(paths)
    if not files:
        _err("softplc test: give the ST files with the tests (after the configuration, if any)")
        return EXIT_USAGE
    for f in files:
        if not Path(f).is_file():
            _err(f"softplc test: {f}: no such file")
            return EXIT_USAGE
    try:
        with collector_off():
            suite = TestSuite.load(config, files)
    except ConfigError as e:
        _err(f"softplc: {e}")
        return EXIT_USAGE
    except CompileError as e:
        report_compile_errors(e)
        return EXIT_USAGE
    except TestError as e:
        _err(f"softplc test: {e}")
        return EXIT_USAGE
    tests = select(suite.tests, pattern)
    tcunit = uses_tcunit(suite.program)
    if not tests and not tcunit:
        what = f" matching -k {pattern!r}" if pattern and suite.tests else ""
        _err(f"softplc test: no tests{what} in {', '.join(files)} ({NO_TESTS})")
        return EXIT_USAGE
    where = f" against {config_label or config}" if config else ""
    results, errors = [], []
    engine_ns, wall_s = 0, 0.0
    try:
        if tests:
            print(f"{len(tests)} test(s) from {len(files)} file(s){where}, {timeouts(tests, timeout_ns)}", flush=True)
            for case in tests:
                result = suite.run(case, timeout_ns)
                results.append(result)
                print_result(result)
        if tcunit:
            run = run_tcunit(suite.config, suite.program, timeout_ns, selector(pattern), suite.tcunit_tasks())
            code = report_tcunit(run, f"{', '.join(files)}{where}", timeout_ns, pattern)
            if code is not None and not tests:
                return code
            results += run.results
            errors += run.errors
            engine_ns, wall_s = run.time_ns, run.wall_s
    except (TaskSetupError, DriverError, EngineError) as e:
        _err(f"softplc: {e}")
        return EXIT_USAGE
    engine_ns += sum(r.time_ns for r in results if r.case.classname is None)
    wall_s += sum(r.wall_s for r in results if r.case.classname is None)
    return finish(results, errors, junit, engine_ns, wall_s)


def run_project_tests(program, config, label: str, *, junit: str | None, pattern: str | None, timeout_ns: int) -> int:
    """The TcUnit suites of a project (compiled as program, run with its own
    tasks, config) as ``softplc test PROJECT`` runs them."""
    from ..engine.scan import EngineError
    from ..engine.tasks import TaskSetupError
    from .tcunit import run_tcunit, uses_tcunit

    if not uses_tcunit(program):
        _err(f"softplc test: no TcUnit test suite in {label} (a FUNCTION_BLOCK that EXTENDS TcUnit.FB_TestSuite)")
        return EXIT_USAGE
    try:
        run = run_tcunit(config, program, timeout_ns, selector(pattern))
    except (TaskSetupError, EngineError) as e:
        _err(f"softplc: {e}")
        return EXIT_USAGE
    code = report_tcunit(run, label, timeout_ns, pattern)
    if code is not None:
        return code
    return finish(run.results, run.errors, junit, run.time_ns, run.wall_s)


def print_result(result) -> None:
    case = result.case
    name = f"{case.classname}@{case.name}" if case.classname else case.name
    word = WORDS[result.outcome]
    print(f"{word:5} {name}  ({result.time_ns / 1e9:.3f} s engine time)  {case.file}:{case.line}", flush=True)
    if result.outcome not in (PASSED, SKIPPED):
        print("      " + result.describe().replace("\n", "\n      "), flush=True)


def report_tcunit(run, label: str, timeout_ns: int, pattern: str | None) -> int | None:
    """Print a TcUnit run: its tests, TcUnit's errors and its summary. An
    exit code when there is nothing to report (no program called RUN, no
    test matched -k), else None."""
    if not run.ran:
        _err(
            f"softplc test: the TcUnit test suites of {label} did not run: no task calls a PROGRAM "
            "that calls TcUnit.RUN() (or RUN_IN_SEQUENCE())"
        )
        return EXIT_USAGE
    if pattern and not run.results:
        _err(f"softplc test: no TcUnit tests matching -k {pattern!r} in {label}")
        return EXIT_USAGE
    print(
        f"TcUnit: {run.suites} test suite(s), {len(run.results)} test(s) in {label}, timeout {timeout_ns / 1e9:g} s",
        flush=True,
    )
    for result in run.results:
        print_result(result)
    for text in run.errors:
        print(f"TcUnit: {text}", flush=True)
    for line in run.log:
        if line.kind == "user" or (line.kind == "result" and line.level == "error"):  # TCUNIT_ADSLOGSTR, the summary
            print(line.text, flush=True)
    return None


def finish(results: list, errors: list, junit: str | None, engine_ns: int, wall_s: float) -> int:
    """The summary line, the JUnit XML, the exit code."""
    counts = {k: sum(r.outcome == k for r in results) for k in (PASSED, FAILED, ERROR, SKIPPED)}
    engine_s = engine_ns / 1e9
    skipped = f", {counts[SKIPPED]} skipped" if counts[SKIPPED] else ""
    print(
        f"{counts[PASSED]} passed, {counts[FAILED]} failed, {counts[ERROR]} error(s){skipped} "
        f"in {engine_s:.3f} s of engine time ({wall_s:.2f} s wall)"
    )
    if junit:
        from .junit import write

        try:
            write(results, junit)
        except OSError as e:
            _err(f"softplc test: --junit: cannot write {junit}: {e.strerror or e}")
            return EXIT_USAGE
        print(f"wrote {junit}")
    ok = counts[PASSED] + counts[SKIPPED] == len(results) and not errors
    return EXIT_PASSED if ok else EXIT_FAILED
