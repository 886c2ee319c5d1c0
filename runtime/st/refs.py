"""References to scalar storage: what REF(), ADR() and VAR_IN_OUT pass for an
elementary variable. Aggregates (arrays, structs, FB instances) are Python
objects already, so a reference to one is the object itself."""

from __future__ import annotations


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


_SCALAR_REFS = (AttrRef, ItemRef, AccessorRef)


def same_ref(a, b) -> bool:
    """Whether two non-NULL references designate the same storage: equal
    scalar references, or the same aggregate object (an array is a list,
    and two lists of equal values are still two arrays)."""
    if a is b:
        return True
    return type(a) is type(b) and type(a) in _SCALAR_REFS and a == b


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
