"""An online change's compile in a process of its own (issue 31: compiling
in the PLC's process held the interpreter lock for tens of milliseconds,
and 10 ms tasks overran).

    worker = CompileProcess()                    # nothing started yet
    worker.start(); worker.warm(config)          # softplc run: started with the watcher, caches filled
    program = worker.compile(config, number)     # CompileError as compile_files raises it
    worker.close()

The child is ``python -m softplc.runtime.engine.compile_process`` with the
PLC's interpreter, environment and working directory: it imports the same
softplc and the same installed plugins, reads the configuration's files,
profile and libraries as compile_files does in the PLC's process, and keeps
its caches (the libraries parsed once) from change to change. A subprocess
rather than multiprocessing: nothing of the PLC's __main__ is imported
again, and the pipe is the child's life line: it reads its requests on
stdin and exits when stdin ends, so it never outlives the PLC (kill -9
included: the kernel closes the pipe). Started once and kept: the start-up
(imports, some 0.5 s) and the first compile's parsing of the libraries are
paid once, at softplc run's start, not at each change.

A request is the files, the profile and the libraries (pickled); the answer
is the Program as program/transfer.py writes it (its generated module's
code object marshal-ed: no compile() in the PLC's process), or the
diagnostics and the source texts of a CompileError. The PLC's process then
only reads it back (transfer.loads), step by step in the scan's idle
(lock_share.pause every 64 objects made) and with the interpreter's
switch interval lowered, so that the scan thread takes the lock at its
release time.
"""

from __future__ import annotations

import contextlib
import itertools
import os
import pickle
import struct
import subprocess
import sys
import threading

from ..program import compile as compile_module
from ..program import compile_files, transfer
from ..st.diagnostics import CompileError
from .lock_share import background, pause

_HEADER = struct.Struct("!Q")
NICE = 10  # the child's niceness: a compile never takes the CPU from the scan


class CompileProcessError(Exception):
    """The compile process could not answer (it ended, or could not start)."""


def _read(stream) -> object | None:
    head = stream.read(_HEADER.size)
    if len(head) < _HEADER.size:
        return None
    (size,) = _HEADER.unpack(head)
    data = stream.read(size)
    if len(data) < size:
        return None
    return pickle.loads(data)


def _write(stream, message: object) -> None:
    data = pickle.dumps(message, protocol=5)
    stream.write(_HEADER.pack(len(data)) + data)
    stream.flush()


def _request(config, number: int, warm: bool = False) -> dict:
    return {
        "programs": [str(p) for p in config.programs],
        "profile": config.profile,
        "libraries": tuple(config.libraries),
        "number": number,
        "warm": warm,
    }


class CompileProcess:
    """The child that compiles, started once and kept (see the module's docstring)."""

    def __init__(self) -> None:
        self._proc: subprocess.Popen | None = None
        self._lock = threading.Lock()  # one request at a time on the pipe
        self.pid: int | None = None  # the child's, once started

    def start(self) -> None:
        with self._lock:
            self._ensure()

    def _ensure(self) -> subprocess.Popen:
        if self._proc is not None and self._proc.poll() is None:
            return self._proc
        self._stop()
        try:
            self._proc = subprocess.Popen(
                [sys.executable, "-m", __name__],
                stdin=subprocess.PIPE,
                stdout=subprocess.PIPE,
                close_fds=True,
            )
        except OSError as exc:
            raise CompileProcessError(f"the compile process cannot start: {exc}") from None
        self.pid = self._proc.pid
        return self._proc

    def _ask(self, request: dict) -> tuple:
        with self._lock:
            proc = self._ensure()
            try:
                assert proc.stdin is not None and proc.stdout is not None
                _write(proc.stdin, request)
                answer = _read(proc.stdout)
            except (OSError, ValueError, AttributeError, pickle.UnpicklingError, EOFError):
                answer = None
            if answer is None:  # it died: the next request starts another
                self._stop()
                raise CompileProcessError("the compile process ended without an answer")
            return answer  # type: ignore[return-value]

    def warm(self, config) -> None:
        """Compile the configuration once, answering nothing: the libraries parsed, the caches filled."""
        self._ask(_request(config, 0, warm=True))

    def compile(self, config):
        """The configuration's Program compiled in the child (CompileError
        with the child's diagnostics; CompileProcessError when it failed).
        Its generated module is named by this process's numbering."""
        answer = self._ask(_request(config, next(compile_module._gen_counter)))
        kind = answer[0]
        if kind == "errors":
            raise CompileError(answer[1], answer[2])
        if kind != "program":
            raise CompileProcessError(f"the compile process failed: {answer[1]}")
        with background():  # the scan waits for the interpreter lock 0.5 ms, not 5
            return transfer.loads(answer[1], pause)  # step by step in the scan's idle

    def _stop(self) -> None:
        proc, self._proc = self._proc, None
        if proc is None:
            return
        with contextlib.suppress(OSError):
            if proc.stdin is not None:
                proc.stdin.close()  # its stdin ends: it exits
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
        if proc.stdout is not None:
            proc.stdout.close()

    def close(self) -> None:
        """The child ended: its stdin closed (it exits after the compile it
        may be in), killed if it has not within 2 s."""
        proc = self._proc
        if proc is not None:
            with contextlib.suppress(OSError, ValueError):
                if proc.stdin is not None:
                    proc.stdin.close()
            try:
                proc.wait(timeout=2)
            except subprocess.TimeoutExpired:
                proc.kill()
        with self._lock:
            self._stop()


# ================================================================ the child


def _compile(request: dict) -> tuple:
    compile_module._gen_counter = itertools.count(request["number"])  # the module's file name: the PLC's numbering
    try:
        program = compile_files(request["programs"], profile=request["profile"], libraries=request["libraries"])
    except CompileError as exc:
        return ("errors", exc.diagnostics, exc.sources)
    if request["warm"]:
        return ("warm",)
    return ("program", transfer.dumps(program))


def main() -> None:
    """The child's loop: a request on stdin, its answer on stdout, until stdin ends."""
    requests = sys.stdin.buffer
    answers = os.fdopen(os.dup(1), "wb")
    os.dup2(2, 1)  # anything printed goes to stderr, not into the answers
    sys.stdin = None
    with contextlib.suppress(OSError):  # the kernel gives a core to the scan first (2 cores: one each)
        os.nice(NICE)
    while True:
        request = _read(requests)
        if request is None:
            return  # the PLC closed the pipe, stopped or died
        try:
            answer = _compile(request)  # type: ignore[arg-type]
        except Exception as exc:  # a bug of the compiler: the PLC reports it, the child goes on
            answer = ("failed", f"{type(exc).__name__}: {exc}"[:300])
        try:
            _write(answers, answer)
        except OSError:
            return


if __name__ == "__main__":
    main()
