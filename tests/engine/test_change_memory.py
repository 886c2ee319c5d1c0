"""What an online change leaves behind (issue 31's soak: RSS flat within
10 %; the scan never waiting for a collection): a program read back from
the compile process is freed as soon as the change replaced it, by
reference counting alone, with the garbage collector off. Before, its
checker's tables were one ring (a POU's info, its tree, a name, the name's
symbol, the POU's info) and the copy of the values another (the carry's
plans): only a full collection freed them, walking the whole heap with the
interpreter lock held (240 ms after ten changes of the default plant)."""

from __future__ import annotations

import contextlib
import gc
import weakref
from pathlib import Path
from types import FunctionType

from softplc.runtime.engine.online_change import OnlineChange
from softplc.testing import PLC

SOURCE = """
FUNCTION_BLOCK Counter
VAR_INPUT step : DINT; END_VAR
VAR_OUTPUT total : DINT; END_VAR
total := total + step;
END_FUNCTION_BLOCK

PROGRAM Main
VAR
    counters : ARRAY[1..3, 1..2] OF Counter;
    n : DINT; {extra}
END_VAR
n := n + 1;
counters[2, 1](step := 2);
END_PROGRAM
"""


def _change(plc: PLC, change: OnlineChange, st: Path, extra: str) -> None:
    st.write_text(SOURCE.replace("{extra}", extra), encoding="utf-8")
    request = change.submit(extra)
    plc.step()
    report = request.wait(0)
    assert report.applied, report.errors


@contextlib.contextmanager
def _changing(tmp_path: Path):
    """(the PLC of SOURCE after 3 scans, its OnlineChange, the ST file)."""
    st = tmp_path / "plant.st"
    st.write_text(SOURCE.replace("{extra}", ""), encoding="utf-8")
    with PLC.from_st([st], cycle="10ms") as plc:
        plc.step(3)
        change = OnlineChange(plc.engine, plc.config)
        try:
            yield plc, change, st
        finally:
            gc.enable()
            gc.unfreeze()  # the change froze the heap: this worker's later garbage is collected as before
            change.stop()


def test_a_replaced_program_is_freed_without_the_garbage_collector(tmp_path):
    with _changing(tmp_path) as (plc, change, st):
        _change(plc, change, st, "a : INT;")
        first = plc.engine.program
        assert first.read_back  # compiled in the compile process
        main = next(p for p in first.checked.pous if p.name.upper() == "MAIN")
        symbol, tables, program = weakref.ref(main.vars["N"]), weakref.ref(main), weakref.ref(first)
        ns = plc.engine.ns
        classes = [v for v in ns.values() if isinstance(v, type) and v.__module__ == ns["__name__"]]
        code = weakref.ref(next(v for c in classes for v in vars(c).values() if isinstance(v, FunctionType)))
        del ns, classes
        del first, main
        plc.step(2)
        gc.disable()
        _change(plc, change, st, "b : INT;")
        # the values went on through both changes
        assert plc["Main.n"] == 7 and plc["Main.counters[2, 1].total"] == 14
        assert (symbol(), tables(), program(), code()) == (None, None, None, None)


def test_two_changes_queued_before_a_scan_both_carry_the_values(tmp_path):
    # the second change's copy was worked out against the program the first replaces
    with _changing(tmp_path) as (plc, change, st):
        st.write_text(SOURCE.replace("{extra}", "a : INT := 1;"), encoding="utf-8")
        first = change.submit("first")
        st.write_text(SOURCE.replace("{extra}", "a : INT := 1; b : INT := 2;"), encoding="utf-8")
        second = change.submit("second")
        plc.step()
        reports = [first.wait(0), second.wait(0)]
        assert [r.applied for r in reports] == [True, True], [r.errors for r in reports]
        assert "Main.n" in reports[1].kept and "Main.b" in reports[1].initialised
        assert plc["Main.n"] == 4 and plc["Main.counters[2, 1].total"] == 8
        assert (plc["Main.a"], plc["Main.b"]) == (1, 2)


def test_the_new_program_is_moved_out_of_the_collectors_walks_once_applied(tmp_path):
    # its module's classes and its instances, made after the read-back was
    # frozen, no longer walked by every collection of the middle generation
    with _changing(tmp_path) as (plc, change, st):
        _change(plc, change, st, "a : INT;")
        assert plc.engine.program.read_back
        main = plc.engine.instances["MAIN"][2]
        walked = {id(o) for o in gc.get_objects()}  # generations 0 to 2: not the frozen ones
        assert id(main) not in walked and id(type(main)) not in walked
        plc.step()
        assert plc["Main.n"] == 5 and plc["Main.counters[2, 1].total"] == 10
