"""What a library's Python functions may read (fblocks/iec/functions.py
StdFunc): the ExecContext (context=True: the engine's date, the running
task), any pointer as a byte view of its target (a 'POINTER TO BYTE'
parameter), and a task hook the program calls as each cycle starts
(runtime/program/context.py ExecContext.begin_task)."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.program import Library, check_files, compile_files
from softplc.runtime.program.context import VIRTUAL_EPOCH_NS

MS = 1_000_000


@pytest.fixture
def lib(tmp_path: Path) -> Library:
    return Library(tmp_path, "Probe", functions="tests.program.context_library")


def run(lib: Library, source: str, cycles: int):
    runner = compile_files([], texts={"main.st": source}, libraries=[lib]).runner("Main", cycle_time_ms=10)
    runner.run(cycles)
    return runner


def test_a_context_function_reads_the_date_of_the_virtual_clock_and_the_task(lib):
    src = """
    PROGRAM Main
    VAR first, now : LINT; idx : DINT; cycles : UDINT; released : LINT; END_VAR
    now := DATE_NS();
    IF first = 0 THEN first := now; END_IF
    idx := TASK_INDEX();
    cycles := TASK_CYCLES();
    released := TASK_RELEASE_NS();
    END_PROGRAM
    """
    r = run(lib, src, 5)
    # virtual time starts on 2000-01-01 and advances 10 ms a cycle
    assert r.get("first") == VIRTUAL_EPOCH_NS
    assert r.get("now") - r.get("first") == 40 * MS
    assert (r.get("idx"), r.get("cycles"), r.get("released")) == (1, 5, 40 * MS)


def test_a_context_function_is_never_folded_into_a_constant(lib):
    src = "PROGRAM Main VAR a, b : LINT; END_VAR a := b; b := DATE_NS(); END_PROGRAM"
    r = run(lib, src, 3)
    assert r.get("b") - r.get("a") == 10 * MS


def test_a_pointer_parameter_takes_any_pointer_as_the_bytes_of_its_target(lib):
    src = """
    TYPE ST_A : STRUCT b : BYTE; w : WORD; END_STRUCT END_TYPE
    PROGRAM Main
    VAR s : ST_A := (b := 16#11, w := 16#2233); d : DINT := 16#44556677; x : ARRAY[0..2] OF INT := [1, 2, 3];
        p0, p2, p3, q0, q3, r4 : BYTE; END_VAR
    p0 := PEEK(ADR(s), 0);
    p2 := PEEK(ADR(s), 2);     (* w sits at offset 2, little-endian *)
    p3 := PEEK(ADR(s), 3);
    q0 := PEEK(ADR(d), 0);
    q3 := PEEK(ADR(d), 3);
    r4 := PEEK(ADR(x), 4);     (* x[2] *)
    END_PROGRAM
    """
    r = run(lib, src, 1)
    got = [r.get(n) for n in ("p0", "p2", "p3", "q0", "q3", "r4")]
    assert got == [0x11, 0x33, 0x22, 0x77, 0x44, 3]


def test_a_pointer_parameter_refuses_what_is_no_pointer(lib):
    src = "PROGRAM Main VAR b : BYTE; d : DINT; END_VAR b := PEEK(d, 0); END_PROGRAM"
    diags, _ = check_files([], texts={"main.st": src}, libraries=[lib])
    assert [(d.code, d.pos.line) for d in diags if d.is_error] == [("E020", 1)]


def test_the_library_task_hook_runs_as_each_cycle_starts(lib):
    src = """
    VAR_GLOBAL TASK_STARTS : UDINT; END_VAR
    PROGRAM Main VAR seen : UDINT; END_VAR seen := TASK_STARTS; END_PROGRAM
    """
    r = run(lib, src, 3)
    assert r.get("seen") == 3  # the hook ran before the program's cycle, three times
