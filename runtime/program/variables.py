"""Program variables by their ST names: locate a variable at a dotted path
(--watch, tests, forcing) and set the fields of a diagnostic struct the
runtime fills (PLC_DIAG and the drivers' diagnostics)."""

from __future__ import annotations

from ..st import types as T
from ..st.rtlib.rtlib import cut_string


def locate(path: str, roots) -> tuple:
    """(holder, attribute, Type) of the variable at an ST path such as
    'motor.speed' (dotted names, no indices; case-insensitive), looked up in each root object in turn (a program
    instance, then the globals). KeyError(path) if there is none."""
    parts = path.split(".")
    for root in roots:
        found = _member(root, parts[0])
        if found is not None:
            break
    else:
        raise KeyError(path)
    for part in parts[1:]:
        holder, attr, _ty = found
        found = _member(getattr(holder, attr), part)
        if found is None:
            raise KeyError(path)
    return found


def _member(obj, name: str):
    """(obj, attribute, Type) of the variable called name (case-insensitive) in obj, or None."""
    for st_name, attr, ty, _section in getattr(type(obj), "_VARS_", ()):
        if st_name.upper() == name.upper():
            return obj, attr, ty
    return None


def global_variable(globals_obj, name: str):
    """The global variable called name, or None when the program was not
    loaded with the library that declares it."""
    try:
        holder, attr, _ty = locate(name, (globals_obj,))
    except KeyError:
        return None
    return getattr(holder, attr)


_UNSEEN = object()


def _fields_of(cls) -> dict:
    """StructWriter's table of a struct class, made once per class and kept
    on it (an online change binds the drivers' 385 diagnostic structs of
    the default plant in the scan thread: a table each cost 40 % of the
    swap)."""
    fields = cls.__dict__.get("_writer_fields")
    if fields is None:
        fields = {}
        for st_name, attr, ty, _section in cls._VARS_:
            t = T.resolve(ty)
            fields[st_name.upper()] = (attr, (t.length, t.wide) if isinstance(t, T.StringType) else None)
        cls._writer_fields = fields
    return fields


class StructWriter:
    """Sets the fields of one ST struct instance by their ST names (a
    STRING field cut to its length); does nothing for a None struct."""

    def __init__(self, struct) -> None:
        self._struct = struct
        # field name (upper) -> (attr, (max length, wide) or None)
        self._fields: dict = {} if struct is None else _fields_of(type(struct))
        self._known: dict = {}  # a name as set() was given it -> its entry of _fields (None: no such field)

    def set(self, **values) -> None:
        struct = self._struct
        if struct is None:
            return
        known = self._known
        for name, value in values.items():
            entry = known.get(name, _UNSEEN)
            if entry is _UNSEEN:  # the drivers set the same fields every scan: looked up once by name
                entry = known[name] = self._fields.get(name.upper())
            if entry is None:
                continue
            attr, length = entry
            if length is not None:
                value = cut_string(str(value), *length)  # a WSTRING's length in UTF-16 units
            setattr(struct, attr, value)

    def get(self, name: str):
        entry = self._fields.get(name.upper())
        return None if entry is None else getattr(self._struct, entry[0])
