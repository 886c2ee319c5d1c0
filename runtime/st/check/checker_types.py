"""The checker's declared types: collecting names, resolving types as written.

The first pass collects every POU and TYPE name (a name declared twice is
E011); type_of resolves a type as written: named types, STRING[n], ARRAY,
subranges, REF_TO, and the STRUCT and enumeration declarations.
"""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from ..limits import MAX_STRING_LENGTH, MAX_TYPE_NESTING, MAX_VAR_ELEMENTS
from ..profile import names_where
from ..syntax.pragmas import has_attribute
from .checker_base import CheckerBase, Scope
from .checker_refs import spec_kind
from .symbols import POUInfo, pyname


class TypeChecks(CheckerBase):
    """Collecting declarations and resolving types."""

    def _collect(self, sf: A.SourceFile) -> None:
        library = sf.path in self.library_files
        for decl in sf.decls:
            if isinstance(decl, A.TypeDecl):
                key = decl.name.upper()
                if self._clash(key, decl.name, decl.pos):
                    continue
                self.type_decls[key] = decl
            elif isinstance(decl, A.POU):
                key = decl.name.upper()
                if self._clash(key, decl.name, decl.pos):
                    continue
                info = POUInfo(
                    decl.name,
                    decl.kind,
                    decl,
                    pyname({"PROGRAM": "P_", "FUNCTION": "F_", "FUNCTION_BLOCK": "FB_"}[decl.kind], decl.name),
                    library=library,
                )
                if decl.kind != "FUNCTION":
                    info.fbtype = T.FBType(decl.name, info)
                if library and key == "F_TRIG" and self.profile.f_trig_first_call_edge:
                    _memory_starts_false(decl)
                self.pous[key] = info
            elif isinstance(decl, A.Interface):
                self._collect_interface(decl, library)

    def _clash(self, key: str, name: str, pos: A.Pos) -> bool:
        if key in T.ELEMENTARY or key in ("STRING", "WSTRING") or key in T.GENERICS:
            self.d.error("E011", f"'{name}' is the name of an elementary type", pos, "choose another name")
            return True
        other = self.type_decls.get(key) or self.pous.get(key)
        if other is not None:
            opos = other.pos if isinstance(other, A.Node) else other.node.pos
            self.d.error("E011", f"'{name}' is declared twice", pos, f"the first declaration is at {opos}")
            return True
        return False

    def _resolve_named_type(self, key: str, pos: A.Pos) -> T.Type | None:
        if key in self.types:
            return self.types[key]
        decl = self.type_decls.get(key)
        if decl is None:
            return None
        if key in self._resolving:
            chain = list(self._resolving)
            names = [self._resolving[k] for k in chain[chain.index(key) :]] + [decl.name]
            self.d.error(
                "E012",
                f"type '{decl.name}' is defined in terms of itself: {' -> '.join(names)}",
                decl.pos,
                "a type cannot contain itself; use REF_TO for recursive structures",
            )
            return None
        if len(self._resolving) >= MAX_TYPE_NESTING:  # run() resolves what a type holds first: only
            self._nested_too_deeply(key, decl, MAX_TYPE_NESTING + 1, decl.spec)  # a chain of CODESYS EXTENDS
            return None
        self._resolving[key] = decl.name
        try:
            spec = decl.spec
            if isinstance(spec, A.StructTypeSpec):
                st = T.StructType(decl.name, pyclass=pyname("S_", decl.name))
                if spec.extends is not None:
                    self._struct_base(st, spec.extends)
                self.types[key] = st  # before fields: REF_TO self is allowed
                for m in spec.members:
                    fkey = m.name.upper()
                    if fkey in st.fields:
                        self.d.error("E011", f"field '{m.name}' is declared twice", m.pos)
                        continue
                    fty = self.type_of(m.type)
                    depth = 1 + self._nesting(fty)
                    if depth > MAX_TYPE_NESTING:  # the field is dropped: its type is reported
                        self._nested_too_deeply(key, decl, depth, m.type)
                        fty = None
                    self._depth[id(st)] = max(self._depth.get(id(st), 1), depth)
                    # an unknown field type (reported, E012) stays None: uses of the field report no more
                    st.fields[fkey] = T.StructField(
                        m.name,
                        fty,  # type: ignore[arg-type]
                        m.init,
                        pyname("f_", m.name),
                    )
                self.structs.append(st)
                ty: T.Type = st
            elif isinstance(spec, A.EnumTypeSpec):
                ty = self._enum_type(decl.name, spec)
                ty.qualified_only = has_attribute(decl, "qualified_only")
                ty.strict = has_attribute(decl, "strict")
                ty.to_string = has_attribute(decl, "to_string")
            else:
                target = self.type_of(spec)
                if target is None:
                    return None
                ty = T.AliasType(decl.name, target)
                depth = self._nesting(ty)
                if depth > MAX_TYPE_NESTING:
                    self._nested_too_deeply(key, decl, depth, spec)
                    return None
            self.types[key] = ty
            if isinstance(ty, T.EnumType) and isinstance(decl.init, A.Name) and decl.init.name.upper() in ty.values:
                # its own value, written bare in its TYPE (`(NONE, ...) := NONE;`): CODESYS and
                # TwinCAT take it there even when the enumeration is qualified_only
                decl.init = A.EnumLiteral(decl.name, decl.init.name, pos=decl.init.pos)
            if decl.init is not None:
                plan = self.init_value(ty, decl.init, Scope(None), decl.name)
                if isinstance(ty, T.EnumType):
                    ty.default = plan
                elif isinstance(ty, T.AliasType):
                    ty.init_value = plan
                else:
                    self.d.error("E024", "a STRUCT takes its initial values in its fields", decl.init.pos)
            return ty
        finally:
            self._resolving.pop(key, None)

    def _nesting(self, t: T.Type | None) -> int:
        """How deep the type t nests: 1 for a STRUCT of elementary fields,
        1 more for each STRUCT or ARRAY around it (without recursion)."""
        d = 0
        while t is not None:
            if isinstance(t, T.AliasType):
                t = t.target
            elif isinstance(t, T.ArrayType):
                d, t = d + 1, t.elem
            elif isinstance(t, T.StructType):
                return d + self._depth.get(id(t), 1)
            else:
                break
        return d

    def _nested_too_deeply(self, key: str, decl: A.TypeDecl, depth: int, spec: A.TypeSpec) -> None:
        """E006 at the first type past MAX_TYPE_NESTING; a type holding one
        already reported (spec: what it holds) is wrong without more errors."""
        self._too_deep.add(key)
        self.types.setdefault(key, None)  # a STRUCT stays, without the field; any other type is unknown
        if self._too_deep.intersection(stored_names(spec)):
            return
        self.d.error(
            "E006",
            f"type '{decl.name}' is nested too deeply: {depth} levels of STRUCTs and ARRAYs, "
            f"more than {MAX_TYPE_NESTING}",
            decl.pos,
            "flatten the data: fewer STRUCTs inside STRUCTs, an ARRAY with more dimensions",
        )

    def type_order(self) -> list:
        """The declared types, each after the types it holds (a field's, an
        element's, a base's type), so that resolving one recurses no deeper
        than its own declaration, however deep the types nest. A type that
        reaches a cycle keeps its place in the declarations (the cycle is
        reported from where it is first met), after the others."""
        order: list = []
        seen: set = set()
        cyclic: set = set()
        for root in self.type_decls:
            if root in seen:
                continue
            seen.add(root)
            stack = [(root, iter(stored_names(self.type_decls[root].spec)))]
            on_stack = {root}
            while stack:
                key, deps = stack[-1]
                dep = next(
                    (d for d in deps if d in self.type_decls and (d not in seen or d in cyclic or d in on_stack)), None
                )
                if dep is None:
                    if key not in cyclic:
                        order.append(key)
                    on_stack.discard(key)
                    stack.pop()
                elif dep in on_stack or dep in cyclic:  # a cycle: everything on the way to it
                    cyclic.update(on_stack)
                else:
                    seen.add(dep)
                    on_stack.add(dep)
                    stack.append((dep, iter(stored_names(self.type_decls[dep].spec))))
        return order + [k for k in self.type_decls if k in cyclic]

    def _struct_base(self, st: T.StructType, spec: A.TypeSpec) -> None:
        """TYPE B EXTENDS A : STRUCT (CODESYS "Extension of a structure"): B
        has A's fields first, at the same places, and a POINTER TO, REFERENCE
        TO or VAR_IN_OUT of A takes a B (oop.extends_fb)."""
        assert isinstance(spec, A.NamedType)
        key = spec.name.upper()
        if key in self._resolving:
            chain = [*self._resolving.values(), spec.name]
            self.d.error("E012", f"STRUCT {st.name} EXTENDS itself: {' -> '.join(chain)}", spec.pos)
            return
        base = self.type_of(spec)
        if base is None:
            return
        if not isinstance(T.resolve(base), T.StructType):
            self.d.error("E012", f"STRUCT {st.name} EXTENDS {base}, which is no STRUCT", spec.pos)
            return
        resolved = T.resolve(base)
        assert isinstance(resolved, T.StructType)
        st.base = resolved
        st.fields.update(resolved.fields)

    def _enum_type(self, name: str, spec: A.EnumTypeSpec) -> T.EnumType:
        base = T.INT
        if spec.base is not None:
            b = self.type_of(spec.base)
            be = T.base_elementary(b) if b is not None else None
            if be is None or not be.is_intlike:
                self.d.error("E020", "the base type of an enumeration must be an integer type", spec.base.pos)
            else:
                base = be
        et = T.EnumType(name, {}, {}, base)
        nxt = 0
        for vname, vexpr, vpos in spec.values:
            vkey = vname.upper()
            if vkey in et.values:
                self.d.error("E011", f"enumerator '{vname}' appears twice in '{name}'", vpos)
                continue
            if vexpr is not None:
                v = self._const_int(vexpr, Scope(None), "an enumerator value")
                if v is not None:
                    nxt = v
            if not T.int_fits(base, nxt):
                self.d.error("E022", f"enumerator value {nxt} does not fit {base.name}", vpos)
            et.values[vkey] = nxt
            et.spelled[vkey] = vname
            self.enumerators.setdefault(vkey, []).append((et, nxt))
            nxt += 1
        return et

    def type_of(self, spec: A.TypeSpec, scope: Scope | None = None) -> T.Type | None:
        """Resolve a type as written; reports and returns None when unknown.
        scope decides which CONSTANTs bounds and lengths may use."""
        scope = scope or Scope(None)
        if isinstance(spec, A.NamedType):
            key = spec.name.upper()
            if key in T.ELEMENTARY:
                return T.ELEMENTARY[key]
            if key in ("STRING", "WSTRING"):
                return T.StringType(self.profile.default_string_length, key == "WSTRING")
            if key == "BIT" and self.profile.bit_type and key not in self.type_decls:
                return T.BIT
            ty = self._resolve_named_type(key, spec.pos)
            if ty is not None:
                return ty
            if key in self.type_decls:
                return None  # declared, but wrong: reported at its declaration
            pou = self.pous.get(key)
            if pou is not None:
                if pou.kind == "FUNCTION_BLOCK":
                    return pou.fbtype
                self.d.error(
                    "E012",
                    f"'{spec.name}' is a {pou.kind}, not a type",
                    spec.pos,
                    "only FUNCTION_BLOCKs can be instantiated as variables",
                )
                return None
            if key in T.GENERICS:
                self.d.error(
                    "E012",
                    f"generic type '{spec.name}' cannot be used in a declaration",
                    spec.pos,
                    "use a concrete type such as INT or REAL",
                )
                return None
            if key == "BIT":
                self.d.error(
                    "E012",
                    "BIT is a CODESYS type",
                    spec.pos,
                    f"write BOOL (the {names_where(lambda p: p.bit_type)} profiles have BIT)",
                )
                return None
            self.d.error(
                "E012",
                f"unknown type '{spec.name}'{self._elsewhere(spec.name)}",
                spec.pos,
                self._suggest(
                    key,
                    list(self.type_decls)
                    + list(T.ELEMENTARY)
                    + [k for k, p in self.pous.items() if p.kind == "FUNCTION_BLOCK"],
                ),
            )
            return None
        if isinstance(spec, A.StringTypeSpec):
            n = self.profile.default_string_length
            if spec.length is not None:
                v = self._const_int(spec.length, scope, "a string length")
                if v is not None:
                    if v < 1 or v > MAX_STRING_LENGTH:
                        self.d.error("E022", f"string length {v} is not within 1..{MAX_STRING_LENGTH}", spec.length.pos)
                    else:
                        n = v
            return T.StringType(n, spec.wide)
        if isinstance(spec, A.ArrayTypeSpec):
            elem = self.type_of(spec.elem, scope)
            if elem is None or not self._not_a_reference(elem, "the element type of an ARRAY", spec.elem.pos):
                return None
            dims: list[tuple[int, int] | None] = []
            count = 1
            for rng in spec.ranges:
                if rng is None:
                    dims.append(None)
                    continue
                lo = self._const_int(rng[0], scope, "an array bound")
                hi = self._const_int(rng[1], scope, "an array bound")
                if lo is None or hi is None:
                    return None
                if hi < lo:
                    self.d.error(
                        "E050",
                        f"array range {lo}..{hi} is empty",
                        rng[0].pos,
                        "the upper bound must not be below the lower bound",
                    )
                    return None
                count *= hi - lo + 1
                if count > MAX_VAR_ELEMENTS:
                    self.d.error(
                        "E054",
                        f"the array has {'more than ' if rng is not spec.ranges[-1] else ''}{count:,} elements; "
                        f"one variable may have {MAX_VAR_ELEMENTS:,}",
                        spec.pos,
                        "make it smaller, or split it into several variables",
                    )
                    return None
                dims.append((lo, hi))
            return T.ArrayType(dims, elem)
        if isinstance(spec, A.SubrangeTypeSpec):
            base = self.type_of(spec.base, scope)
            be = T.base_elementary(base) if base is not None else None
            if be is None or not be.is_integer:
                self.d.error("E020", "a subrange needs an integer base type", spec.pos)
                return None
            lo = self._const_int(spec.lo, scope, "a subrange bound")
            hi = self._const_int(spec.hi, scope, "a subrange bound")
            if lo is None or hi is None:
                return None
            if not (T.int_fits(be, lo) and T.int_fits(be, hi)) or hi < lo:
                self.d.error("E022", f"subrange {lo}..{hi} is not within {be.name}", spec.pos)
                return None
            return T.SubrangeType(be, lo, hi)
        if isinstance(spec, A.RefTypeSpec):
            target = self.type_of(spec.target, scope)
            if target is None or not self._not_a_reference(target, f"the target of {spec_kind(spec)}", spec.target.pos):
                return None
            return T.RefType(target, spec.pointer, spec.reference)
        if isinstance(spec, A.StructTypeSpec):
            self.d.error(
                "E012",
                "an anonymous STRUCT is only allowed in a TYPE declaration",
                spec.pos,
                "declare it with TYPE name : STRUCT ... END_STRUCT END_TYPE",
            )
            return None
        if isinstance(spec, A.EnumTypeSpec):
            return self._enum_type("(anonymous enum)", spec)
        self.d.error("E012", "unsupported type", spec.pos)
        return None


def stored_names(spec: A.TypeSpec | None) -> list:
    """The UPPER names of the types a value of spec holds in itself (not
    those a REF_TO or POINTER TO points at)."""
    names: list = []
    stack = [spec]
    while stack:
        s = stack.pop()
        if isinstance(s, A.NamedType):
            names.append(s.name.upper())
        elif isinstance(s, A.ArrayTypeSpec):
            stack.append(s.elem)
        elif isinstance(s, A.StructTypeSpec):
            stack += [m.type for m in s.members] + [s.extends]
        elif isinstance(s, (A.SubrangeTypeSpec, A.EnumTypeSpec)):
            stack.append(s.base)
    return names


def _memory_starts_false(f_trig: A.POU) -> None:
    """The standard F_TRIG as MatIEC declares it: its memory M (NOT CLK in
    the last call) without the initial value TRUE of fblocks/iec/standard_fbs.st,
    so the first call with CLK FALSE is an edge (the matiec profile). The
    library's AST is this compilation's own copy (parse_cached)."""
    for block in f_trig.var_blocks:
        for d in block.decls:
            if d.name.upper() == "M":
                d.init = None
