"""One way to change a running engine's variables from outside: write
(once), force (held against the program and the buses, as a CODESYS force)
and unforce, each checked against the permissions of the surface asking.

Every surface goes through one ``Access``: the web page, the OPC UA server,
the Modbus server, the test API (``softplc.testing.PLC``). A value is
checked against the variable's ST type in the caller's thread (a wrong path
or value raises at once, naming the variable); the change itself happens in
the scan thread at the start of the next scan, after the inputs are read and
before the forces and the tasks (``Engine.before_tasks``), so a scan never
sees half a write. A caller in the scan thread, or one whose engine is not
running in another thread (a test stepping it), changes the value at once.

    access = Access(engine, {"web": Permission(("*",)), "opcua": Permission(("Main.Setpoint",))})
    access.write("Main.Setpoint", 40.0, surface="opcua")   # waits for the next scan
    future = access.submit("force", "%QX0.1", True, surface="web")  # or not
    access.unforce("%QX0.1", surface="web")

A surface without an entry may write nothing. Patterns are fnmatch
patterns over the variable's path as declared, case-insensitive ("Main.*",
"%Q*", "*"); a pattern covers the fields and elements of what it names.
"""

from __future__ import annotations

import fnmatch
import threading
from collections.abc import Callable
from concurrent.futures import Future
from dataclasses import dataclass
from typing import Any

from .lock_share import pause
from .places import Place, Resolver

OPERATIONS = ("write", "force", "unforce")


class AccessDenied(PermissionError):
    """A write the surface is not allowed: the message names the variable and where to allow it."""

    def __str__(self) -> str:
        return str(self.args[0])


@dataclass(frozen=True)
class Permission:
    """What one surface may change: writable, patterns of paths it may write
    (and force, when force is True)."""

    writable: tuple = ()
    force: bool = True
    #: where the patterns come from, for messages: "[opcua] writable in plant.toml"
    where: str = ""
    #: NaN and infinities may be written into a REAL (the test API); no server's surface may
    non_finite: bool = False

    def allows(self, path: str) -> bool:
        name = path.upper()
        for pattern in self.writable:
            p = pattern.upper()
            if fnmatch.fnmatchcase(name, p) or _covers(p, name):
                return True
        return False


def _covers(pattern: str, name: str) -> bool:
    """'MAIN.PUMP' covers 'MAIN.PUMP.SPEED' and 'MAIN.PUMP[2]'."""
    return any(name.startswith(pattern + sep) for sep in (".", "[")) and fnmatch.fnmatchcase(
        name[: len(pattern)], pattern
    )


class Access:
    """The engine's write, force and unforce for every surface (see the module docstring)."""

    def __init__(self, engine, permissions: dict | None = None) -> None:
        self.engine = engine
        self.permissions: dict[str, Permission] = dict(permissions or {})
        engine.load()
        self._resolver = Resolver(engine)

    def allow(self, surface: str, permission: Permission) -> None:
        self.permissions[surface] = permission

    @property
    def resolver(self) -> Resolver:
        self._resolver = self._resolver.fresh()
        return self._resolver

    def place(self, path: str) -> Place:
        """The variable at path (PathError names the path and what is there)."""
        return self.resolver.place(path)

    def check(self, op: str, path: str, surface: str) -> Place:
        """The place at path if surface may do op there; AccessDenied otherwise."""
        if op not in OPERATIONS:
            raise ValueError(f"unknown operation {op!r} (one of {', '.join(OPERATIONS)})")
        place = self.place(path)
        refusal = denied(op, place.path, surface, self.permissions.get(surface))
        if refusal is not None:
            raise refusal
        return place

    @property
    def forced(self) -> dict:
        """The forced paths and their values, as the one who forced them gave them."""
        return dict(self.engine.forced_values.values())

    # ------------------------------------------------------------ operations

    def submit(self, op: str, path: str, value: Any = None, *, surface: str) -> Future:
        """Check op now (PathError, AccessDenied, ValueError for a value the
        type cannot hold) and carry it out at the start of the next scan; the
        Future's result is the variable's path as declared."""
        place = self.check(op, path, surface)
        return self._schedule(self._action(op, place, value, finite=self._finite(surface)))

    def submit_many(self, op: str, items: list, *, surface: str) -> Future:
        """submit for several (path, value) pairs, carried out together at the
        start of one scan (a Modbus write of two registers holding a REAL: no
        scan sees half of it). Every one is checked first: one refused, none
        is made. The Future's result is the list of the paths as declared."""
        finite = self._finite(surface)
        actions = []
        for path, value in items:
            pause()  # a call thread's: each path while the scan sleeps
            actions.append(self._action(op, self.check(op, path, surface), value, finite=finite))
        return self._schedule(lambda: [action() for action in actions])

    def write(self, path: str, value: Any, *, surface: str, timeout: float = 5.0) -> str:
        """Store value once, at the next scan (the program may change it then)."""
        return self.submit("write", path, value, surface=surface).result(timeout)

    def force(self, path: str, value: Any, *, surface: str, timeout: float = 5.0) -> str:
        """Hold path at value in every scan until unforce."""
        return self.submit("force", path, value, surface=surface).result(timeout)

    def unforce(self, path: str, *, surface: str, timeout: float = 5.0) -> str:
        """Release a force (KeyError when path is not forced); the variable keeps its value."""
        place = self.check("unforce", path, surface)
        if place.path.upper() not in self.engine.forces:
            forced = ", ".join(path for path, _v in self.engine.forced_values.values()) or "nothing"
            raise KeyError(f"{place.path} is not forced (forced: {forced})")
        return self.submit("unforce", path, surface=surface).result(timeout)

    def unforce_all(self, *, surface: str, timeout: float = 5.0) -> list:
        """Release every force the surface may release; the paths released."""
        paths = [path for path, _v in self.engine.forced_values.values()]
        return [self.unforce(p, surface=surface, timeout=timeout) for p in paths]

    def _action(self, op: str, place: Place, value: Any, *, finite: bool) -> Callable[[], str]:
        engine = self.engine
        key = place.path.upper()
        if op == "unforce":

            def unforce() -> str:
                engine.unforce(key)
                return place.path

            return unforce
        apply = place.writer(value, finite=finite)  # checked here, in the caller's thread
        if op == "write":

            def write() -> str:
                apply()
                return place.path

            return write

        def force() -> str:
            engine.force(key, apply)
            engine.forced_values[key] = (place.path, value)
            return place.path

        return force

    def _finite(self, surface: str) -> bool:
        permission = self.permissions.get(surface)
        return permission is None or not permission.non_finite

    # ------------------------------------------------------------ the scan thread

    def _schedule(self, action: Callable[[], Any]) -> Future:
        """action at the start of the next scan (at once when no other thread scans); its Future."""
        future: Future = Future()
        if self._now():
            _run(action, future)
        else:
            self.engine.before_tasks.append(lambda _engine: _run(action, future))
        return future

    def _now(self) -> bool:
        """Change at once: in the scan thread, or when no other thread scans."""
        scanning = self.engine.scan_thread
        return scanning is None or scanning == threading.get_ident()


def denied(op: str, path: str, surface: str, permission: Permission | None) -> AccessDenied | None:
    """Why surface may not do op at path (its path as declared), or None:
    Access.check's verdict, which a server that knows its paths already
    (the Modbus server's addresses) asks without a call to the PLC."""
    if permission is None or not permission.allows(path):
        where = f" (allow it in {permission.where})" if permission is not None and permission.where else ""
        return AccessDenied(f"{path}: {surface} may not {op} it{where}")
    if op == "force" and not permission.force:
        return AccessDenied(f"{path}: {surface} may write but not force{_where(permission)}")
    return None


def _run(action: Callable[[], Any], future: Future) -> None:
    try:
        future.set_result(action())
    except Exception as exc:  # a write that faults (a string too long ...): the caller hears it
        future.set_exception(exc)


def _where(permission: Permission) -> str:
    return f" (see {permission.where})" if permission.where else ""
