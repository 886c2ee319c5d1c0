"""The servers' process, seen from the PLC's: it is started, fed with every
snapshot, answers its calls, and is stopped.

The web page, the OPC UA and the Modbus servers run in a process of their
own (child.py) so that their work never holds the PLC's interpreter lock: a scan that waits
for the lock behind a server publishing 10,000 values a second is late by
milliseconds (benchmarks/README.md, "What the surfaces cost the scan"). They
reach the engine only through the snapshot hub and Access, which is what
crosses the pipe:

    PLC -> servers   ("layout", Layout)          the paths of the snapshots that follow
                     ("snapshot", fields, scanning, records)   each capture, its values as raw
                                                 groups, and the log records since the last (web)
                     ("reply", id, ok, value, 0)      a call's result (or its exception)
                     ("done", id, ok, value, seq)     a submitted write carried out (or refused)
                                                      after the snapshot seq was taken
                     ("stop",)
    servers -> PLC   ("started", urls, errors)   once, after every server tried to listen
                     ("call", id, name, args)    the hub's and Access's methods (submit,
                                                 submit_many ...), Surfaces.call
                     ("log", logger, level, message)

    process = SurfaceProcess(surfaces, {"opcua": config, ...})
    handles = process.start()   # {"opcua": handle with url (and port)}; SurfaceError if one cannot listen
    process.stop()

The snapshot is sent as its raw groups (a tuple per object or array: a few
kilobytes for thousands of values), the layout only when it changes, so the
PLC's side pays a pickling of tens of microseconds per capture, in a thread
of its own, never in the scan.
"""

from __future__ import annotations

import contextlib
import importlib
import logging
import multiprocessing
import threading
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any

from ..engine.lock_share import background
from ..engine.snapshot import Snapshot
from .pipe import FIELDS

log = logging.getLogger("softplc.surfaces")

#: how long a server waits for the PLC to answer a call (an online change waits longer)
START_TIMEOUT_S = 120.0  # a new interpreter importing asyncua on a busy machine
STOP_TIMEOUT_S = 10.0
RESTART_S = 1.0  # after the process ended on its own, the first new one this much later
RESTART_MAX_S = 30.0
#: the calls that wait in the call thread (for a fresh snapshot, a compile
#: and the scan that swaps it in), by name or, for "call", by the function's
#: name; every other call computes there (paths resolved, a tree level
#: built, a watch list laid out again, writes checked)
_WAITING = frozenset({"current", "online_change"})
#: what the servers' process may call on the PLC's side (besides Surfaces.call)
CALLS: dict[str, Callable[..., Any]] = {
    "watch": lambda s, reader, paths: s.hub.watch(reader, paths),
    "unwatch": lambda s, reader: s.hub.unwatch(reader),
    "check": lambda s, op, path, surface: s.access.check(op, path, surface).path,
}


class ProcessError(Exception):
    """The servers' process could not start its servers: the message says which and why."""


@dataclass
class RemoteHandle:
    """A server in the servers' process, as Surfaces.handles holds it."""

    key: str
    url: str
    port: int | None

    def stop(self) -> None:
        """Stopped with the process (SurfaceProcess.stop)."""


class SurfaceProcess:
    def __init__(self, surfaces, configs: dict) -> None:
        self.surfaces = surfaces
        self.configs = configs
        self.handles: dict[str, RemoteHandle] = {}
        self.restarts = 0  # how often the process ended on its own and was started again
        self._ctx = multiprocessing.get_context("spawn")  # a fresh interpreter: no lock or thread of ours copied
        self._conn: Any = None
        self._process: Any = None
        self._receiver: threading.Thread | None = None  # the current process's receiving thread
        self._send_lock = threading.Lock()
        self._sent = 0  # the sequence of the last snapshot sent
        self._layout: Any = None  # the last layout sent
        self._calls = ThreadPoolExecutor(max_workers=4, thread_name_prefix="softplc-servers-call")
        self._stopping = threading.Event()
        self._forwarder = threading.Thread(target=self._forward, name="softplc-servers-forward", daemon=True)
        self._types_sent = True  # False once the layout's types would not pickle (logged once)
        #: the PLC's log for the web page, sent with the snapshots (the records after _logged)
        self._logs: Any = None
        self._logged = 0

    # ------------------------------------------------------------ the caller's thread

    def start(self) -> dict:
        """Start the process and its servers: their handles; ProcessError if one cannot listen."""
        if "web" in self.configs:
            from .web.logbuffer import LogBuffer

            self._logs = LogBuffer()
            self._logs.attach()
        for key, (url, port) in self._spawn().items():
            self.handles[key] = RemoteHandle(key, url, port)
        self._forwarder.start()
        return dict(self.handles)

    def stop(self) -> None:
        self._stopping.set()
        self._end()
        if self._forwarder.is_alive():
            self._forwarder.join(STOP_TIMEOUT_S)
        self._calls.shutdown(wait=False, cancel_futures=True)
        if self._logs is not None:
            self._logs.detach()

    def _spawn(self) -> dict:
        """A new process with every server started: {key: (url, port)}."""
        from . import child  # the servers' side, imported only to name its entry point

        conn, child_conn = self._ctx.Pipe()
        level = logging.getLogger("softplc").getEffectiveLevel()
        permissions = {k: self.surfaces.access.permissions.get(k) for k in self.configs}
        process = self._ctx.Process(
            target=child.main,
            args=(child_conn, self.configs, permissions, level, self.surfaces.hub.period_s),
            name="softplc-servers",
            daemon=True,  # never outlives the PLC
        )
        with self._send_lock:
            self._conn, self._process = conn, process
            self._sent, self._layout, self._logged = 0, None, 0
        process.start()
        child_conn.close()  # the child's end lives in the child: EOF here when it dies
        started: dict = {}
        ready = threading.Event()
        self._receiver = threading.Thread(
            target=self._receive, args=(conn, process, started, ready), name="softplc-servers-receive", daemon=True
        )
        self._receiver.start()
        if not ready.wait(START_TIMEOUT_S) or "urls" not in started:
            self._end()
            raise ProcessError(f"the servers' process did not start within {START_TIMEOUT_S:g} s")
        if started["errors"]:
            self._end()
            key, message = next(iter(started["errors"].items()))
            raise ProcessError(f"[{key}] {message}")
        return started["urls"]

    def _end(self) -> None:
        process, conn, receiver = self._process, self._conn, self._receiver
        self._process = None  # an end asked for: not a crash to recover from
        if process is None:
            return
        if process.is_alive():
            # a process that reads nothing any more leaves a sender blocked on the pipe, holding
            # the lock: it is killed, which ends that send
            asked = self._send_lock.acquire(timeout=STOP_TIMEOUT_S / 10)
            if asked:
                try:
                    conn.send(("stop",))
                except OSError:  # the process is already gone
                    pass
                finally:
                    self._send_lock.release()
            process.join(STOP_TIMEOUT_S if asked else 0)
            if process.is_alive():
                log.error("the servers' process did not stop when asked: killed")
                process.kill()
                process.join(STOP_TIMEOUT_S)
        conn.close()
        if receiver is not None and receiver is not threading.current_thread():
            receiver.join(STOP_TIMEOUT_S)  # it has read the end of the pipe

    def _restart(self) -> None:
        """After the process ended on its own: a new one, tried again and again
        (RESTART_S, doubling up to RESTART_MAX_S) until the PLC stops."""
        wait = RESTART_S
        while not self._stopping.wait(wait):
            try:
                urls = self._spawn()
            except ProcessError as exc:
                log.error("the servers' process: %s (trying again in %g s)", exc, wait)
                wait = min(2 * wait, RESTART_MAX_S)
                continue
            if self._stopping.is_set():  # stopped while it started
                self._end()
                return
            for key, (url, port) in urls.items():
                if key in self.handles:
                    self.handles[key].url, self.handles[key].port = url, port
            self.restarts += 1
            log.warning("the servers' process is back: %s", ", ".join(urls[k][0] for k in urls))
            return

    # ------------------------------------------------------------ to the servers

    def _send(self, message: tuple) -> None:
        with self._send_lock:
            if self._process is None:
                raise OSError("the servers' process is not running")
            self._conn.send(message)  # OSError: the process ended

    def _forward(self) -> None:
        """Every new snapshot to the servers (the latest, when they were slower than the captures)."""
        hub = self.surfaces.hub
        while not self._stopping.is_set():
            snap = hub.next_after(self._sent, timeout=0.5)
            if snap is not None:
                try:
                    self.forward(snap)
                except OSError:  # the servers' process ended: _receive restarts it
                    self._stopping.wait(0.1)

    def forward(self, snap: Snapshot) -> None:
        with self._send_lock:
            if self._process is None:
                raise OSError("the servers' process is not running")
            if snap.sequence <= self._sent:
                return
            if snap.layout is not self._layout:  # after a watch or a change: hundreds of paths and types pickled
                with background():
                    self._send_layout(snap.layout)
                self._layout = snap.layout
            records: list = []
            if self._logs is not None:
                records, self._logged = self._logs.since(self._logged)
            fields = tuple(getattr(snap, f) for f in FIELDS)
            self._conn.send(("snapshot", fields, self.surfaces.hub.scanning, records))
            self._sent = snap.sequence

    def _send_layout(self, layout) -> None:
        """The layout to the servers (under the send lock); without its types
        when one of them does not pickle (Connection.send pickles the whole
        message before it writes a byte, so a refusal sends nothing)."""
        try:
            self._conn.send(("layout", layout))
        except OSError:
            raise
        except Exception as exc:  # an ST type of a watched path that does not pickle
            if self._types_sent:
                log.warning("the servers' process gets the snapshots without their ST types: %s", exc)
                self._types_sent = False
            self._conn.send(("layout", type(layout)(layout.paths, {})))

    # ------------------------------------------------------------ from the servers

    def _receive(self, conn, process, started: dict, ready: threading.Event) -> None:
        """One process's messages, until it ends (restarted unless the PLC stops)."""
        while True:
            try:
                message = conn.recv()
            except (EOFError, OSError):
                ready.set()
                if not self._stopping.is_set() and self._process is process and "urls" in started:
                    log.error(
                        "the servers' process ended (exit code %s): %s are gone until it is restarted",
                        process.exitcode,
                        ", ".join(self.configs),
                    )
                    threading.Thread(target=self._restart, name="softplc-servers-restart", daemon=True).start()
                return
            kind = message[0]
            if kind == "call":
                self._calls.submit(self._call, *message[1:])
            elif kind == "log":
                _name, level, text = message[1:]
                logging.getLogger(_name).log(level, "%s", text)
            elif kind == "started":
                started.update(urls=message[1], errors=message[2])
                ready.set()

    def _call(self, call_id: int | None, name: str, args: tuple) -> None:
        # Watching a thousand paths, a tree, an unwatch, writes: the scan waits
        # for the lock 0.5 ms, not 5 (a live soak caught a call thread outside
        # background() holding it 10 ms). Not while a call waits (an online
        # change, a fresh snapshot): the interval would stay lowered for every
        # other thread meanwhile (what those compute runs in background() itself).
        waiting = (args[1] if name == "call" else name) in _WAITING
        try:
            with contextlib.nullcontext() if waiting else background():
                result = self._carry_out(call_id, name, args)
        except Exception as exc:  # the caller raises it, in the servers' process
            self._reply("reply", call_id, False, exc)
        else:
            self._reply("reply", call_id, True, result)

    def _carry_out(self, call_id: int | None, name: str, args: tuple) -> Any:
        surfaces = self.surfaces
        if name == "request":
            return surfaces.hub.request()
        if name == "current":
            snap = surfaces.hub.current(*args)
            self.forward(snap)  # there before the reply naming it
            return snap.sequence
        if name in ("submit", "submit_many"):
            op, what, value, surface = args
            if name == "submit":
                future = surfaces.access.submit(op, what, value, surface=surface)
            else:  # what: the (path, value) pairs
                future = surfaces.access.submit_many(op, what, surface=surface)
            # answered from a call thread: the scan, which completes the future, never waits on the pipe
            future.add_done_callback(lambda f: self._calls.submit(self._done, call_id, f))
            return None
        if name == "call":
            module, function, rest = args
            if not module.startswith(__package__ + "."):
                raise PermissionError(f"{module}.{function}: not a function of the servers")
            return getattr(importlib.import_module(module), function)(surfaces, *rest)
        return CALLS[name](surfaces, *args)

    def _done(self, call_id: int | None, future) -> None:
        """A write carried out: the servers hear it with the latest
        snapshot's sequence (taken before the write, or after it), and take
        it as done once they have that snapshot, so the next one they get
        is from after the write."""
        exc = future.exception()
        latest = self.surfaces.hub.latest
        sequence = latest.sequence if latest is not None else 0
        self._reply("done", call_id, exc is None, future.result() if exc is None else exc, sequence)

    def _reply(self, kind: str, call_id: int | None, ok: bool, value: Any, sequence: int = 0) -> None:
        if call_id is None:
            return
        try:
            try:
                self._send((kind, call_id, ok, value, sequence))
            except OSError:
                raise
            except Exception:  # an exception (or a result) that does not pickle: its text does
                # (Connection.send pickles the whole message before it writes a byte)
                self._send((kind, call_id, False, RuntimeError(str(value)), sequence))
        except OSError:  # the servers' process ended meanwhile
            pass
