"""Run a small program with libraries softplc ships chosen by name, in
virtual time: the tests of fblocks/libs."""

from __future__ import annotations

from softplc.runtime.program import compile_files
from softplc.runtime.program.shipped import shipped_named


def chosen(*names: str) -> list:
    libs = [shipped_named(n) for n in names]
    assert all(libs), names
    return libs


def program(decls: str, body: str, *libraries: str, profile: str = "codesys"):
    """The Program of PROGRAM Main with those declarations and body."""
    src = f"PROGRAM Main\nVAR\n{decls}\nEND_VAR\n{body}\nEND_PROGRAM\n"
    return compile_files([], texts={"main.st": src}, libraries=chosen(*libraries), profile=profile)


def runner(decls: str, body: str, *libraries: str, cycle_ms: int = 10, profile: str = "codesys"):
    return program(decls, body, *libraries, profile=profile).runner("Main", cycle_time_ms=cycle_ms)


def trace(r, cycles: int, *names: str) -> list:
    """The values of names after each of cycles cycles (one tuple a cycle, a
    bare value when one name)."""
    out = []
    for _ in range(cycles):
        r.run(1)
        values = tuple(r.get(n) for n in names)
        out.append(values[0] if len(names) == 1 else values)
    return out
