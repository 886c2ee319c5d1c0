"""softplc run as a service (README "Running as a service"): the log to a
rotated file, the systemd unit, the container image."""

from __future__ import annotations

import re
import shutil
import subprocess
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


def test_the_systemd_unit_runs_softplc_with_its_log_file_and_reloads_with_sighup(tmp_path):
    unit = (REPO / "deploy" / "softplc.service").read_text(encoding="utf-8")
    settings = dict(
        re.match(r"(\w+)=(.*)", line).groups()
        for line in unit.replace("\\\n", " ").splitlines()
        if re.match(r"\w+=", line)
    )
    assert settings["Type"] == "simple" and settings["User"] == "softplc" and settings["Restart"] == "on-failure"
    assert settings["KillSignal"] == "SIGTERM" and settings["ExecReload"] == "/bin/kill -HUP $MAINPID"
    program, command, config, *options = settings["ExecStart"].split()
    assert (program, command, config) == ("/opt/softplc/bin/softplc", "run", "/etc/softplc/plant.toml")
    # the unit's options are the CLI's own: a run of the default plant with them writes the log file
    log = options.index("--log-file") + 1
    assert options[log] == "/var/log/softplc/softplc.log"
    options[log] = str(tmp_path / "softplc.log")
    proc = softplc("run", "--virtual-time", "--cycles", "1", *options)
    assert proc.returncode == 0, proc.stderr
    assert "stopped after 1 scans" in (tmp_path / "softplc.log").read_text(encoding="utf-8")


def _container_tool() -> str | None:
    for tool in ("docker", "podman"):
        if shutil.which(tool) is None:
            continue
        try:
            if subprocess.run([tool, "info"], capture_output=True, timeout=30).returncode == 0:
                return tool
        except (OSError, subprocess.TimeoutExpired):
            continue
    return None


def test_the_container_image_builds_and_runs_the_default_plant():
    tool = _container_tool()
    if tool is None:
        pytest.skip("no working container tool: `docker info` and `podman info` fail (no daemon) or are missing")
    tag = "softplc-test:latest"
    build = subprocess.run([tool, "build", "-t", tag, str(REPO)], capture_output=True, text=True, timeout=1800)
    assert build.returncode == 0, build.stderr[-3000:]
    try:
        run = subprocess.run(
            [tool, "run", "--rm", tag, "softplc", "run", "--virtual-time", "--duration", "2s"],
            capture_output=True,
            text=True,
            timeout=300,
        )
        assert run.returncode == 0, run.stderr
        assert "stopped after 200 scans: outputs safe" in run.stderr
    finally:
        subprocess.run([tool, "rmi", "-f", tag], capture_output=True, timeout=120)
