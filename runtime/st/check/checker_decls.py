"""The checker's variables: their declarations and initial values.

Declares the globals and the variables of each POU (sections, AT
locations, RETAIN, VAR_EXTERNAL) and evaluates initial values into plans
the code generator emits (init_value).
"""

from __future__ import annotations

from dataclasses import fields
from typing import Any

from .. import ast as A
from .. import types as T
from ..diagnostics import DiagnosticBag
from ..profile import names_where
from .checker_base import CheckerBase, Scope
from .conversions import const_as, same_type
from .symbols import CallInfo, POUInfo, VarSymbol, pyname


class DeclChecks(CheckerBase):
    """Variable declarations and initial values."""

    def _make_var(self, decl: A.VarDecl, block: A.VarBlock, owner: POUInfo | None) -> VarSymbol | None:
        if decl.name.upper() in T.ELEMENTARY and not self._ed2_name(decl, owner):
            # an IEC keyword (CODESYS and TwinCAT refuse it too); as a global it
            # would also hide the standard function of that name (TIME()) from
            # every POU, the library's included, whose errors would then point
            # into files the user did not write (found by tests/fuzz)
            self.d.error(
                "E011",
                f"'{decl.name}' is the name of an elementary type, not a variable's",
                decl.pos,
                f"rename it, e.g. {decl.name}_1",
            )
            return None
        spec, fb_init = self.fb_init_spec(decl.type)  # FB_X(nStart := 5): checker_fbinit.py
        generic = self.generic_input_type(spec, block.kind, owner.kind if owner else None)
        ty = generic[1] if generic is not None else self.type_of(spec, Scope(owner))
        if ty is None:
            return None
        section = block.kind
        rty = T.resolve(ty)
        if isinstance(rty, T.ArrayType) and rty.variable_length and section != "VAR_IN_OUT":
            self.d.error(
                "E050",
                "ARRAY[*] is only allowed for VAR_IN_OUT",
                decl.pos,
                "declare it in VAR_IN_OUT (as CODESYS and TwinCAT want); LOWER_BOUND/UPPER_BOUND give its bounds",
            )
            return None
        prefix = "v_" if owner is not None else "g_"
        sym = VarSymbol(
            decl.name,
            section,
            ty,
            decl.pos,
            pyname(prefix, decl.name),
            owner,
            constant=block.constant,
            retain=block.retain,
            persistent=block.persistent,
            location=decl.location,
            init=decl.init,
            generic=generic[0] if generic is not None else None,
            fb_init=fb_init,
        )
        if decl.location is not None:
            self._check_location_type(sym)
        if block.retain or block.persistent:
            self._check_retained(sym, block)
        if sym.constant:
            # a CONSTANT may size the arrays and strings declared after it
            self._check_var_init(sym, Scope(owner))
            self._inited.add(id(sym))
        return sym

    def _ed2_name(self, decl: A.VarDecl, owner: POUInfo | None) -> bool:
        """A POU's variable named as an ed.3 type (LTIME, LDT ...) where the
        profile reads ed.2 (MatIEC): a plain name there, which hides the
        type's functions in that POU only (a global would hide them from
        every POU, the library's too)."""
        return owner is not None and not self.profile.ed3_type_names_reserved and decl.name.upper() in T.ED3_NAMES

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
        self.d.warning(
            "W111",
            f"{qualifier} has no effect on {sym.name}, {what}",
            sym.pos,
            f"remove {qualifier}; to keep the value, copy it into a VAR {qualifier} "
            "variable of a PROGRAM or FUNCTION_BLOCK",
        )

    def _declare_early_constants(self, files: list) -> None:
        """The global constants of elementary types, declared before the
        named types are resolved: a STRUCT's ARRAY[1..GVL.MaxN] or
        UINT(0..MaxN) reads them, as in CODESYS and TwinCAT."""
        self._early_decls: set = set()
        for sf in files:
            for block in sf.decls:
                if not (isinstance(block, A.VarBlock) and block.kind == "VAR_GLOBAL" and block.constant):
                    continue
                for decl in block.decls:
                    key = decl.name.upper()
                    spec = decl.type
                    if (
                        key in self.globals
                        or not isinstance(spec, A.NamedType)
                        or spec.name.upper() not in T.ELEMENTARY
                    ):
                        continue
                    # tried: a constant whose value reads what is declared
                    # later (a variable, another list's constant) waits for
                    # its list, where that name is known or its error right
                    saved, self.d = self.d, DiagnosticBag()
                    try:
                        sym = self._make_var(decl, block, None)
                    finally:
                        trial, self.d = self.d, saved
                    if sym is None or trial.has_errors:
                        continue
                    self.d.extend(trial.items)
                    sym.section = "VAR_GLOBAL"
                    self.globals[key] = sym
                    self._early_decls.add(id(decl))

    def _declare_globals(self, block: A.VarBlock) -> None:
        if block.kind not in ("VAR_GLOBAL", "VAR_CONFIG"):
            self.d.error(
                "E011", f"{block.kind} is not allowed outside a POU", block.pos, "use VAR_GLOBAL for global variables"
            )
            return
        for decl in block.decls:
            key = decl.name.upper()
            if id(decl) in self._early_decls:
                continue  # declared before the types (_declare_early_constants)
            if key in self.globals:
                self.d.error(
                    "E011",
                    f"global '{decl.name}' is declared twice",
                    decl.pos,
                    f"the first declaration is at {self.globals[key].pos}",
                )
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
            "PROGRAM": (
                "VAR",
                "VAR_INPUT",
                "VAR_OUTPUT",
                "VAR_IN_OUT",
                "VAR_EXTERNAL",
                "VAR_TEMP",
                "VAR_GLOBAL",
                "VAR_STAT",
            ),
            "FUNCTION_BLOCK": ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_EXTERNAL", "VAR_TEMP", "VAR_STAT"),
            "FUNCTION": ("VAR", "VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT", "VAR_EXTERNAL", "VAR_TEMP", "VAR_STAT"),
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
                        self.d.error(
                            "E010",
                            f"VAR_EXTERNAL '{decl.name}' has no VAR_GLOBAL",
                            decl.pos,
                            "declare it in a VAR_GLOBAL block (a GVL or the CONFIGURATION)",
                        )
                        continue
                    ty = self.type_of(decl.type)
                    if ty is not None and not same_type(ty, g.type):
                        self.d.error("E020", f"VAR_EXTERNAL '{decl.name}' is {ty}, the global is {g.type}", decl.pos)
                    if g.constant and not block.constant:
                        self.d.error(
                            "E030", f"global '{decl.name}' is CONSTANT; declare the VAR_EXTERNAL CONSTANT too", decl.pos
                        )
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
        self.check_declared_eno(pou)

    def _check_location_type(self, sym: VarSymbol) -> None:
        addr = sym.location
        if not addr.indices:  # %IX*: each instance gets its address in VAR_CONFIG
            self._check_placeholder(sym)
            return
        ty = T.base_elementary(sym.type)
        want = 1 if (addr.size in ("", "X") or addr.bit is not None) else {"B": 8, "W": 16, "D": 32, "L": 64}[addr.size]
        if addr.table is not None:
            self.d.error("E081", f"{addr.text}: a word table cannot be declared AT", sym.pos)
        elif ty is None or ty.bits != want:
            self.d.error(
                "E081",
                f"{addr.text} is a {want}-bit address; '{sym.name}' is {sym.type}",
                sym.pos,
                "declare a type of the address size (X: BOOL, B: BYTE/SINT, "
                "W: WORD/INT, D: DWORD/DINT/REAL, L: LWORD/LINT/LREAL)",
            )
        else:
            self._address_fits(addr, ty, sym.pos)

    def _check_var_init(self, sym: VarSymbol, scope: Scope) -> None:
        if id(sym) in self._inited:
            return
        if sym.owner is None:  # a global: its own list's names may go bare (namespaces.py)
            self.initialising_list = getattr(self, "list_of", {}).get(sym.name.upper())
            try:
                self._var_init(sym, scope)
            finally:
                self.initialising_list = None
            return
        self._var_init(sym, scope)

    def _var_init(self, sym: VarSymbol, scope: Scope) -> None:
        if sym.fb_init is not None:
            self._check_fb_init_var(sym, scope)
            return
        # VAR_INPUT CONSTANT (CODESYS): an input the POU cannot change, whose
        # value the call gives: read-only, but no compile-time constant
        folded = sym.constant and sym.section not in ("VAR_INPUT", "VAR_IN_OUT")
        if sym.init is None:
            sym.init_value = T.declared_default(sym.type)
            if folded:
                sym.const_value = self.default_value(sym.type)
            return
        function_input = sym.owner is not None and sym.owner.kind == "FUNCTION" and sym.section == "VAR_INPUT"
        at_start = (
            self.profile.initial_values_at_start
            and not sym.constant
            and sym.location is None
            and not (sym.section == "VAR_INPUT" and sym.owner is not None and sym.owner.kind in ("FUNCTION", "METHOD"))
        )
        sym.init_value = self.init_value(
            sym.type, sym.init, scope, sym.name, ref_ok=not function_input, at_start=sym if at_start else None
        )
        if (
            folded
            and sym.init_value is not None
            and T.base_elementary(sym.type) is not None
            or (folded and isinstance(T.resolve(sym.type), T.StringType))
        ):
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

    def init_value(
        self, ty: T.Type, init: Any, scope: Scope, what: str, ref_ok: bool = False, at_start: VarSymbol | None = None
    ) -> Any:
        """Evaluate an initialiser against a type. Returns a plan: a Python
        value for elementary types, ('array', [(count, plan), ...]) for
        arrays (runs in row-major order, as many elements as the array has),
        ('struct', {UPPER: plan}) for structs and FB instances, ('ref', the
        REF()/ADR() call) for a reference (only where ref_ok: a variable's
        own initial value), ('expr', the expression, its type) for a value
        computed when the variable is initialised (at_start: the variable,
        where the profile computes initial values then), None for the
        default."""
        rty = T.resolve(ty)
        if T.is_reference(ty) and isinstance(init, A.Expr):
            return self.reference_init(ty, init, scope, what, ref_ok)
        if isinstance(init, A.ArrayInit):
            if not isinstance(rty, T.ArrayType):
                self.d.error("E024", f"'{what}' is {ty}; an array initialiser needs an ARRAY", init.pos)
                return None
            return self._array_init(rty, init, scope, what, ref_ok)
        if isinstance(init, A.StructInit):
            return self._struct_init(rty, init, scope, what, ref_ok)
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
        if init.const is None and not isinstance(rty, T.RefType) and at_start is not None:
            return self._computed_at_start(at_start, init, ety)
        if init.const is None and not isinstance(rty, T.RefType):
            self.d.error(
                "E024",
                f"the initial value of '{what}' is not a constant expression",
                init.pos,
                "use literals and CONSTANTs here, or assign the value in the code"
                + (
                    ""
                    if self.profile.initial_values_at_start
                    else f" (the {names_where(lambda p: p.initial_values_at_start)} profiles compute a variable's "
                    "at start-up)"
                ),
            )
            return None
        if isinstance(rty, T.RefType):
            return self._ref_init(init, ety, what, ref_ok)
        return const_as(init.const, ety, ty)

    def _computed_at_start(self, sym: VarSymbol, init: A.Expr, ety: T.Type) -> Any:
        """An initial value CODESYS computes when the variable is initialised
        ("any valid ST expression ... constants, other variables or
        functions"; CODESYS "Variable Initialization"): in declaration order,
        so a variable of the same POU or list it reads must be declared
        before it (CODESYS would read that one's 0: E024 here)."""
        for name in _names_in(init):
            other = name.sym
            if not isinstance(other, VarSymbol) or other is sym or other.owner is not sym.owner:
                continue
            if other.pos.file == sym.pos.file and (other.pos.line, other.pos.col) > (sym.pos.line, sym.pos.col):
                self.d.error(
                    "E024",
                    f"the initial value of '{sym.name}' reads '{other.name}', which is initialised after it",
                    name.pos,
                    f"declare '{other.name}' before '{sym.name}': initial values are computed in declaration order",
                )
                return None
            instance_var = sym.owner is not None and sym.owner.kind in ("FUNCTION_BLOCK", "PROGRAM")
            if instance_var and sym.section != "VAR_TEMP" and other.section in ("VAR_TEMP", "VAR_IN_OUT"):
                self.d.error(
                    "E024",
                    f"the initial value of '{sym.name}' reads {other.section} '{other.name}', which has no value "
                    "when the instance is initialised",
                    name.pos,
                    "assign the value in the code",
                )
                return None
        return ("expr", init, ety)

    def _ref_init(self, init: A.Expr, ety: T.Type, what: str, ref_ok: bool) -> Any:
        """A reference's initial value: NULL (or 0), or REF()/ADR() of a
        variable whose place is known before the first cycle."""
        if not isinstance(T.resolve(ety), T.RefType):
            return None  # NULL or 0: the default
        call = init.target if isinstance(init, A.Call) and isinstance(init.target, CallInfo) else None
        literal = call is not None and call.func == "ADR" and isinstance(call.args[0], A.Literal)  # ADR('text')
        if call is None or call.func not in ("REF", "ADR") or not (literal or self._fixed_place(call.args[0])):
            self.d.error(
                "E024",
                f"the initial value of '{what}' is not a reference to a variable at a fixed place",
                init.pos,
                "write REF(variable) (constant indices, no ^) or NULL; assign other references in the code",
            )
        elif not ref_ok:
            self.d.error(
                "E024",
                f"'{what}' cannot start with a reference",
                init.pos,
                "only a variable's own declaration may take one, not a FUNCTION input or a STRUCT field; "
                "assign it in the code",
            )
        else:
            return ("ref", init)
        return None

    @staticmethod
    def _fixed_place(e: A.Expr) -> bool:
        """Whether e designates the same storage whenever it is evaluated: a
        variable, its members, elements at constant indices."""
        while True:
            if isinstance(e, A.Name):
                return isinstance(e.sym, VarSymbol) and e.sym.section != "VAR_IN_OUT"
            if isinstance(e, A.Member):
                e = e.base
            elif isinstance(e, A.Index) and all(isinstance(i.const, int) for i in e.indices):
                e = e.base
            else:
                return False

    def _array_init(self, ty: T.ArrayType, init: A.ArrayInit, scope: Scope, what: str, ref_ok: bool) -> Any:
        if ty.variable_length:
            return None
        # Items fill the array in row-major order (IEC: the last index varies
        # fastest). A repetition n(v) stays one run: n may be huge.
        total = 1
        for lo, hi in ty.dims:
            total *= hi - lo + 1
        runs: list = []
        given = 0
        for count_expr, value in init.items:
            count = 1
            if count_expr is not None:
                n = self._const_int(count_expr, scope, "a repetition count")
                if n is None or n < 0:
                    return None
                count = n
            plan = self.init_value(ty.elem, value, scope, what, ref_ok) if value is not None else None
            given += count
            if count:
                runs.append((count, plan))
        if given > total:
            self.d.error(
                "E052",
                f"{given:,} initial values for '{what}', which has {total:,} elements",
                init.pos,
                "remove values or enlarge the array",
            )
            return None
        if given < total:
            runs.append((total - given, None))
        return ("array", runs)

    def _struct_init(self, ty: T.Type, init: A.StructInit, scope: Scope, what: str, ref_ok: bool) -> Any:
        out = {}
        if isinstance(ty, T.StructType):
            fields = {k: (f.name, f.type) for k, f in ty.fields.items()}
        elif isinstance(ty, T.FBType):
            fields = {
                k: (v.name, v.type) for k, v in ty.pou.vars.items() if v.section in ("VAR_INPUT", "VAR_OUTPUT", "VAR")
            }
        else:
            self.d.error("E024", f"'{what}' is {ty}; a ( := ) initialiser needs a STRUCT or FB", init.pos)
            return None
        for fname, fval, fpos in init.fields:
            k = fname.upper()
            if k not in fields:
                self.d.error("E013", f"{ty} has no member '{fname}'", fpos, self._suggest(k, list(fields)))
                continue
            out[k] = self.init_value(fields[k][1], fval, scope, f"{what}.{fields[k][0]}", ref_ok)
        return ("struct", out)

    def _const_int(self, e: A.Expr, scope: Scope, what: str) -> int | None:
        ty = self.expr(e, scope)
        if ty is None:
            return None
        if e.const is None or isinstance(e.const, bool) or not isinstance(e.const, int):
            self.d.error(
                "E025", f"{what} must be a constant integer expression", e.pos, "use a literal or a VAR CONSTANT"
            )
            return None
        return e.const


def _names_in(e: Any):
    """The names an expression reads, at any depth (not the types and
    constants the checker noted on it)."""
    todo = [e]
    while todo:
        node = todo.pop()
        if isinstance(node, A.Name):
            yield node
        elif isinstance(node, A.Node):
            for f in fields(node):
                if f.name in ("pos", "ty", "const", "implicit_ref", "target", "sym"):
                    continue
                value = getattr(node, f.name, None)
                if isinstance(value, A.Node):
                    todo.append(value)
                elif isinstance(value, list):
                    todo.extend(v for v in value if isinstance(v, A.Node))
