"""What `softplc run` shows: watched values, the status line (terminal and
log form) and the CSV trace, on an engine in virtual time."""

from __future__ import annotations

import csv
import io

import pytest

from softplc.runtime.engine.monitor import StatusReporter, TraceWriter, Watch, status_line
from softplc.runtime.image.memory import AddressError

from .conftest import MS, task

SRC = """
TYPE Mode : (Off, Auto); END_TYPE
VAR_GLOBAL total : DINT; zero : INT; END_VAR
PROGRAM Main
VAR
    n : INT;
    on : BOOL;
    mode : Mode;
    t : TIME;
    out AT %QW1 : INT;
    pair : ARRAY[1..2] OF INT;
END_VAR
n := n + 1; on := NOT on; mode := Auto; t := TIME(); out := n * 10; pair[2] := n;
total := total + 2;
IF n = 5 THEN n := n / zero; END_IF
END_PROGRAM
"""


def test_watch_resolves_variables_globals_and_addresses(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    e.run(cycles=3)
    w = Watch(e, ["Main.n", "Main.on", "Main.mode", "Main.t", "total", "%QW1", "Main.pair"])
    assert w.raw() == [3, 1, 1, 20, 6, 30, "[0,3]"]
    assert w.shown() == [
        ("Main.n", "3"),
        ("Main.on", "true"),
        ("Main.mode", '"Auto"'),
        ("Main.t", '"T#20ms"'),
        ("total", "6"),
        ("%QW1", "30"),
        ("Main.pair", "[0,3]"),
    ]


@pytest.mark.parametrize("path, error", [("Main.nope", KeyError), ("nope", KeyError), ("%QZ1", AddressError)])
def test_watch_refuses_what_does_not_exist(engines, path, error):
    e = engines(SRC, [task("Main", 10, "Main")])
    with pytest.raises(error):
        Watch(e, [path])


def test_trace_has_a_row_per_scan_and_follows_a_restart(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    out = io.StringIO()
    e.after_tick.append(TraceWriter(out, Watch(e, ["Main.n", "Main.on"])))
    e.run(duration_ns=60 * MS)  # the fault at 40 ms: n stays 5
    e.restart()  # a fresh Main: the watch follows the new instance
    e.run(cycles=2)
    rows = list(csv.reader(io.StringIO(out.getvalue())))
    assert rows[0] == ["time_ms", "cycle", "Main.n", "Main.on"]
    assert [r[2] for r in rows[1:]] == ["1", "2", "3", "4", "5", "5", "1", "2"]
    assert [r[0] for r in rows[1:4]] == ["0.0", "10.0", "20.0"]


def test_status_line_shows_tasks_faults_and_watched_values(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    e.run(cycles=2)
    w = Watch(e, ["Main.n"])
    line = status_line(e, w)
    assert line.startswith("t=0.01s | cycles=2 | Main: ") and "overruns 0" in line
    assert line.endswith("faults=0 | Main.n=2")
    e.run(cycles=5)
    line = status_line(e, w)
    assert "Main FAULT:" in line and "faults=1 outputs SAFE" in line


def test_status_reporter_rewrites_the_line_on_a_terminal_and_appends_in_a_log(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    e.run(cycles=1)
    tty, log = io.StringIO(), io.StringIO()
    StatusReporter(e, tty, None, tty=True).show()
    StatusReporter(e, log, None, tty=False).show()
    assert tty.getvalue().startswith("\r\x1b[K") and not tty.getvalue().endswith("\n")
    assert log.getvalue() == status_line(e) + "\n"
