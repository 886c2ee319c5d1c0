"""``softplc test``: run the ST tests of FILES against the plant of CONFIG,
print a line per test and a summary, write JUnit XML.

Exit codes: 0 every test passed, 1 a test failed (an assertion, the timeout
or a runtime fault), 2 the configuration, the ST files or the options are
wrong, or no test was found.
"""

from __future__ import annotations

import sys
from pathlib import Path

EXIT_PASSED, EXIT_FAILED, EXIT_USAGE = 0, 1, 2


def _err(text: str) -> None:
    sys.stderr.write(text + "\n")


def split_arguments(paths: tuple) -> tuple:
    """(CONFIG or None, ST files): a first argument ending in .toml is the configuration."""
    items = [str(p) for p in paths]
    if items and items[0].lower().endswith(".toml"):
        return items[0], items[1:]
    return None, items


def run_tests(paths: tuple, *, junit: str | None, pattern: str | None, timeout_ns: int, report_compile_errors) -> int:
    from ..config import ConfigError
    from ..engine.scan import EngineError
    from ..engine.tasks import TaskSetupError
    from ..plugin.driver import DriverError
    from ..st.diagnostics import CompileError
    from .discover import TestError, select
    from .runner import ERROR, FAILED, PASSED, TestSuite

    config, files = split_arguments(paths)
    if not files:
        _err("softplc test: give the ST files with the tests (after the configuration, if any)")
        return EXIT_USAGE
    for f in files:
        if not Path(f).is_file():
            _err(f"softplc test: {f}: no such file")
            return EXIT_USAGE
    try:
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
    if not tests:
        what = f" matching -k {pattern!r}" if pattern and suite.tests else ""
        _err(
            f"softplc test: no tests{what} in {', '.join(files)} "
            "(a test is a FUNCTION_BLOCK named TEST_... or with {attribute 'test'})"
        )
        return EXIT_USAGE
    where = f" against {config}" if config else ""
    print(f"{len(tests)} test(s) from {len(files)} file(s){where}, timeout {timeout_ns / 1e9:g} s", flush=True)
    results = []
    for case in tests:
        try:
            result = suite.run(case, timeout_ns)
        except (TaskSetupError, DriverError, EngineError) as e:
            _err(f"softplc: {e}")
            return EXIT_USAGE
        results.append(result)
        word = {PASSED: "PASS", FAILED: "FAIL", ERROR: "ERROR"}[result.outcome]
        print(f"{word:5} {case.name}  ({result.time_ns / 1e9:.3f} s engine time)  {case.file}:{case.line}", flush=True)
        if result.outcome != PASSED:
            print("      " + result.describe().replace("\n", "\n      "), flush=True)
    passed = sum(r.outcome == PASSED for r in results)
    failed = sum(r.outcome == FAILED for r in results)
    errors = sum(r.outcome == ERROR for r in results)
    engine_s = sum(r.time_ns for r in results) / 1e9
    wall_s = sum(r.wall_s for r in results)
    print(
        f"{passed} passed, {failed} failed, {errors} error(s) in {engine_s:.3f} s of engine time ({wall_s:.2f} s wall)"
    )
    if junit:
        from .junit import write

        try:
            write(results, junit)
        except OSError as e:
            _err(f"softplc test: --junit: cannot write {junit}: {e.strerror or e}")
            return EXIT_USAGE
        print(f"wrote {junit}")
    return EXIT_PASSED if passed == len(results) else EXIT_FAILED
