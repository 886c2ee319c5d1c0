"""The checker's pointer arithmetic (CODESYS POINTER TO).

CODESYS computes with addresses: ``p := p + SIZEOF(INT)`` steps a POINTER TO
INT one INT on, ``ADR(arr) + i * SIZEOF(INT)`` is the address of arr's i-th
element (counting from 0), ``p2 - p1`` is a distance in bytes and ``p1 < p2``
compares addresses. Here a pointer stays bound to the object it points into
(st/rtlib/refs.py: ElemPtr, ObjPtr), so the same expressions work and a
dereference outside that object is a runtime fault.

The rules: ``pointer + integer``, ``integer + pointer`` and ``pointer -
integer`` are pointers of the same type; ``pointer - pointer`` is a DINT
(bytes); ``<``, ``>``, ``<=``, ``>=`` compare two pointers of one type. A
POINTER TO an ARRAY counts as a pointer to its first element (C's decay), so
``ADR(arr) + 2`` is a POINTER TO the element type. IEC REF_TO allows no
arithmetic (IEC 61131-3 ed. 3, 6.4.4.10: references are not addresses).
"""

from __future__ import annotations

from .. import ast as A
from .. import sizes
from .. import types as T
from ..profile import names_where
from .checker_base import CheckerBase, Scope
from .conversions import same_type
from .symbols import CallInfo


def is_pointer(ty: T.Type | None) -> bool:
    """A CODESYS POINTER TO (ADR() gives one)."""
    if ty is None:
        return False
    r = T.resolve(ty)
    return isinstance(r, T.RefType) and r.pointer and not r.reference


def element_of(ty: T.Type) -> T.Type:
    """What a pointer of type ty steps over: its target, or the element of
    the array it points to."""
    r = T.resolve(ty)
    assert isinstance(r, T.RefType)
    target = T.resolve(r.target)
    if isinstance(target, T.ArrayType) and not target.variable_length:
        return target.elem
    return r.target


class PointerChecks(CheckerBase):
    """Pointer arithmetic and pointer comparisons."""

    def pointer_binary(self, e: A.Binary, lt: T.Type, rt: T.Type) -> T.Type | None:
        """e is `+`, `-`, `<`, `>`, `<=` or `>=` with a reference operand."""
        lp, rp = is_pointer(lt), is_pointer(rt)
        if not lp and not rp:
            return self._pointer_error(
                e,
                f"{lt if isinstance(T.resolve(lt), T.RefType) else rt} allows no arithmetic",
                "IEC REF_TO designates a variable, it is no address; declare a POINTER TO (CODESYS) to compute with it",
            )
        if e.op in ("+", "-") and lp != rp:
            ptr, other = (lt, rt) if lp else (rt, lt)
            if e.op == "-" and rp:
                return self._pointer_error(e, "an integer minus a pointer is no address", "write p - n")
            ob = T.base_elementary(other)
            if ob is None or not ob.is_intlike or ob.is_time or isinstance(T.resolve(other), T.EnumType):
                return self._pointer_error(
                    e, f"a pointer moves by an integer number of bytes, not by {other}", "e.g. p + SIZEOF(INT)"
                )
            elem = self._element_size(e, ptr)
            if elem is None:
                return None
            e.impl = CallInfo("pointer", func="move", rtypes=(elem[1],))
            return T.RefType(elem[0], pointer=True)
        if e.op in ("-", "<", ">", "<=", ">=") and lp and rp:
            le, re_ = element_of(lt), element_of(rt)
            if not same_type(le, re_):
                return self._pointer_error(
                    e, f"pointers to {le} and to {re_} do not point into one object", "compare pointers of one type"
                )
            elem = self._element_size(e, lt)
            if elem is None:
                return None
            e.impl = CallInfo("pointer", func="diff", rtypes=(elem[1],))
            return T.DINT if e.op == "-" else T.BOOL
        return self._pointer_error(
            e,
            f"{lt} {e.op} {rt} is no pointer arithmetic",
            "pointer + integer, pointer - integer, pointer - pointer, or compare two pointers",
        )

    def _element_size(self, e: A.Binary, ptr: T.Type) -> tuple | None:
        elem = element_of(ptr)
        size = sizes.sizeof(elem)
        if size is None:
            self.d.error(
                "E161",
                f"the size of {elem} is not known: a pointer to it cannot move",
                e.pos,
                "point into an array of elementary values, strings or structures",
            )
            return None
        return elem, size

    def pointer_index(self, e: A.Index, ptr: T.Type, scope: Scope) -> T.Type | None:
        """p[i] where the profile allows it (CODESYS, TwinCAT): the i-th
        element from where p points, (p + i * SIZEOF(p^))^, read and
        written. e.via is that dereference."""
        target = T.resolve(T.resolve(ptr).target)  # type: ignore[attr-defined]
        if not self.profile.pointer_index:
            where = names_where(lambda p: p.pointer_index)
            self.d.error(
                "E050", f"{ptr} is not an array", e.pos, f"write (p + i)^ (the {where} profiles index a pointer)"
            )
            return None
        if isinstance(target, T.ArrayType) or len(e.indices) != 1:
            hint = "write p^[i] for an element of the ARRAY it points to" if isinstance(target, T.ArrayType) else None
            self.d.error("E050", f"{ptr} takes one index, as a pointer to its first element", e.pos, hint)
            return None
        ix = e.indices[0]
        ity = self.expr(ix, scope)
        ie = T.base_elementary(ity) if ity is not None else None
        if ity is None or ie is None or not ie.is_intlike or isinstance(T.resolve(ity), T.EnumType):
            if ity is not None:
                self.d.error("E050", f"a pointer's index must be an integer, not {ity}", ix.pos)
            return None
        size = sizes.sizeof(target)
        if size is None:
            self.d.error("E161", f"the size of {target} is not known: a pointer to it cannot be indexed", e.pos)
            return None
        move = A.Binary("+", e.base, ix, pos=e.pos)
        move.ty = T.RefType(T.resolve(ptr).target, pointer=True)  # type: ignore[attr-defined]
        move.impl = CallInfo("pointer", func="index", rtypes=(size,))
        e.via = A.Deref(move, pos=e.pos)
        e.via.ty = move.ty.target
        return e.via.ty

    def string_index(self, e: A.Index, b: T.StringType) -> T.Type | None:
        """s[i]: where the profile allows it (CODESYS V3, TwinCAT 3), the
        i-th byte of a STRING(n), from 0 to n (the last terminator), read
        and written as a BYTE; of a WSTRING the i-th character as a WORD.
        Its bytes are the byte view's (st/rtlib/rt_bytes.py StrLeaf)."""
        if not self.profile.string_index:
            where = names_where(lambda p: p.string_index)
            self.d.error(
                "E050",
                "strings are not indexed",
                e.pos,
                f"use MID(s, 1, pos) (the {where} profiles read s[i] as a byte)",
            )
            return None
        if len(e.indices) != 1:
            self.d.error("E050", f"a string takes one index, {len(e.indices)} given", e.pos)
            return None
        ix = e.indices[0]
        if isinstance(ix.const, int) and not 0 <= ix.const <= b.length:
            self.d.error("E051", f"index {ix.const} is outside 0..{b.length} of {b}", ix.pos)
        return T.WORD if b.wide else T.BYTE

    def _pointer_error(self, e: A.Binary, message: str, hint: str) -> T.Type | None:
        self.d.error("E161", message, e.pos, hint)
        return None
