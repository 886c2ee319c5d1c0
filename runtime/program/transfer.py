"""A compiled Program as bytes and back: what an online change's compile
process (engine/compile_process.py) sends to the PLC's process.

    data = dumps(program)        # in the compiling process
    program = loads(data)        # in the PLC's process: no parsing, no compile()

pickle with three rules of our own (reducer_override), so that the Program
read back is the one compile_files would have made in this process:

  * the types and other values that are module globals of softplc
    (types.BOOL, types.LREAL ...) are sent by name and read back as this
    process's own objects: the checker and the generated code compare
    types by identity (eq=False);
  * functions made by a factory (rt_wrap's wrappers, rt_convert's
    converters: closures) are sent as their code (marshal), their module
    and the values they closed over;
  * a source position (ast.Pos, frozen with slots) is made by _pos, and
    every ROUTE_EVERY-th other instance of a softplc class by _new; both
    count towards loads()'s pace, called every PACE_EVERY of them: the
    read-back of the default plant (1.5 MB, some 10,000 positions) is one
    call into the C unpickler of 35-50 ms, which the PLC's process makes
    step by step in the scan's idle (engine/lock_share). (With positions
    alone, its last 8-10 ms, the tables after the generated module's
    code, had no step: a live soak's tick began 8.9 ms late there);
  * code objects (the generated module's, a closure's) are marshal-ed:
    their bytecode as compiled, with its filename and flags, is loaded
    without compiling again.

A Program read back shares nothing with this process but those globals,
so when an online change has replaced it, release() cuts the links that
make its checker's tables one ring (a POU's info -> its tree -> a name ->
the name's symbol -> the POU's info): it is then freed as soon as the
last reference goes, not by a full collection of the garbage collector
(which holds the interpreter lock, and so the scan, for as long as it
walks every object: 240 ms after ten changes of the default plant).
"""

from __future__ import annotations

import copyreg
import importlib
import io
import marshal
import pickle
import sys
import threading
import types
from collections.abc import Callable

from ..st.ast import Pos
from ..st.types import Type

_PROTOCOL = 5
PACE_EVERY = 64  # objects made by _pos or _new between two calls of loads()'s pace
ROUTE_EVERY = 8  # every 8th plain instance of a softplc class is made by _new
FREE_NS_PER_BYTE = 4  # the unpickler's memo freed: about 4 ms per 1.5 MB read (2-core VM), with room

_loading = threading.local()  # pace, count: the loads() under way in this thread


def _module_global(module: str, name: str):
    return getattr(importlib.import_module(module), name)


def _step(now: bool = False) -> None:
    pace = getattr(_loading, "pace", None)
    if pace is not None:
        _loading.count += 1
        if now or _loading.count % PACE_EVERY == 0:
            pace()


def _pos(file, line, col, end_line, end_col) -> Pos:
    _step()
    return Pos(file, line, col, end_line, end_col)


def _new(cls, *args):
    """What pickle's NEWOBJ does (copyreg.__newobj__), a step of loads() too."""
    _step()
    return cls.__new__(cls, *args)


def _code(data: bytes) -> types.CodeType:
    _step(now=len(data) > 16_384)  # a module's code: 1 ms of marshal and more
    return marshal.loads(data)


def _cell(value) -> types.CellType:
    return types.CellType(value)


def _closure(module: str, code: types.CodeType, name: str, qualname: str, defaults, kwdefaults, cells: tuple):
    fn = types.FunctionType(code, vars(importlib.import_module(module)), name, defaults, cells)
    fn.__qualname__ = qualname
    fn.__kwdefaults__ = kwdefaults
    return fn


_SINGLETONS: tuple[tuple, dict] = ((), {})  # (the modules walked, what _singletons() found)


def _singletons() -> dict:
    """id -> (module, name) of every Type that is a global of a loaded
    softplc module; walked again only when another module is loaded (the
    walk of their globals took 4 ms of an online change's teardown, next
    to the scan, every time)."""
    global _SINGLETONS
    modules = tuple(
        (mod_name, mod)
        for mod_name, mod in list(sys.modules.items())
        if mod_name.startswith("softplc.") and mod is not None
    )
    walked, named = _SINGLETONS
    if walked != modules:  # (modules compare by identity)
        named = {}
        for mod_name, mod in modules:
            for name, value in list(vars(mod).items()):
                if isinstance(value, Type) and not name.startswith("__"):
                    named.setdefault(id(value), (mod_name, name))
        _SINGLETONS = (modules, named)
    return named


class _Pickler(pickle.Pickler):
    def __init__(self, file) -> None:
        super().__init__(file, protocol=_PROTOCOL)
        self._named = _singletons()
        self._instances = 0  # plain instances of softplc classes so far

    def reducer_override(self, obj):
        if type(obj) is Pos:  # some 10,000 of them: by the class, not dataclasses' slow __setstate__
            return (_pos, (obj.file, obj.line, obj.col, obj.end_line, obj.end_col))
        if isinstance(obj, Type):
            named = self._named.get(id(obj))
            return (_module_global, named) if named else self._routed(obj)
        if isinstance(obj, types.CodeType):
            return (_code, (marshal.dumps(obj),))
        if isinstance(obj, types.CellType):
            return (_cell, (obj.cell_contents,))
        if isinstance(obj, types.FunctionType) and obj.__closure__ is not None:
            return (
                _closure,
                (
                    obj.__module__,
                    obj.__code__,
                    obj.__name__,
                    obj.__qualname__,
                    obj.__defaults__,
                    obj.__kwdefaults__,
                    obj.__closure__,
                ),
            )
        return self._routed(obj)

    def _routed(self, obj):
        """Every ROUTE_EVERY-th plain instance of a softplc class (its
        class's own __reduce_ex__ is object's): made by _new on the way
        back, pickle's reduction otherwise kept (its state, its items)."""
        cls = type(obj)
        if (
            isinstance(obj, type)
            or not cls.__module__.startswith("softplc.")
            or cls.__reduce_ex__ is not object.__reduce_ex__
            or cls.__reduce__ is not object.__reduce__
        ):
            return NotImplemented
        self._instances += 1
        if self._instances % ROUTE_EVERY:
            return NotImplemented
        reduced = obj.__reduce_ex__(_PROTOCOL)
        if not isinstance(reduced, tuple) or reduced[0] is not copyreg.__newobj__:
            return NotImplemented
        return (_new, *reduced[1:])


def dumps(program) -> bytes:
    """The Program as bytes for loads() in another process of the same softplc."""
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(max(limit, 20_000))  # a deep AST or type graph: pickle recurses per level
    try:
        out = io.BytesIO()
        _Pickler(out).dump(program)
        return out.getvalue()
    finally:
        sys.setrecursionlimit(limit)


def loads(data: bytes, pace: Callable[..., None] | None = None):
    """The Program dumps() made (release() may take it apart once it is
    replaced). pace() is called every PACE_EVERY objects made, and
    pace(room_ns) once before the unpickler is let go: freeing its memo
    (a reference to every object read, 4 ms for the default plant's
    1.5 MB) is one step that cannot be cut, and wants that much time."""
    limit = sys.getrecursionlimit()
    sys.setrecursionlimit(max(limit, 20_000))
    _loading.pace, _loading.count = pace, 0
    try:
        unpickler = pickle.Unpickler(io.BytesIO(data))
        program = unpickler.load()
        if pace is not None:
            pace(len(data) * FREE_NS_PER_BYTE)
        del unpickler
    finally:
        _loading.pace = None
        sys.setrecursionlimit(limit)
    program.read_back = True
    return program


#: a POU info's links into its own tree and to the other POUs' infos
_POU_LINKS = {"node": None, "result": None, "fbtype": None, "fb": None, "base": None, "sfc": None}
_POU_TABLES = ("vars", "actions", "methods", "properties")


def release(program, pace: Callable[[], None] = lambda: None) -> bool:
    """Cut the rings of a Program loads() read back and that nothing runs
    any more (an online change replaced it); a Program of this process's
    own compile is left alone (its libraries' tables are shared with the
    next compile). True when it was cut. pace() is called before each POU
    (the engine's lock_share.pause: while the scan sleeps)."""
    if not getattr(program, "read_back", False):
        return False
    pending = list(program.checked.pous)
    seen: set = set()
    while pending:
        pou = pending.pop()
        if id(pou) in seen:
            continue
        seen.add(id(pou))
        pace()
        for table in _POU_TABLES:
            members = getattr(pou, table)
            pending += [m for m in members.values() if isinstance(m, type(pou))]
            for member in members.values():
                if hasattr(member, "pou"):  # an action
                    member.node = member.pou = None
            setattr(pou, table, {})
        for name, empty in _POU_LINKS.items():
            setattr(pou, name, empty)
    shared = _singletons()
    for ty in program.checked.types.values():
        if isinstance(ty, Type) and hasattr(ty, "pou") and id(ty) not in shared:
            ty.pou = None
    return True


__all__ = ["dumps", "loads", "release"]
