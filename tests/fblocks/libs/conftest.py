"""Running ST with the vendor libraries softplc ships (fblocks/libs)."""

from __future__ import annotations

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.program.shipped import shipped_named


def libs(*names: str) -> list:
    out = [shipped_named(n) for n in names]
    assert all(out), names
    return out


def run(source: str, *names: str, cycles: int = 1, cycle_time_ms: int = 10, entry: str = "Main"):
    """Compile source (profile twincat) with the named shipped libraries and
    run entry for cycles in virtual time; the runner."""
    prog = compile_files([], profile="twincat", texts={"main.st": source}, libraries=libs(*names))
    runner = prog.runner(entry, cycle_time_ms=cycle_time_ms)
    runner.run(cycles)
    return runner


def check(source: str, *names: str) -> list:
    """(code, line, message) of the diagnostics of source with the libraries."""
    diags, _ = check_files([], profile="twincat", texts={"main.st": source}, libraries=libs(*names))
    return [(d.code, d.pos.line, d.message) for d in diags]
