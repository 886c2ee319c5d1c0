"""`softplc run` and its retain file, as a user runs it: SIGTERM saves it,
a file that cannot be written is not said saved, a save beyond the file
size limit, a path softplc did not write, a signal inside a long loop,
SIGUSR1 restarting a faulted task, and the file surviving SIGKILL."""

from __future__ import annotations

import json
import random
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from softplc.runtime.engine.retain_file import read_file

from .launch_support import FAULTS_AT_SCAN_3, env, no_orphans, spawn, wait_for_line, write_config  # noqa: F401  # no_orphans: autouse
from .test_cli import softplc

# each test starts softplc in a process of its own
pytestmark = pytest.mark.slow

# ---------------------------------------------------------------- signals and retain

COUNTER = """
PROGRAM Counter
VAR RETAIN
    count : UDINT;
END_VAR
VAR
    since_start : UDINT;
END_VAR
count := count + 1;
since_start := since_start + 1;
END_PROGRAM
"""


def _retain_config(tmp_path, period="50ms") -> Path:
    return write_config(
        tmp_path,
        f'[plc]\nprograms = ["counter.st"]\n[retain]\nfile = "counter.retain"\n'
        f'period = "{period}"\n[[task]]\nname = "Main"\ninterval = "10ms"\n'
        'programs = ["Counter"]\n',
        {"counter.st": COUNTER},
    )


@pytest.mark.realtime  # the real clock runs the PLC
def test_sigterm_stops_cleanly_and_saves_retain(tmp_path):
    cfg = _retain_config(tmp_path, period="1h")  # only the final save can write the file
    out = tmp_path / "final.json"
    proc = spawn("run", cfg, "--final-json", out)
    wait_for_line(proc, "running;")  # after the first scan
    proc.send_signal(signal.SIGTERM)
    _stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 0, stderr
    final = json.loads(out.read_text())["Counter"]
    saved = read_file(tmp_path / "counter.retain")
    assert saved.vars["Counter.count"]["value"] == final["count"] >= 1


def test_a_retain_file_that_cannot_be_written_is_not_said_saved(tmp_path):
    # The stop said "retained data saved" whatever the last write did.
    cfg = _retain_config(tmp_path)
    # /proc takes no new file, even from root: every write fails (the start is fine: no file yet)
    cfg.write_text(cfg.read_text().replace('file = "counter.retain"', 'file = "/proc/softplc-test.retain"'))
    result = softplc("run", cfg, "--virtual-time", "--duration", "200ms")
    assert result.returncode == 3, result.stderr  # was 0
    assert "retained data saved" not in result.stderr
    assert "retained data NOT saved: " in result.stderr and "cannot write the retain file" in result.stderr


def test_a_save_beyond_the_file_size_limit_exits_3_and_keeps_the_last_good_file(tmp_path):
    """ulimit -f (RLIMIT_FSIZE): every write of the retain file fails with
    EFBIG (Python ignores SIGXFSZ); the run exited 0."""
    import resource

    cfg = _retain_config(tmp_path)
    (tmp_path / "counter.st").write_text(
        COUNTER.replace("count : UDINT;", "count : UDINT; log : ARRAY[1..2000] OF DINT;")
    )
    first = softplc("run", cfg, "--virtual-time", "--cycles", "30")
    assert first.returncode == 0, first.stderr
    good = (tmp_path / "counter.retain").read_bytes()  # some 6 kB
    assert read_file(tmp_path / "counter.retain").vars["Counter.count"]["value"] == 30

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_FSIZE, (2048, 2048))

    proc = subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", "run", str(cfg), "--virtual-time", "--cycles", "30"],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        env=env(),
        timeout=120,
        preexec_fn=limit,
    )
    assert proc.returncode == 3, proc.stderr
    [line] = [ln for ln in proc.stderr.splitlines() if "retained data NOT saved" in ln]
    said = re.search(
        re.escape(f"retained data NOT saved: {tmp_path / 'counter.retain'}: cannot write the retain file: ")
        + r"File too large; (\d+) of (\d+) writes failed during the run, the file holds the last good one$",
        line,
    )
    assert said is not None and said.group(1) == said.group(2) != "0", line
    assert (tmp_path / "counter.retain").read_bytes() == good  # the first run's, whole
    assert sorted(p.name for p in tmp_path.iterdir()) == ["counter.retain", "counter.st", "plant.toml"]


def test_a_retain_path_softplc_did_not_write_stops_the_start_untouched(tmp_path):
    """Only a file with softplc's header is softplc's to set aside or write over."""
    cfg = _retain_config(tmp_path)
    (tmp_path / "counter.retain").write_text("the plant's notes\n")
    proc = softplc("run", cfg, "--virtual-time", "--cycles", "3")
    assert proc.returncode == 2, proc.stderr
    assert (
        f"softplc: {tmp_path / 'counter.retain'}: not a softplc retain file (no 'softplc-retain' header on line 1)"
        ": softplc would write over it; move it away or name another file in [retain] file\n"
    ) in proc.stderr
    assert (tmp_path / "counter.retain").read_text() == "the plant's notes\n"
    assert not (tmp_path / "counter.retain.corrupt").exists()


# In its second cycle Main enters a loop of 2^31 passes (minutes of work) and
# has no watchdog: only the signal can end it.
LONG_LOOP = """
PROGRAM Main
VAR
    lamp AT %QX0.0 : BOOL;
    stage : INT;
    i, n : DINT;
END_VAR
lamp := TRUE;
stage := stage + 1;
IF stage = 2 THEN
    FOR i := 0 TO 2147483647 DO n := n + 1; END_FOR
END_IF
END_PROGRAM
"""


@pytest.mark.realtime  # the real clock runs the PLC and the signal comes at a real moment
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGINT], ids=lambda s: s.name)
def test_a_signal_stops_a_task_inside_a_long_loop(tmp_path, sig):
    # Before: the signal waited for the loop to end, some 200 s.
    cfg = write_config(
        tmp_path,
        '[plc]\nprograms = ["p.st"]\n[[task]]\nname = "Main"\ninterval = "10ms"\nwatchdog = false\n'
        'programs = ["Main"]\n[outputs]\nsafe = { "%QX0.0" = false }\n',
        {"p.st": LONG_LOOP},
    )
    proc = spawn("run", cfg, "--watch", "Main.stage,%QX0.0")
    # the status line (every 5 s) shows the snapshot of the last scan that ended, the
    # first: the second is in its loop
    wait_for_line(proc, "Main.stage=1")
    proc.send_signal(sig)
    try:
        _stdout, stderr = proc.communicate(timeout=30)  # generous: the stop takes milliseconds
    except subprocess.TimeoutExpired:
        proc.kill()
        raise AssertionError(f"{sig.name} did not stop a task inside a loop within 30 s") from None
    assert proc.returncode == 0, stderr
    assert f"task Main: {sig.name}: its cycle was ended in the loop at {tmp_path / 'p.st'}:11:5" in stderr
    assert f"stopped by {sig.name} after 2 scans: outputs safe" in stderr
    assert "faults=0 outputs SAFE" in stderr  # the last status line


@pytest.mark.realtime  # the real clock runs the PLC
def test_sigusr1_restarts_a_faulted_task(tmp_path):
    cfg = write_config(tmp_path, '[plc]\nprograms = ["p.st"]\n', {"p.st": FAULTS_AT_SCAN_3})
    proc = spawn("run", cfg)
    wait_for_line(proc, "stopped by a runtime fault")
    proc.send_signal(signal.SIGUSR1)
    wait_for_line(proc, "restarted task(s) MainTask")
    proc.send_signal(signal.SIGINT)
    _stdout, stderr = proc.communicate(timeout=60)
    assert proc.returncode == 3  # a fault happened during the run


@pytest.mark.realtime  # the real clock runs the PLC
def test_retain_survives_sigkill_repeatedly(tmp_path):
    """kill -9 at arbitrary moments: the retain file is always whole and
    valid, and each warm start continues from what it holds."""
    cfg = _retain_config(tmp_path)
    retain = tmp_path / "counter.retain"
    rng = random.Random(7)
    previous = 0
    for _round in range(5):
        proc = spawn("run", cfg, "--virtual-time")
        wait_for_line(proc, "running;")
        # Let it write a few times, then kill wherever it is (maybe mid-write).
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            data = read_file(retain) if retain.exists() else None
            if data is not None and data.vars["Counter.count"]["value"] > previous + 20:
                break
            time.sleep(0.01)
        time.sleep(rng.uniform(0, 0.05))
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=30)
        data = read_file(retain)  # raises if the file is torn or the checksum is wrong
        count = data.vars["Counter.count"]["value"]
        assert count > previous
        previous = count
    # A warm start continues from the file; a cold start does not.
    warm = softplc("run", cfg, "--virtual-time", "--cycles", "1", "--final-json", "-")
    assert json.loads(warm.stdout)["Counter"]["count"] == previous + 1, warm.stderr
    cold = softplc("run", cfg, "--virtual-time", "--cycles", "1", "--cold", "--final-json", "-")
    assert json.loads(cold.stdout)["Counter"]["count"] == 1
