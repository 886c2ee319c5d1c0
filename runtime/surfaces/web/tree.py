"""The variable tree of the web page: the program instances, the globals
and the library's globals (CANOPEN_NODE, PLC_DIAG ...), one level at a time.

    children(resolver, "")            # the roots: each program instance, "@globals", "@library"
    children(resolver, "Motor")       # Motor's variables
    children(resolver, "Motor.ltmr")  # an FB instance's (or a struct's) variables
    children(resolver, "Line.parts", offset=100)  # elements 100.. of a big array

Variables marked {attribute 'hide'} are left out, as CODESYS's monitoring
and the OPC UA server leave them out (a path typed in still reaches them).

Each child is a dict: name, path (to read, watch, write it), type (its ST
type by name), kind ("var" for a scalar, "struct", "array", "program",
"group") and, for an array, size. A level holds at most LIMIT children; the
rest is paged with offset ("more" says how many follow). Values are not
here: they come with the snapshots (stream.py).
"""

from __future__ import annotations

from typing import Any

from ...engine.lock_share import pause
from ...engine.places import PathError, Place, Resolver
from ...engine.values import type_text
from ...st import types as T
from ...st.valuejson import SKIPPED_SECTIONS

#: the most children one level shows at once (a big array is paged)
LIMIT = 100
#: the groups at the root: the program's globals and those of the libraries
GLOBALS, LIBRARY = "@globals", "@library"


def children(resolver: Resolver, path: str, offset: int = 0) -> dict:
    """The children of path ("" for the roots) as {"path", "children", "more"};
    PathError names a path that is no variable."""
    path = path.strip()
    if not path:
        items = _roots(resolver)
    elif path in (GLOBALS, LIBRARY):
        items = _globals(resolver, library=path == LIBRARY)
    else:
        entry = resolver.engine.instances.get(path.upper())
        if entry is not None:
            items = _instance(resolver, entry[0], entry[2])
        else:
            return _aggregate(resolver, resolver.place(path), offset)
    return {"path": path, "children": items, "more": 0}


def _roots(resolver: Resolver) -> list:
    engine = resolver.engine
    out: list = [
        {"name": name, "path": name, "type": info.name, "kind": "program"}
        for name, info, obj in engine.instances.values()
        if obj is not None
    ]
    out.append({"name": "Globals", "path": GLOBALS, "type": "", "kind": "group"})
    out.append({"name": "Library globals", "path": LIBRARY, "type": "", "kind": "group"})
    return out


def _globals(resolver: Resolver, library: bool) -> list:
    engine = resolver.engine
    lib = {name.upper() for name in engine.program.library_globals}
    globals_ = engine.ns["_G"]
    hidden = _hidden(globals_)
    out = []
    for st_name, _attr, _ty, section in getattr(type(globals_), "_VARS_", ()):
        if section in SKIPPED_SECTIONS or (st_name.upper() in lib) != library or st_name in hidden:
            continue
        out.append(_child(st_name, resolver.place(st_name)))
    return out


def _instance(resolver: Resolver, name: str, obj: Any) -> list:
    hidden = _hidden(obj)
    return [
        _child(st_name, resolver.place(f"{name}.{st_name}"))
        for st_name, _attr, _ty, section in getattr(type(obj), "_VARS_", ())
        if section not in SKIPPED_SECTIONS and st_name not in hidden
    ]


def _hidden(obj: Any) -> frozenset:
    """The names of obj's {attribute 'hide'} variables."""
    return getattr(type(obj), "_HIDDEN_", frozenset())


def _aggregate(resolver: Resolver, place: Place, offset: int) -> dict:
    r = T.resolve(place.type)
    if place.parts is None:
        raise PathError(f"{place.path} is {type_text(place.type)}: it has no parts to show")
    if isinstance(r, T.ArrayType):
        lo, hi = _bounds(place, r)
        start = lo + max(offset, 0)
        stop = min(hi, start + LIMIT - 1)
        items = []
        for i in range(start, stop + 1):
            items.append(_child(f"[{i}]", resolver.place(f"{place.path}[{i}]")))
        return {"path": place.path, "children": items, "more": max(hi - stop, 0)}
    hidden = _hidden(place.get())
    named = ((p.path.rsplit(".", 1)[-1], p) for p in place.parts().values())
    items = [_child(name, p) for name, p in named if name not in hidden]
    return {"path": place.path, "children": items, "more": 0}


def _bounds(place: Place, r: T.ArrayType) -> tuple:
    dims = r.dims[0]
    if dims is not None:
        return dims
    return 0, len(place.get()) - 1  # an ARRAY[*]: as long as it is now


def _child(name: str, place: Place) -> dict:
    pause()  # a call thread's: each child while the scan sleeps (a level is up to LIMIT of them)
    r = T.resolve(place.type)
    item: dict = {"name": name, "path": place.path, "type": str(place.type)}
    if isinstance(r, T.ArrayType):
        lo, hi = _bounds(place, r)
        item.update(kind="array", size=hi - lo + 1)
    elif place.parts is not None:
        item["kind"] = "struct"
    else:
        item["kind"] = "var"
        if isinstance(r, T.EnumType):
            item["values"] = list(r.spelled.values())
    return item
