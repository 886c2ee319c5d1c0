"""The checker's expressions: literals, names, members, indices, addresses.

Types and folds literals, names and enumerators, members, indices, bit
access, dereferencing and direct addresses. Operators are checked in
checker_operators, calls in checker_calls.
"""

from __future__ import annotations

from .. import ast as A
from .. import types as T
from ..profile import names_where
from ..rtlib import rt_strings
from .checker_base import BUILTINS, CheckerBase, Scope
from .checker_pointers import is_pointer
from .conversions import const_repr
from .symbols import copied_in_out

_TIME_KIND = {
    "time": T.TIME,
    "ltime": T.LTIME,
    "date": T.DATE,
    "tod": T.TOD,
    "dt": T.DT,
    "ldate": T.LDATE,
    "ltod": T.LTOD,
    "ldt": T.LDT,
}
_SECTIONS_READABLE_OUTSIDE = ("VAR_INPUT", "VAR_OUTPUT", "VAR_IN_OUT")
# A chain of operations this long or longer is checked from its first one
# up, in a loop (ExprChecks._check_ahead); a shorter one recursively.
CHAIN_AHEAD = 16


class ExprChecks(CheckerBase):
    """Typing and folding expressions."""

    def expr(self, e: A.Expr, scope: Scope, expected: T.Type | None = None) -> T.Type | None:
        ahead: list = []
        if type(e) is A.Binary:
            if expected is None and id(e) in self._chain_checked:
                return e.ty  # checked ahead, as its parent would have (_check_ahead)
            if type(e.left) is A.Binary:
                ahead = self._check_ahead(e, scope)
        try:
            ty = self._expr(e, scope, expected)
            if ty is not None and (ty.is_ref or isinstance(ty, T.AliasType)):
                ty = self.implicit_deref(e, ty)
        except RecursionError:
            self.d.error(
                "E006",
                "expression nested too deeply for the checker (about 300 levels)",
                e.pos,
                "operands nested in each other, or a chain of literals alone: split it up with variables",
            )
            ty = None
        e.ty = ty
        self._chain_checked.difference_update(ahead)
        return ty

    def _check_ahead(self, e: A.Binary, scope: Scope) -> list:
        """A long chain a + b + c ... (a tree as deep as it is long, on its
        left): its operations below e checked from the first one up, each as
        its parent would check it (its left operand with no expected type:
        checker_operators.py), and kept as checked for the parent; a call
        per operation, not a recursion per operator. The usual short
        expression is checked recursively as it is. Returns the ids kept."""
        below: list = []
        node = e.left
        while type(node) is A.Binary and id(node) not in self._chain_checked and not self._takes_context(node, scope):
            below.append(node)
            node = node.left
        if len(below) < CHAIN_AHEAD:
            return []
        ids = []
        for node in reversed(below):
            self.expr(node, scope)
            self._chain_checked.add(id(node))
            ids.append(id(node))
        return ids

    def _expr(self, e: A.Expr, scope: Scope, expected: T.Type | None) -> T.Type | None:
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
            if isinstance(e.base, A.Name) and e.base.name.upper() in ("THIS", "SUPER"):
                return self._this_deref(e, scope)  # checker_oop.py
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
            return self.call(e, scope, as_statement=False, expected=expected)
        if isinstance(e, A.AssignExpr):
            return self.assign_expr(e, scope)  # checker_stmts.py
        if isinstance(e, A.Located):
            return self._located(e)
        if isinstance(e, A.SchneiderAddress):
            return T.ADDR
        self.d.error("E005", "unsupported expression", e.pos)
        return None

    def _literal(self, e: A.Literal, expected: T.Type | None) -> T.Type | None:
        v = e.value
        if e.c_hex and not self.profile.c_hex_literals:
            self.d.error(
                "E026", "C-style hexadecimal literal", e.pos, f"write 16#{v:X}, or compile with --profile schneider"
            )
        if e.doubled_underscore and not self.profile.doubled_underscores:
            self.d.error(
                "E003",
                "two underscores in a row in a number",
                e.pos,
                "an underscore may only stand between two digits (the "
                f"{names_where(lambda p: p.doubled_underscores)} profiles accept doubled ones)",
            )
        if e.kind in _TIME_KIND:
            ty = _TIME_KIND[e.kind]
            if e.type_name is not None and T.ELEMENTARY.get(e.type_name) is not None:
                ty = T.ELEMENTARY[e.type_name]
            e.const = self._time_repr(ty, v, e)
            return ty
        if e.kind in ("string", "wstring"):
            char = self._char_wanted(e, expected)
            if char is not None:
                return self._char_literal(e, char)
            wide = e.kind == "wstring"
            e.const = v
            exp = T.resolve(expected) if expected is not None else None
            if isinstance(exp, T.StringType) and exp.wide == wide:
                return exp
            return T.StringType(max(rt_strings.string_length(v, wide), 1), wide)  # WSTRING: UTF-16 units
        if e.type_name is not None:
            typed = T.ELEMENTARY.get(e.type_name)
            if typed is None:
                self.d.error("E012", f"unknown type '{e.type_name}' in typed literal", e.pos)
                return None
            if typed.is_bool:
                if e.kind == "bool" or (e.kind == "int" and v in (0, 1)):
                    e.const = bool(v)
                    return typed
            elif typed.is_real and e.kind in ("int", "real"):
                e.const = const_repr(v, typed)  # REAL#0.1 is the binary32 value
                return typed
            elif typed.is_intlike and e.kind == "int":
                if not T.int_fits(typed, v):
                    self.d.error("E022", f"{v} does not fit {typed.name} ({typed.lo}..{typed.hi})", e.pos)
                e.const = v
                return typed
            self.d.error("E003", f"{e.type_name}# does not take this literal", e.pos)
            return None
        if e.kind == "bool":
            e.const = bool(v)
            return T.BOOL
        exp = T.base_elementary(expected) if expected is not None else None
        if isinstance(expected, T.EnumType) or isinstance(T.resolve(expected) if expected else None, T.EnumType):
            exp = None
        if e.kind == "real":
            ty = exp if exp is not None and exp.is_real else T.LREAL
            e.const = const_repr(v, ty)  # 0.1 beside a REAL is REAL#0.1
            return ty
        # untyped integer: the expected type if it fits, else the smallest signed that does
        e.const = v
        if exp is not None and (exp.is_intlike and T.int_fits(exp, v) or exp.is_real):
            return exp
        for cand in (T.INT, T.DINT, T.LINT, T.ULINT):
            if T.int_fits(cand, v):
                return cand
        self.d.error("E022", f"{v} is too large for any integer type", e.pos)
        return None

    @staticmethod
    def _char_wanted(e: A.Literal, expected: T.Type | None) -> T.ElementaryType | None:
        """CHAR or WCHAR if the string literal e is a character: CHAR#'A',
        WCHAR#"A" (IEC 61131-3 ed.3 Table 6), or one character where a CHAR
        of its width is expected."""
        if e.type_name in ("CHAR", "WCHAR"):
            return T.ELEMENTARY[e.type_name]
        exp = T.base_elementary(expected) if expected is not None else None
        if e.type_name is not None or exp is None or not exp.is_char or len(e.value) != 1:
            return None
        return exp if (exp is T.WCHAR) == (e.kind == "wstring") else None

    def _char_literal(self, e: A.Literal, want: T.ElementaryType) -> T.Type | None:
        """A character literal: the code of the character (types.py)."""
        v = e.value
        if len(v) != 1 or ord(v) > (want.hi or 0):
            self.d.error(
                "E028",
                f"a {want.name} literal is one character"
                + (f" of code 0..{want.hi}" if len(v) == 1 else f", not {len(v)}"),
                e.pos,
                f"write {want.name}#'A'" if want is T.CHAR else f'write {want.name}#"A"',
            )
            return None
        e.const = ord(v)
        return want

    def _time_repr(self, ty: T.ElementaryType, ns: int, e: A.Expr) -> int:
        v = ns // ty.unit_ns if ns >= 0 else -((-ns) // ty.unit_ns)
        hi = ty.hi
        if ty.category == T.DURATION and self.profile.unsigned_durations and hi is not None:
            hi = (1 << ty.bits) - 1  # (TwinCAT: profile.py)
        if ty.lo is not None and hi is not None and not (ty.lo <= v <= hi):
            self.d.error(
                "E022",
                f"the literal is outside the range of {ty.name}",
                e.pos,
                "use the L-type (LTIME, LDT ...) for larger values",
            )
        elif ty.hi is not None and v > ty.hi:
            v -= 1 << ty.bits  # stored in the type's bits
        return v

    def _name(self, e: A.Name, scope: Scope, expected: T.Type | None) -> T.Type | None:
        key = e.name.upper()
        pou = scope.pou
        sym = None
        if pou is not None and e.qualifier is None:
            sym = scope.names.get(key) or pou.vars.get(key)
            if sym is None and pou.result is not None and key == pou.name.upper():
                sym = pou.result
            if sym is None:  # a METHOD's FB's variables, a PROPERTY (checker_oop.py)
                hit = self._oop_name(e, key, scope)
                if hit is not None:
                    return hit[0]
            if sym is None and key == "ENO":  # every FUNCTION and FB has one (st/check/checker_eno.py)
                sym = self.implicit_eno(pou)
        if sym is None:
            sym = self.globals.get(key)
            if sym is not None:
                self._check_qualified_only(e)
            elif e.qualifier is not None:
                if key in self._lists.get(e.qualifier.upper(), ()):  # declared, but after the data types
                    self.d.error(
                        "E010",
                        f"'{e.qualifier}.{e.name}' is not known yet where the data types are declared",
                        e.pos,
                        "only global constants of elementary types size the fields of a TYPE; use a literal",
                    )
                return None  # GVL.y where GVL has no y: E019 (namespaces.py)
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
                if pick[0][0].qualified_only:
                    self._enum_qualified_only(e, pick[0][0])
                return pick[0][0]
            self.d.error(
                "E010",
                f"'{e.name}' is an enumerator of several types",
                e.pos,
                f"qualify it, e.g. {cands[0][0].name}#{e.name}",
            )
            return None
        if key in self.pous or key in self.std or key in BUILTINS:
            self.d.error("E010", f"'{e.name}' is a POU, not a variable", e.pos, "call it with parentheses: name(...)")
            return None
        if key == "NULL":
            e.const = None
            return T.NULL
        names = [g.name for g in self.globals.values()]
        if pou is not None:
            names += [v.name for v in pou.vars.values()]
        self.d.error(
            "E010",
            f"unknown name '{e.name}'{self._elsewhere(e.name)}",
            e.pos,
            self._suggest(key, names) or "declare it in a VAR block",
        )
        return None

    def _enum_qualified_only(self, e: A.Name, ty: T.EnumType) -> None:
        """E018: a bare value of an enumeration with {attribute
        'qualified_only'} (CODESYS, TwinCAT: "the enumeration values can
        only be accessed with the type name")."""
        self.d.error(
            "E018",
            f"'{e.name}' is a value of the enumeration {ty.name}, which is qualified_only",
            e.pos,
            f"write {ty.name}.{ty.spelled[e.name.upper()]} ({{attribute 'qualified_only'}} before its TYPE)",
        )

    def _enum_literal(self, e: A.EnumLiteral, expected: T.Type | None) -> T.Type | None:
        if e.type_name is None:
            fake = A.Name(e.value_name, pos=e.pos)
            return self._name(fake, Scope(None), expected)
        ty = self.types.get(e.type_name.upper())
        ty = T.resolve(ty) if ty is not None else None
        if not isinstance(ty, T.EnumType):
            self.d.error(
                "E012",
                f"'{e.type_name}' is not an enumeration type",
                e.pos,
                self._suggest(e.type_name.upper(), [k for k, t in self.types.items() if isinstance(t, T.EnumType)]),
            )
            return None
        v = ty.values.get(e.value_name.upper())
        if v is None:
            self.d.error(
                "E013",
                f"enumeration {ty.name} has no value '{e.value_name}'",
                e.pos,
                self._suggest(e.value_name.upper(), list(ty.values)),
            )
            return None
        e.const = v
        return ty

    def _member(self, e: A.Member, scope: Scope) -> T.Type | None:
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
            hit = self._program_property(e, scope)  # Prog.P (checker_oop.py)
            if hit is not None:
                return hit[0]
        bty = self.expr(e.base, scope)
        if bty is None:
            return None
        return self._member_of(e, bty, scope)

    def _member_of(self, e: A.Member, bty: T.Type, scope: Scope) -> T.Type | None:
        """The member e.name of a base of type bty (checked already)."""
        b = T.resolve(bty)
        key = e.name.upper()
        hit = self._oop_member(e, b, scope)  # a PROPERTY, an interface's (checker_oop.py)
        if hit is not None:
            return hit[0]
        if isinstance(b, T.StructType):
            f = b.fields.get(key)
            if f is None:
                self.d.error("E013", f"{b.name} has no field '{e.name}'", e.pos, self._suggest(key, list(b.fields)))
                return None
            e.sym = f
            return f.type
        if isinstance(b, T.FBType):
            v = b.pou.vars.get(key) or (self.implicit_eno(b.pou) if key == "ENO" else None)
            if v is None:
                self.d.error(
                    "E013",
                    f"{b.name} has no member '{e.name}'",
                    e.pos,
                    self._suggest(key, [k for k, s in b.pou.vars.items() if s.section in _SECTIONS_READABLE_OUTSIDE]),
                )
                return None
            inside = scope.pou is b.pou or self.inside_fb(scope, b.pou)
            if copied_in_out(v, self.profile):
                inside = True  # the instance's own copy (MatIEC): read and written as an input
            if v.section in ("VAR", "VAR_STAT") and not inside and self.profile.internal_read == "warning":
                # read from outside: W113 once checking is done, unless written (E013)
                self._internal_reads[id(e)] = (e, v, b)
            elif v.section not in ("VAR_INPUT", "VAR_OUTPUT") and not inside:
                self.d.error(
                    "E013",
                    f"'{v.name}' is internal to {b.name}",
                    e.pos,
                    "only VAR_INPUT and VAR_OUTPUT are visible outside a block"
                    + (
                        f" (the {names_where(lambda p: p.internal_read == 'warning')} profiles let a VAR be read)"
                        if v.section in ("VAR", "VAR_STAT")
                        else ""
                    ),
                )
                return None
            e.sym = v
            return v.type
        self.d.error("E013", f"{bty} has no members", e.pos)
        return None

    def internal_written(self, e: A.Member) -> bool:
        """E013 when e is an FB's internal variable read from outside where
        the profile allows reading it (_member_of) and this use writes it."""
        hit = self._internal_reads.pop(id(e), None)
        if hit is None:
            return False
        _e, v, b = hit
        self.d.error(
            "E013",
            f"'{v.name}' is internal to {b.name}: it may be read from outside, not written",
            e.pos,
            "give the block an input (or a method or property) that sets it",
        )
        return True

    def report_internal_reads(self) -> None:
        """W113 for each internal variable of an FB instance read from
        outside (CODESYS, TwinCAT: static analysis rule SA0102)."""
        for e, v, b in self._internal_reads.values():
            self.d.warning(
                "W113",
                f"'{v.name}' is internal to {b.name}: read from outside",
                e.pos,
                "make it a VAR_OUTPUT (or a property) of the block if it is meant to be read",
            )
        self._internal_reads.clear()

    def _index(self, e: A.Index, scope: Scope) -> T.Type | None:
        bty = self.expr(e.base, scope)
        if bty is not None and is_pointer(bty):
            return self.pointer_index(e, bty, scope)  # p[i] (checker_pointers.py)
        for ix in e.indices:
            ity = self.expr(ix, scope)
            ie = T.base_elementary(ity) if ity is not None else None
            if ity is not None and (ie is None or not ie.is_intlike):
                self.d.error("E050", f"an array index must be an integer, not {ity}", ix.pos)
        if bty is None:
            return None
        b = T.resolve(bty)
        if isinstance(b, T.StringType):
            return self.string_index(e, b)  # checker_pointers.py
        if not isinstance(b, T.ArrayType):
            self.d.error("E050", f"{bty} is not an array", e.pos)
            return None
        if len(e.indices) != len(b.dims):
            self.d.error("E050", f"{b} has {len(b.dims)} dimension(s), {len(e.indices)} index(es) given", e.pos)
            return None
        for ix, dim in zip(e.indices, b.dims):
            if dim is not None and isinstance(ix.const, int) and not (dim[0] <= ix.const <= dim[1]):
                self.d.error("E051", f"index {ix.const} is outside {dim[0]}..{dim[1]}", ix.pos)
        return b.elem

    def _bit_access(self, e: A.BitAccess, scope: Scope) -> T.Type | None:
        bty = self.expr(e.base, scope)
        self.expr(e.bit, scope)
        if bty is None:
            return None
        be = T.base_elementary(bty)
        if be is None or not be.is_intlike:
            what = "bit access" if e.size == "X" else "a partial access"
            self.d.error("E053", f"{what} needs an integer or bit-string variable, not {bty}", e.pos)
            return None
        if e.size != "X":
            return self._part_access(e, be)
        if not isinstance(e.bit.const, int) or not 0 <= e.bit.const < be.bits:
            self.d.error("E053", f"bit number must be a constant 0..{be.bits - 1} for {be.name}", e.bit.pos)
            return None
        return T.BOOL

    _PARTS = {"B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}

    def _part_access(self, e: A.BitAccess, be: T.ElementaryType) -> T.Type | None:
        """d.%B0, d.%W1, d.%D0, d.%L0 (IEC 61131-3 ed.3 6.5.3, Table 16;
        CODESYS and TwinCAT alike): byte, word, double or long word n of an
        integer or bit string, counted from the least significant; E056
        when the part is not inside the variable's type."""
        part = self._PARTS[e.size]
        count = be.bits // part.bits
        n = e.bit.const
        if count == 0 or not isinstance(n, int) or not 0 <= n < count:
            self.d.error(
                "E056",
                f"{be.name} has no %{e.size}{n}: it is {be.bits} bits"
                + (f", %{e.size}0..%{e.size}{count - 1}" if count else f", smaller than a {part.name}"),
                e.bit.pos,
                f"a {be.name} holds %X0..%X{be.bits - 1}"
                + "".join(f", %{k}0..%{k}{be.bits // t.bits - 1}" for k, t in self._PARTS.items() if t.bits < be.bits),
            )
            return None
        return part

    def _address_fits(self, addr: A.LocatedAddress, ty: T.ElementaryType | None, pos: A.Pos) -> bool:
        """Report (E082) a direct address outside the process image, and
        (E083) an incomplete address %I* used directly."""
        if not addr.indices:
            self.d.error(
                "E083",
                f"{addr.text} is an unconfigured address",
                pos,
                "give the full address (e.g. %IX0.0); %IX* is for a declaration (x AT %IX* : BOOL) "
                "whose address each instance gets in VAR_CONFIG",
            )
            return False
        if self._image_probe is None:
            return True
        try:
            if ty is None:
                self._image_probe.table(addr)
            else:
                self._image_probe.accessor(addr, ty)
        except ValueError as exc:  # the image's AddressError
            self.d.error("E082", str(exc), pos, f"the image areas are {self._image_probe.size // 1024} KiB each")
            return False
        return True

    def _located(self, e: A.Located) -> T.Type | None:
        ty = self._located_type(e)
        if ty is not None and not self._address_fits(
            e.addr, T.base_elementary(ty) if e.addr.table is None else None, e.pos
        ):
            return None
        return ty

    def _located_type(self, e: A.Located) -> T.Type | None:
        a = e.addr
        schneider = self.profile.addressing == "schneider"
        if (a.bit is not None or a.table is not None) and not schneider:
            self.d.error(
                "E080",
                f"{a.text} is Schneider addressing",
                e.pos,
                "compile with --profile schneider, or write %MX<byte>.<bit>",
            )
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
                self.d.error("E080", f"{a.text}: a bit address needs byte.bit", e.pos, f"write %{a.area}X<byte>.<bit>")
                return None
            return T.BOOL
        if schneider:
            return {"B": T.BYTE, "W": T.INT, "D": T.DINT, "L": T.LINT}[a.size]
        return {"B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}[a.size]
