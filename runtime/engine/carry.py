"""Carrying the running values into a newly compiled program (online
change): variable by variable, matched by name, by CODESYS's online-change
rules.

  * a variable that still exists with the same type keeps its value: per
    program instance, per global, and recursively inside function block
    instances and structs (a block or struct that gained, lost or re-typed
    members keeps the others);
  * an array keeps its elements when the element type is unchanged; when its
    bounds changed, the elements whose indices are in both declarations keep
    their values and the others get their initial values (the copy code
    copies what both layouts hold);
  * a new variable has its initial value; a variable whose type changed is
    reset to its initial value; a removed one is dropped;
  * constants, located variables (AT %...: their value is the process
    image's, which an online change leaves as it is), VAR_IN_OUT,
    VAR_EXTERNAL and VAR_TEMP are not carried (they are no state of their
    own);
  * a reference (REF_TO, an interface variable) designates the new copy of
    what it designated when that was carried, else it is reset (CODESYS
    adjusts interfaces; a pointer has to be assigned again).

Names are compared case-insensitively and types by their structure
(retain.type_signature), as the retain file does. The report gives ST
paths: a variable carried whole is one path, a changed block or struct is
reported member by member.
"""

from __future__ import annotations

import operator
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from ..st import types as T
from ..st.rtlib import refs, rt_sfc
from ..st.values import assign_into
from .members import own_globals, own_members
from .retain import type_signature

_SFC_SLOT = "_sfc"  # st/codegen/codegen_sfc.py: the action control blocks of an SFC POU


@dataclass
class Carried:
    """What carrying the values did, by ST path."""

    kept: list = field(default_factory=list)  # paths whose values were carried over
    initialised: list = field(default_factory=list)  # new variables: their initial values
    reset: list = field(default_factory=list)  # (path, why): re-typed, or a reference not carried
    dropped: list = field(default_factory=list)  # variables the new program no longer has
    notes: list = field(default_factory=list)  # array bounds changed, SFC states reset ...


def members(holder_type: T.Type | None, pou=None) -> dict:
    """UPPER name -> (name, python attribute, type) of the carried members
    of an FB or struct type, or of a POU (pou=POUInfo): members.own_members."""
    return {m[0].upper(): m for m in own_members(holder_type, pou)}


def global_members(checked) -> dict:
    return {m[0].upper(): m for m in own_globals(checked)}


class Carry:
    """One online change's copy: call members() for the globals and every
    program instance, then finish(). moved maps id(old object) to the new
    object that took its values (for references); copied lists the new
    FB instances that got values copied (their FB_reinit runs after)."""

    def __init__(self, quiet: frozenset = frozenset()) -> None:
        self.out = Carried()
        self.moved: dict[int, Any] = {}
        self.copied: list = []
        self._refs: list = []  # (path, type, old value, new holder, attribute)
        self._quiet_names = quiet  # UPPER paths carried but not reported (the libraries' globals)
        self._quiet = 0
        # what depends on the types only, worked out once per type (an array of 1,000 blocks
        # compares their types once, not 1,000 times): id -> (the type, its value)
        self._signatures: dict[int, tuple] = {}
        self._members: dict[int, tuple] = {}
        self._plans: dict[tuple, tuple] = {}  # (id(old type), id(new type)) -> (the types, their plan)

    def signature(self, t: T.Type) -> str:
        """type_signature(t), once per type object."""
        got = self._signatures.get(id(t))
        if got is None:
            got = self._signatures[id(t)] = (t, type_signature(t))
        return got[1]

    def same(self, ro: T.Type, rn: T.Type) -> bool:
        return ro is rn or self.signature(ro) == self.signature(rn)

    def members_of(self, t: T.Type) -> dict:
        """members(t), once per type object."""
        got = self._members.get(id(t))
        if got is None:
            got = self._members[id(t)] = (t, members(t))
        return got[1]

    def prepare(self, old_members: dict, new_members: dict) -> None:
        """Work out beforehand, off the scan thread, what depends on the
        types only (signatures, members, the plans of aggregates of the same
        type) for the members of the same name; members() then finds it
        made. The swap of the default plant spends half of its time in the
        scan thread on this."""
        pending = [(old_members, new_members)]
        seen: set = set()
        while pending:
            olds, news = pending.pop()
            for key, (_name, _attr, ty) in news.items():
                old = olds.get(key)
                if old is None:
                    continue
                ro, rn = T.resolve(old[2]), T.resolve(ty)
                while isinstance(ro, T.ArrayType) and isinstance(rn, T.ArrayType):
                    ro, rn = T.resolve(ro.elem), T.resolve(rn.elem)
                if (id(ro), id(rn)) in seen:
                    continue
                seen.add((id(ro), id(rn)))
                if self.same(ro, rn) and type(ro) is type(rn) and rn.is_aggregate:
                    self.plan(ro, rn)
                if isinstance(rn, (T.FBType, T.StructType)) and type(ro) is type(rn):
                    pending.append((self.members_of(ro), self.members_of(rn)))

    # ------------------------------------------------------------ reporting

    def _add(self, kind: str, item) -> None:
        if not self._quiet:
            getattr(self.out, kind).append(item)

    def _mark(self) -> tuple:
        o = self.out
        return len(o.kept), len(o.initialised), len(o.reset), len(o.dropped)

    def _collapse(self, path: str, mark: tuple) -> None:
        """Only kept paths since mark: the aggregate at path is reported as one."""
        now = self._mark()
        if now[1:] == mark[1:] and not self._quiet:
            del self.out.kept[mark[0] :]
            self.out.kept.append(path)

    # ------------------------------------------------------------ carrying

    def members(self, prefix: str, old_members: dict, new_members: dict, old_obj, new_obj) -> None:
        """Every member of new_obj from old_obj's member of the same name."""
        for key, (name, attr, ty) in new_members.items():
            path = f"{prefix}.{name}" if prefix else name
            quiet = path.upper() in self._quiet_names
            self._quiet += quiet
            old = old_members.get(key)
            if old is None:
                self._add("initialised", path)
            else:
                self.value(path, old[2], ty, getattr(old_obj, old[1], None), new_obj, attr)
            self._quiet -= quiet
        for key, (name, _attr, _ty) in old_members.items():
            if key not in new_members:
                path = f"{prefix}.{name}" if prefix else name
                if path.upper() not in self._quiet_names:
                    self._add("dropped", path)
        self.sfc(prefix, old_obj, new_obj)

    def value(self, path: str, old_t: T.Type, new_t: T.Type, old_value, holder, attr: str) -> None:
        """holder.attr (the new program's) := old_value, by the rules."""
        ro, rn = T.resolve(old_t), T.resolve(new_t)
        same = self.same(ro, rn)
        if isinstance(rn, (T.RefType, T.InterfaceType)):
            if same:
                self._refs.append((path, rn, old_value, holder, attr))
            else:
                self._add("reset", (path, _changed(ro, rn)))
            return
        if rn.is_aggregate:
            if not self.into(path, ro, rn, old_value, getattr(holder, attr)):
                self._add("reset", (path, _changed(ro, rn)))
            return
        if same:
            setattr(holder, attr, old_value)
            self._add("kept", path)
        else:
            self._add("reset", (path, _changed(ro, rn)))

    def into(self, path: str, ro: T.Type, rn: T.Type, old, live) -> bool:
        """Copy the aggregate old into live (the new object) in place; False
        when the types are too different (a reset)."""
        if old is None or live is None:
            return False
        same = self.same(ro, rn)
        if same and type(ro) is type(rn):  # the common case: copied by a plan made once per type
            plan = self.plan(ro, rn)
            if plan is not None:
                plan(path, old, live)
                self._add("kept", path)
                return True
        if isinstance(live, (rt_sfc.Step, rt_sfc.ActionFlags)):  # SFC flags: X, T and the step's start
            if not same:
                return False
            live._assign(old)
            self._add("kept", path)
            return True
        if isinstance(rn, (T.FBType, T.StructType)):
            if type(ro) is not type(rn) or ro.name.upper() != rn.name.upper():
                return False  # another block or struct: a new variable of the same name
            self.moved[id(old)] = live
            new_members, old_members = self.members_of(rn), self.members_of(ro)
            if not new_members and not old_members:  # a block with no ST declaration of its own
                if not same:
                    return False
                assign_into(live, old)
                self._add("kept", path)
                return True
            mark = self._mark()
            self.members(path, old_members, new_members, old, live)
            if isinstance(rn, T.FBType):
                self.copied.append(live)
            self._collapse(path, mark)
            return True
        if isinstance(rn, T.ArrayType) and isinstance(ro, T.ArrayType):
            return self.array(path, ro, rn, old, live)
        return False

    def array(self, path: str, ro: T.ArrayType, rn: T.ArrayType, old: list, live: list) -> bool:
        if len(ro.dims) != len(rn.dims) or None in ro.dims or None in rn.dims:
            return False
        eo, en = T.resolve(ro.elem), T.resolve(rn.elem)
        same_elem = self.same(eo, en)
        if isinstance(en, (T.FBType, T.StructType)):
            if type(eo) is not type(en) or eo.name.upper() != en.name.upper():
                return False
        elif not same_elem or isinstance(en, (T.RefType, T.InterfaceType)):
            return False  # another element type; references in arrays are not followed
        if ro.dims == rn.dims:
            self.moved[id(old)] = live
        self._quiet += 1  # elements are not listed one by one
        try:
            self._rows(path, ro.dims, rn.dims, eo, en, old, live)
        finally:
            self._quiet -= 1
        self._add("kept", path)
        if not same_elem:
            self._add("notes", f"{path}: the elements' type {en.name} changed: their members are carried by name")
        if ro.dims != rn.dims:
            both = ", ".join(f"{max(a[0], b[0])}..{min(a[1], b[1])}" for a, b in zip(ro.dims, rn.dims))
            bounds = f"{_dims(ro.dims)} -> {_dims(rn.dims)}"
            self._add("notes", f"{path}: bounds {bounds}: elements [{both}] kept, the others initialised")
        return True

    def _rows(self, path: str, odims: list, ndims: list, eo: T.Type, en: T.Type, old: list, live: list) -> None:
        (olo, ohi), (nlo, nhi) = odims[0], ndims[0]
        for i in range(max(olo, nlo), min(ohi, nhi) + 1):
            o, n = old[i - olo], i - nlo
            if len(odims) > 1:
                self._rows(f"{path}[{i}]", odims[1:], ndims[1:], eo, en, o, live[n])
            elif en.is_aggregate:
                self.into(f"{path}[{i}]", eo, en, o, live[n])
            else:
                live[n] = o

    # ------------------------------------------------------------ plans: aggregates of the same type

    def plan(self, ro: T.Type, rn: T.Type) -> Callable[[str, Any, Any], None] | None:
        """copy(path, old, live) for aggregates of two types of the same
        signature, made once per pair of types: the members' attributes are
        listed once, the plain ones copied with one attrgetter per object.
        It does what the rules above do member by member (references last,
        FB_reinit, an SFC's state), and reports the aggregate as one kept
        path, as they do. None: no plan (the rules go member by member)."""
        key = (id(ro), id(rn))
        got = self._plans.get(key)
        if got is None:
            got = self._plans[key] = (ro, rn, self._make_plan(ro, rn))
        return got[2]

    def _make_plan(self, ro: T.Type, rn: T.Type) -> Callable[[str, Any, Any], None] | None:
        if rn is rt_sfc.STEP_TYPE or rn is rt_sfc.ACTION_TYPE:
            return lambda _path, old, live: live._assign(old)
        if isinstance(ro, T.ArrayType) and isinstance(rn, T.ArrayType):
            return self._array_plan(ro, rn)
        if not isinstance(ro, (T.FBType, T.StructType)) or not isinstance(rn, (T.FBType, T.StructType)):
            return None
        om, nm = self.members_of(ro), self.members_of(rn)
        if om.keys() != nm.keys():  # a member constant in one and not in the other
            return None
        if not nm:  # a block with no ST declaration of its own
            return lambda _path, old, live: assign_into(live, old)
        plain: list = []  # (old attribute, new attribute)
        deep: list = []  # (name, old attribute, new attribute, plan)
        refs: list = []  # (name, old attribute, new attribute, type)
        for key, (name, attr, ty) in nm.items():
            _oname, oattr, oty = om[key]
            r, o = T.resolve(ty), T.resolve(oty)
            if isinstance(r, (T.RefType, T.InterfaceType)):
                refs.append((name, oattr, attr, r))
            elif r.is_aggregate:
                sub = self.plan(o, r)
                if sub is None:
                    return None
                deep.append((name, oattr, attr, sub))
            else:
                plain.append((oattr, attr))
        read = operator.attrgetter(*(o for o, _n in plain)) if plain else None
        targets = [n for _o, n in plain]
        block = isinstance(rn, T.FBType)

        def copy(path: str, old: Any, live: Any) -> None:
            self.moved[id(old)] = live
            if read is not None:
                values = read(old)
                if len(targets) == 1:
                    setattr(live, targets[0], values)
                else:
                    for attr, value in zip(targets, values):
                        setattr(live, attr, value)
            for name, oattr, attr, sub in deep:
                o, n = getattr(old, oattr, None), getattr(live, attr, None)
                if o is None or n is None:
                    self._add("reset", (f"{path}.{name}", "not there to carry"))
                else:
                    sub(f"{path}.{name}", o, n)
            for name, oattr, attr, r in refs:
                self._refs.append((f"{path}.{name}", r, getattr(old, oattr, None), live, attr))
            if block:
                self.copied.append(live)
            self.sfc(path, old, live)

        return copy

    def _array_plan(self, ro: T.ArrayType, rn: T.ArrayType) -> Callable[[str, Any, Any], None] | None:
        en = T.resolve(rn.elem)
        if None in rn.dims or isinstance(en, (T.RefType, T.InterfaceType)):
            return None  # references in arrays are not followed: the rules reset them
        sub = self.plan(T.resolve(ro.elem), en) if en.is_aggregate else None
        if en.is_aggregate and sub is None:
            return None
        depth = len(rn.dims)

        def copy(path: str, old: list, live: list) -> None:
            self.moved[id(old)] = live
            self._quiet += 1  # elements are not listed one by one
            try:
                _copy_rows(path, old, live, depth, sub)
            finally:
                self._quiet -= 1

        return copy

    def sfc(self, path: str, old_obj, new_obj) -> None:
        """The action control blocks of an SFC POU's instance, when its network is unchanged."""
        old, new = getattr(old_obj, _SFC_SLOT, None), getattr(new_obj, _SFC_SLOT, None)
        if old is None or new is None:
            return
        o, n = old.net, new.net
        if (o.transitions, o.assocs, o.n_actions) == (n.transitions, n.assocs, n.n_actions):
            new._assign(old)
        else:
            self._add("notes", f"{path}: the SFC network changed: its action control states start afresh")

    # ------------------------------------------------------------ references

    def finish(self) -> Carried:
        """References last, when every object they may designate has its new copy."""
        for path, rn, value, holder, attr in self._refs:
            new = self._moved_ref(rn, value)
            if new is _GONE:
                self._add("reset", (path, "a reference to something that was not carried over: initialised"))
            else:
                setattr(holder, attr, new)
                self._add("kept", path)
        self._refs.clear()
        self._plans.clear()  # their closures hold this Carry: a ring that only a collection would free
        return self.out

    def _moved_ref(self, rn: T.Type, value):
        if value is None or isinstance(value, (int, refs.AccessorRef)):  # NULL / 0, or a direct address
            return value
        if isinstance(rn, T.InterfaceType):
            return self.moved.get(id(value), _GONE)
        if isinstance(value, refs.AttrRef):
            target = self.moved.get(id(value.obj))
            if target is not None and hasattr(target, value.attr):
                return refs.AttrRef(target, value.attr)
        elif isinstance(value, refs.ItemRef):
            target = self.moved.get(id(value.seq))
            if target is not None:
                return refs.ItemRef(target, value.index)
        elif hasattr(type(value), "_VARS_"):  # a REFERENCE TO an instance held as the object
            return self.moved.get(id(value), _GONE)
        return _GONE


_GONE = object()


def _copy_rows(path: str, old: list, live: list, depth: int, sub) -> None:
    """An array of depth dimensions copied element by element (sub: an
    element's plan, None for plain values). A function of the module, not a
    closure that calls itself: that would be a ring holding the Carry."""
    if depth > 1:
        for o, n in zip(old, live):
            _copy_rows(path, o, n, depth - 1, sub)
    elif sub is None:
        live[:] = old
    else:
        for o, n in zip(old, live):
            sub(path, o, n)


def _changed(ro: T.Type, rn: T.Type) -> str:
    return f"type changed ({_short(type_signature(ro))} -> {_short(type_signature(rn))})"


def _short(text: str, limit: int = 40) -> str:
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _dims(dims: list) -> str:
    return "[" + ", ".join(f"{lo}..{hi}" for lo, hi in dims) + "]"
