"""The units a project is compiled in parts of: each POU (with its methods,
properties and actions), INTERFACE, type, global variable and program
instance of a CONFIGURATION; what each declares, what names it uses, and
where it is (its spans in its file), so that an error is pinned on the unit
it lies in and a unit left out takes the units that name it along.

The units of a parse are numbered in the order of a walk over the parsed
files; a fresh parse of the same texts (libraries.parse_cached) gives the
same numbering, so ``prune`` can leave units out of a new copy.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

from ..st import ast as A

#: kinds of unit that the table counts as POUs
POU_KINDS = ("PROGRAM", "FUNCTION_BLOCK", "FUNCTION", "INTERFACE")
# Fields of AST nodes that hold no names the code uses.
_SKIP = frozenset(("pos", "ty", "const", "sym", "target", "impl", "implicit_ref", "pragmas", "spelling", "name_pos"))


@dataclass
class Unit:
    id: int
    file: str
    kind: str  # a POU kind, INTERFACE, TYPE, VAR_GLOBAL, VAR_BLOCK, CONFIGURATION, INSTANCE
    name: str
    spans: list = field(default_factory=list)  # ((line, col), (end_line, end_col))
    declares: frozenset = frozenset()  # UPPER names
    uses: frozenset = frozenset()  # UPPER names of other declarations it may refer to
    words: frozenset = frozenset()  # UPPER identifiers it holds (which libraries it takes)
    #: the scopes of its variables, innermost last: (spans or None for the
    #: whole unit, UPPER name -> the name of its type as written); a
    #: METHOD's name gives its return type
    scopes: list = field(default_factory=list)
    locals: frozenset = frozenset()  # UPPER names of its own variables (they hide globals)
    #: UPPER name of the POU and of each of its methods -> the types (as
    #: written) of its inputs, in order
    signatures: dict = field(default_factory=dict)
    extends: str | None = None  # the block it EXTENDS, as written
    members: list = field(default_factory=list)  # ids of the units inside it (a block's variables)
    parent: int | None = None  # the unit holding it

    @property
    def is_pou(self) -> bool:
        return self.kind in POU_KINDS

    def holds(self, line: int, col: int) -> bool:
        return any(start <= (line, col) <= end for start, end in self.spans)

    def type_of(self, name: str, line: int, col: int) -> str | None:
        """The type (as written) of the variable name visible at (line,
        col) of the unit: the method's own, else the unit's."""
        key = name.upper()
        found = None
        for spans, types in self.scopes:
            if key in types and (spans is None or any(a <= (line, col) <= b for a, b in spans)):
                found = types[key]  # (scopes go from the outermost in)
        return found

    def declares_variable(self, name: str) -> str | None:
        """The type of a variable name declared anywhere in the unit."""
        key = name.upper()
        return next((types[key] for _spans, types in reversed(self.scopes) if key in types), None)


# What _names does with a value of each type, decided once a type: (what,
# fields), what one of _SKIP_IT, _SEQUENCE, _MAPPING or the node's kind of
# name for the ones that hold one (_NODE for the others)
_SKIP_IT, _SEQUENCE, _MAPPING, _NODE, _NAME, _MEMBER, _TYPE, _ENUM, _POU, _INTERFACE, _CONFIG, _ACTION = range(12)
_KINDS = (
    (A.Name, _NAME),
    (A.Member, _MEMBER),
    (A.NamedType, _TYPE),
    (A.EnumLiteral, _ENUM),
    (A.POU, _POU),
    (A.Interface, _INTERFACE),
    (A.ProgramConfig, _CONFIG),
    (A.Action, _ACTION),
)
_PLANS: dict[type, tuple[int, tuple]] = {}


def _plan(t: type) -> tuple[int, tuple]:
    if issubclass(t, (list, tuple)):
        plan: tuple[int, tuple] = (_SEQUENCE, ())
    elif issubclass(t, dict):
        plan = (_MAPPING, ())
    elif not dataclasses.is_dataclass(t) or issubclass(t, type):
        plan = (_SKIP_IT, ())
    else:
        kind = next((k for cls, k in _KINDS if issubclass(t, cls)), _NODE)
        plan = (kind, tuple(f.name for f in dataclasses.fields(t) if f.name not in _SKIP))
    _PLANS[t] = plan
    return plan


def _names(root: object) -> tuple[set, set]:
    """(identifiers used as names, identifiers used as types or POUs), upper case."""
    names: set = set()
    types: set = set()
    stack = [root]
    plans = _PLANS
    push, pop, extend = stack.append, stack.pop, stack.extend
    while stack:
        n: Any = pop()
        t = type(n)
        plan = plans.get(t) or _plan(t)
        kind = plan[0]
        if kind == _SKIP_IT:
            continue
        if kind == _SEQUENCE:
            extend(n)
            continue
        if kind == _MAPPING:
            extend(n.values())
            continue
        if kind == _NAME:
            names.add(n.name.upper())
            if n.qualifier:
                names.add(n.qualifier.upper())
        elif kind == _MEMBER:
            names.add(n.name.upper())
        elif kind == _TYPE:
            types.update(part.upper() for part in n.name.split("."))
        elif kind == _ENUM:
            if n.type_name:
                types.add(n.type_name.upper())
        elif kind == _POU:
            if n.extends:
                types.add(str(n.extends[0]).upper())
            types.update(str(name).upper() for name, _pos in n.implements)
        elif kind == _INTERFACE:
            types.update(str(name).upper() for name, _pos in n.bases)
        elif kind == _CONFIG:
            types.add(n.type_name.upper())
        elif kind == _ACTION:
            if n.pou_name:
                types.add(n.pou_name.upper())
        for f in plan[1]:
            value = getattr(n, f, None)
            if value is not None and not isinstance(value, (str, int, float, bool)):
                push(value)
    return names, types


def _named(spec: object) -> str | None:
    """The type a declaration names: X of X, ARRAY [..] OF X, POINTER TO X."""
    while isinstance(spec, (A.ArrayTypeSpec, A.RefTypeSpec)):
        spec = spec.elem if isinstance(spec, A.ArrayTypeSpec) else spec.target
    return spec.name if isinstance(spec, A.NamedType) else None


def _typed(blocks: list) -> dict:
    out = {}
    for b in blocks:
        for d in b.decls if isinstance(b, A.VarBlock) else ():
            named = _named(d.type)
            if named is not None:
                out[d.name.upper()] = named
    return out


def _inputs(blocks: list) -> list:
    """The types (as written; '' when not a named type) of the inputs of a POU or method."""
    return [
        _named(d.type) or ""
        for b in blocks
        if isinstance(b, A.VarBlock) and b.kind in ("VAR_INPUT", "VAR_IN_OUT")
        for d in b.decls
    ]


def _scopes(node: object) -> list:
    """(spans, variable -> type) of a declaration: its own variables (and
    its methods' return types), then each method's, property's and
    accessor's."""
    if isinstance(node, A.VarDecl):
        return [(None, _typed([A.VarBlock("VAR_GLOBAL", [node])]))]
    own = _typed(getattr(node, "var_blocks", []))
    if isinstance(node, A.POU) and _named(node.return_type) is not None:
        own[node.name.upper()] = _named(node.return_type)  # F := x sets the result
    inner = []
    for m in getattr(node, "methods", ()):
        if _named(m.return_type) is not None:
            own[m.name.upper()] = _named(m.return_type)
        inner.append(([_span(m.pos)], _typed(m.var_blocks)))
    for prop in getattr(node, "properties", ()):
        if _named(prop.type) is not None:
            own[prop.name.upper()] = _named(prop.type)
        for acc in (prop.getter, prop.setter):
            if acc is not None:
                inner.append(([_span(acc.pos)], _typed(acc.var_blocks)))
    return [(None, own), *inner]


def _locals(node: object) -> set:
    """The variables a POU, method or action declares (they hide globals)."""
    out: set = set()
    stack = [node]
    while stack:
        n = stack.pop()
        if isinstance(n, list):
            stack.extend(n)
        elif isinstance(n, A.VarBlock):
            out.update(d.name.upper() for d in n.decls)
        elif isinstance(n, (A.POU, A.Method, A.Property)):
            stack.extend([getattr(n, "var_blocks", []), getattr(n, "methods", []), getattr(n, "properties", [])])
            for acc in (getattr(n, "getter", None), getattr(n, "setter", None)):
                if acc is not None:
                    stack.append(acc)
    return out


def _span(pos: A.Pos) -> tuple:
    end = (pos.end_line, pos.end_col) if pos.end_line else (pos.line, 10**9)
    return ((pos.line, pos.col), end)


def _spans_of(decl: object) -> list:
    spans = [_span(decl.pos)]  # type: ignore[attr-defined]
    for part in (*getattr(decl, "methods", ()), *getattr(decl, "properties", ()), *getattr(decl, "actions", ())):
        spans.append(_span(part.pos))
    return spans


class Units:
    """The units of a project's parsed files (file -> its SourceFiles)."""

    def __init__(self, parsed: dict) -> None:
        self.all: list[Unit] = []
        self.of_key: dict[tuple, int] = {}  # (file, view, decl[, part ...]) -> unit id
        self.by_file: dict[str, list[Unit]] = {}
        pous: dict[str, int] = {}
        actions: list = []
        for file, views in parsed.items():
            self.by_file.setdefault(file, [])
            for vi, sf in enumerate(views):
                for di, decl in enumerate(sf.decls):
                    key = (file, vi, di)
                    if isinstance(decl, A.Action) and decl.pou_name:
                        actions.append((key, decl))
                    elif isinstance(decl, A.VarBlock):
                        self._block(key, decl)
                    elif isinstance(decl, A.Configuration):
                        self._configuration(key, decl)
                    elif isinstance(decl, (A.POU, A.Interface, A.TypeDecl)):
                        u = self._decl(key, decl)
                        if isinstance(decl, A.POU):
                            pous.setdefault(decl.name.upper(), u.id)
        for key, action in actions:  # ACTION Pou.Name: belongs to its POU
            uid = pous.get(action.pou_name.upper())
            if uid is None:
                uid = self._new(key[0], "ACTION", f"{action.pou_name}.{action.name}", action).id
            unit = self.all[uid]
            unit.spans.append(_span(action.pos))
            names, types = _names(action)
            unit.uses = unit.uses | (names - unit.locals) | types
            unit.words = unit.words | names | types
            self.of_key[key] = uid

    def _new(self, file: str, kind: str, name: str, node: object, parent: int | None = None) -> Unit:
        names, types = _names(node)
        local = _locals(node) if isinstance(node, A.POU) else set()
        u = Unit(
            len(self.all),
            file,
            kind,
            name,
            _spans_of(node),
            words=frozenset(names | types),
            uses=frozenset((names - local) | types),
            scopes=_scopes(node),
            locals=frozenset(local),
            parent=parent,
        )
        self.all.append(u)
        self.by_file[file].append(u)
        return u

    def _decl(self, key: tuple, decl) -> Unit:
        kind = decl.kind if isinstance(decl, A.POU) else ("INTERFACE" if isinstance(decl, A.Interface) else "TYPE")
        u = self._new(key[0], kind, decl.name, decl)
        declared = {decl.name.upper()}
        if isinstance(decl, A.TypeDecl) and isinstance(decl.spec, A.EnumTypeSpec):
            declared.update(str(v[0]).upper() for v in decl.spec.values if isinstance(v, tuple) and v)
        u.declares = frozenset(declared)
        u.uses = u.uses - declared
        if isinstance(decl, A.POU):
            u.extends = str(decl.extends[0]) if decl.extends else None
            u.signatures = {decl.name.upper(): _inputs(decl.var_blocks)}
            u.signatures.update((m.name.upper(), _inputs(m.var_blocks)) for m in decl.methods)
        self.of_key[key] = u.id
        return u

    def _block(self, key: tuple, block: A.VarBlock) -> None:
        """A global variable list: each variable a unit, inside the block's."""
        holder = self._new(key[0], "VAR_BLOCK", block.kind, A.VarBlock(block.kind, [], pos=block.pos))
        self.of_key[key] = holder.id
        for i, d in enumerate(block.decls):
            u = self._new(key[0], "VAR_GLOBAL", d.name, d, parent=holder.id)
            u.declares = frozenset((d.name.upper(),))
            holder.members.append(u.id)
            self.of_key[(*key, i)] = u.id

    def _configuration(self, key: tuple, conf: A.Configuration) -> None:
        """A CONFIGURATION, and each program instance in it a unit of its own."""
        u = self._new(key[0], "CONFIGURATION", conf.name, A.Configuration(conf.name, conf.var_blocks, [], pos=conf.pos))
        declared = {conf.name.upper()}
        for block in conf.var_blocks:
            declared.update(d.name.upper() for d in block.decls)
        for res in conf.resources:
            for block in res.var_blocks:
                declared.update(d.name.upper() for d in block.decls)
        u.declares = frozenset(declared)
        self.of_key[key] = u.id
        for ri, res in enumerate(conf.resources):
            for pi, prog in enumerate(res.programs):
                inst = self._new(key[0], "INSTANCE", prog.name, prog, parent=u.id)
                u.members.append(inst.id)
                self.of_key[(*key, ri, pi)] = inst.id

    # ---------------------------------------------------------------- queries

    def hit(self, file: str, line: int, col: int) -> Unit | None:
        """The innermost unit of file whose spans hold (line, col)."""
        best = None
        for u in self.by_file.get(file, ()):
            if u.holds(line, col) and (best is None or _size(u) < _size(best)):
                best = u
        return best

    def pous(self, file: str) -> list[Unit]:
        return [u for u in self.by_file.get(file, ()) if u.is_pou]


def _size(u: Unit) -> int:
    (l1, _c1), (l2, _c2) = u.spans[0]
    return l2 - l1


def prune(parsed: dict, units: Units, dropped: set) -> list:
    """The SourceFiles of a fresh parse (file -> views, numbered as when
    units was made) without the dropped units."""
    out = []
    for file, views in parsed.items():
        for vi, sf in enumerate(views):
            kept = []
            for di, decl in enumerate(sf.decls):
                uid = units.of_key.get((file, vi, di))
                if uid is not None and uid in dropped:
                    continue
                if isinstance(decl, A.VarBlock):
                    decl.decls = [d for i, d in enumerate(decl.decls) if _kept(units, dropped, file, vi, di, i)]
                elif isinstance(decl, A.Configuration):
                    for ri, res in enumerate(decl.resources):
                        programs = enumerate(res.programs)
                        res.programs = [p for pi, p in programs if _kept(units, dropped, file, vi, di, ri, pi)]
                kept.append(decl)
            sf.decls = kept
            out.append(sf)
    return out


def _kept(units: Units, dropped: set, *key) -> bool:
    return units.of_key.get(key) not in dropped
