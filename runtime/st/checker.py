"""The checker: resolves every name and type, applies the IEC implicit
conversion rules, folds constants and reports coded diagnostics.

It annotates the AST in place (``Expr.ty``, ``Expr.const``, ``Name.sym``,
``Call.target``) and returns a ``CheckedProgram`` the code generator reads.
All errors of all files are collected; the checker never raises on bad input.
"""
from __future__ import annotations

import difflib
from dataclasses import dataclass, field
from typing import Any, Optional, Protocol

from . import ast as A
from . import rtlib
from . import native
from . import types as T
from .conversions import check_implicit, common_type, const_as, generic_fit, is_flexible, same_type
from .diagnostics import DiagnosticBag
from .native import NativeFunction
from .profile import Profile
from .symbols import CallInfo, POUInfo, VarSymbol, pyname

BUILTINS = ("TIME", "LTIME", "REF", "ADR", "SIZEOF")

_TIME_KIND = {
    "time": T.TIME, "ltime": T.LTIME, "date": T.DATE, "tod": T.TOD, "dt": T.DT,
    "ldate": T.LDATE, "ltod": T.LTOD, "ldt": T.LDT,
}
_SECTIONS_READABLE_OUTSIDE = ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT")


@dataclass
class ConfigInfo:
    """A checked CONFIGURATION: tasks and program instances for the engine."""
    name: str
    tasks: list = field(default_factory=list)  # dicts: name, interval_ms, priority, single, pos
    programs: list = field(default_factory=list)  # dicts: name, type (POUInfo), task, args, pos
    node: Any = None


@dataclass
class CheckedProgram:
    pous: list  # POUInfo, user and library
    globals: list  # VarSymbol
    structs: list  # StructType in declaration order
    configurations: list  # ConfigInfo
    types: dict  # UPPER -> Type


class AddressSpace(Protocol):
    """Where direct addresses are checked: a process image laid out for the
    profile's addressing model (runtime/image/memory.ProcessImage). Both
    calls raise ValueError for an address outside it."""
    size: int

    def table(self, addr: A.LocatedAddress) -> Any: ...

    def accessor(self, addr: A.LocatedAddress, ty: T.ElementaryType) -> Any: ...


class _Scope:
    """Where an expression is checked: the POU (or None for global
    initialisers) and the loop nesting for EXIT/CONTINUE."""

    def __init__(self, pou: Optional[POUInfo]) -> None:
        self.pou = pou
        self.loops = 0
        self.for_vars: list = []  # VarSymbols of enclosing FOR loops


class Checker:
    def __init__(self, profile: Profile, diags: DiagnosticBag, std_functions: dict,
                 natives: Optional[dict] = None, image: Optional[AddressSpace] = None) -> None:
        self.profile = profile
        self.d = diags
        self.std = std_functions
        self.natives: dict = natives or {}  # UPPER -> native.NativeFunction
        self.type_decls: dict = {}  # UPPER -> TypeDecl
        self.types: dict = {}  # UPPER -> Type (resolved)
        self._resolving: set = set()
        self.pous: dict = {}  # UPPER -> POUInfo
        self.globals: dict = {}  # UPPER -> VarSymbol
        self.enumerators: dict = {}  # UPPER -> [(EnumType, value)]
        self.structs: list = []
        self.configs: list = []
        self.library_files: set = set()
        self._inited: set = set()  # ids of VarSymbols whose initial value is checked
        self._image_probe = image  # to validate direct addresses (None: not checked)

    # ================================================================ driver

    def run(self, files: list, library_files: tuple = ()) -> CheckedProgram:
        self.library_files = set(library_files)
        for sf in files:
            self._collect(sf)
        for key in list(self.type_decls):
            self._resolve_named_type(key, self.type_decls[key].pos)
        global_blocks = [(b, None) for sf in files for b in sf.decls if isinstance(b, A.VarBlock)]
        for sf in files:
            for decl in sf.decls:
                if isinstance(decl, A.Configuration):
                    global_blocks += [(b, decl) for b in decl.var_blocks]
                    for res in decl.resources:
                        global_blocks += [(b, decl) for b in res.var_blocks]
        for block, _ in global_blocks:
            self._declare_globals(block)
        for pou in self.pous.values():
            self._declare_pou_vars(pou)
        for st in self.structs:
            for f in st.fields.values():
                if f.init is not None:
                    f.init_value = self.init_value(f.type, f.init, _Scope(None), f"{st.name}.{f.name}")
                else:
                    f.init_value = T.declared_default(f.type)
        for sym in self.globals.values():
            self._check_var_init(sym, _Scope(None))
        for pou in self.pous.values():
            scope = _Scope(pou)
            for sym in pou.vars.values():
                self._check_var_init(sym, scope)
            self._stmts(pou.node.body, scope)
        for sf in files:
            for decl in sf.decls:
                if isinstance(decl, A.Configuration):
                    self._configuration(decl)
        return CheckedProgram(list(self.pous.values()), list(self.globals.values()),
                              self.structs, self.configs, self.types)

    # ================================================================ pass 1: collect

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
                info = POUInfo(decl.name, decl.kind, decl, pyname(
                    {"PROGRAM": "P_", "FUNCTION": "F_", "FUNCTION_BLOCK": "FB_"}[decl.kind], decl.name),
                    library=library)
                if decl.kind != "FUNCTION":
                    info.fbtype = T.FBType(decl.name, info)
                self.pous[key] = info

    def _clash(self, key: str, name: str, pos: A.Pos) -> bool:
        if key in T.ELEMENTARY or key in ("STRING", "WSTRING") or key in T.GENERICS:
            self.d.error("E011", f"'{name}' is the name of an elementary type", pos,
                         "choose another name")
            return True
        other = self.type_decls.get(key) or self.pous.get(key)
        if other is not None:
            opos = other.pos if isinstance(other, A.Node) else other.node.pos
            self.d.error("E011", f"'{name}' is declared twice", pos,
                         f"the first declaration is at {opos}")
            return True
        return False

    # ================================================================ types

    def _resolve_named_type(self, key: str, pos: A.Pos) -> Optional[T.Type]:
        if key in self.types:
            return self.types[key]
        decl = self.type_decls.get(key)
        if decl is None:
            return None
        if key in self._resolving:
            self.d.error("E012", f"type '{decl.name}' is defined in terms of itself", decl.pos,
                         "a type cannot contain itself; use REF_TO for recursive structures")
            return None
        self._resolving.add(key)
        try:
            spec = decl.spec
            if isinstance(spec, A.StructTypeSpec):
                st = T.StructType(decl.name, pyclass=pyname("S_", decl.name))
                self.types[key] = st  # before fields: REF_TO self is allowed
                for m in spec.members:
                    fkey = m.name.upper()
                    if fkey in st.fields:
                        self.d.error("E011", f"field '{m.name}' is declared twice", m.pos)
                        continue
                    fty = self.type_of(m.type)
                    st.fields[fkey] = T.StructField(m.name, fty, m.init, pyname("f_", m.name))
                self.structs.append(st)
                ty = st
            elif isinstance(spec, A.EnumTypeSpec):
                ty = self._enum_type(decl.name, spec)
            else:
                target = self.type_of(spec)
                if target is None:
                    return None
                ty = T.AliasType(decl.name, target)
            self.types[key] = ty
            if decl.init is not None:
                plan = self.init_value(ty, decl.init, _Scope(None), decl.name)
                if isinstance(ty, T.EnumType):
                    ty.default = plan
                elif isinstance(ty, T.AliasType):
                    ty.init_value = plan
                else:
                    self.d.error("E024", f"a STRUCT takes its initial values in its fields", decl.init.pos)
            return ty
        finally:
            self._resolving.discard(key)

    def _enum_type(self, name: str, spec: A.EnumTypeSpec) -> T.EnumType:
        base = T.INT
        if spec.base is not None:
            b = self.type_of(spec.base)
            be = T.base_elementary(b) if b is not None else None
            if be is None or not be.is_intlike:
                self.d.error("E020", "the base type of an enumeration must be an integer type",
                             spec.base.pos)
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
                v = self._const_int(vexpr, _Scope(None), "an enumerator value")
                if v is not None:
                    nxt = v
            if not T.int_fits(base, nxt):
                self.d.error("E022", f"enumerator value {nxt} does not fit {base.name}", vpos)
            et.values[vkey] = nxt
            et.spelled[vkey] = vname
            self.enumerators.setdefault(vkey, []).append((et, nxt))
            nxt += 1
        return et

    def type_of(self, spec: A.TypeSpec, scope: Optional[_Scope] = None) -> Optional[T.Type]:
        """Resolve a type as written; reports and returns None when unknown.
        scope decides which CONSTANTs bounds and lengths may use."""
        scope = scope or _Scope(None)
        if isinstance(spec, A.NamedType):
            key = spec.name.upper()
            if key in T.ELEMENTARY:
                return T.ELEMENTARY[key]
            if key in ("STRING", "WSTRING"):
                return T.StringType(self.profile.default_string_length, key == "WSTRING")
            ty = self._resolve_named_type(key, spec.pos)
            if ty is not None:
                return ty
            pou = self.pous.get(key)
            if pou is not None:
                if pou.kind == "FUNCTION_BLOCK":
                    return pou.fbtype
                self.d.error("E012", f"'{spec.name}' is a {pou.kind}, not a type", spec.pos,
                             "only FUNCTION_BLOCKs can be instantiated as variables")
                return None
            if key in T.GENERICS:
                self.d.error("E012", f"generic type '{spec.name}' cannot be used in a declaration",
                             spec.pos, "use a concrete type such as INT or REAL")
                return None
            self.d.error("E012", f"unknown type '{spec.name}'", spec.pos,
                         self._suggest(key, list(self.type_decls) + list(T.ELEMENTARY)
                                       + [k for k, p in self.pous.items() if p.kind == "FUNCTION_BLOCK"]))
            return None
        if isinstance(spec, A.StringTypeSpec):
            n = self.profile.default_string_length
            if spec.length is not None:
                v = self._const_int(spec.length, scope, "a string length")
                if v is not None:
                    if v < 1 or v > 65535:
                        self.d.error("E022", f"string length {v} is not within 1..65535", spec.length.pos)
                    else:
                        n = v
            return T.StringType(n, spec.wide)
        if isinstance(spec, A.ArrayTypeSpec):
            elem = self.type_of(spec.elem, scope)
            if elem is None:
                return None
            dims = []
            for rng in spec.ranges:
                if rng is None:
                    dims.append(None)
                    continue
                lo = self._const_int(rng[0], scope, "an array bound")
                hi = self._const_int(rng[1], scope, "an array bound")
                if lo is None or hi is None:
                    return None
                if hi < lo:
                    self.d.error("E050", f"array range {lo}..{hi} is empty", rng[0].pos,
                                 "the upper bound must not be below the lower bound")
                    return None
                if (hi - lo + 1) > 10_000_000:
                    self.d.error("E050", f"array range {lo}..{hi} is too large", rng[0].pos)
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
            if target is None:
                return None
            return T.RefType(target, spec.pointer)
        if isinstance(spec, A.StructTypeSpec):
            self.d.error("E012", "an anonymous STRUCT is only allowed in a TYPE declaration",
                         spec.pos, "declare it with TYPE name : STRUCT ... END_STRUCT END_TYPE")
            return None
        if isinstance(spec, A.EnumTypeSpec):
            return self._enum_type("(anonymous enum)", spec)
        self.d.error("E012", "unsupported type", spec.pos)
        return None

    # ================================================================ declarations

    def _make_var(self, decl: A.VarDecl, block: A.VarBlock, owner: Optional[POUInfo]) -> Optional[VarSymbol]:
        ty = self.type_of(decl.type, _Scope(owner))
        if ty is None:
            return None
        section = block.kind
        if isinstance(T.resolve(ty), T.ArrayType) and T.resolve(ty).variable_length \
                and section != "VAR_IN_OUT":
            self.d.error("E050", "ARRAY[*] is only allowed for VAR_IN_OUT", decl.pos)
            return None
        prefix = "v_" if owner is not None else "g_"
        sym = VarSymbol(decl.name, section, ty, decl.pos, pyname(prefix, decl.name), owner,
                        constant=block.constant, retain=block.retain, persistent=block.persistent,
                        location=decl.location, init=decl.init)
        if decl.location is not None:
            self._check_location_type(sym)
        if block.retain or block.persistent:
            self._check_retained(sym, block)
        if sym.constant:
            # a CONSTANT may size the arrays and strings declared after it
            self._check_var_init(sym, _Scope(owner))
            self._inited.add(id(sym))
        return sym

    def _check_retained(self, sym: VarSymbol, block: A.VarBlock) -> None:
        """W111 where RETAIN/PERSISTENT cannot keep anything: the engine
        retains a variable's own storage only (runtime/engine/retain.py)."""
        if sym.section in ("VAR_IN_OUT", "VAR_EXTERNAL"):
            what = f"a {sym.section} (it refers to a variable declared elsewhere)"
        elif sym.section == "VAR_TEMP" or (sym.owner is not None and sym.owner.kind == "FUNCTION"):
            what = "a temporary variable (it holds nothing between calls)"
        elif sym.location is not None:
            what = "a located variable (its value is the process image's)"
        else:
            return
        qualifier = "PERSISTENT" if block.persistent else "RETAIN"
        self.d.warning("W111", f"{qualifier} has no effect on {sym.name}, {what}", sym.pos,
                       f"remove {qualifier}; to keep the value, copy it into a VAR {qualifier} "
                       "variable of a PROGRAM or FUNCTION_BLOCK")

    def _declare_globals(self, block: A.VarBlock) -> None:
        if block.kind not in ("VAR_GLOBAL", "VAR_CONFIG"):
            self.d.error("E011", f"{block.kind} is not allowed outside a POU", block.pos,
                         "use VAR_GLOBAL for global variables")
            return
        for decl in block.decls:
            key = decl.name.upper()
            if key in self.globals:
                self.d.error("E011", f"global '{decl.name}' is declared twice", decl.pos,
                             f"the first declaration is at {self.globals[key].pos}")
                continue
            sym = self._make_var(decl, block, None)
            if sym is not None:
                sym.section = "VAR_GLOBAL"
                self.globals[key] = sym

    def _declare_pou_vars(self, pou: POUInfo) -> None:
        node = pou.node
        if pou.kind == "FUNCTION":
            rt = self.type_of(node.return_type) if node.return_type is not None else None
            pou.return_type = rt
            if rt is not None:
                pou.result = VarSymbol(pou.name, "RETURN", rt, node.pos, "r_result", pou)
        elif node.return_type is not None:
            self.d.error("E011", f"a {pou.kind} has no return type", node.return_type.pos)
        allowed = {
            "PROGRAM": ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_EXTERNAL", "VAR_TEMP",
                        "VAR_GLOBAL", "VAR_STAT"),
            "FUNCTION_BLOCK": ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_EXTERNAL",
                               "VAR_TEMP", "VAR_STAT"),
            "FUNCTION": ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_EXTERNAL", "VAR_TEMP",
                         "VAR_STAT"),
        }[pou.kind]
        for block in node.var_blocks:
            if block.kind not in allowed:
                self.d.error("E011", f"{block.kind} is not allowed in a {pou.kind}", block.pos)
                continue
            for decl in block.decls:
                key = decl.name.upper()
                if key in pou.vars or (pou.kind == "FUNCTION" and key == pou.name.upper()):
                    self.d.error("E011", f"'{decl.name}' is declared twice in {pou.name}", decl.pos)
                    continue
                if block.kind == "VAR_EXTERNAL":
                    g = self.globals.get(key)
                    if g is None:
                        self.d.error("E010", f"VAR_EXTERNAL '{decl.name}' has no VAR_GLOBAL", decl.pos,
                                     "declare it in a VAR_GLOBAL block (a GVL or the CONFIGURATION)")
                        continue
                    ty = self.type_of(decl.type)
                    if ty is not None and not same_type(ty, g.type):
                        self.d.error("E020", f"VAR_EXTERNAL '{decl.name}' is {ty}, the global is {g.type}",
                                     decl.pos)
                    if g.constant and not block.constant:
                        self.d.error("E030", f"global '{decl.name}' is CONSTANT; declare the "
                                     "VAR_EXTERNAL CONSTANT too", decl.pos)
                    continue  # references the global symbol directly
                if block.kind == "VAR_GLOBAL":  # a PROGRAM's own globals
                    if key in self.globals:
                        self.d.error("E011", f"global '{decl.name}' is declared twice", decl.pos)
                        continue
                    sym = self._make_var(decl, block, None)
                    if sym is not None:
                        self.globals[key] = sym
                    continue
                sym = self._make_var(decl, block, pou)
                if sym is None:
                    continue
                if sym.location is not None and block.kind not in ("VAR", "VAR_INPUT", "VAR_OUTPUT"):
                    self.d.error("E081", f"AT is not allowed in {block.kind}", decl.pos)
                if block.kind == "VAR_IN_OUT" and decl.init is not None:
                    self.d.error("E024", "a VAR_IN_OUT cannot have an initial value", decl.pos)
                if pou.kind == "FUNCTION" and sym.location is not None:
                    self.d.error("E081", "a FUNCTION cannot have located (AT) variables", decl.pos)
                pou.vars[key] = sym

    def _check_location_type(self, sym: VarSymbol) -> None:
        addr = sym.location
        ty = T.base_elementary(sym.type)
        want = 1 if (addr.size in ("", "X") or addr.bit is not None) else \
            {"B": 8, "W": 16, "D": 32, "L": 64}[addr.size]
        if addr.table is not None:
            self.d.error("E081", f"{addr.text}: a word table cannot be declared AT", sym.pos)
        elif ty is None or ty.bits != want:
            self.d.error("E081", f"{addr.text} is a {want}-bit address; '{sym.name}' is {sym.type}",
                         sym.pos, "declare a type of the address size (X: BOOL, B: BYTE/SINT, "
                         "W: WORD/INT, D: DWORD/DINT/REAL, L: LWORD/LINT/LREAL)")
        else:
            self._address_fits(addr, ty, sym.pos)

    # ================================================================ initial values

    def _check_var_init(self, sym: VarSymbol, scope: _Scope) -> None:
        if id(sym) in self._inited:
            return
        if sym.init is None:
            sym.init_value = T.declared_default(sym.type)
            if sym.constant:
                sym.const_value = self.default_value(sym.type)
            return
        sym.init_value = self.init_value(sym.type, sym.init, scope, sym.name)
        if sym.constant and sym.init_value is not None and T.base_elementary(sym.type) is not None \
                or (sym.constant and isinstance(T.resolve(sym.type), T.StringType)):
            sym.const_value = sym.init_value

    def default_value(self, ty: T.Type) -> Any:
        ty = T.resolve(ty)
        if isinstance(ty, T.ElementaryType):
            return False if ty.is_bool else (0.0 if ty.is_real else 0)
        if isinstance(ty, T.StringType):
            return ""
        if isinstance(ty, T.EnumType):
            return ty.default if ty.default is not None else next(iter(ty.values.values()), 0)
        if isinstance(ty, T.SubrangeType):
            return ty.lo if not ty.lo <= 0 <= ty.hi else 0
        return None

    def init_value(self, ty: T.Type, init: Any, scope: _Scope, what: str) -> Any:
        """Evaluate an initialiser against a type. Returns a plan: a Python
        value for elementary types, ('array', [plans]) for arrays,
        ('struct', {UPPER: plan}) for structs and FB instances, None for the
        default."""
        rty = T.resolve(ty)
        if isinstance(init, A.ArrayInit):
            if not isinstance(rty, T.ArrayType):
                self.d.error("E024", f"'{what}' is {ty}; an array initialiser needs an ARRAY", init.pos)
                return None
            return self._array_init(rty, init, scope, what)
        if isinstance(init, A.StructInit):
            return self._struct_init(rty, init, scope, what)
        if isinstance(rty, T.ArrayType) and isinstance(init, A.Expr):
            # [1, 2] arrives as ArrayInit; a bare expression is an error
            self.d.error("E024", f"'{what}' is an ARRAY; initialise it with [ ... ]", init.pos)
            return None
        if isinstance(rty, (T.StructType, T.FBType)):
            self.d.error("E024", f"'{what}' is {ty}; initialise it with ( field := value, ... )", init.pos)
            return None
        ety = self.expr(init, scope, expected=ty)
        if ety is None:
            return None
        if not self.check_convertible(ety, ty, init, f"the initial value of '{what}'"):
            return None
        if init.const is None and not isinstance(rty, T.RefType):
            self.d.error("E024", f"the initial value of '{what}' is not a constant expression", init.pos,
                         "use literals and CONSTANTs here, or assign the value in the code")
            return None
        if isinstance(rty, T.RefType):
            return None
        return const_as(init.const, ety, ty)

    def _array_init(self, ty: T.ArrayType, init: A.ArrayInit, scope: _Scope, what: str) -> Any:
        if ty.variable_length:
            return None
        # Items fill the array in row-major order (IEC: the last index varies fastest).
        total = 1
        for lo, hi in ty.dims:
            total *= hi - lo + 1
        flat: list = []
        for count_expr, value in init.items:
            count = 1
            if count_expr is not None:
                count = self._const_int(count_expr, scope, "a repetition count")
                if count is None or count < 0:
                    return None
            plan = self.init_value(ty.elem, value, scope, what) if value is not None else None
            flat.extend([plan] * count)
        if len(flat) > total:
            self.d.error("E052", f"{len(flat)} initial values for '{what}', which has {total} elements",
                         init.pos, "remove values or enlarge the array")
            return None
        flat.extend([None] * (total - len(flat)))
        return ("array", flat)

    def _struct_init(self, ty: T.Type, init: A.StructInit, scope: _Scope, what: str) -> Any:
        out = {}
        if isinstance(ty, T.StructType):
            fields = {k: (f.name, f.type) for k, f in ty.fields.items()}
        elif isinstance(ty, T.FBType):
            fields = {k: (v.name, v.type) for k, v in ty.pou.vars.items()
                      if v.section in ("VAR_INPUT", "VAR_OUTPUT", "VAR")}
        else:
            self.d.error("E024", f"'{what}' is {ty}; a ( := ) initialiser needs a STRUCT or FB", init.pos)
            return None
        for fname, fval, fpos in init.fields:
            k = fname.upper()
            if k not in fields:
                self.d.error("E013", f"{ty} has no member '{fname}'", fpos,
                             self._suggest(k, list(fields)))
                continue
            out[k] = self.init_value(fields[k][1], fval, scope, f"{what}.{fields[k][0]}")
        return ("struct", out)

    def _const_int(self, e: A.Expr, scope: _Scope, what: str) -> Optional[int]:
        ty = self.expr(e, scope)
        if ty is None:
            return None
        if e.const is None or isinstance(e.const, bool) or not isinstance(e.const, int):
            self.d.error("E025", f"{what} must be a constant integer expression", e.pos,
                         "use a literal or a VAR CONSTANT")
            return None
        return e.const

    # ================================================================ statements

    def _stmts(self, body: list, scope: _Scope) -> None:
        for s in body:
            try:
                self._stmt(s, scope)
            except RecursionError:
                self.d.error("E005", "statement nested too deeply", s.pos, "split it up")

    def _stmt(self, s: A.Stmt, scope: _Scope) -> None:
        if isinstance(s, A.Assign):
            self._assign(s, scope)
        elif isinstance(s, A.CallStmt):
            self.call(s.call, scope, as_statement=True)
        elif isinstance(s, A.If):
            for cond, body in s.branches:
                self._bool_cond(cond, scope, "IF")
                self._stmts(body, scope)
            if s.else_body:
                self._stmts(s.else_body, scope)
        elif isinstance(s, A.Case):
            self._case(s, scope)
        elif isinstance(s, A.For):
            self._for(s, scope)
        elif isinstance(s, A.While):
            self._bool_cond(s.cond, scope, "WHILE")
            self._loop_body(s.body, scope)
        elif isinstance(s, A.Repeat):
            self._loop_body(s.body, scope)
            self._bool_cond(s.cond, scope, "UNTIL")
        elif isinstance(s, (A.Exit, A.Continue)):
            if scope.loops == 0:
                word = "EXIT" if isinstance(s, A.Exit) else "CONTINUE"
                self.d.error("E070", f"{word} outside a loop", s.pos,
                             "EXIT and CONTINUE belong inside FOR, WHILE or REPEAT")
        elif isinstance(s, A.Return):
            pass
        elif isinstance(s, A.SetReset):
            ty = self.lvalue(s.target, scope)
            if ty is not None and not self._is_bool(ty):
                self.d.error("E020", f"{s.kind} needs a BOOL target, not {ty}", s.target.pos)
        else:
            self.d.error("E005", "unsupported statement", s.pos)

    def _loop_body(self, body: list, scope: _Scope) -> None:
        scope.loops += 1
        self._stmts(body, scope)
        scope.loops -= 1

    def _bool_cond(self, cond: A.Expr, scope: _Scope, what: str) -> None:
        ty = self.expr(cond, scope, expected=T.BOOL)
        if ty is not None and not self._is_bool(ty):
            self.d.error("E020", f"the {what} condition is {ty}, not BOOL", cond.pos,
                         "compare it, e.g. x <> 0")

    def _assign(self, s: A.Assign, scope: _Scope) -> None:
        if s.op == "REF=":
            tty = self.lvalue(s.target, scope)
            vty = self.expr(s.value, scope)
            if tty is None or vty is None:
                return
            rt = T.resolve(tty)
            if not isinstance(rt, T.RefType):
                self.d.error("E020", "REF= needs a REF_TO target", s.target.pos)
            elif not same_type(rt.target, vty):
                self.d.error("E020", f"REF= of {vty} into {tty}", s.value.pos)
            elif not self._is_lvalue_expr(s.value):
                self.d.error("E031", "REF= needs a variable on the right", s.value.pos)
            return
        tty = self.lvalue(s.target, scope)
        if tty is None:
            self.expr(s.value, scope)
            return
        vty = self.expr(s.value, scope, expected=tty)
        if vty is None:
            return
        if s.op in ("S=", "R="):
            if not self._is_bool(tty) or not self._is_bool(vty):
                self.d.error("E020", f"{s.op} needs BOOL on both sides", s.pos)
            return
        self.check_convertible(vty, tty, s.value, "the assignment")

    def _case(self, s: A.Case, scope: _Scope) -> None:
        sty = self.expr(s.selector, scope)
        if sty is None:
            for br in s.branches:
                self._stmts(br.body, scope)
            return
        se = T.resolve(sty)
        if not (isinstance(se, T.EnumType) or (T.base_elementary(se) is not None
                                                and T.base_elementary(se).is_intlike)):
            self.d.error("E060", f"CASE needs an integer or enumeration selector, not {sty}",
                         s.selector.pos)
        seen: list = []  # (lo, hi, pos)
        for br in s.branches:
            for lab in br.labels:
                if isinstance(lab, A.CaseRange):
                    lo = self._case_label(lab.lo, sty, scope)
                    hi = self._case_label(lab.hi, sty, scope)
                    if lo is None or hi is None:
                        continue
                    if hi < lo:
                        self.d.error("E060", f"empty CASE range {lo}..{hi}", lab.pos)
                        continue
                else:
                    lo = hi = self._case_label(lab, sty, scope)
                    if lo is None:
                        continue
                for plo, phi, ppos in seen:
                    if lo <= phi and plo <= hi:
                        self.d.error("E061", "CASE label overlaps an earlier one", lab.pos,
                                     f"the earlier label is at {ppos}")
                        break
                seen.append((lo, hi, lab.pos))
            self._stmts(br.body, scope)
        if s.else_body:
            self._stmts(s.else_body, scope)

    def _case_label(self, e: A.Expr, sty: T.Type, scope: _Scope) -> Optional[int]:
        ty = self.expr(e, scope, expected=sty)
        if ty is None:
            return None
        if e.const is None or isinstance(e.const, (str, float)):
            self.d.error("E060", "a CASE label must be a constant", e.pos,
                         "use literals, enumeration values or CONSTANTs")
            return None
        self.check_convertible(ty, sty, e, "the CASE label")
        return int(e.const)

    def _for(self, s: A.For, scope: _Scope) -> None:
        vty = self.lvalue(s.var, scope)
        ve = T.base_elementary(vty) if vty is not None else None
        if vty is not None and (ve is None or not ve.is_intlike or isinstance(T.resolve(vty), T.EnumType)):
            self.d.error("E071", f"the FOR variable must be an integer, not {vty}", s.var.pos)
            vty = None
        for part in (s.start, s.end, s.step):
            if part is None:
                continue
            pty = self.expr(part, scope, expected=vty)
            if pty is not None and vty is not None:
                self.check_convertible(pty, vty, part, "the FOR bound")
        if s.step is not None and s.step.const == 0:
            self.d.error("E071", "FOR step 0 never ends", s.step.pos)
        sym = s.var.sym if isinstance(s.var, A.Name) else None
        scope.for_vars.append(sym)
        self._loop_body(s.body, scope)
        scope.for_vars.pop()

    # ================================================================ lvalues

    def _is_lvalue_expr(self, e: A.Expr) -> bool:
        return isinstance(e, (A.Name, A.Member, A.Index, A.Deref, A.BitAccess, A.Located))

    def lvalue(self, e: A.Expr, scope: _Scope) -> Optional[T.Type]:
        ty = self.expr(e, scope)
        if ty is None:
            return None
        if not self._is_lvalue_expr(e):
            self.d.error("E031", "this expression cannot be assigned to", e.pos,
                         "the left side of := must be a variable")
            return None
        self._check_writable(e, scope)
        return ty

    def _check_writable(self, e: A.Expr, scope: _Scope) -> None:
        if isinstance(e, A.Name):
            sym = e.sym
            if not isinstance(sym, VarSymbol):
                self.d.error("E031", f"'{e.name}' is not a variable", e.pos)
                return
            if sym.constant:
                self.d.error("E030", f"'{sym.name}' is a CONSTANT", e.pos,
                             "remove CONSTANT from its declaration or assign another variable")
            elif sym.section == "VAR_INPUT" and sym.owner is scope.pou:
                self.d.error("E030", f"'{sym.name}' is an input of {sym.owner.name} and cannot be "
                             "assigned inside it", e.pos, "copy it into a local VAR and change that")
            elif sym in scope.for_vars:
                self.d.error("E072", f"the FOR variable '{sym.name}' must not be changed in the loop",
                             e.pos, "use EXIT to leave the loop early, or a WHILE loop")
        elif isinstance(e, A.Member):
            sym = e.sym
            base_ty = T.resolve(e.base.ty) if e.base.ty is not None else None
            if isinstance(base_ty, T.FBType) and isinstance(sym, VarSymbol):
                if sym.section == "VAR_OUTPUT":
                    self.d.error("E030", f"'{sym.name}' is an output of {base_ty.name}; it is written by "
                                 "the block, not from outside", e.pos,
                                 "read it after the call, e.g. x := inst.Q")
                    return
            self._check_writable(e.base, scope)
        elif isinstance(e, (A.Index, A.BitAccess)):
            self._check_writable(e.base, scope)
        elif isinstance(e, A.Located) and e.addr.table is not None:
            self.d.error("E031", f"the word table {e.addr.text} cannot be assigned as a whole", e.pos,
                         "assign its words one by one")

    # ================================================================ conversions

    def _is_bool(self, ty: T.Type) -> bool:
        e = T.base_elementary(ty)
        return e is not None and e.is_bool and not isinstance(T.resolve(ty), T.EnumType)

    def check_convertible(self, src: T.Type, dst: T.Type, e: A.Expr, what: str) -> bool:
        """Report unless a value of type src may be stored into dst
        implicitly (the rule: conversions.check_implicit)."""
        return check_implicit(src, dst, e, what, self.profile, self.d)

    # ================================================================ expressions

    def expr(self, e: A.Expr, scope: _Scope, expected: Optional[T.Type] = None) -> Optional[T.Type]:
        try:
            ty = self._expr(e, scope, expected)
        except RecursionError:
            self.d.error("E005", "expression nested too deeply", e.pos, "split it up with variables")
            ty = None
        e.ty = ty
        return ty

    def _expr(self, e: A.Expr, scope: _Scope, expected: Optional[T.Type]) -> Optional[T.Type]:
        if isinstance(e, A.Literal):
            return self._literal(e, expected)
        if isinstance(e, A.Name):
            return self._name(e, scope, expected)
        if isinstance(e, A.EnumLiteral):
            return self._enum_literal(e, expected)
        if isinstance(e, A.Member):
            return self._member(e, scope)
        if isinstance(e, A.Index):
            return self._index(e, scope)
        if isinstance(e, A.BitAccess):
            return self._bit_access(e, scope)
        if isinstance(e, A.Deref):
            bty = self.expr(e.base, scope)
            if bty is None:
                return None
            r = T.resolve(bty)
            if not isinstance(r, T.RefType):
                self.d.error("E020", f"^ needs a REF_TO or POINTER TO, not {bty}", e.pos)
                return None
            return r.target
        if isinstance(e, A.Unary):
            return self._unary(e, scope, expected)
        if isinstance(e, A.Binary):
            return self._binary(e, scope, expected)
        if isinstance(e, A.Call):
            return self.call(e, scope, as_statement=False)
        if isinstance(e, A.Located):
            return self._located(e)
        if isinstance(e, A.SchneiderAddress):
            return T.ADDR
        self.d.error("E005", "unsupported expression", e.pos)
        return None

    def _literal(self, e: A.Literal, expected: Optional[T.Type]) -> Optional[T.Type]:
        v = e.value
        if e.c_hex and not self.profile.c_hex_literals:
            self.d.error("E026", "C-style hexadecimal literal", e.pos,
                         f"write 16#{v:X}, or compile with --profile schneider")
        if e.kind in _TIME_KIND:
            ty = _TIME_KIND[e.kind]
            if e.type_name is not None and T.ELEMENTARY.get(e.type_name) is not None:
                ty = T.ELEMENTARY[e.type_name]
            e.const = self._time_repr(ty, v, e)
            return ty
        if e.kind in ("string", "wstring"):
            wide = e.kind == "wstring"
            e.const = v
            exp = T.resolve(expected) if expected is not None else None
            if isinstance(exp, T.StringType) and exp.wide == wide:
                return exp
            return T.StringType(max(len(v), 1), wide)
        if e.type_name is not None:
            ty = T.ELEMENTARY.get(e.type_name)
            if ty is None:
                self.d.error("E012", f"unknown type '{e.type_name}' in typed literal", e.pos)
                return None
            if ty.is_bool:
                if e.kind == "bool" or (e.kind == "int" and v in (0, 1)):
                    e.const = bool(v)
                    return ty
            elif ty.is_real and e.kind in ("int", "real"):
                e.const = float(v)
                return ty
            elif ty.is_intlike and e.kind == "int":
                if not T.int_fits(ty, v):
                    self.d.error("E022", f"{v} does not fit {ty.name} ({ty.lo}..{ty.hi})", e.pos)
                e.const = v
                return ty
            self.d.error("E003", f"{e.type_name}# does not take this literal", e.pos)
            return None
        if e.kind == "bool":
            e.const = bool(v)
            return T.BOOL
        exp = T.base_elementary(expected) if expected is not None else None
        if isinstance(expected, T.EnumType) or isinstance(T.resolve(expected) if expected else None, T.EnumType):
            exp = None
        if e.kind == "real":
            e.const = float(v)
            return exp if exp is not None and exp.is_real else T.LREAL
        # untyped integer: the expected type if it fits, else the smallest signed that does
        e.const = v
        if exp is not None and (exp.is_intlike and T.int_fits(exp, v) or exp.is_real):
            return exp
        for cand in (T.INT, T.DINT, T.LINT, T.ULINT):
            if T.int_fits(cand, v):
                return cand
        self.d.error("E022", f"{v} is too large for any integer type", e.pos)
        return None

    def _time_repr(self, ty: T.ElementaryType, ns: int, e: A.Expr) -> int:
        v = ns // ty.unit_ns if ns >= 0 else -((-ns) // ty.unit_ns)
        if ty.lo is not None and not (ty.lo <= v <= ty.hi):
            self.d.error("E022", f"the literal is outside the range of {ty.name}", e.pos,
                         "use the L-type (LTIME, LDT ...) for larger values")
        return v

    def _name(self, e: A.Name, scope: _Scope, expected: Optional[T.Type]) -> Optional[T.Type]:
        key = e.name.upper()
        pou = scope.pou
        sym = None
        if pou is not None:
            sym = pou.vars.get(key)
            if sym is None and pou.result is not None and key == pou.name.upper():
                sym = pou.result
        if sym is None:
            sym = self.globals.get(key)
        if sym is not None:
            e.sym = sym
            if sym.constant and sym.const_value is not None:
                e.const = sym.const_value
            return sym.type
        # a bare enumerator: the expected enumeration first, else unique
        cands = self.enumerators.get(key)
        if cands:
            exp = T.resolve(expected) if expected is not None else None
            pick = [c for c in cands if c[0] is exp] or (cands if len(cands) == 1 else [])
            if pick:
                e.const = pick[0][1]
                e.sym = pick[0][0]
                return pick[0][0]
            self.d.error("E010", f"'{e.name}' is an enumerator of several types", e.pos,
                         f"qualify it, e.g. {cands[0][0].name}#{e.name}")
            return None
        if key in self.pous or key in self.std or key in BUILTINS:
            self.d.error("E010", f"'{e.name}' is a POU, not a variable", e.pos,
                         "call it with parentheses: name(...)")
            return None
        if key == "NULL":
            e.const = None
            return T.NULL
        names = [g.name for g in self.globals.values()]
        if pou is not None:
            names += [v.name for v in pou.vars.values()]
        self.d.error("E010", f"unknown name '{e.name}'", e.pos, self._suggest(key, names)
                     or "declare it in a VAR block")
        return None

    def _enum_literal(self, e: A.EnumLiteral, expected: Optional[T.Type]) -> Optional[T.Type]:
        if e.type_name is None:
            fake = A.Name(e.value_name, pos=e.pos)
            return self._name(fake, _Scope(None), expected)
        ty = self.types.get(e.type_name.upper())
        ty = T.resolve(ty) if ty is not None else None
        if not isinstance(ty, T.EnumType):
            self.d.error("E012", f"'{e.type_name}' is not an enumeration type", e.pos,
                         self._suggest(e.type_name.upper(),
                                       [k for k, t in self.types.items() if isinstance(t, T.EnumType)]))
            return None
        v = ty.values.get(e.value_name.upper())
        if v is None:
            self.d.error("E013", f"enumeration {ty.name} has no value '{e.value_name}'", e.pos,
                         self._suggest(e.value_name.upper(), list(ty.values)))
            return None
        e.const = v
        return ty

    def _member(self, e: A.Member, scope: _Scope) -> Optional[T.Type]:
        # Type.Value (CODESYS qualified enumerator)
        if isinstance(e.base, A.Name):
            key = e.base.name.upper()
            is_var = scope.pou is not None and key in scope.pou.vars or key in self.globals
            et = self.types.get(key)
            if not is_var and et is not None and isinstance(T.resolve(et), T.EnumType):
                lit = A.EnumLiteral(e.base.name, e.name, pos=e.pos)
                ty = self._enum_literal(lit, None)
                e.const = lit.const
                return ty
        bty = self.expr(e.base, scope)
        if bty is None:
            return None
        b = T.resolve(bty)
        key = e.name.upper()
        if isinstance(b, T.StructType):
            f = b.fields.get(key)
            if f is None:
                self.d.error("E013", f"{b.name} has no field '{e.name}'", e.pos,
                             self._suggest(key, list(b.fields)))
                return None
            e.sym = f
            return f.type
        if isinstance(b, T.FBType):
            v = b.pou.vars.get(key)
            if v is None:
                self.d.error("E013", f"{b.name} has no member '{e.name}'", e.pos,
                             self._suggest(key, [k for k, s in b.pou.vars.items()
                                                 if s.section in _SECTIONS_READABLE_OUTSIDE]))
                return None
            if v.section not in ("VAR_INPUT", "VAR_OUTPUT") and not (scope.pou is b.pou):
                self.d.error("E013", f"'{v.name}' is internal to {b.name}", e.pos,
                             "only VAR_INPUT and VAR_OUTPUT are visible outside a block")
                return None
            e.sym = v
            return v.type
        self.d.error("E013", f"{bty} has no members", e.pos)
        return None

    def _index(self, e: A.Index, scope: _Scope) -> Optional[T.Type]:
        bty = self.expr(e.base, scope)
        for ix in e.indices:
            ity = self.expr(ix, scope)
            ie = T.base_elementary(ity) if ity is not None else None
            if ity is not None and (ie is None or not ie.is_intlike):
                self.d.error("E050", f"an array index must be an integer, not {ity}", ix.pos)
        if bty is None:
            return None
        b = T.resolve(bty)
        if isinstance(b, T.StringType):
            self.d.error("E050", "strings are not indexed", e.pos, "use MID(s, 1, pos)")
            return None
        if not isinstance(b, T.ArrayType):
            self.d.error("E050", f"{bty} is not an array", e.pos)
            return None
        if len(e.indices) != len(b.dims):
            self.d.error("E050", f"{b} has {len(b.dims)} dimension(s), {len(e.indices)} index(es) given",
                         e.pos)
            return None
        for ix, dim in zip(e.indices, b.dims):
            if dim is not None and isinstance(ix.const, int) and not (dim[0] <= ix.const <= dim[1]):
                self.d.error("E051", f"index {ix.const} is outside {dim[0]}..{dim[1]}", ix.pos)
        return b.elem

    def _bit_access(self, e: A.BitAccess, scope: _Scope) -> Optional[T.Type]:
        bty = self.expr(e.base, scope)
        self.expr(e.bit, scope)
        if bty is None:
            return None
        be = T.base_elementary(bty)
        if be is None or not be.is_intlike:
            self.d.error("E053", f"bit access needs an integer or bit-string variable, not {bty}", e.pos)
            return None
        if not isinstance(e.bit.const, int) or not 0 <= e.bit.const < be.bits:
            self.d.error("E053", f"bit number must be a constant 0..{be.bits - 1} for {be.name}", e.bit.pos)
            return None
        return T.BOOL

    def _address_fits(self, addr: A.LocatedAddress, ty: Optional[T.ElementaryType], pos: A.Pos) -> bool:
        """Report (E082) a direct address outside the process image, and
        (E083) a CODESYS placeholder address %I* that nothing maps."""
        if not addr.indices:
            self.d.error("E083", f"{addr.text} is an unconfigured address", pos,
                         "give the full address (e.g. %IX0.0); mapping %I* through VAR_CONFIG "
                         "is not supported")
            return False
        if self._image_probe is None:
            return True
        try:
            if ty is None:
                self._image_probe.table(addr)
            else:
                self._image_probe.accessor(addr, ty)
        except ValueError as exc:   # the image's AddressError
            self.d.error("E082", str(exc), pos, "the image areas are "
                         f"{self._image_probe.size // 1024} KiB each")
            return False
        return True

    def _located(self, e: A.Located) -> Optional[T.Type]:
        ty = self._located_type(e)
        if ty is not None and not self._address_fits(e.addr, T.base_elementary(ty)
                                                     if e.addr.table is None else None, e.pos):
            return None
        return ty

    def _located_type(self, e: A.Located) -> Optional[T.Type]:
        a = e.addr
        schneider = self.profile.addressing == "schneider"
        if (a.bit is not None or a.table is not None) and not schneider:
            self.d.error("E080", f"{a.text} is Schneider addressing", e.pos,
                         "compile with --profile schneider, or write %MX<byte>.<bit>")
            return None
        if a.table is not None:
            if a.size != "W":
                self.d.error("E080", f"{a.text}: tables are of words (%MW)", e.pos)
                return None
            return T.ArrayType([(0, a.table - 1)], T.INT)
        if a.bit is not None:
            if a.size != "W" or not 0 <= a.bit <= 15:
                self.d.error("E080", f"{a.text}: :Xn needs a word address and n in 0..15", e.pos)
                return None
            return T.BOOL
        if a.size in ("", "X"):
            if not schneider and a.size == "" and len(a.indices) < 2:
                self.d.error("E080", f"{a.text}: a bit address needs byte.bit", e.pos,
                             f"write %{a.area}X<byte>.<bit>")
                return None
            return T.BOOL
        if schneider:
            return {"B": T.BYTE, "W": T.INT, "D": T.DINT, "L": T.LINT}[a.size]
        return {"B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}[a.size]

    # ---------------------------------------------------------------- operators

    def _unary(self, e: A.Unary, scope: _Scope, expected: Optional[T.Type]) -> Optional[T.Type]:
        ty = self.expr(e.operand, scope, expected)
        if ty is None:
            return None
        be = T.base_elementary(ty)
        c = e.operand.const
        if e.op == "NOT":
            if be is not None and (be.is_bool or be.is_bits or
                                   (be.is_integer and self.profile.bitwise_on_integers)):
                if isinstance(T.resolve(ty), T.EnumType):
                    be = None
                else:
                    if c is not None:
                        e.const = (not c) if be.is_bool else self._wrap_const(be, ~c)
                    return be
            self.d.error("E023", f"NOT needs BOOL or a bit string, not {ty}", e.pos)
            return None
        if be is None or not (be.is_integer or be.is_real or be.category == T.DURATION or
                              (be.is_bits and self.profile.int_bits_mix)):
            self.d.error("E023", f"unary {e.op} needs a number, not {ty}", e.pos)
            return None
        if c is not None:
            e.const = -c if e.op == "-" else c
            if is_flexible(e.operand) and e.op == "-" and isinstance(c, int) and expected is None:
                # -32768 is an INT literal, not the negation of a DINT
                for cand in (T.INT, T.DINT, T.LINT):
                    if T.int_fits(cand, -c):
                        return cand
        return be

    def _wrap_const(self, t: T.ElementaryType, v: int) -> int:
        return rtlib.wrap(t, v)

    def _binary(self, e: A.Binary, scope: _Scope, expected: Optional[T.Type]) -> Optional[T.Type]:
        op = e.op
        lt = self.expr(e.left, scope)
        rt = self.expr(e.right, scope, expected=lt if is_flexible(e.right) else None)
        if lt is None or rt is None:
            return None
        if is_flexible(e.left) and not is_flexible(e.right):
            lt = self.expr(e.left, scope, expected=rt)
            if lt is None:
                return None
        if op in ("AND", "OR", "XOR", "AND_THEN", "OR_ELSE"):
            return self._logical(e, lt, rt)
        if op in ("=", "<>", "<", ">", "<=", ">="):
            return self._comparison(e, lt, rt)
        return self._arithmetic(e, lt, rt, expected)

    def _logical(self, e: A.Binary, lt: T.Type, rt: T.Type) -> Optional[T.Type]:
        le, re_ = T.base_elementary(lt), T.base_elementary(rt)
        if le is not None and re_ is not None and le.is_bool and re_.is_bool:
            ty = T.BOOL
        elif e.op in ("AND_THEN", "OR_ELSE"):
            self.d.error("E023", f"{e.op} needs BOOL operands", e.pos)
            return None
        elif le is not None and re_ is not None and self._bitwise_ok(le) and self._bitwise_ok(re_):
            ty = self._common(le, re_, e)
            if ty is None:
                return None
        else:
            self.d.error("E023", f"{e.op} needs BOOL or bit-string operands, not {lt} and {rt}", e.pos,
                         "compare numbers first, e.g. (x > 0) AND (y > 0)")
            return None
        lc, rc = e.left.const, e.right.const
        if lc is not None and rc is not None:
            if ty.is_bool:
                e.const = {"AND": lc and rc, "AND_THEN": lc and rc, "OR": lc or rc,
                           "OR_ELSE": lc or rc, "XOR": lc != rc}[e.op]
            else:
                e.const = {"AND": lc & rc, "OR": lc | rc, "XOR": lc ^ rc}[e.op]
        return ty

    def _bitwise_ok(self, t: T.ElementaryType) -> bool:
        return t.is_bool or t.is_bits or (t.is_integer and self.profile.bitwise_on_integers)

    def _comparison(self, e: A.Binary, lt: T.Type, rt: T.Type) -> Optional[T.Type]:
        l, r = T.resolve(lt), T.resolve(rt)
        ok = False
        if isinstance(l, T.EnumType) or isinstance(r, T.EnumType):
            ok = l is r
        elif isinstance(l, T.StringType) and isinstance(r, T.StringType):
            ok = l.wide == r.wide
        elif isinstance(l, T.RefType) or isinstance(r, T.RefType):
            # r = 0 / r <> 0 is how CODESYS and TwinCAT test for NULL
            def refish(t, side):
                return isinstance(t, (T.RefType, T.NullType)) or side.const == 0
            ok = e.op in ("=", "<>") and refish(l, e.left) and refish(r, e.right)
        else:
            le, re_ = T.base_elementary(l), T.base_elementary(r)
            if le is not None and re_ is not None:
                if le.is_bool and re_.is_bool:
                    ok = True
                elif le.is_time or re_.is_time:
                    ok = le.category == re_.category
                elif self._common(le, re_, e, report=False) is not None:
                    ok = True
        if not ok:
            self.d.error("E020", f"cannot compare {lt} with {rt}", e.pos,
                         "convert one side so both have the same type")
            return None
        lc, rc = e.left.const, e.right.const
        if lc is not None and rc is not None and not isinstance(l, T.RefType):
            import operator
            fn = {"=": operator.eq, "<>": operator.ne, "<": operator.lt, ">": operator.gt,
                  "<=": operator.le, ">=": operator.ge}[e.op]
            e.const = fn(lc, rc)
        return T.BOOL

    def _common(self, le: T.ElementaryType, re_: T.ElementaryType, e: A.Expr,
                report: bool = True) -> Optional[T.ElementaryType]:
        c = common_type(le, re_, self.profile)
        if c is None and report:
            self.d.error("E020", f"no common type for {le} and {re_}", e.pos,
                         f"convert one side explicitly, e.g. {le.name}_TO_{re_.name}(...)")
        return c

    def _arithmetic(self, e: A.Binary, lt: T.Type, rt: T.Type, expected: Optional[T.Type]) -> Optional[T.Type]:
        op = e.op
        le, re_ = T.base_elementary(lt), T.base_elementary(rt)
        if le is None or re_ is None or isinstance(T.resolve(lt), T.EnumType) \
                or isinstance(T.resolve(rt), T.EnumType):
            self.d.error("E023", f"'{op}' needs numbers, not {lt} and {rt}", e.pos)
            return None
        if le.is_time or re_.is_time:
            return self._time_arith(e, le, re_)
        num = (T.SIGNED, T.UNSIGNED, T.REALCAT)
        bits_ok = self.profile.int_bits_mix
        for t, side in ((le, e.left), (re_, e.right)):
            if not (t.category in num or (t.is_bits and bits_ok)):
                self.d.error("E023", f"'{op}' needs numbers, not {t.name}", side.pos)
                return None
        if op == "**":
            ty = T.REAL if le is T.REAL and re_ in (T.REAL, T.SINT, T.INT, T.USINT, T.UINT) else T.LREAL
            if le.is_real:
                ty = le
        else:
            ty = self._common(le, re_, e)
            if ty is None:
                return None
        if op == "MOD" and not ty.is_intlike:
            self.d.error("E023", "MOD needs integers", e.pos, "use x - TRUNC(x / y) * y for REAL")
            return None
        lc, rc = e.left.const, e.right.const
        if lc is not None and rc is not None:
            e.const = self._fold_arith(op, lc, rc, ty, e)
        elif op in ("/", "MOD") and rc == 0 and ty.is_intlike:
            self.d.error("E027", "division by the constant zero", e.right.pos)
        return ty

    def _fold_arith(self, op: str, a: Any, b: Any, ty: T.ElementaryType, e: A.Expr) -> Any:
        try:
            if op == "+":
                return a + b
            if op == "-":
                return a - b
            if op == "*":
                return a * b
            if op == "/":
                return rtlib.idiv(int(a), int(b)) if ty.is_intlike else rtlib.rdiv(float(a), float(b))
            if op == "MOD":
                return rtlib.imod(int(a), int(b))
            if op == "**":
                return rtlib.expt(float(a), float(b))
        except ZeroDivisionError:
            self.d.error("E027", "division by the constant zero", e.pos)
        except OverflowError:
            self.d.error("E022", "constant expression overflows", e.pos)
        return None

    def _time_arith(self, e: A.Binary, le: T.ElementaryType, re_: T.ElementaryType) -> Optional[T.Type]:
        op = e.op
        cat = (le.category, re_.category)
        name = None
        ty = None
        if cat == (T.DURATION, T.DURATION) and op in ("+", "-"):
            ty = T.LTIME if T.LTIME in (le, re_) else T.TIME
            if le is not re_:
                name = ("ADD_" if op == "+" else "SUB_") + "LTIME"
        elif le.category == T.DURATION and op in ("*", "/") and (re_.is_integer or re_.is_real):
            ty = le
            name = ("MUL_" if op == "*" else "DIV_") + ("LTIME" if le is T.LTIME else "TIME")
        elif cat == (T.TODCAT, T.DURATION) and op in ("+", "-"):
            ty, name = le, ("ADD_TOD_TIME" if op == "+" else "SUB_TOD_TIME")
        elif cat == (T.DTCAT, T.DURATION) and op in ("+", "-"):
            ty, name = le, ("ADD_DT_TIME" if op == "+" else "SUB_DT_TIME")
        elif op == "-" and le.category == re_.category and le.category in (T.DATECAT, T.TODCAT, T.DTCAT):
            ty = T.TIME
            name = {T.DATECAT: "SUB_DATE_DATE", T.TODCAT: "SUB_TOD_TOD", T.DTCAT: "SUB_DT_DT"}[le.category]
        if ty is None:
            self.d.error("E023", f"'{op}' is not defined for {le.name} and {re_.name}", e.pos,
                         "durations add to durations, dates and times of day; "
                         "a duration multiplies by a number")
            return None
        if name is not None:
            if le.bits == 64 or re_.bits == 64:
                lname = {"ADD_TOD_TIME": "ADD_LTOD_LTIME", "SUB_TOD_TIME": "SUB_LTOD_LTIME",
                         "ADD_DT_TIME": "ADD_LDT_LTIME", "SUB_DT_TIME": "SUB_LDT_LTIME",
                         "SUB_DATE_DATE": "SUB_LDATE_LDATE", "SUB_TOD_TOD": "SUB_LTOD_LTOD",
                         "SUB_DT_DT": "SUB_LDT_LDT"}.get(name)
                if lname in self.std:
                    name = lname
                    if ty is T.TIME:
                        ty = T.LTIME
            func = self.std.get(name)
            if func is None:
                self.d.error("E023", f"'{op}' on {le.name} and {re_.name} is not available", e.pos)
                return None
            e.impl = CallInfo("std", func=func, rtypes=(ty, le, re_), param_types=[le, re_])
        return ty

    # ================================================================ calls

    def call(self, e: A.Call, scope: _Scope, as_statement: bool) -> Optional[T.Type]:
        callee = e.callee
        if isinstance(callee, A.Name):
            key = callee.name.upper()
            local = None
            if scope.pou is not None:
                local = scope.pou.vars.get(key)
            if local is None and key not in self.pous:
                local = self.globals.get(key)
            if local is not None:
                return self._fb_call(e, callee, scope, as_statement)
            pou = self.pous.get(key)
            if pou is not None:
                if pou.kind == "FUNCTION":
                    return self._user_function_call(e, pou, scope)
                if pou.kind == "PROGRAM":
                    self.d.error("E043", f"'{pou.name}' is a PROGRAM; programs are started by tasks",
                                 e.pos, "assign it to a TASK in the CONFIGURATION, or make it a "
                                 "FUNCTION_BLOCK and call an instance")
                else:
                    self.d.error("E043", f"'{pou.name}' is a FUNCTION_BLOCK type, not an instance", e.pos,
                                 f"declare an instance (inst : {pou.name};) and call inst(...)")
                self._check_args_loosely(e, scope)
                return None
            native = self.natives.get(key)
            if native is not None:
                return self._native_call(e, native, scope)
            if key in BUILTINS:
                return self._builtin_call(e, key, scope)
            func = self.std.get(key)
            if func is not None:
                return self._std_call(e, func, scope)
            self.d.error("E043", f"unknown function '{callee.name}'", callee.pos,
                         self._suggest(key, list(self.pous) + list(self.std) + list(BUILTINS))
                         or "declare it as a FUNCTION")
            self._check_args_loosely(e, scope)
            return None
        if isinstance(callee, (A.Member, A.Index)):  # inst.sub(...), timers[i](...)
            return self._fb_call(e, callee, scope, as_statement)
        self.d.error("E043", "this cannot be called", e.pos)
        return None

    def _check_args_loosely(self, e: A.Call, scope: _Scope) -> None:
        for a in e.args:
            if a.value is not None:
                self.expr(a.value, scope)

    def _fb_call(self, e: A.Call, inst: A.Expr, scope: _Scope, as_statement: bool) -> Optional[T.Type]:
        ity = self.expr(inst, scope)
        if ity is None:
            self._check_args_loosely(e, scope)
            return None
        fbt = T.resolve(ity)
        if not isinstance(fbt, T.FBType):
            self.d.error("E043", f"'{self._describe(inst)}' is {ity}, not a function block instance", inst.pos)
            self._check_args_loosely(e, scope)
            return None
        if not as_statement:
            self.d.error("E043", "a function block call is a statement, not a value", e.pos,
                         f"call it on its own line, then read an output, e.g. {self._describe(inst)}.Q")
        info = CallInfo("fb", pou=fbt.pou, instance=inst)
        self._bind_args(e, fbt.pou, info, scope, is_fb=True)
        e.target = info
        return None

    def _describe(self, e: A.Expr) -> str:
        if isinstance(e, A.Name):
            return e.name
        if isinstance(e, A.Member):
            return f"{self._describe(e.base)}.{e.name}"
        return "expression"

    def _user_function_call(self, e: A.Call, pou: POUInfo, scope: _Scope) -> Optional[T.Type]:
        info = CallInfo("function", pou=pou)
        self._bind_args(e, pou, info, scope, is_fb=False)
        e.target = info
        return pou.return_type if pou.return_type is not None else T.BOOL

    def _bind_args(self, e: A.Call, pou: POUInfo, info: CallInfo, scope: _Scope, is_fb: bool) -> None:
        positional = pou.params("VAR_INPUT", "VAR_IN_OUT")
        bound: set = set()
        pos_i = 0
        seen_formal = False
        for a in e.args:
            if a.name is None:
                if seen_formal:
                    self.d.error("E041", "a positional argument after a named one", a.pos,
                                 "name every argument, or put positional ones first")
                if pos_i >= len(positional):
                    self.d.error("E041", f"too many arguments for {pou.name} "
                                 f"(it takes {len(positional)})", a.pos)
                    if a.value is not None:
                        self.expr(a.value, scope)
                    continue
                param = positional[pos_i]
                pos_i += 1
            else:
                seen_formal = True
                param = pou.vars.get(a.name.upper())
                if param is None or param.section not in ("VAR_INPUT", "VAR_IN_OUT", "VAR_OUTPUT"):
                    names = [v.name for v in pou.params("VAR_INPUT", "VAR_IN_OUT", "VAR_OUTPUT")]
                    self.d.error("E040", f"{pou.name} has no parameter '{a.name}'", a.pos,
                                 f"its parameters are: {', '.join(names)}" if names else
                                 f"{pou.name} takes no parameters")
                    if a.value is not None:
                        self.expr(a.value, scope)
                    continue
            key = param.name.upper()
            if key in bound:
                self.d.error("E041", f"parameter '{param.name}' is given twice", a.pos)
                continue
            bound.add(key)
            if param.section == "VAR_OUTPUT":
                if not a.output:
                    self.d.error("E040", f"'{param.name}' is an output; bind it with =>", a.pos,
                                 f"write {param.name} => variable")
                    continue
                if a.value is None:
                    continue
                tty = self.lvalue(a.value, scope)
                if tty is not None:
                    src = T.BOOL if a.negated else param.type
                    self.check_convertible(src, tty, A.Name(param.name, pos=a.pos, ty=param.type),
                                           f"output '{param.name}'")
                info.outputs.append((param, a.value, a.negated))
                continue
            if a.output:
                self.d.error("E040", f"'{param.name}' is an input; pass it with :=", a.pos)
                continue
            if a.value is None:
                continue
            if param.section == "VAR_IN_OUT":
                vty = self.expr(a.value, scope)
                if vty is None:
                    continue
                if not self._is_lvalue_expr(a.value):
                    self.d.error("E042", f"VAR_IN_OUT '{param.name}' needs a variable, not an expression",
                                 a.value.pos, "pass a variable: it is passed by reference")
                    continue
                self._check_writable(a.value, scope)
                if not self._inout_compatible(vty, param.type):
                    self.d.error("E020", f"VAR_IN_OUT '{param.name}' is {param.type}; got {vty}",
                                 a.value.pos, "a reference parameter needs exactly its type")
                    continue
                self._mark_boxed(a.value, scope)
                info.inouts.append((param, a.value))
            else:
                vty = self.expr(a.value, scope, expected=param.type)
                if vty is not None:
                    self.check_convertible(vty, param.type, a.value, f"input '{param.name}'")
                info.inputs.append((param, a.value))
        for param in pou.params("VAR_IN_OUT"):
            if param.name.upper() not in bound:
                self.d.error("E042", f"VAR_IN_OUT '{param.name}' of {pou.name} is not connected", e.pos,
                             f"pass a variable: {param.name} := myVar")
        for _, target, _n in info.outputs:
            self._mark_boxed(target, scope)

    def _inout_compatible(self, arg: T.Type, param: T.Type) -> bool:
        a, p = T.resolve(arg), T.resolve(param)
        if isinstance(p, T.ArrayType) and isinstance(a, T.ArrayType) and p.variable_length:
            return len(a.dims) == len(p.dims) and same_type(a.elem, p.elem)
        if isinstance(p, T.StringType) and isinstance(a, T.StringType):
            return a.wide == p.wide
        return same_type(a, p)

    def _mark_boxed(self, e: A.Expr, scope: _Scope) -> None:
        """A FUNCTION local passed by reference lives in a cell."""
        if isinstance(e, A.Name) and isinstance(e.sym, VarSymbol):
            e.sym.address_taken = True
        if isinstance(e, A.Name) and isinstance(e.sym, VarSymbol) and e.sym.owner is not None \
                and e.sym.owner.kind == "FUNCTION" and not T.resolve(e.sym.type).is_aggregate:
            e.sym.boxed = True

    # ---------------------------------------------------------------- standard functions

    def _std_args(self, e: A.Call, func, scope: _Scope) -> Optional[list]:
        """Match the call's arguments to the parameters of a standard
        function; returns the argument expressions in parameter order."""
        params = list(func.params)
        n_fixed = len(params)
        args = e.args
        if func.extensible:
            n_fixed -= 1
        out: list = []
        if any(a.name is not None for a in args):
            by_name = {}
            for a in args:
                if a.name is None or a.output:
                    self.d.error("E041", f"{func.name}: mix of named and positional arguments", a.pos)
                    return None
                by_name[a.name.upper()] = a
            names = [p[0].upper() for p in params]
            if func.extensible:  # IN1, IN2, ... beyond the fixed ones
                base = names[-1].rstrip("0123456789")
                digits = names[-1][len(base):]
                i = int(digits) + 1 if digits else len(names)
                while True:
                    nxt = f"{base}{i}"
                    if nxt in by_name and nxt not in names:
                        names.append(nxt)
                        i += 1
                    else:
                        break
            for a in args:
                if a.name.upper() not in names:
                    self.d.error("E040", f"{func.name} has no parameter '{a.name}'", a.pos,
                                 f"its parameters are: {', '.join(p[0] for p in params)}")
                    return None
            for n in names:
                if n not in by_name:
                    self.d.error("E041", f"{func.name}: parameter '{n}' is missing", e.pos)
                    return None
                out.append(by_name[n].value)
        else:
            out = [a.value for a in args]
            for a in args:
                if a.output:
                    self.d.error("E040", f"{func.name} has no outputs", a.pos)
                    return None
        need = len(params)
        if len(out) < need or (not func.extensible and len(out) > need):
            self.d.error("E041", f"{func.name} takes {'at least ' if func.extensible else ''}{need} "
                         f"argument(s), {len(out)} given", e.pos,
                         f"{func.name}({', '.join(p[0] for p in params)})")
            return None
        return out

    def _std_call(self, e: A.Call, func, scope: _Scope) -> Optional[T.Type]:
        args = self._std_args(e, func, scope)
        if args is None:
            self._check_args_loosely(e, scope)
            return None
        specs = [p[1] for p in func.params]
        while len(specs) < len(args):
            specs.append(specs[-1])
        # 1) type every argument; untyped literals wait for their type variable
        arg_types: list = []
        for a, spec in zip(args, specs):
            exp = T.ELEMENTARY.get(spec.upper()) if ":" not in spec else None
            if spec.upper() in ("STRING", "WSTRING"):
                exp = T.StringType(self.profile.default_string_length, spec.upper() == "WSTRING")
            arg_types.append(self.expr(a, scope, expected=exp))
        if any(t is None for t in arg_types):
            return None
        # 2) unify type variables
        bindings: dict = {}
        for a, spec, t in zip(args, specs, arg_types):
            if ":" not in spec:
                continue
            var, gen = spec.split(":", 1)
            if is_flexible(a):
                continue
            cur = bindings.get(var)
            bindings[var] = t if cur is None else self._unify(cur, t, e)
            if bindings[var] is None:
                return None
        for a, spec, t in zip(args, specs, arg_types):
            if ":" in spec:
                var = spec.split(":", 1)[0]
                if var not in bindings:
                    bindings[var] = t  # only literals: their own type
        for var, bound in list(bindings.items()):
            gen = next(sp.split(":", 1)[1] for sp in specs if sp.startswith(var + ":"))
            bindings[var] = generic_fit(bound, gen, self.profile)
        # 3) check membership and convertibility
        param_types: list = []
        for i, (a, spec, t) in enumerate(zip(args, specs, arg_types)):
            if ":" in spec:
                var, gen = spec.split(":", 1)
                want = bindings[var]
                if not T.is_generic_member(want, gen):
                    self.d.error("E020", f"{func.name}: {want} is not {gen}", a.pos)
                    return None
                if is_flexible(a):
                    arg_types[i] = self.expr(a, scope, expected=want)
                self.check_convertible(arg_types[i], want, a, f"the argument of {func.name}")
                param_types.append(want)
            elif spec.upper() in T.GENERICS:
                t = generic_fit(t, spec, self.profile)
                if not T.is_generic_member(t, spec):
                    self.d.error("E020", f"{func.name}: argument {i + 1} is {t}, expected {spec}", a.pos)
                    return None
                param_types.append(t)
            else:
                want = T.ELEMENTARY.get(spec.upper())
                if want is None and spec.upper() in ("STRING", "WSTRING"):
                    want = T.StringType(self.profile.default_string_length, spec.upper() == "WSTRING")
                if want is None:
                    self.d.error("E020", f"{func.name}: unknown parameter type {spec}", a.pos)
                    return None
                self.check_convertible(t, want, a, f"argument {i + 1} of {func.name}")
                param_types.append(want)
        ret = func.ret
        if ":" in ret:
            ret = ret.split(":", 1)[0]
        if ret in bindings:
            rty = bindings[ret]
        elif ret.upper() in ("STRING", "WSTRING"):
            rty = T.StringType(255, ret.upper() == "WSTRING")
        else:
            rty = T.ELEMENTARY.get(ret.upper())
            if rty is None:
                self.d.error("E020", f"{func.name}: unknown result type {ret}", e.pos)
                return None
        e.target = CallInfo("std", func=func, args=args, param_types=param_types,
                            rtypes=(rty, *arg_types))
        if all(a.const is not None for a in args) and self._foldable(func):
            try:
                e.const = self._call_impl(func, e.target, [a.const for a in args])
            except Exception:  # not foldable; evaluated at run time
                e.const = None
        return rty

    _FOLDABLE_NAMES = ("ABS", "SQRT", "MAX", "MIN", "LIMIT", "SEL", "MUX", "SHL", "SHR", "ROL", "ROR",
                          "LEN", "CONCAT", "LEFT", "RIGHT", "MID", "TRUNC", "EXPT", "MOVE")

    def _foldable(self, func) -> bool:
        return "_TO_" in func.name or func.name.startswith("TO_") or func.name in self._FOLDABLE_NAMES

    def _call_impl(self, func, info: CallInfo, values: list) -> Any:
        if func.typed:
            return func.impl(info.rtypes, *values)
        return func.impl(*values)

    def _unify(self, a: T.Type, b: T.Type, e: A.Expr) -> Optional[T.Type]:
        if same_type(a, b):
            return a
        ae, be = T.base_elementary(a), T.base_elementary(b)
        if isinstance(T.resolve(a), T.StringType) and isinstance(T.resolve(b), T.StringType):
            return a if T.resolve(a).length >= T.resolve(b).length else b
        if ae is not None and be is not None and not isinstance(T.resolve(a), T.EnumType):
            c = self._common(ae, be, e)
            return c
        self.d.error("E020", f"arguments of types {a} and {b} do not match", e.pos)
        return None

    # ---------------------------------------------------------------- builtins

    def _builtin_call(self, e: A.Call, key: str, scope: _Scope) -> Optional[T.Type]:
        args = [a for a in e.args]
        if key in ("TIME", "LTIME"):
            if args:
                self.d.error("E041", f"{key}() takes no arguments", e.pos,
                             f"{key}() reads the task clock; to convert use TO_{key}(x)")
                return None
            e.target = CallInfo("builtin", func=key)
            return T.TIME if key == "TIME" else T.LTIME
        if len(args) != 1 or args[0].name is not None or args[0].value is None:
            self.d.error("E041", f"{key} takes one argument", e.pos)
            return None
        a = args[0].value
        ty = self.expr(a, scope)
        if ty is None:
            return None
        e.target = CallInfo("builtin", func=key, args=[a])
        if key == "SIZEOF":
            e.const = self._sizeof(ty)
            return T.UDINT if e.const is not None and e.const < (1 << 32) else T.ULINT
        if not self._is_lvalue_expr(a) or (isinstance(a, A.Located)):
            self.d.error("E031", f"{key} needs a variable", a.pos)
            return None
        self._mark_boxed(a, scope)
        if isinstance(a, A.BitAccess):
            self.d.error("E031", f"{key} of a single bit is not possible", a.pos)
            return None
        return T.RefType(ty, pointer=(key == "ADR"))

    def _sizeof(self, ty: T.Type) -> Optional[int]:
        t = T.resolve(ty)
        if isinstance(t, T.ElementaryType):
            return max(1, t.bits // 8)
        if isinstance(t, (T.EnumType, T.SubrangeType)):
            return max(1, T.base_elementary(t).bits // 8)
        if isinstance(t, T.StringType):
            return (t.length + 1) * (2 if t.wide else 1)
        if isinstance(t, T.ArrayType) and not t.variable_length:
            n = 1
            for lo, hi in t.dims:
                n *= hi - lo + 1
            es = self._sizeof(t.elem)
            return None if es is None else n * es
        if isinstance(t, T.StructType):
            sizes = [self._sizeof(f.type) for f in t.fields.values()]
            return None if None in sizes else sum(sizes)
        if isinstance(t, T.RefType):
            return 8
        return None

    def _native_call(self, e: A.Call, fn: NativeFunction, scope: _Scope) -> Optional[T.Type]:
        """A call of a native function (st/native.py): positional arguments
        checked against the declaration's parameter kinds."""
        args = e.args
        if len(args) != len(fn.params) or any(a.name is not None or a.value is None for a in args):
            self.d.error("E041", f"{fn.name} takes {len(fn.params)} positional arguments", e.pos, fn.usage)
            self._check_args_loosely(e, scope)
            return None
        vals = [a.value for a in args]
        tys = [self.expr(v, scope) for v in vals]
        if any(t is None for t in tys):
            return None
        for i, (param, ty, value) in enumerate(zip(fn.params, tys, vals)):
            if not self._native_arg_fits(param, ty):
                self.d.error("E020", f"{fn.name}: {param.label(i + 1)} must be {param.expected}", value.pos)
            elif param.kind == native.WORDS and param.min_words:
                dims = T.resolve(ty).dims[0]
                if dims is not None and dims[1] - dims[0] + 1 < param.min_words:
                    self.d.error("E020", f"{fn.name}: {param.label(i + 1)} needs {param.min_words} words",
                                 value.pos)
        e.target = CallInfo("native", func=fn, args=vals, rtypes=tuple(tys))
        return T.ELEMENTARY[fn.result]

    @staticmethod
    def _native_arg_fits(param: native.Param, ty: T.Type) -> bool:
        if param.kind == native.ADDRESS:
            return isinstance(ty, T.SchneiderAddrType)
        if param.kind == native.STRING:
            return isinstance(T.resolve(ty), T.StringType)
        if param.kind == native.ANY_INT:
            be = T.base_elementary(ty)
            return be is not None and be.is_intlike
        t = T.resolve(ty)   # WORDS: a one-dimensional table of 16-bit words
        return isinstance(t, T.ArrayType) and len(t.dims) == 1 and \
            T.base_elementary(t.elem) is not None and T.base_elementary(t.elem).bits == 16

    # ================================================================ configuration

    def _configuration(self, c: A.Configuration) -> None:
        info = ConfigInfo(c.name, node=c)
        task_names: dict = {}
        for res in c.resources:
            for t in res.tasks:
                key = t.name.upper()
                if key in task_names:
                    self.d.error("E090", f"task '{t.name}' is declared twice", t.pos)
                    continue
                task = {"name": t.name, "interval_ms": None, "priority": 0, "single": None, "pos": t.pos,
                        "resource": res.name}
                for pname, pexpr in t.params.items():
                    p = pname.upper()
                    if p == "INTERVAL":
                        ty = self.expr(pexpr, _Scope(None), expected=T.TIME)
                        if ty is not None and T.base_elementary(ty) is not None and \
                                T.base_elementary(ty).category == T.DURATION and pexpr.const is not None:
                            task["interval_ms"] = pexpr.const * T.base_elementary(ty).unit_ns / 1e6
                            if task["interval_ms"] <= 0:
                                self.d.error("E091", "a task INTERVAL must be positive", pexpr.pos)
                        else:
                            self.d.error("E091", "INTERVAL must be a constant TIME such as T#10ms",
                                         pexpr.pos)
                    elif p == "PRIORITY":
                        v = self._const_int(pexpr, _Scope(None), "PRIORITY")
                        if v is not None:
                            if not 0 <= v <= 255:
                                self.d.error("E091", "PRIORITY must be within 0..255", pexpr.pos)
                            task["priority"] = v
                    elif p == "SINGLE":
                        ty = self.expr(pexpr, _Scope(None))
                        if ty is not None and not self._is_bool(ty):
                            self.d.error("E091", "SINGLE must be a BOOL variable", pexpr.pos)
                        task["single"] = pexpr
                    else:
                        self.d.error("E091", f"unknown task parameter '{pname}'", pexpr.pos,
                                     "TASK parameters are INTERVAL, PRIORITY and SINGLE")
                task_names[key] = task
                info.tasks.append(task)
        inst_names: set = set()
        for res in c.resources:
            for p in res.programs:
                key = p.name.upper()
                if key in inst_names:
                    self.d.error("E090", f"program instance '{p.name}' is declared twice", p.pos)
                    continue
                inst_names.add(key)
                pou = self.pous.get(p.type_name.upper())
                if pou is None or pou.kind != "PROGRAM":
                    self.d.error("E092", f"'{p.type_name}' is not a PROGRAM", p.pos,
                                 self._suggest(p.type_name.upper(),
                                               [k for k, v in self.pous.items() if v.kind == "PROGRAM"]))
                    continue
                if p.task is not None and p.task.upper() not in task_names:
                    self.d.error("E093", f"unknown task '{p.task}'", p.pos,
                                 self._suggest(p.task.upper(), list(task_names)))
                    continue
                fake = A.Call(A.Name(p.type_name, pos=p.pos), p.args, pos=p.pos)
                binding = CallInfo("fb", pou=pou)
                self._bind_args(fake, pou, binding, _Scope(None), is_fb=True)
                info.programs.append({"name": p.name, "type": pou, "task": p.task, "pos": p.pos,
                                      "binding": binding})
        self.configs.append(info)

    # ================================================================ helpers

    def _suggest(self, key: str, names: list) -> Optional[str]:
        close = difflib.get_close_matches(key, [n.upper() for n in names], n=1, cutoff=0.75)
        if close:
            return f"did you mean '{self._spelled(close[0], names)}'?"
        return None

    @staticmethod
    def _spelled(key: str, names: list) -> str:
        for n in names:
            if n.upper() == key:
                return n
        return key
