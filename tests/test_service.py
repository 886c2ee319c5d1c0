"""softplc run as a service (README "Running as a service"): the log to a
rotated file, the systemd unit, the container image."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from .test_cli import softplc

REPO = Path(__file__).resolve().parents[1]
LINE = re.compile(r"\d{4}-\d\d-\d\d \d\d:\d\d:\d\d,\d{3} (t=\d+\.\d{3}s )?softplc (INFO|WARNING|ERROR): .*")

pytestmark = pytest.mark.slow  # each test starts softplc in a process of its own


def log_lines(text: str) -> list:
    return [line for line in text.splitlines() if LINE.fullmatch(line)]


def test_the_log_file_holds_the_log_lines_with_wall_time_and_engine_time(tmp_path):
    log = tmp_path / "plc.log"
    proc = softplc("run", "--virtual-time", "--duration", "3s", "--log-file", log)
    assert proc.returncode == 0, proc.stderr
    lines = log.read_text(encoding="utf-8").splitlines()
    assert lines == log_lines(proc.stderr)  # the same lines as stderr, without the status line
    assert all(LINE.fullmatch(line) for line in lines)
    assert "t=0.000s softplc INFO: running;" in lines[-2]
    assert "t=3.000s softplc INFO: stopped after 300 scans" in lines[-1]


def test_the_log_file_rotates_at_its_size_keeping_the_backups_asked_for(tmp_path):
    log = tmp_path / "plc.log"
    proc = softplc(
        "run", "--virtual-time", "--duration", "2s", "--log-file", log, "--log-max-bytes", "400", "--log-backups", "2"
    )
    assert proc.returncode == 0, proc.stderr
    files = sorted(p.name for p in tmp_path.iterdir())
    assert files == ["plc.log", "plc.log.1", "plc.log.2"]  # the oldest lines dropped
    longest = max(len(line) + 1 for line in log_lines(proc.stderr))
    kept = []
    for name in ("plc.log.2", "plc.log.1", "plc.log"):
        text = (tmp_path / name).read_text(encoding="utf-8")
        assert len(text.encode()) <= max(400, longest), name
        kept += text.splitlines()
    everything = log_lines(proc.stderr)
    assert len(kept) < len(everything) and kept == everything[-len(kept) :]


def test_a_log_file_that_cannot_be_written_is_refused_before_the_run(tmp_path):
    proc = softplc("run", "--virtual-time", "--cycles", "1", "--log-file", tmp_path / "no" / "plc.log")
    assert proc.returncode == 2
    assert f"softplc: --log-file: cannot write {tmp_path / 'no' / 'plc.log'}: No such file or directory" in proc.stderr
