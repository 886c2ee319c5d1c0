"""Byte views: a CODESYS POINTER TO BYTE (WORD, DWORD, REAL, CHAR ..., or an
ARRAY of one of them) over a value of another type, the way ported CODESYS
code and OSCAT walk strings and numbers byte by byte:

    pt : POINTER TO ARRAY[1..255] OF BYTE;  pt := ADR(str);  c := pt^[i];
    pb : POINTER TO BYTE;  pb := ADR(str) + i - 1;  pb^ := pb^ + 32;
    pdw : POINTER TO DWORD;  pdw := ADR(r);  bits := pdw^;  (* a REAL's bits *)

Values are Python objects here, not bytes: a view (refs.BytePtr) keeps the
object it points into (its holder), the object's layout (below) and a byte
offset, and encodes and decodes the bytes it reads and writes as x86
CODESYS lays them out: little-endian, IEEE 754, structures as st/sizes.py
places their fields, a BOOL one byte (any non-zero byte reads TRUE).

A STRING(n) is n+1 bytes, its characters and the terminating 0 (a WSTRING
2(n+1), UTF-16 code units): a byte past the string's end reads 0, writing 0
ends the string there, writing a character at its end or past it makes the
string longer (a gap left between reads 0 and holds character 0), and the
byte of the last terminator (index n) takes 0 only. Padding between
structure fields reads 0 and ignores writes. Past the object's size, before
its start, or outside an array's declared size a read or write is a
'reference' fault, as for the other pointers (st/rtlib/refs.py).
"""

from __future__ import annotations

import struct
from bisect import bisect_right

from .. import sizes
from .. import types as T
from ..faults import RangeFault
from .refs import AttrRef, BytePtr, CellRef, ElemPtr, ItemRef, ObjPtr


class Leaf:
    """An elementary value or a string: encoded whole, patched whole."""

    size = 0
    leaf = True

    def encode(self, value) -> bytes:
        raise NotImplementedError

    def decode(self, data: bytes):
        raise NotImplementedError

    def read(self, ref, o: int, n: int) -> bytes:
        return self.encode(ref.get())[o : o + n]

    def write(self, ref, o: int, data: bytes) -> None:
        b = bytearray(self.encode(ref.get()))
        b[o : o + len(data)] = data
        ref.set(self.decode(bytes(b)))


class IntLeaf(Leaf):
    """Integers, bit strings, CHAR/WCHAR, enumerations, times and dates
    (all kept as ints, st/types.py)."""

    def __init__(self, size: int, signed: bool) -> None:
        self.size = size
        self.signed = signed
        self.mask = (1 << 8 * size) - 1

    def encode(self, value) -> bytes:
        return (int(value) & self.mask).to_bytes(self.size, "little")

    def decode(self, data: bytes):
        return int.from_bytes(data, "little", signed=self.signed)


class BoolLeaf(Leaf):
    size = 1

    def encode(self, value) -> bytes:
        return b"\x01" if value else b"\x00"

    def decode(self, data: bytes):
        return data[0] != 0


class RealLeaf(Leaf):
    def __init__(self, size: int) -> None:
        self.size = size
        self.fmt = "<f" if size == 4 else "<d"

    def encode(self, value) -> bytes:
        return struct.pack(self.fmt, value)

    def decode(self, data: bytes):
        return struct.unpack(self.fmt, data)[0]


class BitsLeaf:
    """A run of BIT fields of a structure in one byte (st/sizes.py): the
    holder is the structure, the fields' bits are bit 0, 1 ... of the byte."""

    size = 1
    leaf = False

    def __init__(self, pynames: tuple) -> None:
        self.pynames = pynames

    def read(self, obj, o: int, n: int) -> bytes:
        return bytes([sum(1 << i for i, name in enumerate(self.pynames) if getattr(obj, name))])[o : o + n]

    def write(self, obj, o: int, data: bytes) -> None:
        if o == 0 and data:
            for i, name in enumerate(self.pynames):
                setattr(obj, name, bool(data[0] >> i & 1))


class StrLeaf(Leaf):
    """STRING(n) / WSTRING(n): the characters, then 0 bytes up to n+1
    characters (CODESYS keeps a string's terminating 0 in its n+1 bytes)."""

    def __init__(self, length: int, wide: bool) -> None:
        self.length = length
        self.cs = 2 if wide else 1
        self.size = (length + 1) * self.cs

    def encode(self, value) -> bytes:
        if self.cs == 1:
            data = bytes(ord(c) & 0xFF for c in value)
        else:  # UTF-16: a character beyond U+FFFF is its surrogate pair (2 WORDs)
            data = value.encode("utf-16-le", "surrogatepass")
        return data + bytes(self.size - len(data))

    def _codes(self, s: str) -> list:
        """s's characters (STRING) or UTF-16 units (WSTRING) as integers."""
        if self.cs == 1:
            return [ord(c) for c in s]
        data = s.encode("utf-16-le", "surrogatepass")
        return list(struct.unpack(f"<{len(data) // 2}H", data))

    def _text(self, codes: list) -> str:
        if self.cs == 1:
            return "".join(map(chr, codes))
        return struct.pack(f"<{len(codes)}H", *codes).decode("utf-16-le", "surrogatepass")

    def read(self, ref, o: int, n: int) -> bytes:
        s = ref.get()
        if self.cs == 1 and n == 1:  # the common case: one character
            return bytes((ord(s[o]) & 0xFF,)) if o < len(s) else b"\x00"
        return self.encode(s)[o : o + n]

    def write(self, ref, o: int, data: bytes) -> None:
        s = ref.get()
        codes = self._codes(s)
        count = len(codes)
        first, last = o // self.cs, (o + len(data) - 1) // self.cs
        if last >= self.length:  # the terminator of the last character stays
            word = bytearray(self.encode(s))
            word[o : o + len(data)] = data
            if any(word[self.length * self.cs :]):
                kind = "WSTRING" if self.cs == 2 else "STRING"
                raise RangeFault("reference", f"writing a character into the terminating 0 of a {kind}({self.length})")
        codes.extend([0] * (last + 1 - len(codes)))
        ends = None
        for ci in range(first, last + 1):
            b = bytearray(codes[ci].to_bytes(self.cs, "little"))
            for k in range(self.cs):
                p = ci * self.cs + k
                if o <= p < o + len(data):
                    b[k] = data[p - o]
            codes[ci] = int.from_bytes(b, "little")
            if codes[ci] == 0 and ci < count and ends is None:
                ends = ci  # a 0 written into the string ends it there
        if ends is not None:
            codes = codes[:ends]
        while codes and codes[-1] == 0:
            codes.pop()
        ref.set(self._text(codes))

    def _char_index(self, i: int) -> None:
        if not 0 <= i <= self.length:
            raise RangeFault(
                "bounds",
                f"string index {i} is outside 0..{self.length} of a {'W' * (self.cs == 2)}STRING({self.length})",
            )

    def byte_at(self, s: str, i: int) -> int:
        """s[i] (CODESYS, TwinCAT): the i-th byte, 0 past the string's end
        (a WSTRING's i-th character code)."""
        self._char_index(i)
        return ord(s[i]) & (0xFF if self.cs == 1 else 0xFFFF) if i < len(s) else 0

    def byte_ref(self, ref, i: int) -> BytePtr:
        """ADR(s[i]), s[i] passed to a VAR_IN_OUT: a byte view at the i-th
        character of the string ref designates."""
        self._char_index(i)
        return BytePtr(ref, self, i * self.cs, IntLeaf(self.cs, False), None)

    def with_byte(self, s: str, i: int, value: int) -> str:
        """s after s[i] := value, as a byte written through a pointer."""
        self._char_index(i)
        cell = CellRef(s)
        self.write(cell, i * self.cs, (int(value) & (0xFF if self.cs == 1 else 0xFFFF)).to_bytes(self.cs, "little"))
        return cell.value


class ArrayLayout:
    """An array (root: the outermost list) of elements of one layout."""

    leaf = False

    def __init__(self, elem, shape: tuple) -> None:
        self.elem = elem
        self.esize = elem.size
        self.shape = shape
        count = 1
        for n in shape:
            count *= n
        self.count = count
        self.size = count * elem.size

    def element(self, root, i: int):
        seq, stride = root, self.count
        for n in self.shape[:-1]:  # row-major, as refs.ElemPtr
            stride //= n
            j, i = divmod(i, stride)
            seq = seq[j]
        return ItemRef(seq, i) if self.elem.leaf else seq[i]

    def read(self, root, o: int, n: int) -> bytes:
        out = b""
        while n > 0:
            i, lo = divmod(o, self.esize)
            chunk = min(n, self.esize - lo)
            out += self.elem.read(self.element(root, i), lo, chunk)
            o, n = o + chunk, n - chunk
        return out

    def write(self, root, o: int, data: bytes) -> None:
        while data:
            i, lo = divmod(o, self.esize)
            chunk = min(len(data), self.esize - lo)
            self.elem.write(self.element(root, i), lo, data[:chunk])
            o, data = o + chunk, data[chunk:]


class StructLayout:
    """A structure: its fields at the offsets st/sizes.py gives them."""

    leaf = False

    def __init__(self, size: int, fields: list) -> None:
        self.size = size
        self.fields = fields  # (offset, pyname, layout), by offset
        self.starts = [f[0] for f in fields]

    def _parts(self, obj, o: int, n: int):
        """(field holder or None for padding, offset in it, bytes) pieces."""
        while n > 0:
            k = bisect_right(self.starts, o) - 1
            if k >= 0 and o < self.fields[k][0] + self.fields[k][2].size:
                start, pyname, lay = self.fields[k]
                chunk = min(n, start + lay.size - o)
                if pyname is None:  # a BitsLeaf: the fields are the structure's own
                    holder = obj
                else:
                    holder = AttrRef(obj, pyname) if lay.leaf else getattr(obj, pyname)
                yield lay, holder, o - start, chunk
            else:
                nxt = self.starts[k + 1] if k + 1 < len(self.starts) else self.size
                chunk = min(n, nxt - o)
                yield None, None, 0, chunk
            o, n = o + chunk, n - chunk

    def read(self, obj, o: int, n: int) -> bytes:
        return b"".join(
            bytes(chunk) if lay is None else lay.read(h, lo, chunk) for lay, h, lo, chunk in self._parts(obj, o, n)
        )

    def write(self, obj, o: int, data: bytes) -> None:
        at = 0
        for lay, h, lo, chunk in self._parts(obj, o, len(data)):
            if lay is not None:
                lay.write(h, lo, data[at : at + chunk])
            at += chunk


def layout_of(ty: T.Type):
    """The byte layout of a value of type ty, or None where byte views do
    not reach (FB instances, pointers, ARRAY[*])."""
    t = T.resolve(ty)
    if isinstance(t, (T.EnumType, T.SubrangeType)):
        return layout_of(t.base)
    if isinstance(t, T.ElementaryType):
        if t.is_bool:
            return BoolLeaf()
        if t.is_real:
            return RealLeaf(t.bits // 8)
        return IntLeaf(max(1, t.bits // 8), t.lo is not None and t.lo < 0)
    if isinstance(t, T.StringType):
        return StrLeaf(t.length, t.wide)
    if isinstance(t, T.ArrayType) and not t.variable_length:
        elem = layout_of(t.elem)
        return None if elem is None else ArrayLayout(elem, tuple(hi - lo + 1 for lo, hi in t.dims))
    if isinstance(t, T.StructType):
        parts = sizes.struct_parts(t)
        size = sizes.sizeof(t)
        if parts is None or size is None:
            return None
        fields: list = []
        for offset, _size, _align, keys in parts:
            f = t.fields[keys[0]]
            if f.type is T.BIT:
                fields.append((offset, None, BitsLeaf(tuple(t.fields[k].pyname for k in keys))))
                continue
            lay = layout_of(f.type)
            if lay is None:
                return None
            fields.append((offset, f.pyname, lay))
        return StructLayout(size, fields)
    return None


def view_unit(ty: T.Type) -> tuple | None:
    """What a pointer of target type ty reads through a byte view: (its
    elementary layout, the element count of the ARRAY it points to, or None),
    None when ty is no such target."""
    t = T.resolve(ty)
    if isinstance(t, T.ArrayType):
        if t.variable_length or len(t.dims) != 1:
            return None
        elem = view_unit(t.elem)
        if elem is None or elem[1] is not None:
            return None
        lo, hi = t.dims[0]
        return elem[0], hi - lo + 1
    if isinstance(t, (T.ElementaryType, T.EnumType, T.SubrangeType)):
        return layout_of(t), None
    return None


def byte_view(src, lay, unit, count):
    """src (a pointer or reference to a value of layout lay, as ADR gives
    it) seen as a pointer to unit (an ARRAY of count of them when count)."""
    t = type(src)
    if src is None:
        return None
    if t is BytePtr:
        return BytePtr(src.holder, src.layout, src.offset, unit, count)
    if t is ObjPtr:
        view = byte_view(src.base, lay, unit, count)
        return BytePtr(view.holder, view.layout, view.offset + src.offset, unit, count)
    if t is ElemPtr:  # into an array of lay's (a decayed ADR(arr), ADR(m[i, j]))
        return BytePtr(src.root, ArrayLayout(lay, src.shape), src.offset, unit, count)
    if t is ItemRef and lay.leaf:  # an element of a one-dimensional array
        return BytePtr(src.seq, ArrayLayout(lay, (len(src.seq),)), src.index * lay.size, unit, count)
    return BytePtr(src, lay, 0, unit, count)
