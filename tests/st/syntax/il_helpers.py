"""What the IL tests share: a program's values cycle by cycle, and an IL
program's against its ST twin's."""

from __future__ import annotations

from softplc.runtime.program import compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.syntax.parser import parse_source


def trace(src: str, names: list, cycles: int = 8, entry: str = "Main", profile: str = "codesys") -> list:
    r = compile_files([], profile, texts={"main.st": src}).runner(entry, cycle_time_ms=10)
    out = []
    for _ in range(cycles):
        r.run(1)
        out.append({n: r.get(n) for n in names})
    return out


def twins(il: str, st: str, names: list, cycles: int = 8, **kw) -> list:
    """The IL program's values each cycle, asserted equal to its ST twin's;
    and the IL really was lowered."""
    sf = parse_source(il, "main.st", DiagnosticBag())
    assert sf.lowered, "no IL body found"
    got = trace(il, names, cycles, **kw)
    assert got == trace(st, names, cycles, **kw)
    return got


def varies(rows: list, name: str) -> set:
    return {repr(r[name]) for r in rows}


# ---------------------------------------------------------------- operators and modifiers
