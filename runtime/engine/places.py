"""Where a test's path points in a loaded program: a variable of a program
instance ('Motor.state'), a global ('G_count'), a field or an element
inside ('Motor.ltmr.Running', 'Line.parts[2].weight', 'grid[1, 3]'), or a
direct address ('%IX0.3', '%QW1'). Names are case-insensitive, as in ST.

``Resolver.place(path)`` gives a ``Place``: its ST type, ``get()`` (the
stored value) and ``writer(value)``, which checks a test's value against the
type once and returns a callable that stores it (a write calls it once, a
force every scan).
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..config.values import cut
from ..image.address import AddressError, default_type, parse_address
from ..st import types as T
from ..st.valuejson import SKIPPED_SECTIONS
from .values import from_python, shown, to_python

#: a longer path is refused before it is looked at (no plant has one; a 1 MB path from a
#: client would take seconds of difflib hints)
MAX_PATH = 4096

_STEP = re.compile(r"\s*(?:(\.)?\s*([A-Za-z_][A-Za-z0-9_]*)|\[([^\]]*)\])\s*")


class PathError(KeyError):
    """A path that names no variable; the message says which part and what
    there is (a long path in it cut, config/values.py cut)."""

    def __str__(self) -> str:
        return cut(str(self.args[0]))


@dataclass
class Place:
    path: str
    type: T.Type
    get: Callable[[], Any]
    set: Callable[[Any], None] | None  # None for an aggregate (written part by part)
    parts: Callable[[], dict] | None = None  # aggregate: its parts by key (field name or index)
    #: a plain variable's object and attribute (get is getattr(holder, attr)): readers of many
    #: variables fetch those of one object at once (engine/snapshot.py)
    holder: Any = None
    attr: str | None = None
    #: an element of an array of plain values: get is holder[index] (holder the list)
    index: int | None = None

    def read(self) -> Any:
        return to_python(self.type, self.get())

    def writer(self, value: Any, *, finite: bool = False) -> Callable[[], None]:
        """A callable storing value (checked now: ValueError names the path
        and the type); finite: no NaN or infinity into a REAL (values.py)."""
        r = T.resolve(self.type)
        if self.set is not None:
            stored = from_python(self.type, value, self.path, finite=finite)
            setter = self.set
            return lambda: setter(stored)
        assert self.parts is not None
        parts = self.parts()
        if isinstance(r, T.ArrayType):
            if not isinstance(value, (list, tuple)) or len(value) != len(parts):
                raise ValueError(f"{self.path} is {r.name}: write a list of {len(parts)} values, not {shown(value)}")
            writers = [part.writer(v, finite=finite) for part, v in zip(parts.values(), value)]
        else:
            if not isinstance(value, dict):
                raise ValueError(f"{self.path} is {r.name}: write a dict of its fields, not {shown(value)}")
            writers = []
            for name, v in value.items():
                part = parts.get(str(name).upper())
                if part is None:
                    raise ValueError(f"{self.path} ({r.name}) has no field {shown(name)} (it has {_names(parts)})")
                writers.append(part.writer(v, finite=finite))

        def write_all() -> None:
            for w in writers:
                w()

        return write_all


def _names(parts: dict) -> str:
    return ", ".join(p.path.rsplit(".", 1)[-1] for p in parts.values())


class Resolver:
    """Paths in one loaded engine (engine.load() has run)."""

    def __init__(self, engine) -> None:
        self.engine = engine
        self.generation = engine.generation  # the program instances it knows
        self.image = engine.image
        self.located: dict = {}  # (class, attribute) -> LocatedAddress
        ns = engine.ns
        checked = engine.program.checked
        for info in checked.pous:
            cls = ns.get(info.pyname)
            for var in info.vars.values():
                if var.location is not None and cls is not None:
                    self.located[(cls, var.pyname)] = var.location
        gcls = type(ns["_G"])
        for var in checked.globals:
            if var.location is not None:
                self.located[(gcls, var.pyname)] = var.location

    def fresh(self) -> Resolver:
        """This resolver, or a new one when the engine's program instances
        were replaced since (a restart, an online change: new classes too)."""
        return self if self.generation == self.engine.generation else Resolver(self.engine)

    def place(self, path: str) -> Place:
        if not isinstance(path, str) or not path.strip():
            raise PathError(
                f"expected a variable path such as 'Main.count' or an address such as '%QX0.0', got {shown(path)}"
            )
        if len(path) > MAX_PATH:  # before any search (difflib's hints are quadratic in the length)
            raise PathError(f"{shown(path)}: longer than any variable's path (at most {MAX_PATH} characters)")
        path = path.strip()
        if path.startswith("%"):
            return self._address(path)
        steps = self._steps(path)
        first = steps[0]
        if not isinstance(first, str):
            raise PathError(f"{path}: a path starts with a name")
        entry = self.engine.instances.get(first.upper())
        if entry is not None and len(steps) > 1:
            obj, done, rest = entry[2], entry[0], steps[1:]
            place = self._member(obj, rest[0], done, path)
        else:
            rest = self._without_list(steps)
            place = self._member(self.engine.ns["_G"], rest[0], "", path, top=True)
        for step in rest[1:]:
            place = self._step(place, step, path)
        return place

    def _without_list(self, steps: list) -> list:
        """GVL.speed names the global speed of the list GVL (the file GVL.st,
        st/check/namespaces.py), unless a global is called GVL."""
        first, second = steps[0], steps[1] if len(steps) > 1 else None
        names = self.engine.program.checked.global_lists.get(first.upper())
        if not names or not isinstance(second, str) or second.upper() not in names:
            return steps
        if any(v[0].upper() == first.upper() for v in getattr(type(self.engine.ns["_G"]), "_VARS_", ())):
            return steps
        return steps[1:]

    # ------------------------------------------------------------ parsing

    @staticmethod
    def _steps(path: str) -> list:
        steps: list = []
        pos = 0
        while pos < len(path):
            m = _STEP.match(path, pos)
            if m is None or (m.group(2) is not None and bool(m.group(1)) != bool(steps)):
                raise PathError(f"{path}: cannot read the path at {path[pos:]!r}")
            if m.group(2) is not None:
                steps.append(m.group(2))
            else:
                try:
                    steps.append(tuple(int(i.strip()) for i in m.group(3).split(",")))
                except ValueError:
                    raise PathError(f"{path}: an index is an integer, not [{m.group(3)}]") from None
            pos = m.end()
        if not steps:
            raise PathError(f"{path}: empty path")
        return steps

    # ------------------------------------------------------------ steps

    def _address(self, path: str) -> Place:
        try:
            addr = parse_address(path, self.image.addressing)
            ty = default_type(addr)
            get = self.image.reader(addr, ty)
            get()
        except (AddressError, ValueError) as exc:
            raise PathError(f"{path}: {exc}") from None
        image = self.image
        return Place(addr.text, ty, get, lambda v: image.write(addr, v, ty))

    def _member(self, obj: Any, name: str, done: str, path: str, top: bool = False) -> Place:
        here = f"{done}.{name}" if done else name
        for st_name, attr, ty, _section in getattr(type(obj), "_VARS_", ()):
            if st_name.upper() == name.upper():
                return self._attr_place(obj, attr, ty, f"{done}.{st_name}" if done else st_name)
        known = [v[0] for v in getattr(type(obj), "_VARS_", ())]
        if top:
            known = [e[0] for e in self.engine.instances.values()] + [
                k for k in known if k not in self.engine.program.library_globals
            ]
        close = difflib.get_close_matches(name, known, n=1, cutoff=0.6)
        hint = f" (did you mean '{(done + '.') if done else ''}{close[0]}'?)" if close else ""
        what = f"'{done}'" if done else "the program instances and globals"
        raise PathError(f"{path}: no variable {here} in {what}{hint}")

    def _attr_place(self, obj: Any, attr: str, ty: T.Type, text: str) -> Place:
        location = self.located.get((type(obj), attr))
        if location is not None:
            image = self.image
            elem = T.base_elementary(ty) or default_type(location)
            try:
                get = image.reader(location, elem)
            except (AddressError, ValueError):  # read says so when asked
                get = lambda: image.read(location, elem)  # noqa: E731
            return Place(text, ty, get, lambda v: image.write(location, v, elem))
        r = T.resolve(ty)
        if isinstance(r, T.ArrayType):
            return self._array_place(lambda: getattr(obj, attr), r, text)
        if isinstance(r, (T.StructType, T.FBType)):
            return self._struct_place(getattr(obj, attr), ty, text)
        return Place(text, ty, lambda: getattr(obj, attr), lambda v: setattr(obj, attr, v), holder=obj, attr=attr)

    def _struct_place(self, value: Any, ty: T.Type, text: str) -> Place:
        def parts() -> dict:
            return {
                st_name.upper(): self._attr_place(value, attr, vty, f"{text}.{st_name}")
                for st_name, attr, vty, section in type(value)._VARS_
                if section not in SKIPPED_SECTIONS
            }

        return Place(text, ty, lambda: value, None, parts)

    def _array_place(self, get_list: Callable[[], list], t: T.ArrayType, text: str) -> Place:
        def parts() -> dict:
            out: dict = {}
            lo, hi = t.dims[0] if t.dims[0] is not None else (0, len(get_list()) - 1)
            for i in range(lo, hi + 1):
                out[i] = self._index(get_list, t, (i,), text)
            return out

        return Place(text, t, get_list, None, parts)

    def _index(self, get_list: Callable[[], list], t: T.ArrayType, index: tuple, text: str) -> Place:
        """The element (or the sub-array, for fewer indices than dimensions) at index."""
        lst = get_list()
        for k, i in enumerate(index):
            lo, hi = t.dims[k] if t.dims[k] is not None else (0, len(lst) - 1)
            if not lo <= i <= hi:
                raise PathError(f"{text}[{', '.join(map(str, index))}]: index {i} is outside {lo}..{hi}")
            if k < len(index) - 1:
                lst = lst[i - lo]
        last_lo = t.dims[len(index) - 1][0] if t.dims[len(index) - 1] is not None else 0
        pos = index[-1] - last_lo
        here = f"{text}[{', '.join(map(str, index))}]"
        holder = lst
        if len(index) < len(t.dims):
            sub = T.ArrayType(t.dims[len(index) :], t.elem)
            return self._array_place(lambda: holder[pos], sub, here)
        r = T.resolve(t.elem)
        if isinstance(r, T.ArrayType):
            return self._array_place(lambda: holder[pos], r, here)
        if isinstance(r, (T.StructType, T.FBType)):
            return self._struct_place(holder[pos], t.elem, here)
        return Place(here, t.elem, lambda: holder[pos], lambda v: holder.__setitem__(pos, v), holder=holder, index=pos)

    def _step(self, place: Place, step, path: str) -> Place:
        r = T.resolve(place.type)
        if isinstance(step, tuple):
            if not isinstance(r, T.ArrayType):
                raise PathError(f"{path}: {place.path} is {r.name}, not an array")
            if len(step) > len(r.dims):
                raise PathError(f"{path}: {place.path} has {len(r.dims)} dimension(s), not {len(step)}")
            return self._index(place.get, r, step, place.path)
        if not isinstance(r, (T.StructType, T.FBType)):
            raise PathError(f"{path}: {place.path} is {r.name}, it has no field {step}")
        return self._member(place.get(), step, place.path, path)
