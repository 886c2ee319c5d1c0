"""TcUnit's tests under `softplc test` (runtime/testing/tcunit.py,
command.py), as a user runs them: a TwinCAT project whose PRG_TEST calls
TcUnit.RUN(), unchanged; ST files with test suites, alone or beside a
configured plant; the lines printed, file:line of a failed assert in the
.TcPOU, the JUnit XML, the exit codes; and pytest's collector."""

from __future__ import annotations

import shutil
import xml.etree.ElementTree as ET
from pathlib import Path

from .test_command import softplc
from .test_st_pytest_plugin import pytest_in

DEMO = Path(__file__).parent / "data" / "tcunit" / "TcUnitDemo"
SUITE = DEMO / "Test" / "FB_Lamp_Test.TcPOU"

SUITES_ST = """\
FUNCTION_BLOCK FB_Math_Test EXTENDS TcUnit.FB_TestSuite
METHOD Adds
TEST('Adds');
AssertEquals_INT(Expected := 4, Actual := 2 + 2, Message := 'two and two');
TEST_FINISHED();
END_METHOD
METHOD Subtracts
TEST('Subtracts');
AssertEquals_INT(Expected := 1, Actual := 3 - {minus}, Message := 'three less two');
TEST_FINISHED();
END_METHOD
Adds();
Subtracts();
END_FUNCTION_BLOCK

PROGRAM PRG_TEST
VAR
    fbMath_Test : FB_Math_Test;
END_VAR
{run}
END_PROGRAM
"""


def _line_of(path: Path, text: str) -> int:
    return next(i for i, line in enumerate(path.read_text().splitlines(), 1) if text in line)


def test_a_twincat_projects_tests_run_unchanged_with_their_places_and_values(tmp_path):
    proc = softplc(DEMO, "--junit", tmp_path / "out.xml")
    assert proc.returncode == 1, proc.stdout + proc.stderr
    out = proc.stdout
    assert "TcUnit: 1 test suite(s), 4 test(s) in TwinCAT PLC project TcUnitDemo, timeout 60 s" in out
    test_line = _line_of(SUITE, "TEST('ExpectsTooManyPresses')")
    assert f"PASS  PRG_TEST.fbLamp_Test@LightsAfterTheDelay  (0.050 s engine time)  {SUITE}:" in out
    assert f"FAIL  PRG_TEST.fbLamp_Test@ExpectsTooManyPresses  (0.000 s engine time)  {SUITE}:{test_line}" in out
    assert_line = _line_of(SUITE, "AssertEquals(Expected := nExpected,")
    assert f"{SUITE}:{assert_line}:1: AssertEquals failed: five presses" in out  # in the .TcPOU, as TwinCAT numbers it
    assert "expected: 5" in out and "actual:   4" in out
    assert "FAILED TEST 'PRG_TEST.fbLamp_Test@ExpectsTooManyPresses', EXP: 5, ACT: 4, MSG: five presses" in out
    assert "SKIP  PRG_TEST.fbLamp_Test@NotReadyYet" in out
    assert "| Tests: 4\n| Successful tests: 3\n| Failed tests: 1" in out  # TcUnit's summary: a skipped test succeeds
    assert "2 passed, 1 failed, 0 error(s), 1 skipped" in out
    root = ET.parse(tmp_path / "out.xml").getroot()
    assert (root.get("tests"), root.get("failures"), root.get("skipped")) == ("4", "1", "1")
    (suite,) = root.iter("testsuite")
    assert suite.get("name") == "PRG_TEST.fbLamp_Test"
    cases = {c.get("name"): c for c in suite.iter("testcase")}
    assert list(cases) == ["LightsAfterTheDelay", "CountsEachPress", "ExpectsTooManyPresses", "NotReadyYet"]
    failure = cases["ExpectsTooManyPresses"].find("failure")
    assert failure.get("message") == (
        "FAILED TEST 'PRG_TEST.fbLamp_Test@ExpectsTooManyPresses', EXP: 5, ACT: 4, MSG: five presses"
    )
    assert failure.get("type") == "AssertEquals" and f"{SUITE}:{assert_line}:1" in failure.text
    assert cases["NotReadyYet"].find("skipped") is not None
    assert cases["LightsAfterTheDelay"].get("assertions") == "2"  # as TcUnit counts: the same assert once


def test_the_project_file_itself_and_k(tmp_path):
    proc = softplc(DEMO / "TcUnitDemo.plcproj", "-k", "Count")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "PASS  PRG_TEST.fbLamp_Test@CountsEachPress" in proc.stdout and "ExpectsTooManyPresses" not in proc.stdout
    proc = softplc(DEMO, "-k", "nosuch")
    assert proc.returncode == 2 and "no TcUnit tests matching -k 'nosuch'" in proc.stderr


def test_st_files_with_test_suites(tmp_path):
    passing = tmp_path / "suites.st"
    passing.write_text(SUITES_ST.format(minus=2, run="TcUnit.RUN();"))
    proc = softplc(passing)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "2 passed, 0 failed, 0 error(s)" in proc.stdout
    failing = tmp_path / "failing.st"
    failing.write_text(SUITES_ST.format(minus=1, run="TcUnit.RUN_IN_SEQUENCE();"))
    proc = softplc(failing)
    assert proc.returncode == 1
    assert f"{failing}:9:1: AssertEquals_INT failed: three less two" in proc.stdout


def test_suites_beside_a_configured_plant_see_it(tmp_path):
    (tmp_path / "plant.st").write_text(
        "VAR_GLOBAL gTicks : INT; END_VAR\nPROGRAM Plant\ngTicks := gTicks + 1;\nEND_PROGRAM\n"
    )
    (tmp_path / "plant.toml").write_text(
        '[plc]\nprograms = ["plant.st"]\n[[task]]\nname = "Main"\ninterval = "10ms"\nprograms = ["Plant"]\n'
    )
    test = tmp_path / "plant_test.st"
    waits = "TEST('Adds');\nIF gTicks = 3 THEN  (* at 20 ms: the plant's task ran at 0, 10, 20 ms, before this one *)"
    test.write_text(
        SUITES_ST.format(minus=2, run="TcUnit.RUN();")
        .replace("TEST('Adds');", waits)
        .replace("Message := 'two and two');\nTEST_FINISHED();", "Message := 'two and two');\nTEST_FINISHED();\nEND_IF")
    )
    proc = softplc(tmp_path / "plant.toml", test)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "PASS  PRG_TEST.fbMath_Test@Adds  (0.020 s engine time)" in proc.stdout
    assert "2 passed, 0 failed, 0 error(s) in 0.020 s of engine time" in proc.stdout


def test_usage_errors_exit_2(tmp_path):
    idle = tmp_path / "idle.st"
    idle.write_text(SUITES_ST.format(minus=2, run=";"))  # no TcUnit.RUN()
    proc = softplc(idle)
    assert proc.returncode == 2 and "did not run: no task calls a PROGRAM that calls TcUnit.RUN()" in proc.stderr
    empty = tmp_path / "empty"
    empty.mkdir()
    (empty / "main.st").write_text("PROGRAM Main\n;\nEND_PROGRAM\n")
    proc = softplc(empty)
    assert proc.returncode == 2 and "no TcUnit test suite in folder" in proc.stderr
    broken = tmp_path / "broken"
    shutil.copytree(DEMO, broken)
    text = (broken / "Test" / "PRG_TEST.TcPOU").read_text()
    (broken / "Test" / "PRG_TEST.TcPOU").write_text(text.replace("TcUnit.RUN();", "TcUnit.RUN(nosuch);"))
    proc = softplc(broken)
    assert proc.returncode == 2 and "PRG_TEST.TcPOU:" in proc.stderr and "Traceback" not in proc.stderr


def test_pytest_collects_a_file_of_suites_as_one_item(tmp_path):
    (tmp_path / "test_math.st").write_text(SUITES_ST.format(minus=1, run="TcUnit.RUN();"))
    (tmp_path / "pytest.ini").write_text("[pytest]\n")
    proc = pytest_in(tmp_path, "-rA")
    assert proc.returncode == 1, proc.stdout + proc.stderr
    out = proc.stdout
    assert "FAILED test_math.st::TcUnit" in out and "1 failed" in out
    assert "FAIL PRG_TEST.fbMath_Test@Subtracts" in out
    assert "FAILED TEST 'PRG_TEST.fbMath_Test@Subtracts', EXP: 1, ACT: 2, MSG: three less two" in out
