"""[plc] realtime_priority (engine/clock.py): on the real clock the PLC's
threads run under SCHED_FIFO, the scan at the priority given and every other
thread one below (those the scan starts inherit its own); where the system refuses, the PLC says so and runs at
normal priority. Each case is a real `softplc run`: a test must not put the
test process itself under SCHED_FIFO."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys

import pytest

from ..launch_support import env, wait_for_line, write_config

SRC = "PROGRAM Main\nVAR n : DINT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"
CONFIG = """[plc]
programs = ["p.st"]
realtime_priority = 40

[[task]]
name = "Main"
interval = "10ms"
programs = ["Main"]
"""


def _may_use_fifo() -> bool:
    probe = "import os; os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(1))"
    return subprocess.run([sys.executable, "-c", probe], capture_output=True).returncode == 0


ALLOWED = _may_use_fifo()


def _run(cfg, prefix: list) -> subprocess.Popen:
    return subprocess.Popen(
        [*prefix, sys.executable, "-m", "softplc.runtime.cli", "run", str(cfg), "--duration", "60s"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        env=env(),
    )


def _stop(proc: subprocess.Popen) -> str:
    proc.send_signal(signal.SIGINT)
    _out, rest = proc.communicate(timeout=60)
    assert proc.returncode == 0, rest
    return rest


@pytest.mark.skipif(not ALLOWED, reason="SCHED_FIFO takes root or CAP_SYS_NICE, which this user has not")
def test_the_scan_runs_under_sched_fifo_and_the_other_threads_one_below(tmp_path):
    proc = _run(write_config(tmp_path, CONFIG, {"p.st": SRC}), [])
    try:
        wait_for_line(proc, "the PLC runs under SCHED_FIFO, the scan at priority 40")
        policies = {}
        for tid in os.listdir(f"/proc/{proc.pid}/task"):
            try:
                policies[int(tid)] = (os.sched_getscheduler(int(tid)), os.sched_getparam(int(tid)).sched_priority)
            except ProcessLookupError:  # a thread that ended meanwhile
                continue
        assert policies[proc.pid] == (os.SCHED_FIFO, 40), policies  # softplc run scans in its main thread
        # the others one below, but those the scan started (they inherit its priority)
        assert set(policies.values()) <= {(os.SCHED_FIFO, 40), (os.SCHED_FIFO, 39)}, policies
        assert (os.SCHED_FIFO, 39) in policies.values(), policies
    finally:
        _stop(proc)


@pytest.mark.skipif(ALLOWED and shutil.which("setpriv") is None, reason="util-linux's setpriv drops CAP_SYS_NICE")
def test_without_the_right_the_plc_warns_and_runs_at_normal_priority(tmp_path):
    drop = ["setpriv", "--bounding-set=-sys_nice"] if ALLOWED else []  # root: run without the right
    proc = _run(write_config(tmp_path, CONFIG, {"p.st": SRC}), drop)
    try:
        lines = wait_for_line(proc, "realtime_priority = 40: the scan runs at normal priority")
        assert "Operation not permitted" in lines[-1] and "CAP_SYS_NICE" in lines[-1]
        assert all(os.sched_getscheduler(int(tid)) == os.SCHED_OTHER for tid in os.listdir(f"/proc/{proc.pid}/task"))
    finally:
        _stop(proc)
