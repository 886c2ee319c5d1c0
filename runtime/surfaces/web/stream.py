"""The live values of the web page: server-sent events fed by one thread.

One thread (the Broadcaster's) waits for snapshots of the engine, at most
one per period (the [web] period, 250 ms by default: 4 updates a second),
while at least one page is open, and hands each to the event loop; every
page's event stream (``events``) waits there for the next one and sends
what that page watches. The snapshots are the hub's own when it takes them
at least as often (it does under surfaces/host.py, at the fastest server's
period), else asked for (SnapshotHub.wait_fresh). What every page gets
alike (tasks, drivers, faults, forces) is encoded once per snapshot. So the
scan only ever pays the hub's capture, whatever the number of pages, the
event loop never blocks on the engine, and a slow page only slows its own
stream.

Each page has a client id; ``Broadcaster.watch(client, paths)`` sets its
watched paths (through ``hub.watch``). What the server keeps per page is
bounded: at most MAX_CLIENTS event streams (a slot is taken when the
request comes, so a thousand at once cannot all pass the check), and a
page that watched without opening its stream is forgotten after
PENDING_S, or sooner when more than MAX_PENDING such pages wait (the
oldest first): a client that posts watches under new ids and never reads
leaves nothing behind. Its event stream sends:

    event: state
    data: {"sequence", "cycle", "time_ns", "generation", "outputs_safe",
           "tasks": [...], "drivers": [...], "faults": [...], "forced": {path: value},
           "values": {path: value as JSON}, "numbers": {path: float}, "log": [records]}
"""

from __future__ import annotations

import asyncio
import json
import logging
import math
import threading
import time
from collections.abc import AsyncIterator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from ...engine.snapshot import Snapshot
from . import plc
from .logbuffer import LogBuffer

log = logging.getLogger("softplc.web")

#: a comment line this often keeps proxies and the browser from closing a quiet stream
KEEPALIVE_S = 10.0
#: the faults a page gets (the latest); the count says how many there were
FAULTS_SHOWN = 20
#: event streams at once: more are refused (503) rather than load the PLC
MAX_CLIENTS = 20
#: pages that watched but have no stream open: at most this many, each kept this long
MAX_PENDING = 20
PENDING_S = 30.0


class Broadcaster:
    def __init__(self, surfaces, period_s: float, logs: LogBuffer) -> None:
        self.surfaces = surfaces  # host.Surfaces, or child.RemoteSurfaces in the servers' process
        self.hub = surfaces.hub
        self.period_s = period_s
        self.logs = logs
        self.snapshot: Snapshot | None = None
        self.closing = False
        self.clients: dict[str, tuple] = {}  # client id -> its watched paths (canonical)
        self.streams = 0  # open event streams (changed in the event loop only)
        self._stream_of: dict[str, object] = {}  # client id -> its newest stream (a reconnection replaces it)
        self._loop: asyncio.AbstractEventLoop | None = None
        self._changed: asyncio.Event | None = None
        self._wanted = threading.Event()  # set while a stream is open
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._since: dict[str, int] = {}  # client id -> the last snapshot taken before its watch
        self._pending: dict[str, float] = {}  # client id without a stream -> when it watched (oldest first)
        self._common: tuple = (0, "")  # (sequence, the JSON every page gets of that snapshot)
        # watch and unwatch, one at a time and in order, each waiting for the PLC's answer
        self._hub_calls = ThreadPoolExecutor(max_workers=1, thread_name_prefix="softplc-web-watch")

    # ------------------------------------------------------------ lifecycle (the event loop)

    def start(self, loop: asyncio.AbstractEventLoop) -> None:
        self._loop = loop
        self._changed = asyncio.Event()
        self._thread = threading.Thread(target=self._run, name="softplc-web-snapshots", daemon=True)
        self._thread.start()

    def close(self) -> None:
        """End every event stream (from any thread): the server can then stop."""
        self.closing = True
        loop = self._loop
        if loop is not None and not loop.is_closed():
            try:
                loop.call_soon_threadsafe(self._wake_streams)
            except RuntimeError:  # the loop closed meanwhile
                pass

    def stop(self) -> None:
        self.closing = True
        self._stop.set()
        self._wanted.set()
        if self._thread is not None:
            self._thread.join(timeout=5)
        self._hub_calls.shutdown(wait=True)

    # ------------------------------------------------------------ the snapshot thread

    def _run(self) -> None:
        while not self._stop.is_set():
            if not self._wanted.wait(0.5):
                continue
            started = time.monotonic()
            snap = self._take()
            loop = self._loop
            if snap is not None and loop is not None and not self._stop.is_set():
                try:
                    loop.call_soon_threadsafe(self._publish, snap)
                except RuntimeError:  # the loop closed: the server stops
                    return
            self._stop.wait(max(self.period_s - (time.monotonic() - started), 0.0))

    def _take(self) -> Snapshot | None:
        hub = self.hub
        try:
            if hub.period_s > self.period_s:  # the hub's own snapshots come too seldom
                return hub.wait_fresh(timeout=0.5)
            seen = self.snapshot.sequence if self.snapshot is not None else 0
            snap = hub.next_after(seen, timeout=0.5)
            if snap is None:
                raise TimeoutError
            return snap
        except TimeoutError:
            if not self.hub.scanning:  # not running (stopped, or stepped by a test)
                return self._capture()
            return None

    def _capture(self) -> Snapshot | None:
        try:
            return self.hub.capture()
        except Exception as exc:  # an engine not started yet ...: nothing to show, say why once
            log.debug("web: no snapshot: %s", exc)
            return None

    # ------------------------------------------------------------ the event loop

    def _publish(self, snap: Snapshot) -> None:
        self.snapshot = snap
        self._wake_streams()

    def _wake_streams(self) -> None:
        changed, self._changed = self._changed, asyncio.Event()
        if changed is not None:
            changed.set()

    async def next_snapshot(self, after: int) -> Snapshot | None:
        """The first snapshot newer than sequence after; None after KEEPALIVE_S or when closing."""
        while not self.closing:
            snap = self.snapshot
            if snap is not None and snap.sequence > after:
                return snap
            changed = self._changed
            assert changed is not None
            try:
                await asyncio.wait_for(changed.wait(), timeout=KEEPALIVE_S)
            except TimeoutError:
                return None
        return None

    async def watch(self, client: str, paths: list) -> tuple:
        """Watch paths for client: (the canonical paths, {path: why not} for the others)."""
        self._forget_pending(time.monotonic())
        if client not in self._stream_of:  # its stream is to come: kept a while
            self._pending.pop(client, None)
            self._pending[client] = time.monotonic()
            while len(self._pending) > MAX_PENDING:
                self._forget(next(iter(self._pending)))
        loop = asyncio.get_running_loop()
        # after the unwatches of the pages forgotten: the same thread, in order
        good, errors, since = await loop.run_in_executor(
            self._hub_calls, self.surfaces.call, plc.watch, _reader(client), paths
        )
        if client in self._pending or client in self._stream_of:  # not forgotten meanwhile
            self._since[client] = since  # the next snapshot has them
            self.clients[client] = tuple(good)
        return good, errors

    def _forget_pending(self, now: float) -> None:
        for client, since in list(self._pending.items()):
            if now - since > PENDING_S:
                self._forget(client)

    def _forget(self, client: str) -> None:
        """Nothing kept of client any more."""
        self._pending.pop(client, None)
        self.clients.pop(client, None)
        self._since.pop(client, None)
        try:
            self._hub_calls.submit(self.hub.unwatch, _reader(client))
        except RuntimeError:  # the server stops: nothing is watched any more
            pass

    # ------------------------------------------------------------ event streams (the event loop)

    def open(self, client: str) -> object | None:
        """Take a stream's slot for client when the request comes: its token,
        None when MAX_CLIENTS streams are open. close(client, token) gives it back."""
        if self.streams >= MAX_CLIENTS:
            return None
        self.streams += 1
        self._wanted.set()
        self._pending.pop(client, None)
        token = self._stream_of[client] = object()
        return token

    def close_stream(self, client: str, token: object) -> None:
        self.streams -= 1
        if self.streams <= 0:
            self._wanted.clear()
        if self._stream_of.get(client) is token:  # not when the page reconnected meanwhile
            del self._stream_of[client]
            self._forget(client)

    async def events(self, client: str) -> AsyncIterator[str]:
        """The event stream of one page (its slot taken by open()), until it goes or the server stops."""
        sent = 0
        logged = 0
        yield "retry: 2000\n\n"
        while not self.closing:
            snap = await self.next_snapshot(max(sent, self._since.get(client, 0)))
            if snap is None:
                if self.closing:
                    break
                yield ": keep-alive\n\n"
                continue
            sent = snap.sequence
            records, logged = self.logs.since(logged)
            values, numbers = watched_payload(snap, self.clients.get(client, ()))
            tail = _dumps({"values": values, "numbers": numbers, "log": records})
            yield "event: state\ndata: " + self._common_json(snap) + "," + tail[1:] + "\n\n"

    def _common_json(self, snap: Snapshot) -> str:
        """common_payload(snap) as JSON without its closing brace, made once per snapshot."""
        sequence, text = self._common
        if sequence != snap.sequence:
            text = _dumps(common_payload(snap))[:-1]
            self._common = (snap.sequence, text)
        return text


def _reader(client: str) -> str:
    return f"web:{client}"


def _dumps(data: dict) -> str:
    return json.dumps(data, separators=(",", ":"))


def common_payload(snap: Snapshot) -> dict:
    """What every page gets of a snapshot: the engine's state."""
    return {
        "sequence": snap.sequence,
        "cycle": snap.cycle,
        "time_ns": snap.time_ns,
        "generation": snap.generation,
        "outputs_safe": snap.outputs_safe,
        "tasks": [dict(vars(t)) for t in snap.tasks],
        "drivers": [_finite(dict(vars(d))) for d in snap.drivers],
        "faults": list(snap.faults[-FAULTS_SHOWN:]),
        "fault_count": len(snap.faults),
        "forced": {path: _jsonable(value) for path, value in snap.forced.items()},
    }


def watched_payload(snap: Snapshot, paths) -> tuple:
    """What one page gets of its watched paths: (values as JSON, the numbers among them for the trend)."""
    values: dict = {}
    numbers: dict = {}
    snap_values = snap.values
    for path in paths:
        if path not in snap_values:
            continue
        raw = snap_values[path]
        # a path without its type (the servers' process got a layout whose types did not pickle): as stored
        values[path] = _finite(snap.json(path) if path in snap.types else raw)
        if isinstance(raw, (bool, int, float)) and math.isfinite(raw):
            numbers[path] = float(raw)
    return values, numbers


def _jsonable(value: Any) -> Any:
    """A forced value as its forcer gave it: JSON data, or its text."""
    if value is None or isinstance(value, (bool, int, str)):
        return value
    if isinstance(value, float):
        return value if math.isfinite(value) else str(value)
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    return str(value)


def _finite(value: Any) -> Any:
    """JSON has no NaN or infinity: those go as text ("nan", "inf")."""
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, list):
        return [_finite(v) for v in value]
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    return value
