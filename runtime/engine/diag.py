"""The engine's side of PLC_DIAG (fblocks/system/plc_diag.st): the global
struct a program reads to see the engine's state. Written only on events
(start, fault, restart), so the scan pays nothing for it."""
from __future__ import annotations

from ..st import types as T
from ..st.loader import locate


class DiagVariable:
    def __init__(self, globals_obj) -> None:
        self._fields: dict = {}  # field name (upper) -> (attr, max length or None)
        try:
            holder, attr, _ty = locate("PLC_DIAG", (globals_obj,))
        except KeyError:  # not loaded with the system library
            self._struct = None
            return
        self._struct = getattr(holder, attr)
        for st_name, attr, ty, _section in type(self._struct)._VARS_:
            t = T.resolve(ty)
            self._fields[st_name.upper()] = (attr, t.length if isinstance(t, T.StringType) else None)

    def set(self, **values) -> None:
        if self._struct is None:
            return
        for name, value in values.items():
            entry = self._fields.get(name.upper())
            if entry is None:
                continue
            attr, length = entry
            if length is not None:
                value = str(value)[:length]
            setattr(self._struct, attr, value)

    def get(self, name: str):
        entry = self._fields.get(name.upper())
        return None if entry is None else getattr(self._struct, entry[0])
