"""Marks of a bus log's frames in a trace's plot (`softplc plot --bus-log
FILE --mark TEXT`): the default plant run with a trace and a bus log, its
NMT starts (one per node, CiA 301) and its LTMR's heartbeats marked."""

from __future__ import annotations

import re

import pytest

from ..test_cli import softplc


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    where = tmp_path_factory.mktemp("marks")
    done = softplc(
        "run",
        "--virtual-time",
        "--duration",
        "1s",
        "--watch",
        "Pump.state",
        "--trace",
        where / "run.csv",
        "--bus-log",
        where / "run.asc",
        cwd=where,
    )
    assert done.returncode == 0, done.stderr
    return where


def marks_in(svg: str) -> set[int]:
    return {int(n) for n in re.findall(r'id="mark-(\d+)"', svg)}


def test_the_frames_a_mark_names_are_drawn_through_the_plot(run):
    out = run / "nmt.svg"
    done = softplc("plot", run / "run.csv", "-o", out, "--bus-log", run / "run.asc", "--mark", "NMT start")
    assert done.returncode == 0, done.stderr
    assert "marked 2 frame(s)" in done.stderr  # motor (40) and pump (20)
    assert marks_in(out.read_text()) == {0, 1}


def test_several_texts_and_frames_over_the_run(run):
    out = run / "beats.svg"
    done = softplc(
        "plot",
        run / "run.csv",
        "-o",
        out,
        "--bus-log",
        run / "run.asc",
        "--mark",
        "motor (40) heartbeat",
        "--mark",
        "NMT start",
    )
    assert done.returncode == 0, done.stderr
    # the LTMR's heartbeat every 100 ms (its 1017h = 100 in io_config/default.toml) for 1 s, and the two starts
    count = int(re.search(r"marked (\d+) frame", done.stderr).group(1))
    assert 2 + 9 <= count <= 2 + 11
    assert marks_in(out.read_text()) == set(range(count))


def test_mark_without_a_bus_log_is_a_usage_error(run):
    done = softplc("plot", run / "run.csv", "-o", run / "x.svg", "--mark", "NMT")
    assert done.returncode == 2
    assert "--bus-log and --mark go together" in done.stderr
