"""pytest runs ST tests too: every test_*.st file it collects is compiled
(with the configuration's programs) and each test FUNCTION_BLOCK in it is a
pytest item; a failure shows the ST file:line:column, the message and both
values. A file with TcUnit test suites (blocks that EXTEND
TcUnit.FB_TestSuite, run by its PROGRAM calling TcUnit.RUN()) is one more
item, "TcUnit": TcUnit's tests are known only once they run, all in one
PLC, so the item runs them all and fails with every failed test.
Registered as the pytest11 entry point ``softplc_st``.

    pytest --softplc-config io_config/default.toml st_programs/tests/

The configuration comes from --softplc-config or the ini option
softplc_config (relative to the rootdir); without one the tests run alone.
The timeout from --softplc-timeout or softplc_timeout (default 60s). -p
no:softplc_st turns the collector off.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from ..durations import EXAMPLES, parse_duration_ns

# The runner (and with it the engine, the buses, the compiler) is imported
# when a test_*.st file is collected, not by every pytest run with softplc
# installed.
DEFAULT_TIMEOUT_NS = 60_000_000_000


def pytest_addoption(parser) -> None:
    group = parser.getgroup("softplc_st", "tests written in ST (softplc)")
    group.addoption("--softplc-config", metavar="TOML", help="the configuration ST tests run against")
    group.addoption("--softplc-timeout", metavar="DURATION", help="engine time an ST test may take (default 60s)")
    parser.addini("softplc_config", "the configuration ST tests run against (relative to the rootdir)", default="")
    parser.addini("softplc_timeout", "engine time an ST test may take", default="")


def pytest_collect_file(file_path: Path, parent):
    if file_path.suffix.lower() == ".st" and file_path.name.lower().startswith("test_"):
        return StFile.from_parent(parent, path=file_path)
    return None


def _config_path(config) -> Path | None:
    given = config.getoption("softplc_config")
    if given:
        return Path(given)
    ini = config.getini("softplc_config")
    return config.rootpath / ini if ini else None


def _timeout_ns(config) -> int:
    text = config.getoption("softplc_timeout") or config.getini("softplc_timeout")
    if not text:
        return DEFAULT_TIMEOUT_NS
    ns = parse_duration_ns(text)
    if ns is None or ns <= 0:
        raise pytest.UsageError(f"softplc timeout: {text!r} is not a positive duration (examples: {EXAMPLES})")
    return ns


class StCollectError(Exception):
    """The configuration or the ST files are wrong: the message says where."""


class StFile(pytest.File):
    def collect(self):
        from ..config import ConfigError
        from ..st.diagnostics import CompileError
        from .discover import TestError
        from .runner import TestSuite

        try:
            suite = TestSuite.load(_config_path(self.config), [str(self.path)])
        except (ConfigError, TestError) as e:
            raise StCollectError(str(e)) from None
        except CompileError as e:
            raise StCollectError("\n".join(d.format(e.sources) for d in e.diagnostics)) from None
        for case in suite.tests:
            yield StItem.from_parent(self, name=case.name, suite=suite, case=case)
        from .tcunit import uses_tcunit

        if uses_tcunit(suite.program):
            yield TcUnitItem.from_parent(self, name="TcUnit", suite=suite)

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, StCollectError):
            return str(excinfo.value)
        return super().repr_failure(excinfo)


class StTestFailed(Exception):
    def __init__(self, result) -> None:
        super().__init__(result.describe())
        self.result = result


class StItem(pytest.Item):
    def __init__(self, *, suite, case, **kwargs) -> None:
        super().__init__(**kwargs)
        self.suite = suite
        self.case = case

    def runtest(self) -> None:
        from .runner import PASSED

        result = self.suite.run(self.case, _timeout_ns(self.config))
        self.user_properties.append(("engine_time", f"{result.time_ns / 1e9:.3f}"))
        if result.outcome != PASSED:
            raise StTestFailed(result)

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, StTestFailed):
            r = excinfo.value.result
            return f"{self.case.name} {r.outcome} after {r.time_ns / 1e9:.3f} s of engine time\n{r.describe()}"
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.path, self.case.line - 1, f"ST test {self.case.name}"


class TcUnitFailed(Exception):
    def __init__(self, text: str) -> None:
        super().__init__(text)
        self.text = text


class TcUnitItem(pytest.Item):
    """The TcUnit test suites of a test_*.st file, run together."""

    def __init__(self, *, suite, **kwargs) -> None:
        super().__init__(**kwargs)
        self.suite = suite

    def runtest(self) -> None:
        from .command import WORDS
        from .runner import PASSED, SKIPPED
        from .tcunit import run_tcunit

        run = run_tcunit(
            self.suite.config, self.suite.program, _timeout_ns(self.config), None, self.suite.tcunit_tasks()
        )
        self.user_properties.append(("engine_time", f"{run.time_ns / 1e9:.3f}"))
        lines = [] if run.ran else ["no task calls a PROGRAM that calls TcUnit.RUN()"]
        for r in run.results:
            if r.outcome not in (PASSED, SKIPPED):
                lines.append(f"{WORDS[r.outcome]} {r.case.classname}@{r.case.name} ({r.case.file}:{r.case.line})")
                lines.append("  " + r.describe().replace("\n", "\n  "))
        lines += [f"TcUnit: {text}" for text in run.errors]
        if lines:
            raise TcUnitFailed("\n".join(lines))

    def repr_failure(self, excinfo, style=None):
        if isinstance(excinfo.value, TcUnitFailed):
            return excinfo.value.text
        return super().repr_failure(excinfo)

    def reportinfo(self):
        return self.path, 0, "TcUnit test suites"
