"""Code generation of pointer arithmetic (CODESYS POINTER TO).

The checker marks `p + n`, `p - n`, `p - q` and `p < q` with a CallInfo
of kind 'pointer' (checker_pointers.py); the generated code calls the
helpers of st/rtlib/refs.py, which keep a pointer bound to its object. Plain
references and code without pointers never reach this module.
"""

from __future__ import annotations

from .. import ast as A
from .. import sizes
from .. import types as T
from ..rtlib import refs, rt_bytes
from .codegen_base import CodeGenBase, array_type


class PointerGen(CodeGenBase):
    """Pointer arithmetic and the decay of a POINTER TO an ARRAY."""

    def pointer_op(self, e: A.Binary) -> str:
        esize = e.impl.rtypes[0]
        if e.impl.func == "index":  # p[i] (checker_pointers.py): i elements on
            return f"_ptr_add({self.pointer_operand(e.left)}, ({self.ex(e.right)}) * {esize}, {esize})"
        if e.impl.func == "move":
            left_is_ptr = isinstance(T.resolve(e.left.ty), T.RefType)
            ptr, delta = (e.left, e.right) if left_is_ptr else (e.right, e.left)
            amount = self.ex(delta)
            if e.op == "-":
                amount = f"-({amount})"
            return f"_ptr_add({self.pointer_operand(ptr)}, {amount}, {esize})"
        diff = f"_ptr_diff({self.pointer_operand(e.left)}, {self.pointer_operand(e.right)}, {esize})"
        if e.op == "-":
            return diff
        return f"({diff} {e.op} 0)"

    def pointer_operand(self, e: A.Expr) -> str:
        """A pointer operand; a POINTER TO an ARRAY as its first element."""
        r = T.resolve(e.ty)
        assert isinstance(r, T.RefType)
        return self.decay_code(self.ex(e), r.target)

    def decay_code(self, code: str, target: T.Type) -> str:
        arr = T.resolve(target)
        if not isinstance(arr, T.ArrayType) or arr.variable_length:
            return code
        esize = sizes.sizeof(arr.elem)
        shape = tuple(hi - lo + 1 for lo, hi in arr.dims)
        return f"_elem_ptr({code}, {esize}, {shape!r})"

    def byte_view_code(self, code: str, src: T.Type | None, dst: T.Type) -> str:
        """A pointer seen as a POINTER TO BYTE (WORD, ...) over its target's
        bytes (st/rtlib/rt_bytes.py)."""
        assert src is not None
        s, d = T.resolve(src), T.resolve(dst)
        assert isinstance(s, T.RefType) and isinstance(d, T.RefType)
        unit = rt_bytes.view_unit(d.target)
        assert unit is not None
        lay = self.const(rt_bytes.layout_of(s.target))
        return f"{self.const(rt_bytes.byte_view)}({code}, {lay}, {self.const(unit[0])}, {unit[1]!r})"

    def _field_view(self, e: A.Member) -> str | None:
        """ADR(s.a) of an elementary field of a STRUCT: a byte view of the
        structure at the field's offset, so that ADR(s.a) + SIZEOF(s.a)
        reaches the next field as in CODESYS's memory (st/rtlib/rt_bytes.py)."""
        st = T.resolve(e.base.ty)
        if not isinstance(st, T.StructType) or not isinstance(e.sym, T.StructField) or e.sym.type is T.BIT:
            return None  # (ADR of a BIT: a reference to its BOOL)
        unit = rt_bytes.layout_of(e.ty)
        lay = rt_bytes.layout_of(st)
        offsets = sizes.field_offsets(st)
        if unit is None or lay is None or offsets is None or isinstance(unit, rt_bytes.StrLeaf) or not unit.leaf:
            return None
        offset = offsets[e.name.upper()][0]
        return f"{self.const(refs.BytePtr)}({self.ex(e.base)}, {self.const(lay)}, {offset}, {self.const(unit)}, None)"

    def adr_code(self, e: A.Expr) -> str:
        """ADR(x): REF(x), but an element of a multi-dimensional array or an
        aggregate element is an ElemPtr into the whole array, so that
        arithmetic can step across rows and over structures."""
        if isinstance(e, A.Literal):  # ADR('text'): a copy of the literal (profile.adr_of_literal)
            return f"_CellRef({self.ex(e)})"
        if isinstance(e, A.Member) and e.implicit_ref is None:
            field = self._field_view(e)
            if field is not None:
                return field
        if not isinstance(e, A.Index) or isinstance(T.resolve(e.base.ty), T.StringType):
            return self.ref_code(e)
        arr = array_type(e.base.ty)
        if arr.variable_length or (len(arr.dims) == 1 and not T.resolve(arr.elem).is_aggregate):
            return self.ref_code(e)
        esize = sizes.sizeof(arr.elem)
        if esize is None:
            return self.ref_code(e)
        shape = [hi - lo + 1 for lo, hi in arr.dims]
        terms = []
        stride = 1
        for ix, dim, n in reversed(list(zip(e.indices, arr.dims, shape))):
            terms.append(f"({self._index_code(ix, dim)}) * {stride * esize}")
            stride *= n
        return f"_ElemPtr({self.ex(e.base)}, {' + '.join(terms)}, {esize}, {tuple(shape)!r})"
