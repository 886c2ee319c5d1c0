"""The one rule for what an instance owns: the members that a warm start
keeps (retain.py), an online change copies (carry.py) and both compare by
type. A STRUCT's fields; of a program's or FB's variables (and of the
globals) those that are neither another's (VAR_IN_OUT, VAR_EXTERNAL: the
sections of SKIPPED_SECTIONS, and VAR_TEMP), nor a place of the process
image (AT %...), nor a CONSTANT (the program's, whatever an instance did)."""

from __future__ import annotations

from ..st import types as T
from ..st.valuejson import SKIPPED_SECTIONS


def owned(var) -> bool:
    """A variable (a POU's, a global) that its instance owns."""
    return var.section not in SKIPPED_SECTIONS and var.location is None and not var.constant


def own_members(holder_type: T.Type | None, pou=None) -> list:
    """(name, python attribute, type) of the members of a STRUCT or FB type,
    or of a POU (pou=POUInfo), in declaration order."""
    if pou is None and isinstance(holder_type, T.FBType):
        pou = holder_type.pou
    if pou is not None:
        return [(v.name, v.pyname, v.type) for v in pou.vars.values() if owned(v)]
    if isinstance(holder_type, T.StructType):
        return [(f.name, f.pyname, f.type) for f in holder_type.fields.values()]
    return []


def own_globals(checked) -> list:
    """(name, python attribute, type) of the globals the program owns."""
    return [(g.name, g.pyname, g.type) for g in checked.globals if owned(g)]
