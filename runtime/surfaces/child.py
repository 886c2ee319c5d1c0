"""The servers' process (see process.py for the PLC's side and the messages).

The web page, the OPC UA and the Modbus servers run here unchanged: they
are given a ``RemoteSurfaces`` in place of the PLC's ``Surfaces``, whose
``hub`` holds the snapshots the PLC sends, whose ``access`` carries writes
to the PLC, where the one permission check and the one write API do the
rest, whose ``call`` runs a server's function in the PLC's process (the web
page's tree, restart, online change: web/plc.py) and whose ``logs`` holds
the PLC's log records for the web page (sent with the snapshots).

The process runs at a lower priority than the PLC (``NICE``): on a busy
machine the scan comes first, as CODESYS's communication comes after its
IEC tasks. It ignores SIGINT and SIGHUP (the PLC's to handle) and ends when
the PLC says stop or its end of the pipe closes.
"""

from __future__ import annotations

import importlib
import itertools
import logging
import os
import signal
import threading
from concurrent.futures import Future
from typing import Any

from ..engine.snapshot import Layout, Snapshot
from ..io.ratelog import PeerLogFilter
from .pipe import CALL_TIMEOUT_S, FIELDS, SERVERS, PlcBusy, start_failure
from .web.logbuffer import LogBuffer

#: added to the servers' niceness: they yield the CPU to the scan
NICE = 5


class PlcGone(ConnectionError):
    """The PLC's process ended or closed the pipe."""


class _Link:
    """The pipe to the PLC: calls with their replies, one sender at a time."""

    def __init__(self, conn) -> None:
        self.conn = conn
        self._lock = threading.Lock()
        self._ids = itertools.count(1)
        self._waiting: dict[int, Future] = {}  # call id -> the reply's future
        self._done: dict[int, Future] = {}  # submit id -> the write's future
        self.closed = threading.Event()

    def send(self, message: tuple) -> None:
        if self.closed.is_set():
            raise PlcGone("the PLC is gone")
        with self._lock:
            try:
                self.conn.send(message)
            except OSError as exc:
                raise PlcGone(f"the PLC is gone: {exc}") from None

    def call(self, name: str, *args, done: Future | None = None, timeout: float = CALL_TIMEOUT_S) -> Any:
        call_id = next(self._ids)
        reply: Future = Future()
        self._waiting[call_id] = reply
        if done is not None:
            self._done[call_id] = done
        try:
            self.send(("call", call_id, name, args))
            try:
                return reply.result(timeout)
            except TimeoutError:  # concurrent.futures' own, without a word
                raise PlcBusy(f"the PLC did not answer within {timeout:g} s: busy, or stopping") from None
        except BaseException:
            self._done.pop(call_id, None)
            raise
        finally:
            self._waiting.pop(call_id, None)

    def answered(self, kind: str, call_id: int, ok: bool, value: Any, sequence: int, hub: RemoteHub) -> None:
        future = (self._waiting if kind == "reply" else self._done).get(call_id)
        if kind == "done" or not ok:
            self._done.pop(call_id, None)
        if future is None:
            return
        if kind == "done":  # once the snapshot before the write is here: the next one is after it
            hub.after(sequence, lambda: _settle(future, ok, value))
        else:
            _settle(future, ok, value)

    def close(self) -> None:
        """The PLC is gone: every call waiting and every write not confirmed fails."""
        self.closed.set()
        for future in [*self._waiting.values(), *self._done.values()]:
            if not future.done():
                future.set_exception(PlcGone("the PLC is gone"))


def _settle(future: Future, ok: bool, value: Any) -> None:
    if future.done():  # the PLC went meanwhile (close())
        return
    if ok:
        future.set_result(value)
    else:
        future.set_exception(value)


class RemoteHub:
    """The snapshot hub's face to the servers, fed by the PLC."""

    def __init__(self, link: _Link, period_s: float, logs: LogBuffer) -> None:
        self._link = link
        self.period_s = period_s  # the PLC's hub's: it captures at least this often while scanning
        self.logs = logs
        self.latest: Snapshot | None = None
        self.scanning = False
        self._layout: Layout | None = None
        self._fresh = threading.Condition()
        self._parked: list = []  # (sequence, callable): run once that snapshot is here

    def after(self, sequence: int, action) -> None:
        """action() once the snapshot of sequence (or a later one) is here (the receiving thread)."""
        if self.latest is not None and self.latest.sequence >= sequence or sequence == 0:
            action()
        else:
            self._parked.append((sequence, action))

    def received(self, message: tuple) -> None:
        if message[0] == "layout":
            self._layout = message[1]
            return
        fields, scanning, records = message[1], message[2], message[3]
        if records:
            self.logs.extend(records)
        assert self._layout is not None  # the PLC sends a layout before the first snapshot
        snap = Snapshot(layout=self._layout, **dict(zip(FIELDS, fields)))
        with self._fresh:
            if self.latest is None or snap.sequence > self.latest.sequence:
                self.latest = snap
            self.scanning = scanning
            self._fresh.notify_all()
        if self._parked:
            due = [action for seq, action in self._parked if seq <= snap.sequence]
            self._parked = [(seq, action) for seq, action in self._parked if seq > snap.sequence]
            for action in due:
                action()

    def watch(self, reader: str, paths) -> list:
        return self._link.call("watch", reader, list(paths))

    def unwatch(self, reader: str) -> None:
        try:
            self._link.call("unwatch", reader)
        except PlcGone:  # stopping after the PLC: nothing is watched anymore
            pass

    def request(self) -> None:
        self._link.send(("call", None, "request", ()))

    def next_after(self, sequence: int, timeout: float) -> Snapshot | None:
        """SnapshotHub.next_after: the latest snapshot once it is newer than sequence (None after timeout)."""
        with self._fresh:
            self._fresh.wait_for(lambda: self.latest is not None and self.latest.sequence > sequence, timeout)
            latest = self.latest
            return latest if latest is not None and latest.sequence > sequence else None

    def wait_fresh(self, timeout: float = 5.0) -> Snapshot:
        """SnapshotHub.wait_fresh: a snapshot taken after this call."""
        return self.current(fresh=True)

    def capture(self) -> Snapshot:
        """A snapshot taken now, when the PLC does not scan (else the next one)."""
        return self.current(fresh=True)

    def current(self, fresh: bool = False) -> Snapshot:
        sequence = self._link.call("current", fresh)
        with self._fresh:
            if not self._fresh.wait_for(lambda: self.latest is not None and self.latest.sequence >= sequence, 5):
                raise TimeoutError("the PLC's snapshot did not arrive")
            assert self.latest is not None
            return self.latest


class RemoteAccess:
    """Access's face to the servers: each call checked and carried out in the PLC."""

    def __init__(self, link: _Link, permissions: dict) -> None:
        self._link = link
        self.permissions = {k: v for k, v in permissions.items() if v is not None}

    def check(self, op: str, path: str, surface: str) -> str:
        """The path as declared if surface may do op there (AccessDenied, PathError as Access.check)."""
        return self._link.call("check", op, path, surface)

    def submit(self, op: str, path: str, value: Any = None, *, surface: str) -> Future:
        done: Future = Future()
        self._link.call("submit", op, path, value, surface, done=done)
        return done

    def submit_many(self, op: str, items: list, *, surface: str) -> Future:
        """Access.submit_many: the pairs carried out in one scan."""
        done: Future = Future()
        self._link.call("submit_many", op, list(items), None, surface, done=done)
        return done


class RemoteSurfaces:
    """What a server module's start(surfaces, config) is given in this process."""

    def __init__(self, link: _Link, permissions: dict, period_s: float) -> None:
        self.link = link
        self.logs = LogBuffer()  # the PLC's log records, as they come with the snapshots
        self.hub = RemoteHub(link, period_s, self.logs)
        self.access = RemoteAccess(link, permissions)

    def call(self, function, *args, timeout: float = CALL_TIMEOUT_S) -> Any:
        """function(the PLC's Surfaces, *args), run in the PLC's process."""
        return self.link.call("call", function.__module__, function.__qualname__, args, timeout=timeout)


def main(conn, configs: dict, permissions: dict, level: int, period_s: float) -> None:
    """The process's entry point (process.py starts it)."""
    for signum in (signal.SIGINT, signal.SIGHUP):
        signal.signal(signum, signal.SIG_IGN)
    try:  # a PLC under SCHED_FIFO ([plc] realtime_priority) passed it on: the servers do without
        os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))
    except (OSError, AttributeError):  # not Linux
        pass
    try:
        os.nice(NICE)
    except OSError:  # not allowed here: the same priority as the PLC
        pass
    link = _Link(conn)
    _log_to(link, level)
    surfaces = RemoteSurfaces(link, permissions, period_s)
    stop = threading.Event()
    reader = threading.Thread(target=_receive, args=(link, surfaces.hub, stop), name="plc", daemon=True)
    reader.start()

    handles: dict = {}
    errors: dict = {}
    for key, config in configs.items():
        try:
            handles[key] = importlib.import_module(SERVERS[key], __package__).start(surfaces, config)
        except OSError as exc:
            errors[key] = start_failure(config.host, config.port, exc)
            break
        except Exception as exc:  # a bad certificate, a users file ...: the PLC reports it
            text, prefix = str(exc), f"[{key}] "  # the PLC puts the section in front
            errors[key] = text[len(prefix) :] if text.startswith(prefix) else f"{type(exc).__name__}: {text}"
            break
    urls = {key: (handle.url, getattr(handle, "port", None)) for key, handle in handles.items()}
    try:
        link.send(("started", urls, errors))
        if not errors:
            stop.wait()
    finally:
        for handle in reversed(list(handles.values())):
            try:
                handle.stop()
            except Exception as exc:  # one server's trouble does not keep the others running
                logging.getLogger("softplc.surfaces").error("stopping: %s", exc)
        link.close()


def _receive(link: _Link, hub: RemoteHub, stop: threading.Event) -> None:
    try:
        while True:
            message = link.conn.recv()
            kind = message[0]
            if kind in ("layout", "snapshot"):
                hub.received(message)
            elif kind in ("reply", "done"):
                _kind, call_id, ok, value, sequence = message
                link.answered(kind, call_id, ok, value, sequence, hub)
            elif kind == "stop":
                break
    except (EOFError, OSError):  # the PLC is gone
        pass
    finally:
        link.close()
        stop.set()


class _ToPlc(logging.Handler):
    """Log records to the PLC's log (its file, its rotation)."""

    def __init__(self, link: _Link) -> None:
        super().__init__()
        self.link = link

    def emit(self, record: logging.LogRecord) -> None:
        try:
            self.link.send(("log", record.name, record.levelno, self.format(record)))
        except Exception:  # the PLC is gone: nobody to tell
            pass


def _log_to(link: _Link, level: int) -> None:
    """softplc's records from level on, the libraries' (asyncua, pymodbus)
    warnings and errors: what the PLC's process shows of them. What a
    client drives is in every record here (an OPC UA client's malformed
    chunks made asyncua write 10,000 tracebacks): each is rate limited and
    sent as one line, without its traceback (io/ratelog.py PeerLogFilter)."""
    root = logging.getLogger()
    handler = _ToPlc(link)
    handler.addFilter(PeerLogFilter(burst=3))
    root.handlers[:] = [handler]
    root.setLevel(logging.WARNING)
    logging.getLogger("softplc").setLevel(level)
