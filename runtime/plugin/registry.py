"""The registry: the buses and devices this installation knows.

They are found through Python entry points, read once per process:

    [project.entry-points."softplc.buses"]
    canopen = "softplc.runtime.io.canopen:BUS"

    [project.entry-points."softplc.devices"]
    ltmr = "softplc.runtime.devices.ltmr:DEVICE"

so a package installed beside softplc adds a device (or a bus) by naming
its ``Device`` (or ``Bus``) in its own pyproject. The configuration, the
compiler and the engine ask the registry and name no bus or device
themselves. Tests add one for a while with ``extended(...)``.

Order is each plugin's ``order`` (then its name): it decides the order of
configuration checks, of drivers in the scan and of types in messages.

The compile side asks only for the plugins' ST libraries and the names of
their native functions (``plugin_libraries``, ``plugin_natives``), and a
configuration without a bus section or a [[sim]] table only for the keys of
the buses' sections (``plugin_sections``): those come from an index kept in
softplc's cache (runtime/cache.py, keyed by the installed entry points and
the contents of their packages; the entry points themselves are kept under
the folders of sys.path and the distributions in them: _points), so a
program that uses no bus and no device compiles, and a configuration that
names none loads and runs, without importing one; a native function's
plugin is loaded when a program calls it.
"""

from __future__ import annotations

import importlib.util
import os
import sys
from collections.abc import Iterator, Mapping
from contextlib import contextmanager
from pathlib import Path

from .. import cache
from ..st.native import NativeFunction
from .seams import Bus, Device, GeneratedFile, PackageFile, StLibrary

BUS_GROUP = "softplc.buses"
DEVICE_GROUP = "softplc.devices"


class PluginError(Exception):
    """A bus or device that cannot be registered (a name used twice, an
    entry point that does not load)."""


class Registry:
    def __init__(self) -> None:
        self._buses: dict[str, Bus] = {}
        self._devices: dict[str, Device] = {}
        #: bumped at every change, for caches of what is derived from the registry
        self.version = 0

    # ---------------------------------------------------------------- contents

    @property
    def buses(self) -> list[Bus]:
        return sorted(self._buses.values(), key=lambda p: (p.order, p.name))

    @property
    def devices(self) -> list[Device]:
        return sorted(self._devices.values(), key=lambda p: (p.order, p.name))

    def bus(self, name: str) -> Bus:
        return self._buses[name]

    def add(self, plugin: Bus | Device) -> None:
        if isinstance(plugin, Bus):
            table: dict = self._buses
        elif isinstance(plugin, Device):
            table = self._devices
            taken = self.sim_types()
            for sim_type in plugin.sim_types:
                if sim_type in taken:
                    raise PluginError(f"device {plugin.name}: sim type {sim_type!r} is device {taken[sim_type].name}'s")
            if plugin.sim_types and plugin.simulator is None:
                raise PluginError(f"device {plugin.name}: sim types {', '.join(plugin.sim_types)} but no simulator")
        else:
            raise PluginError(f"not a Bus or a Device: {plugin!r}")
        if plugin.name in table:
            raise PluginError(f"two plugins are called {plugin.name!r}")
        table[plugin.name] = plugin
        self.version += 1

    def remove(self, plugin: Bus | Device) -> None:
        table: dict = self._buses if isinstance(plugin, Bus) else self._devices
        if table.get(plugin.name) is plugin:
            del table[plugin.name]
            self.version += 1

    # ---------------------------------------------------------------- what the core asks

    def _plugins(self) -> list:
        return [*self.buses, *self.devices]

    def natives(self) -> dict[str, NativeFunction]:
        """Every native function, by ST name (upper case)."""
        out: dict[str, NativeFunction] = {}
        for plugin in self._plugins():
            for fn in plugin.natives:
                if fn.name in out:
                    raise PluginError(f"{plugin.name}: native function {fn.name} is declared twice")
                out[fn.name] = fn
        return out

    def libraries(self) -> list[StLibrary]:
        """The ST files of every bus and device (compiled on demand)."""
        return [lib for plugin in self._plugins() for lib in plugin.libraries]

    def sim_types(self) -> dict[str, Device]:
        """[[sim]] type -> the device that simulates it, in registry order."""
        return {t: device for device in self.devices for t in device.sim_types}

    def files(self, kind: str) -> dict[str, PackageFile]:
        """The files of a kind the devices ship, by name: files("eds")["ltmr"]."""
        return {name: f for device in self.devices for name, f in device.files.get(kind, {}).items()}

    def device_with_name(self, name: str) -> Device | None:
        return self._devices.get(name)

    def device_with_file(self, kind: str, name: str) -> Device | None:
        """The device that ships the file of a kind by that name (an EDS), if any."""
        for device in self.devices:
            if name in device.files.get(kind, {}):
                return device
        return None

    def generated(self) -> list[GeneratedFile]:
        return [g for device in self.devices for g in device.generated]


_registry: Registry | None = None


def registry() -> Registry:
    """The process's registry, with every installed entry point loaded."""
    global _registry
    if _registry is None:
        from importlib import metadata

        reg = Registry()
        for group in (BUS_GROUP, DEVICE_GROUP):
            for ep in metadata.entry_points(group=group):
                try:
                    plugin = ep.load()
                except Exception as exc:
                    raise PluginError(
                        f"entry point {ep.name} = {ep.value!r} ({group}) does not load: {type(exc).__name__}: {exc}"
                    ) from exc
                reg.add(plugin)
        _registry = reg
    return _registry


@contextmanager
def extended(*plugins: Bus | Device) -> Iterator[Registry]:
    """The process's registry with plugins added until the block ends, as
    if they were installed (tests; an application embedding softplc)."""
    reg = registry()
    added = []
    try:
        for plugin in plugins:
            reg.add(plugin)
            added.append(plugin)
        yield reg
    finally:
        for plugin in reversed(added):
            reg.remove(plugin)


# ---------------------------------------------------------------- what the compile side asks, lazily


def plugin_libraries() -> list[StLibrary]:
    """The ST files of every bus and device (registry().libraries()),
    without loading a plugin when the index is in the cache."""
    if _registry is not None:
        return _registry.libraries()
    return [StLibrary(package, file) for package, file in _index()[0]]


def plugin_natives(extra: tuple[NativeFunction, ...] = ()) -> Mapping[str, NativeFunction]:
    """Every native function by ST name (registry().natives()) and extra
    ones a caller compiles with; a plugin's are loaded when one of their
    names is looked up."""
    extras = {fn.name: fn for fn in extra}
    if _registry is not None:
        return {**_registry.natives(), **extras}
    return _LazyNatives(_index()[1], extras)


def plugin_sections() -> tuple[tuple[str, bool], ...]:
    """(key, many) of every bus's configuration section, in registry order
    (registry().buses' sections), without loading a plugin when the index
    is in the cache."""
    if _registry is not None:
        return _sections(_registry)
    return _index()[2]


def loaded() -> bool:
    """Whether the process's registry is loaded (every plugin imported)."""
    return _registry is not None


def _sections(reg: Registry) -> tuple[tuple[str, bool], ...]:
    return tuple((s.key, bool(s.many)) for bus in reg.buses for s in bus.sections)


class _LazyNatives(Mapping):
    def __init__(self, names: tuple, extras: dict) -> None:
        self._names = frozenset(names) | frozenset(extras)
        self._extras = extras

    def __getitem__(self, name: str) -> NativeFunction:
        if name in self._extras:
            return self._extras[name]
        if name not in self._names:
            raise KeyError(name)
        return registry().natives()[name]

    def __iter__(self) -> Iterator[str]:
        return iter(sorted(self._names))

    def __len__(self) -> int:
        return len(self._names)


#: what an index holds, part of its key (an index of another layout is another entry)
_INDEX_FORMAT = "libraries, natives, sections"


_found: tuple | None = None  # the process's index, once found


def _index() -> tuple:
    """((package, file) of every plugin's ST library, in registry order;
    the names of their native functions; (key, many) of the buses'
    configuration sections): from the cache, else from the loaded registry
    (and kept); found once a process (its key hashes the plugins' sources)."""
    global _found
    if _found is None:
        _found = _find_index()
    return _found


def _find_index() -> tuple:
    # keyed by the entry points and their packages' code, not by their
    # distributions' names and versions: each of those parses a METADATA
    # file (37 of them: a fifth of `softplc check`'s start-up)
    entries = [repr((group, name, value)).encode() + _package_code(module) for group, name, value, module in _points()]
    key = cache.key("plugins", _INDEX_FORMAT, *entries)
    found = cache.load("plugins", key)
    if isinstance(found, tuple) and len(found) == 3:
        return found
    reg = registry()
    found = (
        tuple((lib.package, lib.file) for lib in reg.libraries()),
        tuple(sorted(reg.natives())),
        _sections(reg),
    )
    cache.store("plugins", key, found)
    return found


def _points() -> list:
    """(group, name, value, module) of every installed bus and device entry
    point. importlib.metadata, which finds them, costs `softplc check` a
    fifteenth of its time to import and read, so what it found is kept in
    the cache under the folders of sys.path and the distributions they hold
    (_place): installing or removing one adds or removes its .dist-info
    folder there, and a new key reads them again."""
    installed = {os.path.realpath(p) for p in (sys.prefix, sys.base_prefix, sys.exec_prefix)}
    key = cache.key("entry-points", *(_place(entry, installed) for entry in sys.path))
    found = cache.load("entry-points", key)
    if isinstance(found, list):
        return found
    from importlib import metadata

    eps = metadata.entry_points()
    found = [(g, ep.name, ep.value, ep.module) for g in (BUS_GROUP, DEVICE_GROUP) for ep in eps.select(group=g)]
    cache.store("entry-points", key, found)
    return found


def _place(entry: str, installed: set) -> str:
    """What of a folder of sys.path says which distributions it holds. A
    folder of the Python installation or the virtual environment
    (site-packages, the standard library): its time, which changes only
    when something is installed there. Any other (the current folder, which
    `python -c` and `python -m pytest` put on sys.path, a project's folder,
    PYTHONPATH's): the names and times of the .dist-info and .egg-info
    folders in it and of their entry_points.txt, so that editing a
    project's files does not read the entry points again."""
    path = entry or "."
    real = os.path.realpath(path)
    if not os.path.isdir(real) or any(real == root or real.startswith(root + os.sep) for root in installed):
        return f"{entry}\0{_mtime(path)}"  # a zip file, a folder of the installation, or none at all
    infos = []
    try:
        with os.scandir(path) as found:
            for item in found:
                if item.name.endswith((".dist-info", ".egg-info")):
                    points = _mtime(os.path.join(item.path, "entry_points.txt"))
                    infos.append(f"{item.name}:{_mtime(item.path)}:{points}")
    except OSError:
        return f"{entry}\0{_mtime(path)}"
    return "\0".join([entry, *sorted(infos)])


def _mtime(path: str) -> str:
    """A file's or folder's time, "-" when there is none."""
    try:
        return str(os.stat(path).st_mtime_ns)
    except OSError:
        return "-"


def _package_code(module: str) -> bytes:
    """A hash of the sources of the package (or module) an entry point
    names, found without importing it (but for its parents)."""
    try:
        spec = importlib.util.find_spec(module)
    except Exception:
        spec = None
    if spec is None or spec.origin is None:
        return b"?"
    origin = Path(spec.origin)
    files = sorted(origin.parent.rglob("*.py")) if spec.submodule_search_locations else [origin]
    return cache.code_hash(*files)
