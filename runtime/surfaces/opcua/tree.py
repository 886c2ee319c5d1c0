"""What the OPC UA server publishes: the variable tree of a loaded engine,
walked once through ``engine/places.py`` (no asyncua here).

    Objects
      Main                    a program instance (an object)
        speed                 a scalar (a variable)
        t                     an FB instance (an object) with its variables
        pair                  a struct (an object) with its fields
        levels                an array of scalars (one array-valued variable)
        axes                  an array of structs: an object per element,
          [1] [2] ...         at most ELEMENT_OBJECTS of them
      Globals                 a folder: the program's globals (not the libraries')

Every variable's NodeId is its ST path as the engine names it
(``ns=2;s=Main.speed``); an object's too (``ns=2;s=Main.t``). A path the
snapshot hub watches is one scalar value: a scalar variable watches itself,
an array variable each of its elements. ``walk`` stops at ``limit`` watched
paths and says how many variables it left out.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

from ...engine.places import Place, Resolver
from ...st import types as T
from ...st.valuejson import SKIPPED_SECTIONS
from .typemap import UaType, ua_type

READER = "opcua"  # the surface's name: its snapshot reader and its permission
#: an array of structs or FB instances shows at most this many elements as objects
ELEMENT_OBJECTS = 100
GLOBALS = "Globals"
GLOBALS_ID = "#Globals"  # not an ST name: a global called Globals keeps its NodeId


@dataclass
class Variable:
    path: str  # the ST path; the NodeId's string
    name: str  # the browse name
    ua: UaType  # of the value, or of each element of an array
    writable: bool = False
    dims: tuple = ()  # an array: the length of each dimension
    elements: tuple = ()  # an array: the element paths, row by row

    @property
    def watched(self) -> tuple:
        return self.elements if self.dims else (self.path,)


@dataclass
class Object:
    node_id: str
    name: str
    type_name: str  # the ST type (the object's description)
    children: list = field(default_factory=list)
    folder: bool = False


@dataclass
class Tree:
    roots: list  # Objects
    variables: list  # every Variable, depth first
    left_out: int = 0  # variables beyond the limit

    @property
    def watched(self) -> list:
        return [p for v in self.variables for p in v.watched]

    @property
    def enums(self) -> dict:
        """The enumeration types the variables use, by name."""
        out: dict = {}
        for v in self.variables:
            if v.ua.enum is not None:
                out.setdefault(v.ua.enum.name, v.ua.enum)
        return out


def published(surfaces, limit: int) -> Tree:
    """The tree of the engine's current program as [opcua] publishes it,
    its writable variables those [opcua] writable names. Called with the
    PLC's surfaces (surfaces/host.py ``Surfaces.call``): from the servers'
    process, it runs in the PLC's and the tree comes back."""
    permission = surfaces.access.permissions.get(READER)
    return walk(surfaces.engine, surfaces.hub.resolver, permission.allows if permission else _never, limit)


def _never(_path: str) -> bool:
    return False


def walk(engine, resolver: Resolver, writable: Callable[[str], bool], limit: int) -> Tree:
    """The program instances and the program's globals of engine (loaded)."""
    walker = _Walker(resolver, writable, limit)
    roots = []
    for name, _info, obj in engine.instances.values():
        roots.append(walker.instance(name, obj))
    globals_ = engine.ns["_G"]
    skip = engine.program.library_globals | getattr(type(globals_), "_HIDDEN_", frozenset())
    folder = Object(GLOBALS_ID, GLOBALS, "global variables", folder=True)
    for st_name, _attr, _ty, section in type(globals_)._VARS_:
        if st_name in skip or section in SKIPPED_SECTIONS:
            continue
        walker.add(folder, resolver.place(st_name), st_name)
    roots.append(folder)
    return Tree(roots, walker.variables, walker.left_out)


class _Walker:
    def __init__(self, resolver: Resolver, writable: Callable[[str], bool], limit: int) -> None:
        self.resolver = resolver
        self.writable = writable
        self.budget = limit
        self.variables: list[Variable] = []
        self.left_out = 0

    def instance(self, name: str, obj) -> Object:
        node = Object(name, name, type(obj).__name__)
        for st_name, _attr, _ty, _section in _own_vars(obj):
            node_place = self.resolver.place(f"{name}.{st_name}")
            self.add(node, node_place, st_name)
        return node

    def add(self, parent: Object, place: Place, name: str) -> None:
        r = T.resolve(place.type)
        scalar = ua_type(r)
        if scalar is not None:
            self._variable(parent, Variable(place.path, name, scalar, self.writable(place.path)))
        elif isinstance(r, T.ArrayType):
            self._array(parent, place, name, r)
        elif isinstance(r, (T.StructType, T.FBType)) and place.parts is not None:
            node = Object(place.path, name, r.name)
            hidden: frozenset = getattr(type(place.get()), "_HIDDEN_", frozenset())
            for part in place.parts().values():
                field_name = part.path.rsplit(".", 1)[-1]
                if field_name not in hidden:
                    self.add(node, part, field_name)
            parent.children.append(node)
        # references, pointers and interfaces have no value of their own to publish

    def _array(self, parent: Object, place: Place, name: str, r: T.ArrayType) -> None:
        elem = ua_type(r.elem)
        if elem is not None and not r.variable_length:
            dims = tuple(hi - lo + 1 for lo, hi in r.dims)
            elements = tuple(_leaves(place))
            variable = Variable(place.path, name, elem, self.writable(place.path), dims, elements)
            self._variable(parent, variable)
            return
        node = Object(place.path, name, r.name)
        assert place.parts is not None
        for i, part in enumerate(place.parts().values()):
            if i == ELEMENT_OBJECTS:
                self.left_out += 1
                break
            self.add(node, part, part.path[len(place.path) :])
        parent.children.append(node)

    def _variable(self, parent: Object, variable: Variable) -> None:
        cost = len(variable.watched)
        if cost > self.budget:
            self.left_out += 1
            return
        self.budget -= cost
        parent.children.append(variable)
        self.variables.append(variable)


def _own_vars(obj) -> list:
    hidden: frozenset = getattr(type(obj), "_HIDDEN_", frozenset())
    return [v for v in type(obj)._VARS_ if v[3] not in SKIPPED_SECTIONS and v[0] not in hidden]


def _leaves(place: Place) -> list:
    """The element paths of an array of scalars, row by row."""
    if place.parts is None:
        return [place.path]
    out: list = []
    for part in place.parts().values():
        out.extend(_leaves(part))
    return out
