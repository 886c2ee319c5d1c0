"""Traces in memory: the Recorder keeps what a plot needs, and CSV traces
of `softplc run` are read back with their kinds."""

from __future__ import annotations

import pytest

from softplc.runtime.engine.monitor import TraceWriter, Watch
from softplc.runtime.trace.reading import read_trace
from softplc.runtime.trace.series import Recorder, Series, TraceFileError, read_csv

from .conftest import MS, SRC, WATCHED, task


def test_a_series_keeps_the_changes_and_the_last_sample_before_each():
    s = Series("x", "real")
    for t, v in [(0, 1.0), (1, 1.0), (2, 1.0), (3, 5.0), (4, 6.0), (5, 6.0), (6, 6.0)]:
        s.add(t, v)
    s.finish()
    # a line through these is the line through every sample
    assert list(zip(s.times, s.values)) == [(0, 1.0), (2, 1.0), (3, 5.0), (4, 6.0), (6, 6.0)]


def test_recorder_samples_every_scan_in_engine_time(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    recorder = Recorder(Watch(e, WATCHED))
    e.after_tick.append(recorder)
    e.run(duration_ns=1000 * MS)
    trace = recorder.trace()
    by = {s.name: s for s in trace.series}
    assert by["Main.mode"].levels == ("Off", "Auto", "Manual")
    assert list(zip(by["Main.mode"].times, by["Main.mode"].values)) == [
        (0.0, "Auto"),
        (0.01, "Auto"),
        (0.02, "Manual"),
        (0.99, "Manual"),
    ]
    assert by["%QW1"].values == [0xFF00, 0xFF00] and by["%QW1"].times == [0.0, 0.99]
    assert len(by["Main.x"].times) == 100  # changes every scan: every sample kept
    assert by["Main.on"].kind == "bool" and by["Main.name"].kind == "text"


def test_read_csv_gives_each_column_a_kind(engines, tmp_path):
    e = engines(SRC, [task("Main", 10, "Main")])
    path = tmp_path / "run.csv"
    with path.open("w", newline="", encoding="utf-8") as f:
        e.after_tick.append(TraceWriter(f, Watch(e, WATCHED)))
        e.run(duration_ns=50 * MS)
    trace = read_trace(path)
    kinds = {s.name: s.kind for s in trace.series}
    assert kinds == {
        "Main.n": "int",
        "Main.on": "bool",
        "Main.mode": "enum",
        "Main.x": "real",
        "Main.t": "int",
        "total": "int",
        "%QW1": "int",
        "Main.name": "text",
    }
    n = next(s for s in trace.series if s.name == "Main.n")
    assert list(zip(n.times, n.values)) == [(0.0, -3), (0.01, -6), (0.02, -9), (0.03, -12), (0.04, -15)]


@pytest.mark.parametrize(
    "text, message",
    [
        ("a,b\n1,2\n", r"bad\.csv: not a CSV trace of softplc run"),
        ("time_ms,cycle,x\n0.0,1,1\n10.0,2\n", r"bad\.csv:3: 2 values, the header names 3"),
        ("time_ms,cycle,x\nzero,1,1\n", r"bad\.csv:2: time_ms 'zero' is not a number"),
    ],
)
def test_read_csv_names_the_file_and_line_of_a_bad_trace(tmp_path, text, message):
    bad = tmp_path / "bad.csv"
    bad.write_text(text)
    with pytest.raises(TraceFileError, match=message):
        read_csv(bad)


def test_read_trace_knows_csv_and_vcd_only(tmp_path):
    with pytest.raises(TraceFileError, match=r"run\.txt: not a trace softplc reads"):
        read_trace(tmp_path / "run.txt")


def test_select_keeps_the_order_given_and_names_an_unknown_signal(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    recorder = Recorder(Watch(e, WATCHED))
    e.after_tick.append(recorder)
    e.run(cycles=1)
    trace = recorder.trace("run.csv")
    assert trace.select(["Main.x", "Main.n"]).names() == ["Main.x", "Main.n"]
    with pytest.raises(KeyError, match="no signal Main.nope in run.csv"):
        trace.select(["Main.nope"])
