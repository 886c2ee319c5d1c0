"""RETAIN and PERSISTENT variables: which ones, their snapshot, the retain
file and the rules that bring them back at a start.

Start modes:

  cold  every variable gets its initial value; nothing is restored.
  warm  RETAIN and PERSISTENT variables get the values saved last, when the
        program's retained layout is unchanged. When the program changed (the
        layout hash differs: a new program version was loaded), PERSISTENT
        variables are restored one by one where the path and the type
        signature still match; RETAIN variables get their initial values.

Which variables are retained (CODESYS semantics):

  * VAR_GLOBAL RETAIN / PERSISTENT variables; path = the name, "G_total";
  * a PROGRAM instance's VAR RETAIN / PERSISTENT (also VAR_INPUT, VAR_OUTPUT,
    VAR_STAT with the qualifier); path = "<instance>.<name>", "Main.count";
  * inside FUNCTION_BLOCK instances that are not retained themselves (a program
    or global variable of an FB type, and recursively through their FB-typed
    variables): the FB's own RETAIN / PERSISTENT variables, in every instance;
    path "Main.motor1.hours". Arrays of FB instances and FB instances inside
    structs are not searched: declare the array (or struct) RETAIN to keep it.

A retained aggregate (ARRAY, STRUCT, FB instance) is retained whole, except
its VAR_IN_OUT / VAR_EXTERNAL / VAR_TEMP members (references to other data,
or nothing between calls), located (AT %...) members (they live in the process
image) and REF_TO / POINTER values (addresses in the memory of the old
process): those keep their initial values. A variable declared RETAIN
PERSISTENT counts as PERSISTENT. A located variable (AT %MW10) is never
retained: its value is the process image's.

Names are case-insensitive in ST, so paths are matched and hashed
case-insensitively and type signatures are upper case: renaming `count` to
`Count` keeps the value.

The retain file (its format, the atomic write, the writer thread) is
engine/retain_file.py.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Callable
from dataclasses import dataclass, field
from operator import attrgetter
from typing import Any

from ..st import types as T
from ..st.rtlib.rtlib import string_length
from .members import own_members, owned
from .values import lone_surrogate, without_lone_surrogates

RETAIN = "RETAIN"
PERSISTENT = "PERSISTENT"

FORMAT = "softplc-retain"
VERSION = 1


# ================================================================ type signatures


def type_signature(t: T.Type) -> str:
    """Canonical text of a type's structure: equal for two programs that
    declare the type the same way (names are upper-cased, as ST ignores case),
    different after any change a saved value could not survive."""
    t = T.resolve(t)
    if isinstance(t, T.ElementaryType):
        return t.name
    if isinstance(t, T.StringType):
        return t.name
    if isinstance(t, T.SubrangeType):
        return f"{t.base.name}({t.lo}..{t.hi})"
    if isinstance(t, T.EnumType):
        values = ",".join(f"{k}:={v}" for k, v in t.values.items())
        name = "" if t.name.startswith("(") else " " + t.name.upper()  # anonymous enum
        return f"ENUM{name}:{t.base.name}({values})"
    if isinstance(t, T.ArrayType):
        dims = ", ".join("*" if d is None else f"{d[0]}..{d[1]}" for d in t.dims)
        return f"ARRAY[{dims}] OF {type_signature(t.elem)}"
    if isinstance(t, T.RefType):
        # The target's name only: a REF_TO value is never saved, and a
        # struct may refer to itself (a linked list) through one.
        return ("POINTER TO " if t.pointer else "REF_TO ") + str(T.resolve(t.target)).upper()
    if isinstance(t, (T.StructType, T.FBType)):
        members = ";".join(f"{name.upper()}:{type_signature(mt)}" for name, _attr, mt in _members(t))
        return f"{t.name.upper()}{{{members}}}"
    return str(t).upper()  # ADR#, NULL; str() is the name (which Type itself does not declare)


def _members(t: T.StructType | T.FBType) -> list:
    """(name, python attribute, type) of the members of a STRUCT or FB type
    that belong to its retained state, in declaration order (members.py's
    rule: a CONSTANT member is the program's, and is not kept)."""
    return own_members(t)


# ================================================================ snapshot codecs
# An encoder turns a live value into JSON-ready data (a deep copy). It is
# built once per variable at plan time so the scan thread only runs tight
# closures. _NO_DATA marks types with nothing to save (references).

_NO_DATA = object()


def _encoder(t: T.Type):
    """None for a scalar (immutable: the value is its own copy), _NO_DATA for
    a type with nothing to save, else a function value -> data."""
    t = T.resolve(t)
    if isinstance(t, T.RefType):
        return _NO_DATA
    if isinstance(t, T.ArrayType):
        elem = _encoder(t.elem)
        if elem is _NO_DATA:
            return _NO_DATA
        return _array_encoder(len(t.dims), elem)
    if isinstance(t, (T.StructType, T.FBType)):
        members = []
        for name, attr, mt in _members(t):
            enc = _encoder(mt)
            if enc is not _NO_DATA:
                members.append((name, attrgetter(attr), enc))
        if not members:
            return _NO_DATA

        def encode_object(obj, members=tuple(members)):
            # declaration order, so the file reads like the declaration
            return {name: (get(obj) if enc is None else enc(get(obj))) for name, get, enc in members}

        return encode_object
    if isinstance(t, (T.ElementaryType, T.StringType, T.EnumType, T.SubrangeType)):
        return None
    return _NO_DATA  # ADR#, NULL: not storable types


def _has_data(t: T.Type) -> bool:
    """Whether values of t have anything to save (not only references)."""
    t = T.resolve(t)
    if isinstance(t, T.ArrayType):
        return _has_data(t.elem)
    if isinstance(t, (T.StructType, T.FBType)):
        return any(_has_data(mt) for _name, _attr, mt in _members(t))
    return isinstance(t, (T.ElementaryType, T.StringType, T.EnumType, T.SubrangeType))


def _array_encoder(ndims: int, elem) -> Callable:
    if ndims == 1:
        if elem is None:
            return list
        return lambda v: [elem(x) for x in v]
    inner = _array_encoder(ndims - 1, elem)
    return lambda v: [inner(row) for row in v]


# ================================================================ restore (decode)


class _BadValue(Exception):
    """A saved value that does not fit its type (a hand-edited file)."""


def _check(t: T.Type, data: Any, where: str, repaired: list | None = None) -> Any:
    """The saved data validated against type t (floats made floats); raises
    _BadValue naming the element. Nothing is written here, so a bad value
    leaves the whole variable untouched. A string holding a lone surrogate
    (which an older softplc let a client write) is restored with U+FFFD in
    its place, the element's path added to repaired: the rest of the text
    is worth keeping, and no STRING may hold the surrogate."""
    t = T.resolve(t)
    if isinstance(t, T.ElementaryType) and t.is_bool:
        if not isinstance(data, bool):
            raise _BadValue(f"{where}: expected TRUE/FALSE, found {_short(data)}")
        return data
    if isinstance(t, T.ElementaryType) and t.is_real:
        if isinstance(data, bool) or not isinstance(data, (int, float)):
            raise _BadValue(f"{where}: expected a number, found {_short(data)}")
        try:
            return float(data)
        except OverflowError:
            raise _BadValue(f"{where}: {_short(data)} is too large for a {t.name}") from None
    if isinstance(t, (T.ElementaryType, T.EnumType, T.SubrangeType)):
        lo, hi = (t.lo, t.hi) if isinstance(t, (T.ElementaryType, T.SubrangeType)) else (t.base.lo, t.base.hi)
        if isinstance(data, bool) or not isinstance(data, int):
            raise _BadValue(f"{where}: expected an integer, found {_short(data)}")
        if lo is not None and hi is not None and not lo <= data <= hi:
            raise _BadValue(f"{where}: {data} is outside {lo}..{hi}")
        return data
    if isinstance(t, T.StringType):
        if not isinstance(data, str):
            raise _BadValue(f"{where}: expected a string, found {_short(data)}")
        if string_length(data, t.wide) > t.length:  # a WSTRING's: UTF-16 units
            raise _BadValue(
                f"{where}: the string is longer than {t.length} {'UTF-16 units' if t.wide else 'characters'}"
            )
        if lone_surrogate(data) is not None:
            data = without_lone_surrogates(data)
            if repaired is not None:
                repaired.append(where)
        return data
    if isinstance(t, T.ArrayType):
        return _check_array(t.dims, t.elem, data, where, repaired)
    if isinstance(t, (T.StructType, T.FBType)):
        if not isinstance(data, dict):
            raise _BadValue(f"{where}: expected an object, found {_short(data)}")
        by_name = {k.upper(): v for k, v in data.items()}
        out = {}
        for name, _attr, mt in _members(t):
            if not _has_data(mt):
                continue
            if name.upper() not in by_name:
                raise _BadValue(f"{where}.{name}: missing")
            out[name.upper()] = _check(mt, by_name[name.upper()], f"{where}.{name}", repaired)
        return out
    raise _BadValue(f"{where}: a {t} cannot be restored")


def _check_array(dims: list, elem: T.Type, data: Any, where: str, repaired: list | None = None) -> list:
    lo, hi = dims[0]
    if not isinstance(data, list) or len(data) != hi - lo + 1:
        raise _BadValue(f"{where}: expected a list of {hi - lo + 1} elements, found {_short(data)}")
    if len(dims) > 1:
        return [_check_array(dims[1:], elem, row, f"{where}[{lo + i}]", repaired) for i, row in enumerate(data)]
    return [_check(elem, x, f"{where}[{lo + i}]", repaired) for i, x in enumerate(data)]


def _short(data: Any) -> str:
    return _clip(json.dumps(data, allow_nan=True, default=str), 40)


def _clip(text: Any, limit: int = 80) -> str:
    # keep log lines readable when a signature or value is large
    text = str(text)
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _apply(t: T.Type, holder: Any, attr: str, data: Any) -> None:
    """holder.attr := checked data. Aggregates are updated in place, so
    references to them (REF, VAR_IN_OUT, cached FB instances) stay valid."""
    rt = T.resolve(t)
    if rt.is_aggregate:
        _apply_into(rt, getattr(holder, attr), data)
    else:
        setattr(holder, attr, data)


def _apply_into(t: T.Type, obj: Any, data: Any) -> None:
    t = T.resolve(t)
    if isinstance(t, T.ArrayType):
        _apply_array(len(t.dims), t.elem, obj, data)
        return
    assert isinstance(t, (T.StructType, T.FBType)), t  # an aggregate (is_aggregate) other than an array
    for name, attr, mt in _members(t):
        if name.upper() in data:
            _apply(mt, obj, attr, data[name.upper()])


def _apply_array(ndims: int, elem: T.Type, live: list, data: list) -> None:
    if ndims > 1:
        for row, drow in zip(live, data):
            _apply_array(ndims - 1, elem, row, drow)
    elif T.resolve(elem).is_aggregate:
        for item, ditem in zip(live, data):
            _apply_into(elem, item, ditem)
    elif _has_data(elem):
        live[:] = data


# ================================================================ the plan


@dataclass(eq=False)
class RetainedVar:
    """One retained variable and where its value lives: getattr(holder, attr)."""

    path: str
    kind: str  # RETAIN or PERSISTENT
    signature: str
    holder: object
    attr: str
    type: T.Type
    encode: Any = field(default=None, repr=False)  # live value -> data (None: a scalar)

    def __post_init__(self) -> None:
        if self.encode is None:
            enc = _encoder(self.type)
            self.encode = None if enc is _NO_DATA else enc


def _kind(sym) -> str | None:
    if sym.persistent:
        return PERSISTENT  # RETAIN PERSISTENT counts as PERSISTENT
    if sym.retain:
        return RETAIN
    return None


def plan_retain(checked, instances: dict, globals_obj) -> list:
    """The retained variables of a loaded program, sorted by path.
    instances: program instance name -> (POUInfo, instance object);
    globals_obj: the loaded module's ``_G``."""
    plan: list[RetainedVar] = []
    for sym in checked.globals:
        _visit(plan, sym.name, sym, globals_obj, set())
    for inst_name, (info, obj) in instances.items():
        for sym in info.vars.values():
            _visit(plan, f"{inst_name}.{sym.name}", sym, obj, set())
    plan.sort(key=lambda rv: rv.path.upper())
    seen: dict = {}
    for rv in plan:
        key = rv.path.upper()
        if key in seen:
            raise ValueError(
                f"two retained variables have the path {rv.path}: rename the program "
                "instance or the global variable so they differ"
            )
        seen[key] = rv
    return plan


def _visit(plan: list, path: str, sym, holder, active: set) -> None:
    if not owned(sym):
        return
    kind = _kind(sym)
    if kind is not None:
        if _has_data(sym.type):  # a REF_TO has nothing to keep
            plan.append(RetainedVar(path, kind, type_signature(sym.type), holder, sym.pyname, sym.type))
        return
    t = T.resolve(sym.type)
    if isinstance(t, T.FBType) and t.pou is not None:
        obj = getattr(holder, sym.pyname, None)
        if obj is None or id(obj) in active:
            return
        active.add(id(obj))
        for inner in t.pou.vars.values():
            _visit(plan, f"{path}.{inner.name}", inner, obj, active)
        active.discard(id(obj))


def layout_hash(plan) -> str:
    """SHA-256 (hex) over the sorted "path kind signature" lines: equal for
    two loads of the same program, different when a retained variable was
    added, removed, renamed, re-typed or changed between RETAIN and
    PERSISTENT."""
    lines = sorted(f"{rv.path.upper()} {rv.kind} {rv.signature}" for rv in plan)
    return hashlib.sha256("\n".join(lines).encode("utf-8")).hexdigest()


def snapshot(plan) -> dict:
    """path -> JSON-ready deep copy of the value (plain lists, dicts and
    scalars; floats exact, inf/nan kept as floats). Runs in the scan thread
    between cycles, so it only copies: the writer thread encodes."""
    out = {}
    for rv in plan:
        v = getattr(rv.holder, rv.attr)
        out[rv.path] = v if rv.encode is None else rv.encode(v)
    return out


@dataclass
class RetainData:
    """What a retain file holds."""

    layout: str
    saved_ns: int
    cycle: int
    vars: dict  # path -> {"kind": str, "type": signature, "value": data}


def capture(plan, saved_ns: int, cycle: int) -> RetainData:
    values = snapshot(plan)
    return RetainData(
        layout_hash(plan),
        int(saved_ns),
        int(cycle),
        {rv.path: {"kind": rv.kind, "type": rv.signature, "value": values[rv.path]} for rv in plan},
    )


@dataclass
class RestoreReport:
    restored: list  # paths
    dropped: list  # (path, reason): retained variables that got their initial values in a warm start
    mode: str
    layout_matched: bool
    #: (path, the strings in it): restored with U+FFFD for a lone surrogate (written by an older softplc)
    repaired: list = field(default_factory=list)


def restore(plan, data: RetainData | None, mode: str) -> RestoreReport:
    """Write saved values into the live instances by the start-mode rules
    (module docstring). In a warm start every planned variable is either in
    ``restored`` or in ``dropped`` with the reason; a cold start lists
    neither (everything is initialised on purpose)."""
    mode = mode.lower()
    if mode not in ("cold", "warm"):
        raise ValueError(f"unknown start mode {mode!r} (use 'cold' or 'warm')")
    matched = data is not None and data.layout == layout_hash(plan)
    report = RestoreReport([], [], mode, matched)
    if mode == "cold":
        return report
    if data is None:
        report.dropped = [(rv.path, "no retain data") for rv in plan]
        return report
    saved = {p.upper(): entry for p, entry in data.vars.items()}
    for rv in plan:
        entry = saved.get(rv.path.upper())
        if not matched and rv.kind == RETAIN:
            report.dropped.append((rv.path, "program changed (RETAIN)"))
            continue
        if entry is None:
            report.dropped.append((rv.path, "not in the file"))
            continue
        if entry.get("type") != rv.signature:
            report.dropped.append(
                (rv.path, f"type changed (saved {_clip(entry.get('type'))}, now {_clip(rv.signature)})")
            )
            continue
        repaired: list = []
        try:
            value = _check(rv.type, entry.get("value"), rv.path, repaired)
        except _BadValue as exc:
            report.dropped.append((rv.path, f"bad value in the file ({exc})"))
            continue
        _apply(rv.type, rv.holder, rv.attr, value)
        report.restored.append(rv.path)
        if repaired:
            report.repaired.append((rv.path, repaired))
    return report
