"""What the surfaces see of a running engine: one snapshot API.

The status line, ``--watch``, the web page, the OPC UA server and the Modbus
server all read the engine through a ``SnapshotHub``: at the end of a scan
(an ``after_tick`` callback, in the scan thread) the hub copies what its
readers asked for into an immutable ``Snapshot`` and hands it over; the
readers, in their own threads, only ever look at snapshots. The scan never
waits for a reader and a reader never sees a half-written scan.

    hub = SnapshotHub(engine, period_s=0.1)  # attaches itself to the engine
    hub.watch("web", ["Motor.state", "%QW0"])   # the paths a reader needs
    snap = hub.latest                           # None until the first capture
    snap = hub.wait_fresh(timeout=2)            # one taken after this call
    snap.values["Motor.state"]                  # the value as stored (see Snapshot)

A snapshot is taken at most every ``period_s`` seconds of wall time (the
readers are people and HMIs, on the wall clock, whatever clock the engine
runs on), and at the end of the next scan after ``request()``. Between two
captures the scan pays one clock read.

On the real clock the copy is made in the time between two scans, by a
thread of the hub's, not in the scan: copying a few thousand values costs
about a millisecond on a busy machine, which would stretch the scan that
pays for it. The next scan starts only once the copy is done
(``Engine.before_tick``), so a snapshot is still the state at the end of
one scan; it is late only when the copy outlasts the gap before the next
scan. In virtual time (a test stepping the engine) the copy is made in the
scan, so a test sees it as soon as the scan ends.
"""

from __future__ import annotations

import functools
import logging
import operator
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from ..st import types as T
from ..st.valuejson import encode_value
from .lock_share import background, pause
from .places import PathError, Place, Resolver

log = logging.getLogger("softplc.engine")


@dataclass(frozen=True)
class TaskState:
    name: str
    interval_ns: int | None
    priority: int
    cycles: int
    last_ns: int
    mean_ns: float
    max_ns: int
    jitter_max_ns: int
    overruns: int
    fault: str | None  # the runtime fault that stopped the task, with its ST location
    programs: tuple  # the program instances it runs, by name


@dataclass(frozen=True)
class DriverState:
    name: str
    ok: bool
    message: str
    details: dict = field(default_factory=dict)  # the driver's own: nodes, EMCY history ...


@dataclass(frozen=True)
class Snapshot:
    """The engine at the end of one scan.

    values: by path as watched; a scalar as the engine stores it (BOOL as
    bool, integers and bit strings as int, REAL as float, TIME and the
    dates as integers in their unit, an enumeration as its integer value,
    STRING as str); an array or a struct as ``valuejson.encode_value``
    gives it (a copy). ``types`` gives each path's ST type, ``json(path)``
    the value as `softplc exec` prints it. image: the %I, %Q and %M bytes."""

    sequence: int  # 1, 2, ... per capture
    cycle: int
    time_ns: int  # engine time
    wall: float  # time.time() at the capture
    tasks: tuple
    drivers: tuple
    faults: tuple  # str per runtime fault since start
    outputs_safe: bool
    forced: dict  # path -> value as forced
    layout: Layout  # the paths raw holds, and their types
    raw: tuple  # the values as read, one tuple per group of the layout (None: not readable)
    image: dict
    generation: int  # engine.generation: a new program or restarted instances

    @cached_property
    def values(self) -> dict:
        """path -> value, built when first asked (by a reader, not the scan)."""
        return self.layout.values(self.raw)

    @property
    def types(self) -> dict:
        return self.layout.types

    def json(self, path: str) -> Any:
        """The value at path as JSON data (enumerations by name, TIME as T#...)."""
        value = self.values[path]
        return value if isinstance(value, (dict, list)) else encode_value(self.types[path], value)


class Layout:
    """What a capture reads: groups of paths, each read with one call
    (the plain variables of one object with one attrgetter, the elements of
    one array of plain values with one itemgetter, anything else alone), and
    the paths' ST types. A layout sent to another process (pickled) keeps
    its paths and types only: it can build values from raw, not read."""

    def __init__(self, paths: tuple, types: dict, readers: tuple = ()) -> None:
        self.paths = paths  # per group, its paths
        self.types = types  # path -> ST type
        self.readers = readers  # per group, a callable giving its values as a tuple

    def values(self, raw: tuple) -> dict:
        out: dict = {}
        for paths, group in zip(self.paths, raw):
            if group is not None:
                out.update(zip(paths, group))
        return out

    def read(self) -> tuple:
        """Each group's values (None for a group that cannot be read now)."""
        raw: list = []
        append = raw.append
        for reader in self.readers:
            try:
                append(reader())
            except Exception:  # not there (yet), an element gone with a resized array: left out
                append(None)
        return tuple(raw)

    def __getstate__(self) -> dict:
        return {"paths": self.paths, "types": self.types, "readers": ()}


class SnapshotHub:
    """Snapshots of one engine for every reader (see the module docstring)."""

    def __init__(self, engine, period_s: float = 0.1, resolver: Resolver | None = None, attach: bool = True) -> None:
        self.engine = engine
        self.period_s = period_s
        engine.load()
        self._resolver = resolver if resolver is not None else Resolver(engine)
        #: the engine.generation the watched places were resolved in (_rewatch sets it once they are)
        self._placed_generation = self._resolver.generation
        self._watched: dict[str, tuple] = {}  # reader -> its paths
        self._places: dict[str, Place] = {}  # path -> Place, the union of the readers' paths
        self._layout: Layout = _layout_of({})  # how capture() reads them
        self._lock = threading.Lock()  # readers change _watched; the scan thread reads _layout
        self._fresh = threading.Condition()
        self._requested = False
        self._next = 0.0
        self._sequence = 0
        self._capturing = threading.Lock()  # one capture at a time
        self._copying = threading.Lock()  # held while the copier copies: the next scan waits for it
        self._copy_due = threading.Event()
        self._copier: threading.Thread | None = None
        self._copier_lock = threading.Lock()  # the copier ends, or is started, never both
        self._rewatch_due = False  # the copier resolves the paths again (scan thread: set; copier: cleared)
        self.latest: Snapshot | None = None
        if attach:  # else: capture() only, when asked (a status line of a stopped engine)
            engine.after_tick.append(self._after_tick)
            engine.before_tick.append(self._copied)

    # ------------------------------------------------------------ readers

    @property
    def resolver(self) -> Resolver:
        """Paths of the engine's current program (a new one after an online change)."""
        self._resolver = self._resolver.fresh()
        return self._resolver

    def watch(self, reader: str, paths) -> list:
        """Make paths part of every snapshot for reader (replacing what it
        watched before). Returns the paths as resolved (canonical spelling);
        PathError names the first path that names no variable. (A call
        thread's: each path waits for the scan's idle, lock_share.pause.)"""
        resolver = self.resolver
        resolved = []
        for path in paths:
            pause()
            resolved.append(resolver.place(path))
        return self.watch_places(reader, resolved)

    def watch_places(self, reader: str, resolved: list) -> list:
        """watch() of places the caller has resolved already (with this
        hub's resolver): a caller that sorts the paths that name a variable
        from those that do not does not resolve them twice."""
        with self._lock:  # the new layout is made here, not under the capture's lock: the scan never waits for it
            self._watched[reader] = tuple(p.path for p in resolved)
            places = dict(self._places)
            for place in resolved:
                places[place.path] = place
            self._set_places(self._prune(places), paced=True)
        with self._capturing:  # a capture under way with the old layout ends first: the next one has them
            pass
        return [p.path for p in resolved]

    def unwatch(self, reader: str) -> None:
        with self._lock:
            self._watched.pop(reader, None)
            self._set_places(self._prune(dict(self._places)), paced=True)

    def _set_places(self, places: dict, paced: bool) -> None:
        """(Under _lock, which the scan never takes; paced: a reader's or the copier's, see _rewatch.)"""
        self._places = places
        self._layout = _layout_of(places, paced)  # one assignment: the scan thread sees the old layout or the new

    def _prune(self, places: dict) -> dict:
        wanted = {p for paths in self._watched.values() for p in paths}
        return {k: v for k, v in places.items() if k in wanted}

    def request(self) -> None:
        """Take a snapshot at the end of the next scan, whatever the period."""
        self._requested = True

    def wait_fresh(self, timeout: float = 5.0) -> Snapshot:
        """A snapshot taken after this call (TimeoutError when no scan ends in time)."""
        with self._fresh:
            seen = self._sequence
            self._requested = True
            if not self._fresh.wait_for(lambda: self._sequence > seen, timeout):
                raise TimeoutError(f"no scan ended within {timeout} s (is the engine running?)")
            assert self.latest is not None
            return self.latest

    def next_after(self, sequence: int, timeout: float) -> Snapshot | None:
        """The latest snapshot once it is newer than sequence (None after
        timeout); asks for none: what forwards every capture waits here."""
        with self._fresh:
            self._fresh.wait_for(lambda: self._sequence > sequence, timeout)
            return self.latest if self._sequence > sequence else None

    @property
    def scanning(self) -> bool:
        """A thread scans the engine: a write waits for a scan and a snapshot after it."""
        return self.engine.scan_thread is not None

    # ------------------------------------------------------------ the scan thread

    def _after_tick(self, engine) -> None:
        if not self._requested:
            now = time.monotonic()
            if now < self._next:
                return
            self._next = now + self.period_s
        self._requested = False
        if engine.clock.virtual or engine.scan_thread != threading.get_ident():
            self.capture()  # a test's tick, or one outside run(): no time between scans to use
            return
        if self._rewatch_due or self._placed_generation != engine.generation:
            # an online change or a restart: the copier resolves the readers'
            # paths again while the scans go on (it reads no value; 860 paths
            # took 20-30 ms, which the next scan waited for, a 10 ms task late
            # by two periods); the first copy of the new program follows it.
            # No copy is asked for until it is done: the resolver is the new
            # program's from its start, and a scan waiting for that copy
            # waited for the whole resolving (100 ms ticks in a live soak)
            self._requested = True
            if not self._rewatch_due:
                self._rewatch_due = True
                self._wake_copier()
            return
        self._copying.acquire()  # free: this tick began after the last copy was done
        self._wake_copier()

    def _wake_copier(self) -> None:
        with self._copier_lock:
            self._copy_due.set()
            if self._copier is None:
                self._copier = threading.Thread(target=self._copy, name="softplc-snapshot", daemon=True)
                self._copier.start()

    def _copied(self, engine) -> None:
        """At the start of a tick: wait for the copy of the last one's end."""
        if self._copying.locked():
            with self._copying:
                pass

    def _copy(self) -> None:
        """The copier: a capture each time the scan asks for one, between
        two scans; it ends when the engine stops scanning."""
        while True:
            if not self._copy_due.wait(1.0):
                with self._copier_lock:
                    if self.engine.scan_thread is None and not self._copy_due.is_set():
                        self._copier = None
                        return
                continue
            self._copy_due.clear()
            if self._rewatch_due:  # the scan did not wait: no copy, no lock to give back
                try:
                    self._rewatch(paced=True)
                except Exception as exc:  # the paths kept; tried again after the next scan
                    log.error("snapshot: resolving the watched paths again: %s", exc)
                finally:
                    self._rewatch_due = False
                continue
            try:
                self.capture()
            except Exception as exc:  # a snapshot lost, never the next scan
                log.error("snapshot: %s", exc)
            finally:
                self._copying.release()

    def current(self, fresh: bool = False) -> Snapshot:
        """The latest snapshot while another thread scans (fresh: one taken
        after this call, with what was watched just before); one taken now
        when none does (before the first scan, after the run, in a test)."""
        scanning = self.engine.scan_thread
        if scanning is None or scanning == threading.get_ident():
            return self.capture()
        return self.latest if self.latest is not None and not fresh else self.wait_fresh()

    def capture(self) -> Snapshot:
        """Take a snapshot now (the scan thread, or a test between two scans)."""
        with self._capturing:
            return self._capture()

    def _capture(self) -> Snapshot:
        engine = self.engine
        if self._placed_generation != engine.generation:
            self._rewatch()
        layout = self._layout
        raw = layout.read()
        snap = Snapshot(
            sequence=self._sequence + 1,
            cycle=engine.cycle,
            time_ns=engine.clock.now_ns(),
            wall=time.time(),
            tasks=tuple(_task_state(t) for t in engine.tasks),
            drivers=tuple(_driver_state(d) for d in engine.drivers),
            faults=tuple(str(f) for f in engine.faults),
            outputs_safe=engine.outputs_safe,
            forced=dict(engine.forced_values.values()),
            layout=layout,
            raw=raw,
            image={area: bytes(data) for area, data in engine.image.areas.items()},
            generation=engine.generation,
        )
        with self._fresh:
            self.latest = snap
            self._sequence = snap.sequence
            self._fresh.notify_all()
        return snap

    def _rewatch(self, paced: bool = False) -> None:
        """After an online change or a restart the places point at the old
        objects: resolve every reader's paths again (a path that is gone is
        dropped from the snapshots). paced: each path waits for the scan's
        idle (lock_share.pause): the copier's, which the scan never waits
        for; not a capture's, which it may wait for."""
        resolver = self.resolver
        generation = resolver.generation  # a failure below leaves _placed_generation: tried again
        places: dict = {}
        with self._lock:  # a reader may watch meanwhile (a call thread)
            watched = list(self._watched.values())
        with background(paced=paced):  # 860 paths: 20-30 ms, the scans going on
            for paths in watched:
                for path in paths:
                    if paced:
                        pause()
                    try:
                        places[path] = resolver.place(path)
                    except PathError:
                        continue
        with self._lock:
            self._set_places(places, paced)
            self._placed_generation = generation


def _layout_of(places: dict, paced: bool = False) -> Layout:
    """How to read places fast. A group is the plain variables (an
    elementary, string, enumeration or subrange value) of one object, read
    with one attrgetter call, or the plain elements of one array, read with
    one itemgetter call; anything else (a located variable, an aggregate, a
    reference) is a group of its own, read through its place, an aggregate
    copied as JSON data."""
    by_holder: dict = {}
    alone = []
    for path, place in places.items():
        if paced:
            pause()
        plain = isinstance(T.resolve(place.type), _PLAIN)
        if plain and place.holder is not None:
            key = (id(place.holder), place.attr is None)
            _holder, keys, paths = by_holder.setdefault(key, (place.holder, [], []))
            keys.append(place.attr if place.attr is not None else place.index)
            paths.append(path)
        else:
            alone.append(((path,), _one(place.get, None if plain else place.type)))
    groups = [(tuple(paths), _fetch(holder, keys)) for holder, keys, paths in by_holder.values()]
    groups.extend(alone)
    return Layout(
        tuple(paths for paths, _reader in groups),
        {path: place.type for path, place in places.items()},
        tuple(reader for _paths, reader in groups),
    )


def _fetch(holder, keys: list) -> Callable[[], tuple]:
    """A callable giving holder's attributes (str keys) or items (int keys) as a tuple."""
    if len(keys) == 1:
        (key,) = keys
        if isinstance(key, str):
            return lambda: (getattr(holder, key),)
        return lambda: (holder[key],)
    getter = operator.attrgetter(*keys) if isinstance(keys[0], str) else operator.itemgetter(*keys)
    return functools.partial(getter, holder)


def _one(get: Callable[[], Any], aggregate) -> Callable[[], tuple]:
    if aggregate is None:
        return lambda: (get(),)
    return lambda: (encode_value(aggregate, get()),)  # a copy


#: the types a snapshot holds as stored: immutable values (bool, int, float, str)
_PLAIN = (T.ElementaryType, T.StringType, T.EnumType, T.SubrangeType)


def _task_state(task) -> TaskState:
    s = task.stats
    return TaskState(
        name=task.name,
        interval_ns=task.interval_ns,
        priority=task.priority,
        cycles=s.cycles,
        last_ns=s.last_ns,
        mean_ns=s.mean_ns,
        max_ns=s.max_ns,
        jitter_max_ns=s.jitter_max_ns,
        overruns=s.overruns,
        fault=None if task.fault is None else str(task.fault),
        programs=tuple(name for name, _info, _obj in task.instances),
    )


def _driver_state(driver) -> DriverState:
    try:
        status = driver.status()
        details = driver.details()
    except Exception as exc:  # a driver's report is no reason to lose the snapshot
        return DriverState(driver.name, False, f"status unavailable: {exc}")
    return DriverState(driver.name, status.ok, status.message, details)
