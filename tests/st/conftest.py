"""Helpers for compiling and running small ST programs in tests."""

from __future__ import annotations

from contextlib import contextmanager

import pytest

from softplc.fblocks.iec.functions import STANDARD_FUNCTIONS
from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.check.checker import Checker
from softplc.runtime.st.codegen.codegen import CodeGen
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.profile import get_profile
from softplc.runtime.st.syntax.parser import parse_source


def prog(decls: str, body: str) -> str:
    """A PROGRAM main with the declarations decls (in one VAR block) and
    the statements body; its first statement is on line 5."""
    return f"PROGRAM main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"


@contextmanager
def plain_codegen():
    """The code generator without its optimisations (CodeGen.optimise), to
    compare the optimised code with; a cached module is still used unless
    the caller also disables the cache."""
    before = CodeGen.optimise
    CodeGen.optimise = False
    try:
        yield
    finally:
        CodeGen.optimise = before


def run_st(
    source: str,
    cycles: int = 1,
    entry: str = "main",
    profile: str = "codesys",
    cycle_time_ms: int = 10,
    name: str = "test.st",
):
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


def check_st(source: str, profile: str = "codesys", natives: dict | None = None, name: str = "test.st"):
    """Parse and check source alone (no library, no process image), as
    program/compile.py drives the Checker; returns (CheckedProgram, list of
    diagnostics in the order reported). natives: UPPER name -> NativeFunction."""
    diags = DiagnosticBag()
    sf = parse_source(source, name, diags, get_profile(profile))
    checked = Checker(get_profile(profile), diags, STANDARD_FUNCTIONS, natives or {}).run([sf])
    return checked, list(diags.items)


def pou_body(checked, name: str = "main") -> list:
    """The checked statements of a POU."""
    return next(p for p in checked.pous if p.name.upper() == name.upper()).node.body


@pytest.fixture
def st():
    return run_st
