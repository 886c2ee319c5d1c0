"""What the web page asks of the PLC's process: each function is run there,
with the PLC's ``Surfaces`` (host.py), through ``surfaces.call`` (in the
servers' process, child.py's RemoteSurfaces sends the call over the pipe and
waits for its answer; in the PLC's process it is a plain call). The page
itself, in the servers' process, holds no engine: it reads the snapshots it
is sent and reaches the engine only here, through the hub and the one Access.

    surfaces.call(plc.info)                          # {"online_change", "tasks"}
    surfaces.call(plc.tree_level, "Main", 0)         # tree.children of the current program
    surfaces.call(plc.watch, "web:page", paths)      # (canonical paths, {path: why not}, sequence)
    surfaces.call(plc.checked, "write", "Main.n", True, "5")   # (path as declared, value typed)
    surfaces.call(plc.restart)                       # the faulted tasks' names, restarted
    surfaces.call(plc.online_change, "web page")     # the report as JSON data
"""

from __future__ import annotations

from typing import Any

from ...config.values import LONG, got
from ...engine.lock_share import pause
from ...engine.values import shown
from ...st import types as T
from . import tree


class NotForced(Exception):
    """An unforce of a variable not forced (answered 409)."""


class OnlineChangeOff(Exception):
    """The page asked for an online change, and softplc run has it off (answered 404)."""


def info(surfaces) -> dict:
    """What /api/info tells of the PLC (the [web] section's part is the page's own)."""
    engine = surfaces.engine
    return {
        "online_change": getattr(surfaces, "online_change", None) is not None,
        "tasks": [t.name for t in engine.tasks],
    }


def tree_level(surfaces, path: str, offset: int) -> dict:
    """One level of the variable tree (tree.children); PathError names a path that is no variable."""
    return tree.children(surfaces.hub.resolver, path, offset)


def watch(surfaces, reader: str, paths: list) -> tuple:
    """Watch the paths that name a variable for reader: (their canonical
    paths, {path: why not} for the others, the sequence of the latest
    snapshot: the next one has them). A snapshot is asked for at once."""
    places, errors = [], {}
    hub = surfaces.hub
    resolver = hub.resolver
    for path in paths:
        pause()  # a call thread's: while the scan sleeps
        try:
            places.append(resolver.place(path))
        except (KeyError, ValueError) as exc:  # PathError is a KeyError
            errors[path if len(path) <= LONG else got(path)] = str(exc)  # a long path as a message cuts it
    good = hub.watch_places(reader, places)
    latest = hub.latest
    hub.request()
    return good, errors, latest.sequence if latest is not None else 0


def checked(surfaces, op: str, path: str, surface: str, has_value: bool, value: Any) -> tuple:
    """(the path as declared, the value as the scan is to take it) of a
    write, force or unforce the page asks for: AccessDenied, PathError,
    NotForced or ValueError when it may not be made (a refusal first,
    whatever the value)."""
    place = surfaces.access.check(op, path, surface)
    if op == "unforce":
        if place.path.upper() not in surfaces.engine.forces:
            raise NotForced(f"{place.path} is not forced")
        return place.path, None
    if not has_value:
        raise ValueError(f"{place.path}: no value to {op}")
    return place.path, _typed(place, value)


def restart(surfaces) -> list:
    """Restart the tasks a runtime fault stopped: their names ([] when none is stopped)."""
    engine = surfaces.engine
    faulted = [t.name for t in engine.faulted_tasks()]
    if faulted:
        engine.request_restart()
    return faulted


def online_change(surfaces, who: str) -> dict:
    """Compile the ST files and swap them in (softplc run's OnlineChange): its report as JSON data."""
    changer = getattr(surfaces, "online_change", None)
    if changer is None:
        raise OnlineChangeOff("online change is off (softplc run --online-change turns it on)")
    report = changer.request(who)
    return {"applied": report.applied, "summary": report.summary(), "lines": report.lines()}


def _typed(place, value: Any) -> Any:
    """A value typed on the page is text: a REAL takes it as a number (the
    other types read their literals themselves: TRUE, 16#FF, T#2s, an enumerator)."""
    r = T.resolve(place.type)
    if isinstance(value, str) and isinstance(r, T.ElementaryType) and r.is_real:
        try:
            return float(value.strip())
        except ValueError:
            raise ValueError(f"{place.path} is {r.name}: write a number, not {shown(value)}") from None
    return value
