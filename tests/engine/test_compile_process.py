"""The online change's compile in a process of its own (issue 31: the
compile in the PLC's process held the interpreter lock, 10 ms tasks
overran): the program comes back compiled, a compile error comes back as
the same diagnostics, the child ends with the PLC. Counted, never timed
(the times are benchmarks/bench_online_change.py's)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

from softplc.runtime.engine.online_change import OnlineChange
from softplc.runtime.program import check_files
from softplc.testing import PLC

COUNTER = "PROGRAM Main\nVAR n : DINT; {extra} END_VAR\nn := n + 1;\nEND_PROGRAM\n"

# every builtin compile() of a generated module in this process (CPython's audit event "compile")
_COMPILED: list = []
_counting: list = []


def _audit(event: str, args: tuple) -> None:
    if event == "compile" and _counting and str(args[1]).startswith("<softplc-"):
        _COMPILED.append(args[1])


sys.addaudithook(_audit)


def plant(tmp_path: Path, source: str) -> PLC:
    st = tmp_path / "plant.st"
    st.write_text(source, encoding="utf-8")
    return PLC.from_st([st], cycle="10ms")


def test_the_change_is_compiled_in_another_process_not_in_the_plcs(tmp_path):
    with plant(tmp_path, COUNTER.format(extra="")) as plc:
        plc.step(3)
        (tmp_path / "plant.st").write_text(COUNTER.format(extra="added : INT := 7;"), encoding="utf-8")
        change = OnlineChange(plc.engine, plc.config)
        _counting.append(True)
        try:
            request = change.submit("test")
        finally:
            _counting.clear()
        try:
            plc.step()
            report = request.wait(0)
            assert report.applied, report.errors
            assert plc["Main.n"] == 4 and plc["Main.added"] == 7
            # compiled by the child: no compile() of a generated module here
            assert _COMPILED == []
            assert change.worker.pid is not None and change.worker.pid != os.getpid()
            # the generated module is named in this process's numbering: its faults map to its lines
            assert plc.engine.program.filename in plc.engine.program.linemaps
        finally:
            change.stop()


def test_a_compile_error_comes_back_as_the_same_diagnostics(tmp_path):
    with plant(tmp_path, COUNTER.format(extra="")) as plc:
        plc.step(2)
        broken = tmp_path / "plant.st"
        broken.write_text(COUNTER.format(extra="").replace("n := n + 1;", "n := n + ;\nm := 1;"), encoding="utf-8")
        change = OnlineChange(plc.engine, plc.config)
        try:
            report = change.submit("test").wait(0)
        finally:
            change.stop()
        diagnostics, sources = check_files([broken], plc.config.profile)  # what this process would say
        errors = [d for d in diagnostics if d.is_error]
        assert not report.applied and errors
        assert report.diagnostics == errors
        assert report.errors[1:] == [d.format(sources) for d in errors]
        plc.step()
        assert plc["Main.n"] == 3  # the running program went on


def test_the_compile_process_ends_when_the_change_stops(tmp_path):
    with plant(tmp_path, COUNTER.format(extra="")) as plc:
        change = OnlineChange(plc.engine, plc.config)
        change.worker.start()
        proc = change.worker._proc
        assert proc is not None and proc.poll() is None
        change.stop()
        assert proc.returncode is not None  # waited for: ended, not left behind


PARENT = textwrap.dedent(
    """
    import sys
    from softplc.runtime.engine.compile_process import CompileProcess
    worker = CompileProcess()
    worker.start()
    print(worker.pid, flush=True)
    sys.stdin.read()  # until the test kills this process
    """
)


def test_the_compile_process_does_not_outlive_a_plc_killed_with_sigkill():
    parent = subprocess.Popen([sys.executable, "-c", PARENT], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        child = int(parent.stdout.readline())
        os.kill(child, 0)  # it runs
        parent.send_signal(signal.SIGKILL)
        parent.wait()
        deadline = time.monotonic() + 60  # a bound on the wait, not a measurement
        while _alive(child) and time.monotonic() < deadline:
            time.sleep(0.05)
        assert not _alive(child)  # its stdin ended with the parent: it exited
    finally:
        if parent.poll() is None:
            parent.kill()


def _alive(pid: int) -> bool:
    """Whether pid is a running process (a zombie, reparented and not yet reaped, is not)."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False
