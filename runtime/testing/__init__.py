"""Tests written in ST: test FUNCTION_BLOCKs with ASSERT_* calls, run in
virtual time against the configured plant by ``softplc test`` and by pytest.

    natives.py       the assertion functions (native functions, st/native.py)
                     and the service that records them
    discover.py      which POUs of the test files are tests
    runner.py        one engine per test: the plant's tasks and the test's
    junit.py         the JUnit XML report
    command.py       ``softplc test``: output and exit codes
    pytest_plugin.py the pytest collector of test_*.st files (entry point softplc_st)

Nothing below this package knows it: the test runner compiles with its own
native functions (compile_files(natives=...)) and binds their service on
the engine's ExecContext, the way a bus driver binds its own.
"""
