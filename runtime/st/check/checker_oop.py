"""The checker's object-oriented ST: METHOD, PROPERTY, EXTENDS, INTERFACE.

IEC 61131-3 ed.3 6.6.5 (methods, EXTENDS, SUPER, THIS, ABSTRACT, FINAL,
access specifiers) and 6.6.6 (interfaces, the assignment attempt ?=), with
the CODESYS and TwinCAT additions (PROPERTY with GET/SET, INTERNAL,
__QUERYINTERFACE, body inheritance with SUPER^()).

A METHOD or PROPERTY accessor is checked as a FUNCTION whose POUInfo has
``fb`` set: its variables live in the call, names it does not declare are
looked up in its FUNCTION_BLOCK (inherited members included), then
globally. VAR_INST variables live in the instance. A derived
FUNCTION_BLOCK holds its base's variables first, then its own.

Codes: E140 EXTENDS/IMPLEMENTS names, E141 a member declared twice or an
override of another signature, E142 ABSTRACT, E143 FINAL, E144 access
(PRIVATE, PROTECTED, INTERNAL), E145 an interface not implemented, E146
THIS/SUPER, E147 PROPERTY, E148 interfaces and methods in expressions.
"""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from .checker_base import Scope
from .checker_oop_rules import OopRules
from .oop import access_of, all_interfaces, find_action, find_method, find_property, is_method_owner
from .symbols import CallInfo, POUInfo, PropertyInfo, VarSymbol, pyname

# The marker of THIS^ and SUPER^ (Name.sym of THIS / SUPER under ^).
THIS = "THIS"
SUPER = "SUPER"


class OopChecks(OopRules):
    """Methods, properties, inheritance and interfaces."""

    # ------------------------------------------------------------ collecting

    def _collect_interface(self, decl: A.Interface, library: bool) -> None:
        key = decl.name.upper()
        if self._clash(key, decl.name, decl.pos) or key in self.types:
            if key in self.types:
                self.d.error("E011", f"'{decl.name}' is declared twice", decl.pos)
            return
        self.types[key] = T.InterfaceType(decl.name, decl, library=library)

    # ------------------------------------------------------------ declaring

    def _oop_declare(self) -> None:
        """After every POU's own variables: interfaces, then the
        FUNCTION_BLOCKs base first (inherited variables, methods,
        properties, the rules of ABSTRACT, FINAL and IMPLEMENTS)."""
        itfs = [t for t in self.types.values() if isinstance(t, T.InterfaceType)]
        for itf in itfs:
            self._declare_interface(itf)
        done: set = set()
        for pou in list(self.pous.values()):
            if pou.kind in ("FUNCTION_BLOCK", "PROGRAM"):  # CODESYS: methods of programs too
                self._declare_fb(pou, done, [])

    def _declare_interface(self, itf: T.InterfaceType) -> None:
        node: A.Interface = itf.node
        for name, pos in node.bases:
            b = self.types.get(name.upper())
            if not isinstance(b, T.InterfaceType):
                self.d.error("E140", f"'{name}' is not an INTERFACE", pos, "an INTERFACE EXTENDS interfaces only")
            elif b is itf or itf in all_interfaces(b):
                self.d.error("E140", f"INTERFACE {itf.name} extends itself through {name}", pos)
            else:
                itf.bases.append(b)
        for m in node.methods:
            if m.body:
                self.d.error(
                    "E148",
                    f"the METHOD {m.name} of INTERFACE {itf.name} has a body",
                    m.pos,
                    "an interface declares methods; a FUNCTION_BLOCK that IMPLEMENTS it defines them",
                )
            info = self._method_info(m, None, f"m_{m.name.lower()}")
            if info is not None and not self._member_free(itf.methods, itf.properties, m.name, m.pos, itf.name):
                itf.methods[m.name.upper()] = info
        for p in node.properties:
            prop = self._property_info(p, None, itf)
            if prop is not None and not self._member_free(itf.methods, itf.properties, p.name, p.pos, itf.name):
                itf.properties[p.name.upper()] = prop

    def _member_free(self, methods: dict, props: dict, name: str, pos: A.Pos, owner: str, fb_vars=None) -> bool:
        """Report (E141) and return True when name is taken already."""
        key = name.upper()
        if key in methods or key in props or (fb_vars is not None and key in fb_vars):
            self.d.error("E141", f"'{name}' is declared twice in {owner}", pos, "rename one of them")
            return True
        return False

    def _method_info(self, m: A.Method, fb: POUInfo | None, py: str) -> POUInfo | None:
        """A METHOD (or accessor) as a FUNCTION: its variables declared,
        VAR_INST ones in the instance of fb."""
        blocks = [b for b in m.var_blocks if b.kind != "VAR_INST"]
        node = A.POU("FUNCTION", m.name, blocks, m.body or [], return_type=m.return_type, pos=m.pos)
        info = POUInfo(m.name, "FUNCTION", node, py, fb=fb, modifiers=m.modifiers)
        info.library = fb.library if fb is not None else False
        self._declare_pou_vars(info)
        for b in m.var_blocks:
            if b.kind != "VAR_INST":
                continue
            if fb is None:
                self.d.error("E148", "VAR_INST belongs to a METHOD of a FUNCTION_BLOCK", b.pos)
                continue
            for decl in b.decls:
                key = decl.name.upper()
                if key in info.vars or key == m.name.upper():
                    self.d.error("E011", f"'{decl.name}' is declared twice in {m.name}", decl.pos)
                    continue
                sym = self._make_var(decl, b, fb)
                if sym is None:
                    continue
                # CODESYS: VAR_INST keeps its value in the instance between calls
                sym.section = "VAR_INST"
                sym.name = f"{m.name}.{decl.name}"  # one of the instance's variables: named by its method
                sym.pyname = pyname(f"i{len(m.name)}_{m.name.lower()}_", decl.name)
                info.vars[key] = sym
                fb.vars[f"{m.name.upper()}.{key}"] = sym
        return info

    def _property_info(self, p: A.Property, fb: POUInfo | None, owner) -> PropertyInfo | None:
        ty = self.type_of(p.type)
        if ty is None:
            return None
        prop = PropertyInfo(p.name, ty, p.pos, owner, modifiers=p.modifiers)
        getter, setter = p.getter, p.setter
        if fb is None and getter is None and setter is None:
            getter = A.Method(p.name, [], [], None, (), pos=p.pos)
            setter = A.Method(p.name, [], [], None, (), pos=p.pos)
        if getter is not None:
            getter.return_type = p.type
            prop.getter = self._method_info(getter, fb, f"pg_{p.name.lower()}")
        if setter is not None:
            info = self._method_info(setter, fb, f"ps_{p.name.lower()}")
            if info is not None:
                # the property's name is the value assigned (CODESYS)
                sym = VarSymbol(p.name, "VAR_INPUT", ty, p.pos, pyname("v_", p.name), info)
                info.vars = {p.name.upper(): sym, **info.vars}
                self._inited.add(id(sym))
            prop.setter = info
        return prop

    def _declare_fb(self, pou: POUInfo, done: set, chain: list) -> None:
        if id(pou) in done:
            return
        node: A.POU = pou.node
        if pou in chain:
            names = " -> ".join(p.name for p in [*chain[chain.index(pou) :], pou])
            self.d.error("E140", f"FUNCTION_BLOCK {pou.name} extends itself: {names}", node.pos)
            node.extends = None
            return
        pou.modifiers = node.modifiers
        if node.extends is not None:
            name, pos = node.extends
            base = self.pous.get(name.upper())
            if base is None or base.kind != "FUNCTION_BLOCK":
                self.d.error(
                    "E140",
                    f"'{name}' is not a FUNCTION_BLOCK",
                    pos,
                    self._suggest(name.upper(), [p.name for p in self.pous.values() if p.kind == "FUNCTION_BLOCK"]),
                )
            else:
                self._declare_fb(base, done, [*chain, pou])
                if "FINAL" in base.modifiers:
                    self.d.error("E143", f"{base.name} is FINAL: no FUNCTION_BLOCK extends it", pos)
                elif id(base) in done:  # (not: a cycle, reported)
                    pou.base = base
        done.add(id(pou))
        self._inherit_vars(pou)
        for name, pos in node.implements:
            itf = self.types.get(name.upper())
            if not isinstance(itf, T.InterfaceType):
                self.d.error("E140", f"'{name}' is not an INTERFACE", pos, "IMPLEMENTS names interfaces")
            else:
                pou.interfaces.append(itf)
        for m in node.methods:
            if self._member_free(pou.methods, pou.properties, m.name, m.pos, pou.name, pou.vars):
                continue
            info = self._method_info(m, pou, f"m_{m.name.lower()}")
            if info is not None:
                pou.methods[m.name.upper()] = info
                self._check_override(pou, info, m)
        for p in node.properties:
            if self._member_free(pou.methods, pou.properties, p.name, p.pos, pou.name, pou.vars):
                continue
            prop = self._property_info(p, pou, pou)
            if prop is not None:
                pou.properties[p.name.upper()] = prop
                self._check_property_override(pou, prop)
        self._check_abstract(pou)
        self._check_implements(pou)
        self._check_lifecycle(pou)

    def _inherit_vars(self, pou: POUInfo) -> None:
        if pou.base is None:
            return
        own = pou.vars
        merged = dict(pou.base.vars)
        for key, sym in own.items():
            if key in merged:
                self.d.error(
                    "E141",
                    f"'{sym.name}' is declared in {pou.base.name} already",
                    sym.pos,
                    f"{pou.name} EXTENDS {pou.base.name} and inherits its variables: rename it or remove it",
                )
                continue
            merged[key] = sym
        pou.vars = merged

    # ------------------------------------------------------------ bodies

    def _oop_bodies(self) -> None:
        for pou in list(self.pous.values()):
            for m in pou.methods.values():
                self._oop_body(m)
            for p in pou.properties.values():
                for acc in (p.getter, p.setter):
                    if acc is not None:
                        self._oop_body(acc)
        # a PROPERTY without GET named anywhere but as an assignment's target
        for e in self._setter_only:
            if id(e) not in self._assigned:
                self.d.error("E147", f"PROPERTY {e.sym.name} has no GET: it cannot be read", e.pos)

    def _oop_body(self, m: POUInfo) -> None:
        scope = Scope(m)
        for sym in m.vars.values():
            self._check_var_init(sym, scope)
        self._stmts(m.node.body, scope)

    # ------------------------------------------------------------ names and members

    @staticmethod
    def owner_fb(scope: Scope) -> POUInfo | None:
        """The FUNCTION_BLOCK (or PROGRAM) whose body or method scope is."""
        p = scope.pou
        if p is None:
            return None
        if p.fb is not None:
            return p.fb
        return p if p.kind in ("FUNCTION_BLOCK", "PROGRAM") else None

    def _property_use(self, e: A.Name | A.Member, prop: PropertyInfo) -> tuple:
        e.sym = prop
        if prop.getter is None:
            self._setter_only.append(e)
        return (prop.type,)

    def _oop_name(self, e: A.Name, key: str, scope: Scope) -> tuple | None:
        """A name a METHOD or FB body does not declare itself: a variable
        or PROPERTY of its FUNCTION_BLOCK; THIS or SUPER without ^."""
        fb = self.owner_fb(scope)
        if fb is None:
            return None
        if key in (THIS, SUPER) and fb.kind == "FUNCTION_BLOCK":  # a PROGRAM has none: a name like any
            self.d.error(
                "E146",
                f"{e.name} is a pointer to the instance: write {e.name}^",
                e.pos,
                f"{e.name}^.member, {e.name}^.Method()",
            )
            return (None,)
        if scope.pou is not fb:
            sym = fb.vars.get(key)
            if sym is not None:
                e.sym = sym
                if sym.constant and sym.const_value is not None:  # the block's VAR CONSTANT
                    e.const = sym.const_value
                return (sym.type,)
        prop = find_property(fb, key)
        if prop is not None:
            return self._property_use(e, prop)
        return None

    def _this_deref(self, e: A.Deref, scope: Scope) -> T.Type | None:
        """THIS^ (the instance) or SUPER^ (the instance as its base)."""
        name: A.Name = e.base  # type: ignore[assignment]
        key = name.name.upper()
        fb = self.owner_fb(scope)
        if fb is None or fb.kind != "FUNCTION_BLOCK":
            self.d.error("E146", f"{name.name}^ is only defined in a FUNCTION_BLOCK or its METHODs", e.pos)
            return None
        if key == SUPER:
            if fb.base is None:
                self.d.error("E146", f"{fb.name} EXTENDS no FUNCTION_BLOCK: SUPER^ has nothing to refer to", e.pos)
                return None
            name.sym = SUPER
            return fb.base.fbtype
        name.sym = THIS
        return fb.fbtype

    def _check_access(self, modifiers: tuple, owner: POUInfo, what: str, pos: A.Pos, scope: Scope) -> None:
        """PRIVATE: the FB itself; PROTECTED: it and those derived from it;
        INTERNAL: the same namespace (a library's POUs, or the user's);
        PUBLIC: everywhere (IEC 61131-3 ed.3 6.6.5.7, CODESYS)."""
        access = access_of(modifiers)
        if access == "PUBLIC":
            return
        here = self.owner_fb(scope)
        if access == "PRIVATE":
            ok = here is owner
        elif access == "PROTECTED":
            ok = here is not None and is_method_owner(here, owner)
        else:
            ok = (scope.pou.library if scope.pou is not None else False) == owner.library
        if not ok:
            where = {
                "PRIVATE": f"{owner.name} itself",
                "PROTECTED": f"{owner.name} and the blocks that extend it",
                "INTERNAL": "its own library",
            }[access]
            self.d.error("E144", f"{what} is {access}: it is only visible in {where}", pos)

    def _oop_member(self, e: A.Member, b: T.Type, scope: Scope) -> tuple | None:
        """base.name where base is an FB instance (a PROPERTY) or an interface."""
        key = e.name.upper()
        if isinstance(b, T.InterfaceType):
            prop = find_property(b, key)
            if prop is None:
                self.d.error(
                    "E013",
                    f"INTERFACE {b.name} has no property '{e.name}'",
                    e.pos,
                    self._suggest(key, [p.name for p in b.properties.values()]),
                )
                return (None,)
            return self._property_use(e, prop)
        if isinstance(b, T.FBType) and b.pou is not None:
            prop = find_property(b.pou, key)
            if prop is not None:
                self._check_access(prop.modifiers, prop.owner, f"{prop.owner.name}.{prop.name}", e.pos, scope)
                return self._property_use(e, prop)
        return None

    def program_named(self, base: A.Expr, scope: Scope) -> POUInfo | None:
        """The PROGRAM base names (``Prog`` in ``Prog.M()``, ``Prog.P``) when
        it has methods or properties and no variable has that name. CODESYS
        calls a program's methods from other POUs: a PROGRAM is one
        instance."""
        if not isinstance(base, A.Name) or base.qualifier is not None:
            return None
        key = base.name.upper()
        if (scope.pou is not None and key in scope.pou.vars) or key in self.globals:
            return None
        fb = self.owner_fb(scope)
        if fb is not None and fb is not scope.pou and key in fb.vars:
            return None
        prog = self.pous.get(key)
        if prog is None or prog.kind != "PROGRAM" or not (prog.methods or prog.properties):
            return None
        return prog

    def _program_property(self, e: A.Member, scope: Scope) -> tuple | None:
        """Prog.P: a PROPERTY of a PROGRAM, read or written from anywhere."""
        prog = self.program_named(e.base, scope)
        prop = find_property(prog, e.name.upper()) if prog is not None else None
        if prog is None or prop is None or not isinstance(e.base, A.Name):
            return None
        e.base.sym = prog
        self._check_access(prop.modifiers, prog, f"{prog.name}.{prop.name}", e.pos, scope)
        return self._property_use(e, prop)

    def inside_fb(self, scope: Scope, fb: POUInfo) -> bool:
        """Whether scope is fb's body or method, or a derived block's."""
        here = self.owner_fb(scope)
        return here is not None and is_method_owner(here, fb)

    # ------------------------------------------------------------ calls

    def _oop_call(self, e: A.Call, scope: Scope, as_statement: bool) -> tuple | None:
        """A call that is a METHOD's (M(), THIS^.M(), inst.M(), itf.M(),
        SUPER^.M()), SUPER^() or an instance of the FB's own (inner() in a
        METHOD). None: not one of those."""
        callee = e.callee
        fb = self.owner_fb(scope)
        if isinstance(callee, A.Name):
            if fb is None:
                return None
            key = callee.name.upper()
            if scope.pou is not None and key in scope.pou.vars:
                return None
            sym = fb.vars.get(key)
            if sym is not None:
                callee.sym = sym
                callee.ty = sym.type
                return (self._fb_call(e, callee, scope, as_statement, typed=True),)
            m = find_method(fb, key)
            if m is None:
                return None
            return (self._method_call(e, m, None, None, scope, as_statement),)
        if isinstance(callee, A.Deref) and isinstance(callee.base, A.Name):
            key = callee.base.name.upper()
            if key not in (THIS, SUPER):
                return None
            ty = self.expr(callee, scope)
            if ty is None:
                return (None,)
            if key == THIS:
                self.d.error(
                    "E146",
                    "THIS^() would call the block's own body from inside it",
                    e.pos,
                    "call a METHOD, or SUPER^() for the base's body",
                )
                return (None,)
            if e.args:
                self.d.error("E041", "SUPER^() takes no arguments", e.pos, "set the inputs, then call SUPER^()")
            if not as_statement:
                self.d.error("E043", "SUPER^() is a statement, not a value", e.pos)
            sup = T.resolve(ty)
            assert isinstance(sup, T.FBType)  # _this_deref gives SUPER^ the base's type
            e.target = CallInfo("method", pou=sup.pou, func="body")
            return (None,)
        if not isinstance(callee, A.Member):
            return None
        key = callee.name.upper()
        if key in self.action_names and isinstance(callee.base, A.Name) and callee.base.name.upper() in self.pous:
            return None  # Prog.Act(): an ACTION (checker_actions.py)
        prog = self.program_named(callee.base, scope)
        m = find_method(prog, key) if prog is not None else None
        if m is not None and isinstance(callee.base, A.Name):  # Prog.M(): a PROGRAM's method (CODESYS)
            callee.base.sym = prog
            return (self._method_call(e, m, callee.base, None, scope, as_statement),)
        bty = self.expr(callee.base, scope)
        if bty is None:
            self._check_args_loosely(e, scope)
            return (None,)
        b = T.resolve(bty)
        if isinstance(b, T.InterfaceType):
            m = find_method(b, key)
            if m is None:
                self.d.error(
                    "E013",
                    f"INTERFACE {b.name} has no method '{callee.name}'",
                    callee.pos,
                    self._suggest(key, [x.name for x in b.methods.values()]),
                )
                self._check_args_loosely(e, scope)
                return (None,)
            return (self._method_call(e, m, callee.base, "interface", scope, as_statement),)
        if isinstance(b, T.FBType) and b.pou is not None:
            m = find_method(b.pou, key)
            if m is not None:
                base = callee.base
                is_super = isinstance(base, A.Deref) and getattr(base.base, "sym", None) == SUPER
                return (self._method_call(e, m, base, "super" if is_super else None, scope, as_statement),)
            if find_action(b.pou, key) is not None:
                return None  # inst.Act(): an ACTION of the block or its base (checker_actions.py)
        callee.ty = self._member_of(callee, bty, scope)
        return (self._fb_call(e, callee, scope, as_statement, typed=True),)

    def _method_call(
        self, e: A.Call, m: POUInfo, inst: A.Expr | None, how: str | None, scope: Scope, as_statement: bool
    ) -> T.Type | None:
        owner = m.fb
        if owner is not None:
            self._check_access(m.modifiers, owner, f"{owner.name}.{m.name}", e.pos, scope)
        if how == "super" and owner is not None and "ABSTRACT" in m.modifiers:
            self.d.error("E142", f"{owner.name}.{m.name} is ABSTRACT: SUPER^.{m.name}() has nothing to call", e.pos)
        info = CallInfo("method", pou=m, instance=inst, func=how)
        self._bind_args(e, m, info, scope, is_fb=False)
        e.target = info
        if m.return_type is None and not as_statement:
            self.d.error(
                "E148",
                f"METHOD {m.name} has no return type: it is not a value",
                e.pos,
                f"declare METHOD {m.name} : <type>, or call it as a statement",
            )
            return None
        return m.return_type

    # ------------------------------------------------------------ interfaces

    def _query_interface(self, e: A.Call, scope: Scope) -> T.Type | None:
        """__QUERYINTERFACE(src, dst) (CODESYS): dst := src when the instance
        behind src implements dst's interface; TRUE if it does."""
        args = [a.value for a in e.args]
        if len(args) != 2 or any(a is None for a in args) or any(a.name is not None for a in e.args):
            self.d.error("E041", "__QUERYINTERFACE takes two arguments", e.pos, "__QUERYINTERFACE(itfSource, itfDest)")
            return None
        src, dst = args
        sty, dty = self.expr(src, scope), self.lvalue(dst, scope)
        if sty is None or dty is None:
            return None
        if not isinstance(T.resolve(sty), (T.InterfaceType, T.FBType)) or not isinstance(
            T.resolve(dty), T.InterfaceType
        ):
            self.d.error("E148", f"__QUERYINTERFACE needs interfaces, not {sty} and {dty}", e.pos)
            return None
        e.target = CallInfo("builtin", func="__QUERYINTERFACE", args=[src, dst])
        return T.BOOL

    def _assignment_attempt(self, s: A.Assign, scope: Scope) -> None:
        """target ?= source (IEC 61131-3 ed.3 6.6.6.7): the instance when it
        implements the target's interface, else NULL."""
        tty = self.lvalue(s.target, scope)
        vty = self.expr(s.value, scope)
        if tty is None or vty is None:
            return
        if not isinstance(T.resolve(tty), T.InterfaceType) or not isinstance(
            T.resolve(vty), (T.InterfaceType, T.FBType)
        ):
            self.d.error(
                "E148",
                f"?= assigns an interface to an interface variable, not {vty} to {tty}",
                s.pos,
                "itfTarget ?= itfSource;",
            )
