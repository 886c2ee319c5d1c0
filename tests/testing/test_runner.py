"""Running ST tests without a plant: discovery, one fresh instance per
test, the end of a test (TEST_FINISHED, a failure, a fault, the timeout)."""

from __future__ import annotations

import pytest

from softplc.runtime.st.diagnostics import CompileError
from softplc.runtime.testing.discover import TestError, select
from softplc.runtime.testing.runner import ERROR, FAILED, PASSED, TestSuite

SOURCE = """\
FUNCTION_BLOCK TEST_Counts
VAR
    n : INT;
END_VAR
n := n + 1;
IF n = 3 THEN
    ASSERT_EQUAL(3, n, 'a fresh instance: three calls');
    TEST_FINISHED();
END_IF;
END_FUNCTION_BLOCK

FUNCTION_BLOCK CountsAgain
{attribute 'test'}
VAR
    n : INT;
END_VAR
n := n + 1;
ASSERT_TRUE(n < 5, 'stops at the first failure');
END_FUNCTION_BLOCK

FUNCTION_BLOCK TEST_Faults
VAR
    zero : INT;
    x : INT;
END_VAR
IF TIME() >= T#50ms THEN
    x := 10 / zero;
END_IF;
END_FUNCTION_BLOCK

FUNCTION_BLOCK TEST_Waits
ASSERT_TRUE(TRUE, 'never finishes');
END_FUNCTION_BLOCK

FUNCTION_BLOCK Helper
VAR_OUTPUT
    Q : BOOL;
END_VAR
END_FUNCTION_BLOCK

PROGRAM Plant
VAR
    ticks : INT;
END_VAR
ticks := ticks + 1;
END_PROGRAM
"""


@pytest.fixture
def suite(tmp_path):
    path = tmp_path / "tests.st"
    path.write_text(SOURCE, encoding="utf-8")
    return TestSuite.load(None, [str(path)])


def test_tests_are_function_blocks_named_test_or_with_the_attribute(suite):
    assert [(t.name, t.line) for t in suite.tests] == [
        ("TEST_Counts", 1),
        ("CountsAgain", 12),
        ("TEST_Faults", 21),
        ("TEST_Waits", 31),
    ]
    assert [t.name for t in select(suite.tests, "count")] == ["TEST_Counts", "CountsAgain"]
    assert [t.name for t in select(suite.tests, "test_*s")] == ["TEST_Counts", "TEST_Faults", "TEST_Waits"]


def test_a_test_runs_every_cycle_until_test_finished_in_a_fresh_instance(suite):
    first = suite.run(suite.tests[0])
    again = suite.run(suite.tests[0])
    for result in (first, again):
        assert (result.outcome, result.time_ns, result.asserts, result.failures) == (PASSED, 20_000_000, 1, [])


def test_a_test_ends_with_the_cycle_of_its_first_failure(suite):
    result = suite.run(suite.tests[1])
    assert (result.outcome, result.time_ns) == (FAILED, 40_000_000)
    (failure,) = result.failures
    assert (failure.site.line, failure.site.col, failure.message) == (18, 1, "stops at the first failure")
    assert failure.time_ns == 40_000_000


def test_a_runtime_fault_in_a_test_is_an_error_with_its_st_position(suite):
    result = suite.run(suite.tests[2])
    assert result.outcome == ERROR and result.time_ns == 50_000_000
    assert "tests.st:27:5" in result.error and "division by zero" in result.error


def test_a_test_that_never_finishes_fails_at_the_timeout_in_engine_time(suite):
    result = suite.run(suite.tests[3], timeout_ns=300_000_000)
    assert result.outcome == FAILED and result.failures == []
    assert result.time_ns == 300_000_000
    assert result.error == "timed out after 0.3 s of engine time without TEST_FINISHED()"


def test_a_sim_fault_without_the_simulator_fails_naming_what_there_is(tmp_path):
    path = tmp_path / "t.st"
    path.write_text(
        "FUNCTION_BLOCK TEST_Fault\nSIM_FAULT('pump', 'over_current', 0, TRUE);\nTEST_FINISHED();\nEND_FUNCTION_BLOCK\n"
    )
    suite = TestSuite.load(None, [str(path)])
    (failure,) = suite.run(suite.tests[0]).failures
    assert (failure.site.line, failure.function, failure.message) == (2, "SIM_FAULT", "no simulated device 'pump'")
    assert failure.expected == "one of: none in this configuration"


def test_errors_in_the_test_files_are_compile_errors(tmp_path):
    path = tmp_path / "t.st"
    path.write_text("FUNCTION_BLOCK TEST_Bad\nASSERT_EQUAL(1, 'one', 'm');\nEND_FUNCTION_BLOCK\n")
    with pytest.raises(CompileError) as caught:
        TestSuite.load(None, [str(path)])
    assert [(d.pos.line, d.code) for d in caught.value.diagnostics if d.is_error] == [(2, "E020")]


def test_a_test_never_touches_the_plants_retain_file(tmp_path):
    (tmp_path / "plant.st").write_text("PROGRAM Plant\nVAR RETAIN\n    n : INT;\nEND_VAR\nn := n + 1;\nEND_PROGRAM\n")
    (tmp_path / "plant.toml").write_text(
        '[plc]\nprograms = ["plant.st"]\n[retain]\nfile = "plant.retain"\nperiod = "10ms"\n'
    )
    (tmp_path / "t.st").write_text(
        "FUNCTION_BLOCK TEST_Runs\nIF TIME() >= T#100ms THEN TEST_FINISHED(); END_IF;\nEND_FUNCTION_BLOCK\n"
    )
    suite = TestSuite.load(tmp_path / "plant.toml", [str(tmp_path / "t.st")])
    assert suite.run(suite.tests[0]).outcome == PASSED
    assert not (tmp_path / "plant.retain").exists()


def test_a_test_may_have_its_own_timeout(tmp_path):
    path = tmp_path / "t.st"
    path.write_text(
        "FUNCTION_BLOCK TEST_Short\n{attribute 'timeout' := 'T#200ms'}\nVAR\n    n : INT;\nEND_VAR\n"
        "n := n + 1;\nEND_FUNCTION_BLOCK\n"
    )
    suite = TestSuite.load(None, [str(path)])
    assert suite.tests[0].timeout_ns == 200_000_000
    result = suite.run(suite.tests[0])  # the default would be 60 s
    assert (result.outcome, result.time_ns) == (FAILED, 200_000_000)
    assert result.error == "timed out after 0.2 s of engine time without TEST_FINISHED()"


def test_a_wrong_timeout_attribute_names_the_test(tmp_path):
    path = tmp_path / "t.st"
    path.write_text("FUNCTION_BLOCK TEST_Bad\n{attribute 'timeout' := 'soon'}\nEND_FUNCTION_BLOCK\n")
    with pytest.raises(TestError, match=r"t\.st:1:1: TEST_Bad: timeout 'soon' is not a positive duration"):
        TestSuite.load(None, [str(path)])
