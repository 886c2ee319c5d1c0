"""A scenario's writes in a running engine (config/scenario.py: [init],
[[schedule]], `softplc run --set`): each path and value checked once the
program is loaded, then written at the start of a scan, after the inputs
are read and before the tasks run (where a write of the web page or of a
test lands): [init] at the first scan, over the initial and retained
values; a [[schedule]] entry at the first scan at or after its time from
the first scan's. Each write is logged (INFO), so that a run's log says
what the scenario did and when.

    scenario = Scenario(config.init, config.schedule)
    errors = scenario.check(engine)     # [(key, message)]: a wrong path or value
    scenario.install(engine)
"""

from __future__ import annotations

import logging
from collections import deque

from ..config.values import cut
from .places import PathError, Resolver
from .values import shown

log = logging.getLogger("softplc.scenario")


class Scenario:
    def __init__(self, init: list, schedule: list) -> None:
        self.init = list(init)
        self.schedule = sorted(schedule, key=lambda w: w.at_ns)
        self._due: deque = deque()
        self._start_ns: int | None = None
        self._resolver: Resolver | None = None
        self.done: list = []  # (engine time ns, ScenarioWrite) of each write made

    def __bool__(self) -> bool:
        return bool(self.init or self.schedule)

    def check(self, engine) -> list:
        """(key, message) of each write whose path names no variable or
        whose value the variable's type does not take (the engine loaded)."""
        try:
            engine.load()
        except Exception:  # the initial values fault: the run's own load reports it, as ever
            return []
        resolver = Resolver(engine)
        errors = []
        for write in (*self.init, *self.schedule):
            try:
                place = resolver.place(write.path)
            except PathError as exc:
                errors.append((write.key, str(exc)))
                continue
            try:
                place.writer(write.value, finite=True)
            except ValueError as exc:
                errors.append((write.where_value, str(exc)))
        return errors

    def install(self, engine) -> None:
        self._due = deque(self.schedule)
        engine.before_tick.append(self._tick)

    def _tick(self, engine) -> None:
        if not self._due and self._start_ns is not None:
            return  # all written (left in before_tick: the engine iterates it as it is)
        now = engine.clock.now_ns()
        if self._start_ns is None:
            self._start_ns = now
            for write in self.init:
                engine.before_tasks.append(lambda e, w=write: self._write(e, w))
        while self._due and now - self._start_ns >= self._due[0].at_ns:
            write = self._due.popleft()
            engine.before_tasks.append(lambda e, w=write: self._write(e, w))

    def _write(self, engine, write) -> None:
        resolver = self._resolver = (self._resolver or Resolver(engine)).fresh()
        try:  # an online change may have taken the variable away, or changed its type
            resolver.place(write.path).writer(write.value, finite=True)()
        except (PathError, ValueError) as exc:
            log.warning("scenario: %s not written: %s", write.key, exc)
            return
        now = engine.clock.now_ns()
        self.done.append((now, write))
        log.info("scenario: t=%.3fs %s := %s (%s)", now / 1e9, cut(write.path), shown(write.value), write.key)
