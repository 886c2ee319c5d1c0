"""Cold, warm and new-version starts of the engine with a retain file, and
the retain period on the virtual clock."""

from __future__ import annotations

from softplc.runtime.engine.retain_file import RetainStore, read_file

from .conftest import MS, compile_st, make_engine, task

V1 = """
VAR_GLOBAL PERSISTENT
    totalParts : UDINT;
END_VAR
VAR_GLOBAL RETAIN
    shift : INT := 1;
END_VAR

PROGRAM Line
VAR RETAIN
    count : INT;
    lastSpeed : REAL;
END_VAR
VAR PERSISTENT
    hours : TIME;
END_VAR
VAR
    scratch : INT := 5;
END_VAR
count := count + 1;
totalParts := totalParts + 2;
lastSpeed := 12.5;
hours := TIME();
scratch := scratch + 1;
IF count = 3 THEN shift := 2; END_IF
END_PROGRAM
"""

# Version 2: a new variable, one PERSISTENT variable changed type, so the
# retained layout differs.
V2 = (
    V1.replace("VAR_GLOBAL RETAIN\n", "VAR_GLOBAL RETAIN\n    added : BOOL;\n")
    .replace("hours : TIME;", "hours : LTIME;")
    .replace("hours := TIME();", "hours := LTIME();")
)


def _engine(source, store_path, mode, **kw):
    return make_engine(
        compile_st(source),
        [task("Main", 10, "Line")],
        retain_store=RetainStore(store_path),
        retain_period_ns=100 * MS,
        start_mode=mode,
        **kw,
    )


def _run_and_stop(source, path, mode, duration_ms=100):
    e = _engine(source, path, mode)
    e.run(duration_ns=duration_ms * MS)
    e.stop()
    return e


def test_warm_start_restores_retain_and_persistent(tmp_path):
    path = tmp_path / "plant.retain"
    first = _run_and_stop(V1, path, "warm")
    assert first.get("Line.count") == 10
    e = _engine(V1, path, "warm")
    assert e.restore_report.layout_matched
    assert (e.get("Line.count"), e.get("totalParts"), e.get("shift"), e.get("Line.hours")) == (10, 20, 2, 90)
    assert e.get("Line.lastSpeed") == 12.5
    assert e.get("Line.scratch") == 5  # not retained: initialised
    e.run(duration_ns=10 * MS)
    assert e.get("Line.count") == 11
    e.stop()


def test_cold_start_initialises_everything(tmp_path):
    path = tmp_path / "plant.retain"
    _run_and_stop(V1, path, "warm")
    e = _engine(V1, path, "cold")
    assert (e.get("Line.count"), e.get("totalParts"), e.get("shift"), e.get("Line.hours")) == (0, 0, 1, 0)
    e.stop()


def test_new_program_version_keeps_matching_persistent_only(tmp_path):
    path = tmp_path / "plant.retain"
    _run_and_stop(V1, path, "warm")
    e = _engine(V2, path, "warm")
    report = e.restore_report
    assert not report.layout_matched
    assert e.get("totalParts") == 20  # PERSISTENT, same name and type: kept
    assert e.get("Line.hours") == 0  # PERSISTENT but TIME -> LTIME: initialised
    assert (e.get("Line.count"), e.get("shift")) == (0, 1)  # RETAIN: a new version starts them afresh
    dropped = dict(report.dropped)
    assert "Line.hours" in dropped and "Line.count" in dropped and "shift" in dropped
    e.stop()


def test_retained_data_is_never_older_than_the_period(tmp_path):
    path = tmp_path / "plant.retain"
    e = _engine(V1, path, "warm")
    e.run(duration_ns=1234 * MS)
    e.retain_store.flush()
    data = read_file(path)
    assert e.clock.now_ns() - data.saved_ns <= 100 * MS
    assert data.vars["Line.count"]["value"] == data.saved_ns // (10 * MS) + 1
    e.stop()
    assert read_file(path).vars["Line.count"]["value"] == 124  # stop saves the final state


def test_restart_after_a_fault_keeps_retain_values(tmp_path):
    src = V1.replace(
        "scratch := scratch + 1;", "scratch := scratch + 1;\nIF count = 5 THEN scratch := 1 / (count - 5); END_IF"
    )
    e = make_engine(compile_st(src), [task("Main", 10, "Line")])
    e.run(duration_ns=100 * MS)
    assert e.faults and e.get("Line.count") == 5
    e.restart()
    assert e.get("Line.count") == 5 and e.get("Line.scratch") == 5  # RETAIN kept, the rest initialised
    e.stop()
