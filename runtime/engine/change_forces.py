"""The forces across an online change (online_change.py): each force of a
variable is resolved again by its path in the new program and keeps its
value where the variable is still there with the same type; else it is
released. A force of an address stays as it is (the image is the same)."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from ..program import Program
from ..st import types as T
from ..st.values import assign_into, copy_value
from .retain import type_signature

_STEP = re.compile(r"\s*(?:\.?\s*([A-Za-z_][A-Za-z0-9_]*)|\[([^\]]*)\])")


def _cell(program: Program, ns: dict, instances: dict, path: str):
    """(get, set, type) of the variable at path ('Main.a.b[2, 3].c', a global,
    'GVL.x') in a loaded program; KeyError if there is none."""
    steps = [(m.group(1), m.group(2)) for m in _STEP.finditer(path)]
    if not steps or steps[0][0] is None:
        raise KeyError(path)
    first = steps[0][0].upper()
    entry = instances.get(first)
    if entry is not None and len(steps) > 1:
        obj, steps = entry[2], steps[1:]
    else:
        obj = ns["_G"]
        if first in program.checked.global_lists and len(steps) > 1:
            steps = steps[1:]  # GVL.x: the list's name
    holder: Any = obj
    attr: Any = None  # an attribute name, or a list index
    ty: Any = None
    for name, index in steps:
        if attr is not None:
            holder = holder[attr] if isinstance(attr, int) else getattr(holder, attr)
        if name is not None:
            found = [(a, t) for n, a, t, _s in getattr(type(holder), "_VARS_", ()) if n.upper() == name.upper()]
            if not found:
                raise KeyError(path)
            attr, ty = found[0]
            continue
        arr = T.resolve(ty)
        if not isinstance(arr, T.ArrayType):
            raise KeyError(path)
        subs = [int(x) for x in index.split(",")]
        for k, i in enumerate(subs):
            lo, hi = arr.dims[k]
            if not lo <= i <= hi:
                raise KeyError(path)
            if k:
                holder = holder[attr] if isinstance(attr, int) else getattr(holder, attr)
            attr = i - lo
        ty = arr.elem
    if attr is None:
        raise KeyError(path)
    return _accessors(holder, attr, ty)


def _accessors(holder, attr, ty) -> tuple:
    if isinstance(attr, int):
        return (lambda: holder[attr]), (lambda v: holder.__setitem__(attr, v)), ty
    return (lambda: getattr(holder, attr)), (lambda v: setattr(holder, attr, v)), ty


def rebind_forces(engine, program: Program, ns: dict, instances: dict, forces: dict) -> list:
    """The forces (key -> store) of the program, ns and instances an online
    change replaced, resolved again in engine's new one: (key, "kept" or
    "released: why") each; engine.forces holds the new stores."""
    out = []
    for key in list(forces):
        if key.startswith("%"):
            continue
        try:
            get, _set, old_t = _cell(program, ns, instances, key)
            value = copy_value(get())  # the forced value: the force stored it after the last scan's tasks
        except (KeyError, ValueError, TypeError, IndexError):
            old_t = None
        try:
            get, set_, new_t = _cell(engine.program, engine.ns, engine.instances, key)
        except (KeyError, ValueError, TypeError, IndexError):
            new_t = None
        if old_t is None or new_t is None:
            engine.unforce(key)
            out.append((key, "released: the variable is gone"))
        elif type_signature(old_t) != type_signature(new_t):
            engine.unforce(key)
            out.append((key, "released: its type changed"))
        else:
            engine.forces[key] = _store(get, set_, new_t, value)
            out.append((key, "kept"))
    return out


def _store(get, set_, ty, value) -> Callable[[], None]:
    if T.resolve(ty).is_aggregate:
        return lambda: assign_into(get(), value)
    return lambda: set_(value)
