"""pytest collects test_*.st files through the softplc_st entry point: each
ST test a pytest item, a failure shown with its ST file:line:column and both
values. Run in a subprocess, in a directory of its own, as a user runs it."""

from __future__ import annotations

import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

FAILING = Path(__file__).parent / "data" / "failing_assert.st"

PLANT = """\
PROGRAM Plant
VAR
    out AT %QW0 : INT;
END_VAR
out := out + 1;
END_PROGRAM
"""

PLANT_TEST = """\
FUNCTION_BLOCK TEST_SeesThePlant
VAR
    out AT %QW0 : INT;
END_VAR
IF TIME() = T#100ms THEN
    ASSERT_EQUAL(11, out, 'the plant ran at 0, 10 .. 100 ms: before the test in each tick');
    TEST_FINISHED();
END_IF;
END_FUNCTION_BLOCK
"""


def pytest_in(directory: Path, *args):
    return subprocess.run(
        [sys.executable, "-m", "pytest", "-p", "no:cacheprovider", "-p", "no:xdist", *map(str, args)],
        capture_output=True,
        text=True,
        cwd=directory,
        stdin=subprocess.DEVNULL,
        timeout=300,
    )


def test_st_tests_are_pytest_items_and_failures_show_the_st_place(tmp_path):
    shutil.copy(FAILING, tmp_path / "test_failing.st")
    (tmp_path / "pytest.ini").write_text("[pytest]\nsoftplc_timeout = 500ms\n")
    proc = pytest_in(tmp_path, "-rA", "--junitxml", tmp_path / "j.xml")
    out = proc.stdout
    assert proc.returncode == 1, out + proc.stderr
    assert "2 failed, 1 passed" in out
    where = tmp_path / "test_failing.st"
    assert f"{where}:12:5: ASSERT_EQUAL failed: the light is red" in out
    assert "expected: E_Light#Red" in out and "actual:   E_Light#Green" in out
    assert "timed out after 0.5 s of engine time without TEST_FINISHED()" in out
    assert "PASSED test_failing.st::TEST_Passes" in out
    names = {c.get("name"): [x.tag for x in c] for c in ET.parse(tmp_path / "j.xml").getroot().iter("testcase")}
    assert "failure" in names["TEST_FailsOnPurpose"] and "failure" not in names["TEST_Passes"]


def test_the_configuration_comes_from_the_ini_file(tmp_path):
    (tmp_path / "plant.st").write_text(PLANT)
    (tmp_path / "plant.toml").write_text(
        '[plc]\nprograms = ["plant.st"]\n[[task]]\nname = "Main"\ninterval = "10ms"\nprograms = ["Plant"]\n'
    )
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "test_plant.st").write_text(PLANT_TEST)
    (tmp_path / "pytest.ini").write_text("[pytest]\nsoftplc_config = plant.toml\n")
    proc = pytest_in(tmp_path, "-v")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "tests/test_plant.st::TEST_SeesThePlant PASSED" in proc.stdout


def test_a_compile_error_is_a_collection_error_with_the_diagnostic(tmp_path):
    (tmp_path / "test_bad.st").write_text("FUNCTION_BLOCK TEST_Bad\nASSERT_EQUAL(1, 'one', 'm');\nEND_FUNCTION_BLOCK\n")
    (tmp_path / "pytest.ini").write_text("[pytest]\n")
    proc = pytest_in(tmp_path)
    assert proc.returncode == 2, proc.stdout + proc.stderr
    assert "test_bad.st:2:" in proc.stdout and "E020" in proc.stdout and "Traceback" not in proc.stdout


def test_the_plugin_costs_a_pytest_run_without_st_files_no_engine_import():
    probe = (
        "import sys, softplc.runtime.testing.st_pytest_plugin as p; "
        "print('softplc.runtime.testing.runner' in sys.modules, 'softplc.runtime.engine.scan' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=60).stdout
    assert out.split() == ["False", "False"]
    from softplc.runtime.testing import runner
    from softplc.runtime.testing import st_pytest_plugin as pytest_plugin

    assert pytest_plugin.DEFAULT_TIMEOUT_NS == runner.DEFAULT_TIMEOUT_NS
