"""Object-oriented ST lookups the checker, the conversions and the code
generator share: members along EXTENDS, the interfaces a block is."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .. import types as T

if TYPE_CHECKING:
    from .symbols import POUInfo

_ACCESS = ("PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL")


def access_of(modifiers: tuple) -> str:
    return next((m for m in modifiers if m in _ACCESS), "PUBLIC")


def is_method_owner(p: POUInfo | None, fb: POUInfo) -> bool:
    """Whether p is fb or a FUNCTION_BLOCK derived from it."""
    while p is not None:
        if p is fb:
            return True
        p = p.base
    return False


def find_method(owner, key: str):
    """The METHOD named key (UPPER) of an FB (inherited too) or an interface."""
    return _find_member(owner, key, "methods")


def find_property(owner, key: str):
    """The PROPERTY named key (UPPER) of an FB (inherited too) or an interface."""
    return _find_member(owner, key, "properties")


def _find_member(owner, key: str, kind: str):
    if isinstance(owner, T.InterfaceType):
        return _itf_member(owner, key, kind)
    p = owner
    while p is not None:
        m = getattr(p, kind).get(key)
        if m is not None:
            return m
        p = p.base
    return None


def _itf_member(itf: T.InterfaceType, key: str, what: str, seen: set | None = None):
    seen = seen if seen is not None else set()
    if id(itf) in seen:
        return None
    seen.add(id(itf))
    m = getattr(itf, what).get(key)
    if m is not None:
        return m
    for b in itf.bases:
        m = _itf_member(b, key, what, seen)
        if m is not None:
            return m
    return None


def all_interfaces(x) -> list:
    """Every interface an FB (with its bases) or interface is one of."""
    out: list = []
    todo = []
    if isinstance(x, T.InterfaceType):
        todo.append(x)
    else:
        p = x
        while p is not None:
            todo += p.interfaces
            p = p.base
    while todo:
        i = todo.pop()
        if i not in out:
            out.append(i)
            todo += i.bases
    return out


def interface_accepts(src: T.Type, itf: T.InterfaceType) -> bool:
    """An FB instance or interface value may be stored into a variable of itf."""
    s = T.resolve(src)
    if isinstance(s, T.FBType):
        return s.pou is not None and itf in all_interfaces(s.pou)
    if isinstance(s, T.InterfaceType):
        return itf in all_interfaces(s)
    return False


def extends_fb(src: T.Type, dst: T.Type) -> bool:
    """src is a FUNCTION_BLOCK type that EXTENDS dst (at any depth): an
    instance of it may stand for one of dst where a reference to dst is
    taken (VAR_IN_OUT, REFERENCE TO, REF_TO, POINTER TO). CODESYS
    "Extension of a Function Block": "an instance of the derived FB can be
    used wherever an instance of the base FB is expected"; calls of
    methods through the reference then run the derived block's overrides."""
    s, d = T.resolve(src), T.resolve(dst)
    if isinstance(s, T.StructType) and isinstance(d, T.StructType):  # STRUCT EXTENDS (CODESYS)
        base = s.base
        while base is not None and base is not d:
            base = base.base
        return base is d
    if not isinstance(s, T.FBType) or not isinstance(d, T.FBType) or s.pou is None or d.pou is None:
        return False
    return s.pou is not d.pou and is_method_owner(s.pou, d.pou)


def fb_hint(src: T.Type, dst: T.Type) -> str | None:
    """The hint of an E020 where one FUNCTION_BLOCK type stands for another
    it does not extend; None when they are not both blocks."""
    s, d = T.resolve(src), T.resolve(dst)
    if not isinstance(s, T.FBType) or not isinstance(d, T.FBType):
        return None
    return f"{s.name} does not EXTEND {d.name}: pass an instance of {d.name} or of a block that EXTENDS it"


def fb_init_inputs(pou: POUInfo | None) -> list:
    """The further inputs of the FB_init methods of a block and its bases
    (after bInitRetains and bInCopyCode), the derived block's first, each
    name once: what a declaration ``fb : FB_X(nStart := 5)`` sets."""
    out: list = []
    seen: set = set()
    p = pou
    while p is not None:
        m = p.methods.get("FB_INIT")
        if m is not None:
            for v in m.params("VAR_INPUT")[2:]:
                if v.name.upper() not in seen:
                    seen.add(v.name.upper())
                    out.append(v)
        p = p.base
    return out


def find_action(pou: POUInfo | None, key: str):
    """The ACTION named key (UPPER) of a PROGRAM or FUNCTION_BLOCK, or one
    it inherits through EXTENDS (an action is code of the block that
    works on its variables, which a derived block has too)."""
    p = pou
    while p is not None:
        a = p.actions.get(key)
        if a is not None:
            return a
        p = p.base
    return None
