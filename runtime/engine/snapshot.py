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
"""

from __future__ import annotations

import operator
import threading
import time
from dataclasses import dataclass, field
from typing import Any

from ..st import types as T
from ..st.valuejson import encode_value
from .places import PathError, Place, Resolver


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
    values: dict
    types: dict
    image: dict  # area letter -> bytes
    generation: int  # engine.generation: a new program or restarted instances

    def json(self, path: str) -> Any:
        """The value at path as JSON data (enumerations by name, TIME as T#...)."""
        value = self.values[path]
        return value if isinstance(value, (dict, list)) else encode_value(self.types[path], value)


class SnapshotHub:
    """Snapshots of one engine for every reader (see the module docstring)."""

    def __init__(self, engine, period_s: float = 0.1, resolver: Resolver | None = None, attach: bool = True) -> None:
        self.engine = engine
        self.period_s = period_s
        engine.load()
        self._resolver = resolver if resolver is not None else Resolver(engine)
        self._watched: dict[str, tuple] = {}  # reader -> its paths
        self._places: dict[str, Place] = {}  # path -> Place, the union of the readers' paths
        self._plan: tuple = _plan_of({})  # how capture() reads them
        self._lock = threading.Lock()  # readers change _watched; the scan thread reads _plan
        self._fresh = threading.Condition()
        self._requested = False
        self._next = 0.0
        self._sequence = 0
        self.latest: Snapshot | None = None
        if attach:  # else: capture() only, when asked (a status line of a stopped engine)
            engine.after_tick.append(self._after_tick)

    # ------------------------------------------------------------ readers

    @property
    def resolver(self) -> Resolver:
        """Paths of the engine's current program (a new one after an online change)."""
        self._resolver = self._resolver.fresh()
        return self._resolver

    def watch(self, reader: str, paths) -> list:
        """Make paths part of every snapshot for reader (replacing what it
        watched before). Returns the paths as resolved (canonical spelling);
        PathError names the first path that names no variable."""
        resolved = [self.resolver.place(p) for p in paths]
        with self._lock:
            self._watched[reader] = tuple(p.path for p in resolved)
            places = dict(self._places)
            for place in resolved:
                places[place.path] = place
            self._set_places(self._prune(places))
        return [p.path for p in resolved]

    def unwatch(self, reader: str) -> None:
        with self._lock:
            self._watched.pop(reader, None)
            self._set_places(self._prune(dict(self._places)))

    def _set_places(self, places: dict) -> None:
        self._places = places
        self._plan = _plan_of(places)  # one assignment: the scan thread sees the old plan or the new

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

    # ------------------------------------------------------------ the scan thread

    def _after_tick(self, engine) -> None:
        if not self._requested:
            now = time.monotonic()
            if now < self._next:
                return
            self._next = now + self.period_s
        self._requested = False
        self.capture()

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
        engine = self.engine
        if self._resolver.generation != engine.generation:
            self._rewatch()
        groups, others, types = self._plan
        values: dict = {}
        for fetch, holder, paths in groups:  # the plain variables of one object, in one call
            try:
                values.update(zip(paths, fetch(holder)))
            except AttributeError:  # not there (yet): left out, as a path that cannot be read
                continue
        for path, get, aggregate in others:
            try:
                value = get()
            except Exception:  # an element gone with a resized string or an index: leave it out
                continue
            values[path] = value if aggregate is None else encode_value(aggregate, value)  # a copy
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
            values=values,
            types=types,
            image={area: bytes(data) for area, data in engine.image.areas.items()},
            generation=engine.generation,
        )
        with self._fresh:
            self.latest = snap
            self._sequence = snap.sequence
            self._fresh.notify_all()
        return snap

    def _rewatch(self) -> None:
        """After an online change or a restart the places point at the old
        objects: resolve every reader's paths again (a path that is gone is
        dropped from the snapshots)."""
        resolver = self.resolver
        places: dict = {}
        for paths in self._watched.values():
            for path in paths:
                try:
                    places[path] = resolver.place(path)
                except PathError:
                    continue
        with self._lock:
            self._set_places(places)


def _plan_of(places: dict) -> tuple:
    """How to read places fast: (groups, others, types). A group is the
    plain variables of one object (an elementary, string, enumeration or
    subrange value in an attribute), read with one attrgetter call; the
    others (located variables, array elements, aggregates, references) each
    through its place, an aggregate copied as JSON data."""
    by_holder: dict = {}
    others = []
    for path, place in places.items():
        t = T.resolve(place.type)
        if place.holder is not None and isinstance(t, _PLAIN):
            by_holder.setdefault(id(place.holder), (place.holder, [], []))
            _holder, attrs, paths = by_holder[id(place.holder)]
            attrs.append(place.attr)
            paths.append(path)
        else:
            plain = isinstance(t, _PLAIN)
            others.append((path, place.get, None if plain else place.type))
    groups = tuple((_fetch(attrs), holder, tuple(paths)) for holder, attrs, paths in by_holder.values())
    return groups, tuple(others), {path: place.type for path, place in places.items()}


def _fetch(attrs: list):
    """A callable giving the attributes' values of an object as a tuple."""
    if len(attrs) == 1:
        (attr,) = attrs
        return lambda obj: (getattr(obj, attr),)
    return operator.attrgetter(*attrs)


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
