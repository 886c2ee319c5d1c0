"""References to scalar storage: what REF(), ADR() and VAR_IN_OUT pass for an
elementary variable. Aggregates (arrays, structs, FB instances) are Python
objects already, so a reference to one is the object itself.

Pointer arithmetic (CODESYS POINTER TO) keeps a pointer bound to the object
it points into: an ElemPtr is an array (the outermost Python list) and a
byte offset into it, mapped to an element by the element size
(st/sizes.py); an ObjPtr is any other reference moved by a byte offset.
Either may point anywhere, as a C pointer may; dereferencing one that is
not on an element of its own object is a 'reference' fault, never another
variable's memory.
"""

from __future__ import annotations

from ..faults import NULL_REFERENCE, RangeFault
from .rt_strings import cut_string


class AttrRef:
    """A variable held as an attribute of an instance (or of the globals)."""

    __slots__ = ("obj", "attr")

    def __init__(self, obj, attr: str) -> None:
        self.obj = obj
        self.attr = attr

    def get(self):
        return getattr(self.obj, self.attr)

    def set(self, value) -> None:
        setattr(self.obj, self.attr, value)

    def __eq__(self, other) -> bool:
        return isinstance(other, AttrRef) and other.obj is self.obj and other.attr == self.attr

    def __hash__(self) -> int:
        return hash((id(self.obj), self.attr))


class ItemRef:
    """An element of an array (a Python list, or an image table view)."""

    __slots__ = ("seq", "index")

    def __init__(self, seq, index: int) -> None:
        self.seq = seq
        self.index = index

    def get(self):
        return self.seq[self.index]

    def set(self, value) -> None:
        self.seq[self.index] = value

    def __eq__(self, other) -> bool:
        return isinstance(other, ItemRef) and other.seq is self.seq and other.index == self.index

    def __hash__(self) -> int:
        return hash((id(self.seq), self.index))


class CellRef:
    """A standalone cell: the local variable of a FUNCTION passed on by
    reference, written back when the callee returns."""

    __slots__ = ("value",)

    def __init__(self, value) -> None:
        self.value = value

    def get(self):
        return self.value

    def set(self, value) -> None:
        self.value = value


class AccessorRef:
    """A direct address in the process image, through its get/set pair."""

    __slots__ = ("get", "set")

    def __init__(self, getter, setter) -> None:
        self.get = getter
        self.set = setter

    def __eq__(self, other) -> bool:
        return isinstance(other, AccessorRef) and other.get is self.get

    def __hash__(self) -> int:
        return hash(id(self.get))


class ElemPtr:
    """A pointer into an array: root (the array's outermost list), a byte
    offset from its first element, the element size and the array's shape
    (elements per dimension)."""

    __slots__ = ("root", "offset", "esize", "shape", "count")

    def __init__(self, root: list, offset: int, esize: int, shape: tuple) -> None:
        self.root = root
        self.offset = offset
        self.esize = esize
        self.shape = shape
        count = 1
        for n in shape:
            count *= n
        self.count = count

    def _place(self) -> tuple:
        """(the innermost list, the index in it) of the element pointed at."""
        i, skew = divmod(self.offset, self.esize)
        if skew or not 0 <= i < self.count:
            where = " (between two elements)" if skew and 0 <= i < self.count else ""
            raise RangeFault(
                "reference",
                f"pointer outside its array: byte offset {self.offset}{where} in an array of "
                f"{self.count} elements of {self.esize} bytes",
            )
        seq, stride = self.root, self.count
        for n in self.shape[:-1]:  # row-major: the last index varies fastest
            stride //= n
            j, i = divmod(i, stride)
            seq = seq[j]
        return seq, i

    def get(self):
        seq, i = self._place()
        return seq[i]

    def set(self, value) -> None:
        seq, i = self._place()
        seq[i] = value

    def key(self) -> tuple:
        try:
            seq, i = self._place()
        except RangeFault:
            return (id(self.root), "+", self.offset)
        return (id(seq), i)


class ObjPtr:
    """Any other reference moved by a byte offset: only offset 0 (back at
    the variable) can be dereferenced; aggregate: base is the object."""

    __slots__ = ("base", "offset", "aggregate")

    def __init__(self, base, offset: int, aggregate: bool) -> None:
        self.base = base
        self.offset = offset
        self.aggregate = aggregate

    def _at(self):
        if self.offset:
            raise RangeFault(
                "reference",
                f"pointer {self.offset:+} bytes off its variable (pointers move within arrays only)",
            )
        return self.base

    def get(self):
        base = self._at()
        return base if self.aggregate else base.get()

    def set(self, value) -> None:
        self._at().set(value)

    def key(self) -> tuple:
        return (*_key(self.base), "+", self.offset) if self.offset else _key(self.base)


class BytePtr:
    """A byte view (st/rtlib/rt_bytes.py): a pointer to unit (an elementary
    layout; an ARRAY of count of them when count is not None) at a byte
    offset into holder, an object of the given layout (a scalar reference
    for a leaf, else the list or structure itself)."""

    __slots__ = ("holder", "layout", "offset", "unit", "count")

    def __init__(self, holder, layout, offset: int, unit, count: int | None) -> None:
        self.holder = holder
        self.layout = layout
        self.offset = offset
        self.unit = unit
        self.count = count

    def read(self, offset: int):
        n = self.unit.size
        if offset < 0 or offset + n > self.layout.size:
            raise RangeFault(
                "reference",
                f"byte pointer outside its variable: byte offset {offset} in {self.layout.size} bytes",
            )
        return self.unit.decode(self.layout.read(self.holder, offset, n))

    def write(self, offset: int, value) -> None:
        n = self.unit.size
        if offset < 0 or offset + n > self.layout.size:
            raise RangeFault(
                "reference",
                f"byte pointer outside its variable: byte offset {offset} in {self.layout.size} bytes",
            )
        self.layout.write(self.holder, offset, self.unit.encode(value))

    def get(self):
        if self.count is not None:
            return ByteArrayView(self)
        return self.read(self.offset)

    def set(self, value) -> None:
        self.write(self.offset, value)

    def key(self) -> tuple:
        lay = self.layout
        if lay.leaf:
            base = _key(self.holder)
            return (*base, "+", self.offset) if self.offset else base
        if hasattr(lay, "shape") and lay.elem.leaf:  # on an element: as ElemPtr and ItemRef say it
            i, skew = divmod(self.offset, lay.esize)
            if not skew and 0 <= i < lay.count:
                item = lay.element(self.holder, i)
                return (id(item.seq), item.index)
        for start, pyname, flay in getattr(lay, "fields", ()):  # on a field of a structure: as AttrRef
            if start == self.offset and flay.leaf and flay.size == self.unit.size:
                return (id(self.holder), pyname)
        return (id(self.holder), "+", self.offset)


class ByteArrayView:
    """p^ of a byte view that points to an ARRAY: p^[i] reads and writes
    the i-th unit from p (i from 0 here: the code generator subtracts the
    array's lower bound and checks its upper one)."""

    __slots__ = ("ptr",)

    def __init__(self, ptr: BytePtr) -> None:
        self.ptr = ptr

    def __getitem__(self, i: int):
        p = self.ptr
        return p.read(p.offset + i * p.unit.size)

    def __setitem__(self, i: int, value) -> None:
        p = self.ptr
        p.write(p.offset + i * p.unit.size, value)

    def __len__(self) -> int:  # a := p^ and p^ := a copy the elements the ARRAY declares
        return self.ptr.count or 0

    def __iter__(self):
        return (self[i] for i in range(len(self)))


class CutRef:
    """A string variable reached through a reference (VAR_IN_OUT, REF=,
    a POINTER TO STRING) declared longer than the variable: what is
    stored through it is cut at the variable's own length."""

    __slots__ = ("ref", "length", "wide")

    def __init__(self, ref, length: int, wide: bool = False) -> None:
        self.ref = ref
        self.length = length
        self.wide = wide  # a WSTRING: length in UTF-16 units (rt_strings.cut_string)

    def get(self):
        return self.ref.get()

    def set(self, value) -> None:
        self.ref.set(cut_string(value, self.length, self.wide))

    def key(self) -> tuple:
        return _key(self.ref)


def cut_ref(ref, length: int, wide: bool = False):
    """ref, storing at most length characters (a WSTRING: UTF-16 units; None stays NULL)."""
    if ref is None or (type(ref) is CutRef and ref.length <= length):
        return ref
    return CutRef(ref, length, wide)


_SCALAR_REFS = (AttrRef, ItemRef, AccessorRef)
_POINTERS = (ElemPtr, ObjPtr, BytePtr, CutRef)


def _key(r) -> tuple:
    """What a reference designates, comparable across its representations."""
    t = type(r)
    if t in _POINTERS:
        return r.key()
    if t is AttrRef:
        return (id(r.obj), r.attr)
    if t is ItemRef:
        return (id(r.seq), r.index)
    if t is AccessorRef:
        return (id(r.get),)
    return (id(r),)


def same_ref(a, b) -> bool:
    """Whether two non-NULL references designate the same storage: equal
    scalar references, or the same aggregate object (an array is a list,
    and two lists of equal values are still two arrays)."""
    if a is b:
        return True
    if type(a) in _POINTERS or type(b) in _POINTERS:
        return _key(a) == _key(b)
    return type(a) is type(b) and type(a) in _SCALAR_REFS and a == b


def deref(ref):
    """The aggregate a REF_TO/POINTER TO an array, struct or FB designates."""
    if ref is None:
        raise RangeFault("reference", NULL_REFERENCE)
    if type(ref) in _POINTERS:
        return ref.get()
    return ref


def elem_ptr(array, esize: int, shape: tuple):
    """A pointer to an array, taken as a pointer to its first element."""
    if array is None:
        return None
    if type(array) is BytePtr and array.count is not None:
        return BytePtr(array.holder, array.layout, array.offset, array.unit, None)
    if type(array) in _POINTERS:
        return array
    return ElemPtr(array, 0, esize, shape)


def assign_get(ref, value):
    """(x := value) as an expression (CODESYS): store through ref, give the value."""
    ref.set(value)
    return value


def ptr_add(p, delta: int, esize: int):
    """p + delta bytes (CODESYS: p := p + SIZEOF(INT) steps one INT)."""
    if p is None:
        raise RangeFault("reference", "pointer arithmetic on a NULL pointer")
    t = type(p)
    if t is ElemPtr:
        return ElemPtr(p.root, p.offset + delta, p.esize, p.shape)
    if t is BytePtr:
        return BytePtr(p.holder, p.layout, p.offset + delta, p.unit, None)
    if t is ObjPtr:
        if p.offset + delta == 0:
            return p.base
        return ObjPtr(p.base, p.offset + delta, p.aggregate)
    if t is ItemRef:
        return ElemPtr(p.seq, p.index * esize + delta, esize, (len(p.seq),))
    if delta == 0:
        return p
    return ObjPtr(p, delta, t not in _SCALAR_REFS and t is not CellRef and t is not CutRef)


def ptr_diff(a, b, esize: int) -> int:
    """a - b in bytes, both pointing into one object (else a fault)."""
    if a is None or b is None:
        raise RangeFault("reference", "pointer arithmetic on a NULL pointer")
    ka, kb = _order(a, esize), _order(b, esize)
    if ka[0] != kb[0]:
        raise RangeFault("reference", "pointers into different variables subtracted or compared")
    return ka[1] - kb[1]


def _order(p, esize: int) -> tuple:
    """(the object pointed into, the byte offset in it)."""
    t = type(p)
    if t is ElemPtr:
        return id(p.root), p.offset
    if t is ItemRef:
        return id(p.seq), p.index * esize
    if t is ObjPtr:
        return _key(p.base), p.offset
    if t is BytePtr:
        return (_key(p.holder) if p.layout.leaf else id(p.holder)), p.offset
    return _key(p), 0


def eno_ok(ref, value):
    """A standard function's call that ran: its ENO => target is TRUE
    (IEC 61131-3 ed.3 6.6.1.6); the call's value passes through."""
    ref.set(True)
    return value


def eno_skip(ref, value):
    """A call that EN kept from running: its ENO => target is FALSE."""
    ref.set(False)
    return value


class PartRef:
    """A bit or a partial access (x.3, x.%W1) of a variable reached by ref:
    what an output bound to it (=> w.3) writes through."""

    __slots__ = ("ref", "shift", "mask", "full", "half")

    def __init__(self, ref, shift: int, width: int, bits: int, signed: bool) -> None:
        self.ref = ref
        self.shift = shift
        self.mask = ((1 << width) - 1) << shift
        self.full = (1 << bits) - 1
        self.half = 1 << (bits - 1) if signed else 0

    def get(self):
        v = (self.ref.get() & self.mask) >> self.shift
        return v != 0 if self.mask == 1 << self.shift else v

    def set(self, value) -> None:
        new = self.ref.get() & (self.full ^ self.mask) | (int(value) << self.shift) & self.mask
        if self.half:
            new = ((new + self.half) & self.full) - self.half
        self.ref.set(new)
