"""Running TcUnit test suites written in ST, as `softplc test` runs them:
compiled with the TcUnit library softplc ships, PRG_TEST in the default
10 ms task, in virtual time until TcUnit reports every test finished."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.testing.runner import FAILED, PASSED, SKIPPED, _no_plant
from softplc.runtime.testing.tcunit import run_tcunit, tcunit_library

PRG_TEST = """
PROGRAM PRG_TEST
VAR
{suites}
END_VAR
TcUnit.{run}();
END_PROGRAM
"""


def suite(name: str, methods: str, body: str, extra: str = "") -> str:
    """A FUNCTION_BLOCK name EXTENDS TcUnit.FB_TestSuite with methods and body."""
    return f"FUNCTION_BLOCK {name} EXTENDS TcUnit.FB_TestSuite\n{extra}\n{methods}\n{body}\nEND_FUNCTION_BLOCK\n"


def method(name: str, body: str, decls: str = "", test: str | None = None) -> str:
    """METHOD name: TEST('name') (or the given test name), body, TEST_FINISHED()."""
    title = test if test is not None else name
    return f"METHOD {name}\n{decls}\nTEST('{title}');\n{body}\nTEST_FINISHED();\nEND_METHOD\n"


@pytest.fixture
def tcunit(tmp_path: Path):
    """tcunit(source, suites={'Inst': 'FB_X'}, run='RUN', timeout_s=10) -> TcUnitRun."""

    def run(source: str, suites: dict, run: str = "RUN", timeout_s: float = 10, profile: str = "twincat", select=None):
        decls = "\n".join(f"    {inst} : {fb};" for inst, fb in suites.items())
        path = tmp_path / "suites.st"
        path.write_text(source + PRG_TEST.format(suites=decls, run=run), encoding="utf-8")
        program = compile_files([str(path)], profile=profile, libraries=[tcunit_library()])
        return run_tcunit(_no_plant([str(path)]), program, int(timeout_s * 1e9), select)

    return run


def outcomes(run) -> dict:
    """'Suite@Test' -> passed / failed / skipped / error."""
    return {f"{r.case.classname}@{r.case.name}": r.outcome for r in run.results}


def failures(run) -> list:
    """TcUnit's FAILED TEST lines, in order."""
    return [f.detail for r in run.results for f in r.failures]


__all__ = ["FAILED", "PASSED", "SKIPPED", "failures", "outcomes", "method", "suite"]
