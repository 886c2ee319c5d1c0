"""What generated code calls for object-oriented ST (codegen_oop.py):
calls through interfaces, the assignment attempt, __QUERYINTERFACE."""

from __future__ import annotations

from typing import Any

from .. import types as T


def query_interface(obj: Any, name: str) -> Any:
    """The instance obj when its class implements the interface name
    (upper case), else None (IEC 61131-3 ed.3 6.6.6.7: ?= gives NULL)."""
    if obj is not None and name in getattr(type(obj), "_ITFS_", ()):
        return obj
    return None


def query_into(found: Any, ref: Any) -> bool:
    """__QUERYINTERFACE(src, dst): dst designates the instance and the
    result is TRUE when it implements dst's interface; else FALSE and dst
    is left as it was (CODESYS)."""
    if found is None:
        return False
    ref.set(found)
    return True


def fb_init_args(given: dict | None, names: tuple) -> dict:
    """Of the FB_init inputs a declaration gives (by Python name), those
    one FB_init of the chain declares; the others keep their defaults."""
    if not given:
        return {}
    return {k: v for k, v in given.items() if k in names}


def exit_instances(namespace: dict, roots: list, in_copy_code: bool = False) -> None:
    """FB_exit(bInCopyCode := in_copy_code) of every instance reachable from
    roots (program instances, the globals), when the program is taken down
    (FALSE) or replaced by an online change (TRUE): an instance's own before
    its variables', and in a derived block the derived one's before the
    base's (TwinCAT "Behavior with derived function blocks"). Nothing is
    walked unless some block has FB_exit."""
    if not any(isinstance(c, type) and "m_fb_exit" in c.__dict__ for c in namespace.values()):
        return
    seen: set = set()
    todo = list(reversed(roots))
    while todo:
        obj = todo.pop()
        if id(obj) in seen:
            continue
        seen.add(id(obj))
        if isinstance(obj, list):
            todo += reversed(obj)
            continue
        meta = getattr(type(obj), "_VARS_", None)
        if meta is None:
            continue
        for cls in type(obj).__mro__:
            fn = cls.__dict__.get("m_fb_exit")
            if fn is not None:
                fn(obj, in_copy_code)
        inner = []
        for _name, attr, ty, section in meta:
            if section in ("VAR_IN_OUT", "VAR_EXTERNAL") or isinstance(T.resolve(ty), (T.RefType, T.InterfaceType)):
                continue  # a reference to a variable that lives elsewhere
            value = getattr(obj, attr, None)
            if isinstance(value, list) or hasattr(type(value), "_VARS_"):
                inner.append(value)
        todo += reversed(inner)


def reinit_instance(obj: Any) -> bool:
    """FB_reinit() of an instance an online change copied, if its block
    has one: the most derived block's only (a base's runs when that one
    calls SUPER^.FB_reinit(), CODESYS "Method: FB_Init, FB_Reinit, FB_Exit").
    True if there was one."""
    fn = getattr(type(obj), "m_fb_reinit", None)
    if fn is None:
        return False
    fn(obj)
    return True
