"""How TcUnit runs tests (fblocks/libs/tcunit/service.py), as its
documentation has it (tcunit.org: "Introduction user guide", FAQ 1, 2, 7)
and its verifier project checks it: tests over several cycles, asserts
reported once, asserts after TEST_FINISHED ignored, TEST_ORDERED,
duplicate and disabled tests, TEST_FINISHED_NAMED, RUN_IN_SEQUENCE, a test
that never finishes."""

from __future__ import annotations

from .conftest import FAILED, PASSED, SKIPPED, failures, method, outcomes, suite


def test_a_test_runs_over_cycles_until_test_finished(tcunit):
    # FAQ 1: the block under test and a timer as VAR_INST of the test's method
    methods = """
METHOD WaitsForTheTimer
VAR_INST
    fbTimer : TON := (PT := T#100MS);
    nCycles : INT;
END_VAR
TEST('WaitsForTheTimer');
fbTimer(IN := TRUE);
nCycles := nCycles + 1;
IF fbTimer.Q THEN
    AssertEquals_INT(Expected := 11, Actual := nCycles, Message := 'cycles of 10 ms');
    TEST_FINISHED();
END_IF
END_METHOD
"""
    run = tcunit(suite("FB_Timer", methods, "WaitsForTheTimer();"), {"Timer": "FB_Timer"})
    (result,) = run.results
    assert (result.outcome, result.time_ns, result.asserts) == (PASSED, 100_000_000, 1)
    assert run.errors == [] and run.time_ns == 100_000_000  # the run ends in the cycle TcUnit finishes


def test_the_same_failed_assert_in_every_cycle_is_reported_once_and_a_new_one_again(tcunit):
    methods = """
METHOD Repeats
VAR_INST
    n : INT;
END_VAR
TEST('Repeats');
n := n + 1;
AssertEquals_INT(Expected := 0, Actual := 1, Message := 'always the same');
AssertEquals_INT(Expected := 0, Actual := n, Message := 'a new actual value');
IF n = 3 THEN
    TEST_FINISHED();
END_IF
END_METHOD
"""
    run = tcunit(suite("FB_Rep", methods, "Repeats();"), {"Rep": "FB_Rep"})
    head = "FAILED TEST 'PRG_TEST.Rep@Repeats', EXP: 0, ACT:"
    assert failures(run) == [
        f"{head} 1, MSG: always the same",
        f"{head} 1, MSG: a new actual value",
        f"{head} 2, MSG: a new actual value",
        f"{head} 3, MSG: a new actual value",
    ]
    assert run.results[0].asserts == 4  # TcUnit counts the asserts it reported


def test_an_identical_assert_made_twice_in_a_cycle_is_two_asserts(tcunit):
    body = "AssertEquals_INT(Expected := 1, Actual := 2, Message := 'twice');\n" * 2
    run = tcunit(suite("FB_Twice", method("Twice", body), "Twice();"), {"T": "FB_Twice"})
    assert len(failures(run)) == 2 and run.results[0].asserts == 2


def test_asserts_after_test_finished_are_ignored(tcunit):
    methods = method(
        "Test_AssertImmediatelyAfterFinished",
        "TEST_FINISHED();\nAssertEquals_INT(Expected := 1, Actual := 2, Message := 'after finished');",
    )
    methods += """
METHOD Test_LongTest
VAR_INST
    n : INT;
END_VAR
TEST('Test_LongTest');
n := n + 1;
IF n = 2 THEN
    TEST_FINISHED();
END_IF
IF n > 2 THEN  (* the suite still calls it: TcUnit ignores the asserts *)
    AssertTrue(Condition := FALSE, Message := 'once finished');
END_IF
END_METHOD
METHOD Test_ShortTest
VAR_INST
    n : INT;
END_VAR
TEST('Test_ShortTest');
n := n + 1;
IF n = 5 THEN
    TEST_FINISHED();
END_IF
END_METHOD
"""
    body = "Test_AssertImmediatelyAfterFinished();\nTest_LongTest();\nTest_ShortTest();"
    run = tcunit(suite("FB_Skip", methods, body), {"SkipAssertionsWhenFinished": "FB_Skip"})
    assert set(outcomes(run).values()) == {PASSED} and failures(run) == []


def test_ordered_tests_run_one_after_the_other(tcunit):
    methods = """
METHOD First
VAR_INST
    n : INT;
END_VAR
IF TEST_ORDERED('First') THEN
    n := n + 1;
    AssertFalse(Condition := IS_TEST_FINISHED('Second'), Message := 'Second before First');
    IF n = 3 THEN
        TEST_FINISHED();
    END_IF
END_IF
END_METHOD
METHOD Second
IF TEST_ORDERED('Second') THEN
    AssertTrue(Condition := IS_TEST_FINISHED('First'), Message := 'First not finished');
    TEST_FINISHED();
END_IF
END_METHOD
METHOD NotInOrder
VAR
    ok : BOOL;
END_VAR
ok := TEST_ORDERED('NotInOrder');
(* not its turn until First and Second finished: an assert is ignored while TEST_ORDERED is FALSE *)
AssertTrue(Condition := ok, Message := 'asserted before its turn');
IF ok THEN
    TEST_FINISHED();
END_IF
END_METHOD
"""
    run = tcunit(suite("FB_Ordered", methods, "NotInOrder();\nFirst();\nSecond();"), {"Ordered": "FB_Ordered"})
    # TEST_ORDERED's order is the order of the first calls: NotInOrder, First, Second
    assert outcomes(run) == {
        "PRG_TEST.Ordered@NotInOrder": PASSED,
        "PRG_TEST.Ordered@First": PASSED,
        "PRG_TEST.Ordered@Second": PASSED,
    }
    took = {r.case.name: r.time_ns for r in run.results}
    assert took == {"NotInOrder": 0, "First": 20_000_000, "Second": 0}
    # NotInOrder in cycle 1 (0 ms), First in cycles 2-4 (10-30 ms), Second in cycle 5 (40 ms): a test
    # finished is seen as such, and the next one's turn comes, in the cycle after
    assert run.time_ns == 40_000_000


def test_a_test_name_used_twice_in_a_cycle_is_reported_once_and_its_asserts_ignored(tcunit):
    methods = method("TestOne", "AssertEquals_INT(Expected := 1, Actual := 1, Message := 'm');") + method(
        "TestOneAgain", "AssertEquals_INT(Expected := 1, Actual := 2, Message := 'the duplicate');", test="TestOne"
    )
    body = "TestOne();\nTestOneAgain();\nTestOneAgain();"
    run = tcunit(suite("FB_Same", methods, body), {"CreateFourTestsWithSameName": "FB_Same"})
    assert outcomes(run) == {"PRG_TEST.CreateFourTestsWithSameName@TestOne": PASSED}
    assert run.errors == [
        "Test with name 'TestOne' already exists in test suite 'PRG_TEST.CreateFourTestsWithSameName'"
    ]


def test_a_disabled_test_is_skipped_under_its_name_without_the_prefix(tcunit):
    methods = method(
        "Disabled", "AssertTrue(Condition := FALSE, Message := 'never');", test="DISABLED_ThisShouldNotRun"
    )
    methods += method("Enabled", "AssertTrue(Condition := TRUE, Message := 'm');")
    run = tcunit(suite("FB_Dis", methods, "Disabled();\nEnabled();"), {"CreateDisabledTest": "FB_Dis"})
    assert outcomes(run) == {
        "PRG_TEST.CreateDisabledTest@ThisShouldNotRun": SKIPPED,
        "PRG_TEST.CreateDisabledTest@Enabled": PASSED,
    }
    assert failures(run) == []
    summary = [line.text for line in run.log if line.kind == "result" and line.level == "error"]
    assert summary[1:5] == ["| Test suites: 1", "| Tests: 2", "| Successful tests: 2", "| Failed tests: 0"]


def test_test_finished_named_finishes_another_test_of_the_suite(tcunit):
    methods = """
METHOD Starts
VAR_INST
    n : INT;
END_VAR
TEST('Starts');
TEST('Finisher');
n := n + 1;
IF n = 2 THEN
    TEST_FINISHED_NAMED('Starts');
    TEST_FINISHED();
END_IF
END_METHOD
"""
    run = tcunit(suite("FB_Named", methods, "Starts();"), {"TestFinishedNamed": "FB_Named"})
    assert outcomes(run) == {"PRG_TEST.TestFinishedNamed@Starts": PASSED, "PRG_TEST.TestFinishedNamed@Finisher": PASSED}


def test_test_finished_named_of_a_test_that_is_not_stops_the_run(tcunit):
    methods = method("Waits", "TEST_FINISHED_NAMED('NoSuchTest');\nAssertTrue(TRUE, 'm');")
    methods = methods.replace("TEST_FINISHED();\nEND_METHOD", "END_METHOD")
    run = tcunit(suite("FB_Nope", methods, "Waits();"), {"TestFinishedNamedDoesNotExist": "FB_Nope"})
    assert run.errors[0] == "Failed to find test 'NoSuchTest'"
    assert "TEST_FINISHED_NAMED('NoSuchTest')" in run.errors[1]
    (result,) = run.results
    assert result.outcome == FAILED and "not finished when TcUnit stopped the run" in result.error


def test_a_test_that_never_finishes_fails_at_the_timeout(tcunit):
    methods = "METHOD Forever\nTEST('Forever');\nAssertTrue(TRUE, 'm');\nEND_METHOD\n"
    methods += method("Quick", "AssertTrue(TRUE, 'm');")
    run = tcunit(suite("FB_Forever", methods, "Forever();\nQuick();"), {"F": "FB_Forever"}, timeout_s=0.5)
    assert outcomes(run) == {"PRG_TEST.F@Forever": FAILED, "PRG_TEST.F@Quick": PASSED}
    assert "timed out after 0.5 s of engine time without TEST_FINISHED()" in run.results[0].error
    assert run.errors == ["timed out after 0.5 s of engine time: a test never called TEST_FINISHED()"]


def test_run_in_sequence_runs_one_suite_after_the_other(tcunit):
    source = (
        """
VAR_GLOBAL
    nCycle : INT;
    nFirstDone : INT;
END_VAR
"""
        + suite(
            "FB_Slow",
            """
METHOD Slow
VAR_INST
    n : INT;
END_VAR
TEST('Slow');
n := n + 1;
IF n = 3 THEN
    nFirstDone := nCycle;
    TEST_FINISHED();
END_IF
END_METHOD
""",
            "nCycle := nCycle + 1;\nSlow();",
        )
        + suite(
            "FB_Next",
            method("Next", "AssertTrue(Condition := nFirstDone > 0, Message := 'ran beside the first suite');"),
            "nCycle := nCycle + 1;\nNext();",
        )
    )
    suites = {"First": "FB_Slow", "Second": "FB_Next"}
    seq = tcunit(source, suites, run="RUN_IN_SEQUENCE")
    assert outcomes(seq) == {"PRG_TEST.First@Slow": PASSED, "PRG_TEST.Second@Next": PASSED}
    together = tcunit(source, suites, run="RUN")
    assert outcomes(together)["PRG_TEST.Second@Next"] == FAILED  # RUN: every suite from the first cycle


def test_an_empty_suite_is_finished_after_its_first_cycle(tcunit):
    source = suite("FB_Empty", "", ";") + suite("FB_One", method("One", "AssertTrue(TRUE, 'm');"), "One();")
    run = tcunit(source, {"EmptyTestSuite": "FB_Empty", "One": "FB_One"})
    assert run.suites == 2 and outcomes(run) == {"PRG_TEST.One@One": PASSED}
    assert run.time_ns == 10_000_000 and "| Test suites: 2" in [line.text for line in run.log]


def test_suites_inside_blocks_and_arrays_have_their_instance_paths(tcunit):
    source = suite("FB_S", method("T", "AssertEquals_INT(1, 2, 'm');"), "T();") + (
        "FUNCTION_BLOCK FB_Holder\nVAR\n    inner : FB_S;\n    many : ARRAY[1..2] OF FB_S;\nEND_VAR\n"
        "END_FUNCTION_BLOCK\n"
    )
    run = tcunit(source, {"holder": "FB_Holder"})
    assert [r.case.classname for r in run.results] == [
        "PRG_TEST.holder.inner",
        "PRG_TEST.holder.many[1]",
        "PRG_TEST.holder.many[2]",
    ]


def test_k_runs_the_tests_it_selects_and_skips_the_others(tcunit):
    methods = method("Alpha", "AssertTrue(FALSE, 'm');") + method("Beta", "AssertTrue(TRUE, 'm');")
    run = tcunit(suite("FB_K", methods, "Alpha();\nBeta();"), {"K": "FB_K"}, select=lambda path: "BETA" in path.upper())
    assert outcomes(run) == {"PRG_TEST.K@Beta": PASSED} and failures(run) == []


def test_tcunit_adslogstr_and_write_protected(tcunit):
    source = "FUNCTION_BLOCK FB_Guarded\nVAR\n    nLocked : INT;\nEND_VAR\nEND_FUNCTION_BLOCK\n" + suite(
        "FB_Tools",
        method(
            "Writes",
            "TCUNIT_ADSLOGSTR(msgCtrlMask := 16#04, msgFmtStr := 'Test number %s', strArg := '1');\n"
            "WRITE_PROTECTED_INT(Ptr := ADR(n), Value := 42);\n"
            "AssertEquals_INT(Expected := 42, Actual := n, Message := 'written through its address');",
            "VAR n : INT; END_VAR",
        ),
        "Writes();",
    )
    run = tcunit(source, {"Tools": "FB_Tools"})
    assert outcomes(run) == {"PRG_TEST.Tools@Writes": PASSED}
    assert [(line.level, line.text) for line in run.log if line.kind == "user"] == [("error", "Test number 1")]
    assert run.errors == []  # the user's own messages are not TcUnit's errors


def test_without_softplc_test_run_does_nothing():
    from softplc.runtime.program import compile_files
    from softplc.runtime.testing.tcunit import tcunit_library

    source = "VAR_GLOBAL nCalls : INT; END_VAR\n" + suite(
        "FB_Counted", method("T", "AssertTrue(FALSE, 'm');"), "nCalls := nCalls + 1;\nT();"
    )
    source += "PROGRAM PRG_TEST\nVAR s : FB_Counted; END_VAR\nTcUnit.RUN();\nEND_PROGRAM\n"
    program = compile_files([], texts={"suites.st": source}, profile="twincat", libraries=[tcunit_library()])
    runner = program.runner("PRG_TEST", cycle_time_ms=10)
    runner.run(3)  # softplc run: the natives' fallback, no test runner
    assert runner.get("nCalls") == 0
