"""`softplc test` as a user runs it: the shipped example against the default
plant, a test that fails on purpose, the JUnit XML, the exit codes."""

from __future__ import annotations

import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "st_programs" / "tests" / "test_default_plant.st"
DEFAULT = REPO / "io_config" / "default.toml"
FAILING = Path(__file__).parent / "data" / "failing_assert.st"


def softplc(*args, cwd=None):
    env = dict(os.environ, PYTHONIOENCODING="utf-8")
    env.pop("SOFTPLC_DEBUG", None)
    return subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", "test", *map(str, args)],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        cwd=cwd,
        env=env,
        timeout=300,
    )


def cases(xml_path: Path) -> dict:
    """testcase name -> (its failure or error element's tag, or None), from the parsed XML."""
    root = ET.parse(xml_path).getroot()
    assert root.tag == "testsuites"
    out = {}
    for suite in root.iter("testsuite"):
        for case in suite.iter("testcase"):
            bad = [child.tag for child in case if child.tag in ("failure", "error")]
            out[case.get("name")] = (bad[0] if bad else None, case)
    return out


@pytest.mark.slow
def test_the_shipped_example_passes_against_the_default_plant(tmp_path):
    proc = softplc(DEFAULT, EXAMPLE, "--junit", tmp_path / "out.xml", cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    names = ["TEST_MotorForwardThenReverse", "TEST_PumpHighThenLowSpeed", "TEST_DriveReachesSpeed"]
    names.append("TEST_PumpRecoversFromATrip")
    for name in names:
        assert f"PASS  {name}" in proc.stdout
    assert "4 passed, 0 failed, 0 error(s)" in proc.stdout
    found = cases(tmp_path / "out.xml")
    assert sorted(found) == sorted(names)
    assert all(bad is None for bad, _case in found.values())
    root = ET.parse(tmp_path / "out.xml").getroot()
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("4", "0", "0")


def test_a_failing_st_assert_names_its_place_and_both_values_and_exits_1(tmp_path):
    proc = softplc(FAILING, "--timeout", "1s", "--junit", tmp_path / "out.xml")
    assert proc.returncode == 1, proc.stdout + proc.stderr
    out = proc.stdout
    assert f"FAIL  TEST_FailsOnPurpose  (0.000 s engine time)  {FAILING}:6" in out
    assert f"{FAILING}:12:5: ASSERT_EQUAL failed: the light is red" in out
    assert "expected: E_Light#Red" in out and "actual:   E_Light#Green" in out
    assert f"{FAILING}:13:1: ASSERT_EQUAL failed: the answer" in out
    assert "expected: 42" in out and "actual:   41" in out
    assert "PASS  TEST_Passes  (0.250 s engine time)" in out
    assert "timed out after 1 s of engine time without TEST_FINISHED()" in out
    assert "1 passed, 2 failed, 0 error(s)" in out
    found = cases(tmp_path / "out.xml")
    assert {name: bad for name, (bad, _c) in found.items()} == {
        "TEST_FailsOnPurpose": "failure",
        "TEST_Passes": None,
        "TEST_NeverFinishes": "failure",
    }
    failure = found["TEST_FailsOnPurpose"][1].find("failure")
    assert failure.get("message") == f"{FAILING}:12:5: the light is red"
    assert "expected: E_Light#Red" in failure.text and "actual:   E_Light#Green" in failure.text


@pytest.mark.slow
def test_the_default_plant_has_a_name_of_its_own(tmp_path):
    """Issue 33: the embedded default plant had no name on softplc test's
    command line (its TOML is inside the installed package)."""
    proc = softplc("--default-plant", EXAMPLE, "-k", "DriveReachesSpeed", cwd=tmp_path)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert proc.stdout.startswith("1 test(s) from 1 file(s) against the default plant, timeout 60 s\n")
    assert "PASS  TEST_DriveReachesSpeed" in proc.stdout
    both = softplc("--default-plant", DEFAULT, EXAMPLE, cwd=tmp_path)
    assert both.returncode == 2 and "--default-plant or a CONFIG" in both.stderr


def test_the_header_names_the_timeouts_the_tests_have_of_their_own(tmp_path):
    """Issue 33: the header said "timeout 60 s" where a test's own
    {attribute 'timeout'} applied."""
    path = tmp_path / "test_own.st"
    path.write_text(
        "FUNCTION_BLOCK TEST_Short\n{attribute 'timeout' := 'T#200ms'}\nTEST_FINISHED();\nEND_FUNCTION_BLOCK\n"
        "FUNCTION_BLOCK TEST_Plain\nTEST_FINISHED();\nEND_FUNCTION_BLOCK\n"
    )
    proc = softplc(path, "--timeout", "2s")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert proc.stdout.startswith("2 test(s) from 1 file(s), timeout 2 s, 1 of their own (0.2 s)\n")
    alone = softplc(path, "-k", "Short")
    assert alone.stdout.startswith("1 test(s) from 1 file(s), each test's own timeout (0.2 s)\n")


def test_k_selects_tests_by_name(tmp_path):
    proc = softplc(FAILING, "-k", "passes")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "1 passed, 0 failed" in proc.stdout and "FailsOnPurpose" not in proc.stdout


@pytest.mark.parametrize(
    "args, message",
    [
        (("-k", "nosuch"), "no tests matching -k 'nosuch'"),
        (("--timeout", "soon"), "'soon' is not a positive duration"),
    ],
)
def test_usage_errors_exit_2(args, message):
    proc = softplc(FAILING, *args)
    assert proc.returncode == 2 and message in proc.stderr


def test_compile_errors_exit_2_with_file_line_column(tmp_path):
    bad = tmp_path / "test_bad.st"
    bad.write_text("FUNCTION_BLOCK TEST_Bad\nASSERT_EQUAL(1, 'one', 'm');\nEND_FUNCTION_BLOCK\n")
    proc = softplc(bad)
    assert proc.returncode == 2
    assert f"{bad}:2:" in proc.stderr and "E020" in proc.stderr and "Traceback" not in proc.stderr


def test_a_bad_configuration_exits_2_naming_the_file(tmp_path):
    config = tmp_path / "plant.toml"
    config.write_text('[plc]\nprograms = ["nosuch.st"]\n')
    proc = softplc(config, FAILING)
    assert proc.returncode == 2 and str(config) in proc.stderr and "Traceback" not in proc.stderr


def test_files_without_tests_exit_2(tmp_path):
    plain = tmp_path / "plain.st"
    plain.write_text("FUNCTION_BLOCK Helper\nEND_FUNCTION_BLOCK\n")
    proc = softplc(plain)
    assert proc.returncode == 2 and "a test is a FUNCTION_BLOCK named TEST_" in proc.stderr
