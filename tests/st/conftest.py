"""Helpers for compiling and running small ST programs in tests."""
from __future__ import annotations

import pytest

from softplc.runtime.program import check_files, compile_files


def run_st(source: str, cycles: int = 1, entry: str = "main", profile: str = "codesys",
           cycle_time_ms: int = 10, name: str = "test.st"):
    """Compile source, run entry for `cycles` cycles in virtual time and
    return the runner (read variables with runner.get('x'))."""
    prog = compile_files([], profile=profile, texts={name: source})
    runner = prog.runner(entry, cycle_time_ms=cycle_time_ms)
    runner.run(cycles)
    return runner


def diagnostics(source: str, profile: str = "codesys", name: str = "test.st"):
    diags, _sources = check_files([], profile=profile, texts={name: source})
    return diags


def codes(source: str, profile: str = "codesys") -> list:
    return [d.code for d in diagnostics(source, profile)]


@pytest.fixture
def st():
    return run_st
