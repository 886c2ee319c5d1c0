"""What the tests of `softplc run` as a user runs it share: softplc started
in a process of its own (spawn), read until a line comes (wait_for_line),
a configuration with its ST files (write_config), and no PLC left running
after a test (the autouse fixture no_orphans, imported by each module)."""

from __future__ import annotations

import os
import subprocess
import sys
import time
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[1]


def env():
    env = dict(os.environ, PYTHONIOENCODING="utf-8")
    env.pop("SOFTPLC_DEBUG", None)
    return env


_SPAWNED: list = []


@pytest.fixture(autouse=True)
def no_orphans():
    """A failing test must not leave a PLC running (and eating a core)."""
    yield
    while _SPAWNED:
        proc = _SPAWNED.pop()
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=30)
        for stream in (proc.stdout, proc.stderr):
            stream.close()


def spawn(*args, cwd=None):
    proc = subprocess.Popen(
        [sys.executable, "-m", "softplc.runtime.cli", *map(str, args)],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        stdin=subprocess.DEVNULL,
        text=True,
        cwd=cwd,
        env=env(),
    )
    _SPAWNED.append(proc)
    return proc


def wait_for_line(proc, needle: str, limit_s: float = 60) -> list:
    """Read the process's stderr until a line contains needle; the lines read.
    The limit only stops a broken test from hanging, it decides nothing."""
    lines = []
    deadline = time.monotonic() + limit_s
    while time.monotonic() < deadline:
        line = proc.stderr.readline()
        if not line:
            break
        lines.append(line)
        if needle in line:
            return lines
    proc.kill()
    raise AssertionError(f"never saw {needle!r}; stderr so far:\n{''.join(lines)}")


def write_config(tmp_path, text: str, programs: dict) -> Path:
    for name, source in programs.items():
        (tmp_path / name).write_text(source)
    cfg = tmp_path / "plant.toml"
    cfg.write_text(text)
    return cfg


#: a program that divides by zero in its third scan (a runtime fault of task Main)
FAULTS_AT_SCAN_3 = (
    "PROGRAM Main\nVAR n, d : INT; END_VAR\nn := n + 1;\nIF n = 3 THEN\n    n := n / d;\nEND_IF\nEND_PROGRAM\n"
)
