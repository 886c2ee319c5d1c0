"""What `softplc run` shows: watched values, the status line (terminal and
log form) and the CSV trace, on an engine in virtual time."""

from __future__ import annotations

import csv
import io

import pytest

from softplc.runtime.engine.monitor import StatusReporter, TraceWriter, Watch, fit, status_line
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
    assert w.raw() == [3, 1, "Auto", 20, 6, 30, "[0,3]"]
    assert w.shown() == [
        ("Main.n", "3"),
        ("Main.on", "true"),
        ("Main.mode", '"Auto"'),
        ("Main.t", '"T#20ms"'),
        ("total", "6"),
        ("%QW1", "30"),
        ("Main.pair", "[0,3]"),
    ]


def test_watch_describes_each_signal_for_the_traces(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    w = Watch(e, ["Main.n", "Main.on", "Main.mode", "Main.t", "total", "%QW1", "%QX0.1", "Main.pair"])
    kinds = [(i.path, i.kind, i.type_name, i.bits, i.signed) for i in w.signals()]
    assert kinds == [
        ("Main.n", "int", "INT", 16, True),
        ("Main.on", "bool", "BOOL", 1, False),
        ("Main.mode", "enum", "Mode", 0, False),
        ("Main.t", "int", "TIME", 32, True),
        ("total", "int", "DINT", 32, True),
        ("%QW1", "int", "WORD", 16, False),
        ("%QX0.1", "bool", "BOOL", 1, False),
        ("Main.pair", "text", "ARRAY[1..2] OF INT", 0, False),
    ]
    assert w.signals()[2].levels == ("Off", "Auto")


def test_watch_takes_array_elements_as_the_testing_api_does(engines):
    """Issue 33: --watch 'CANOPEN_NODE[33].State' answered "no variable",
    though the testing API's paths take indices."""
    e = engines(SRC, [task("Main", 10, "Main")])
    e.run(cycles=3)
    w = Watch(e, ["Main.pair[2]", "Main.pair[1]", "Main.n"])
    assert w.raw() == [3, 0, 3]
    assert [(i.path, i.kind, i.type_name) for i in w.signals()][:1] == [("Main.pair[2]", "int", "INT")]
    assert w.shown()[0] == ("Main.pair[2]", "3")
    out = io.StringIO()
    e.after_tick.append(TraceWriter(out, w))
    e.run(cycles=1)
    assert out.getvalue().splitlines()[1] == "30.0,4,4,0,4"


@pytest.mark.parametrize(
    ("path", "message"),
    [("Main.pair[3]", "Main.pair[3]"), ("Main.nope[1]", "nope"), ("Main.n[1]", "Main.n[1]")],
)
def test_watch_of_an_element_that_is_not_there_names_it(engines, path, message):
    e = engines(SRC, [task("Main", 10, "Main")])
    with pytest.raises(KeyError) as info:
        Watch(e, [path])
    assert message in str(info.value)


@pytest.mark.parametrize("path, error", [("Main.nope", KeyError), ("nope", KeyError), ("%QZ1", AddressError)])
def test_watch_refuses_what_does_not_exist(engines, path, error):
    e = engines(SRC, [task("Main", 10, "Main")])
    with pytest.raises(error):
        Watch(e, [path])


def test_trace_writes_enumerations_by_name(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    out = io.StringIO()
    e.after_tick.append(TraceWriter(out, Watch(e, ["Main.mode", "Main.n"])))
    e.run(cycles=2)
    assert out.getvalue().splitlines() == ["time_ms,cycle,Main.mode,Main.n", "0.0,1,Auto,1", "10.0,2,Auto,2"]


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


def test_a_long_status_line_is_cut_to_the_terminal_width_and_rewritten_in_place(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    e.run(cycles=1)
    w = Watch(e, ["Main.n", "Main.on", "Main.mode", "Main.t", "total", "Main.pair"])
    full = status_line(e, w)
    assert len(full) > 60
    term = io.StringIO()
    reporter = StatusReporter(e, term, w, tty=True, columns=60)
    reporter.show()
    reporter.show()
    shown = term.getvalue().split("\r\x1b[K")
    assert shown[0] == "" and len(shown) == 3  # two refreshes, each clearing the row first
    assert all(len(line) == 59 and line.endswith("…") for line in shown[1:])  # one column free
    assert "\n" not in term.getvalue()  # one row, rewritten
    assert shown[1][:-1] == full[:58]
    reporter.show(final=True)  # the last line, at the end of the run, is whole
    assert term.getvalue().endswith("\r\x1b[K" + full + "\n")


def test_the_status_line_in_a_log_is_whole_and_on_lines_of_its_own(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    e.run(cycles=1)
    w = Watch(e, ["Main.n", "Main.on", "Main.mode", "Main.t", "total", "Main.pair"])
    log = io.StringIO()
    reporter = StatusReporter(e, log, w, tty=False, columns=40)
    reporter.show()
    reporter.show()
    assert log.getvalue() == (status_line(e, w) + "\n") * 2


def test_the_terminal_width_comes_from_columns(engines, monkeypatch):
    e = engines(SRC, [task("Main", 10, "Main")])
    e.run(cycles=1)
    monkeypatch.setenv("COLUMNS", "30")
    term = io.StringIO()
    StatusReporter(e, term, None, tty=True).show()
    assert len(term.getvalue()) == len("\r\x1b[K") + 29


@pytest.mark.parametrize(
    "line, columns, shown",
    [("abcdef", 10, "abcdef"), ("abcdefghij", 10, "abcdefgh…"), ("abcdefghi", 10, "abcdefghi"), ("abc", 1, "…")],
)
def test_fit(line, columns, shown):
    assert fit(line, columns) == shown
