"""Sizes and alignment of ST types as CODESYS lays them out on a 64-bit
target: what SIZEOF answers and the byte steps pointer arithmetic takes.

The rule (CODESYS "Attribute: pack_mode", the 8-byte mode; TwinCAT 3 on
x64 uses the same, "Attribute 'pack_mode'"; CODESYS Control Win/Linux x64
lay structures out so by default):

* BOOL, SINT, USINT, BYTE: 1 byte; INT, UINT, WORD: 2; DINT, UDINT, DWORD,
  REAL, TIME, DATE, TOD, DT: 4; LINT, ULINT, LWORD, LREAL, LTIME, LDATE,
  LTOD, LDT: 8. An elementary value is aligned to its own size.
* STRING(n) takes n+1 bytes, WSTRING(n) 2(n+1); strings sit at any byte
  address (alignment 1).
* A pointer, REF_TO or REFERENCE TO takes 8 bytes, aligned to 8.
* An enumeration or subrange takes its base type's room.
* ARRAY: the element size times the number of elements, aligned as its
  element.
* STRUCT: the fields in declaration order, each at the next offset
  divisible by its alignment; the structure is aligned to its largest
  field's alignment and its size rounded up to it (so that the elements of
  an array of it stay aligned).
* BIT (CODESYS "Data type: BIT"): a run of consecutive BIT fields of a
  STRUCT shares bytes, eight to a byte, the first field in bit 0; a BIT
  anywhere else is a BOOL's byte.

Function block instances hold what the compiler adds (a vtable pointer ...):
their size is not known here (None).
"""

from __future__ import annotations

from . import types as T

#: bytes of a pointer, REF_TO or REFERENCE TO: a 64-bit target
POINTER_SIZE = 8

#: the largest alignment any value gets (pack mode 8)
PACK = 8


def layout(ty: T.Type, _seen: frozenset = frozenset()) -> tuple[int, int] | None:
    """(size in bytes, alignment) of a value of type ty, or None when the
    type has no fixed layout (FB instances, ARRAY[*])."""
    t = T.resolve(ty)
    if isinstance(t, T.ElementaryType):
        size = max(1, t.bits // 8)
        return size, min(size, PACK)
    if isinstance(t, (T.EnumType, T.SubrangeType)):
        return layout(t.base)
    if isinstance(t, T.StringType):
        return (t.length + 1) * (2 if t.wide else 1), 1
    if isinstance(t, T.RefType):
        return POINTER_SIZE, min(POINTER_SIZE, PACK)
    if isinstance(t, T.ArrayType):
        if t.variable_length:
            return None
        elem = layout(t.elem, _seen)
        if elem is None:
            return None
        n = 1
        for lo, hi in t.dims:
            n *= hi - lo + 1
        return n * elem[0], elem[1]
    if isinstance(t, T.StructType) and id(t) not in _seen:
        parts = struct_parts(t, _seen | {id(t)})
        if parts is None:
            return None
        align = max((a for _o, _s, a, _k in parts), default=1)
        end = parts[-1][0] + parts[-1][1] if parts else 0
        return _round_up(end, align), align
    return None


def struct_parts(t: T.StructType, _seen: frozenset = frozenset()) -> list | None:
    """[(byte offset, size, alignment, UPPER field names)] of a structure in
    order: one field each, or a run of up to eight BIT fields in one byte
    (their names bit 0 first). None when a field has no fixed layout."""
    parts: list = []
    offset = 0
    run: list | None = None  # the names of the BIT run being filled
    for key, f in t.fields.items():
        if f.type is T.BIT:
            if run is not None and len(run) < 8:
                run.append(key)
                continue
            run = [key]
            parts.append((offset, 1, 1, run))
            offset += 1
            continue
        run = None
        fl = layout(f.type, _seen)
        if fl is None:
            return None
        offset = _round_up(offset, fl[1])
        parts.append((offset, fl[0], fl[1], [key]))
        offset += fl[0]
    return parts


def sizeof(ty: T.Type) -> int | None:
    """SIZEOF of a value of type ty in bytes (None: not known)."""
    lay = layout(ty)
    return None if lay is None else lay[0]


def field_offsets(t: T.StructType) -> dict | None:
    """UPPER field name -> (byte offset, size) in a structure (a BIT
    field: the byte it shares with its run)."""
    parts = struct_parts(t)
    if parts is None:
        return None
    return {key: (offset, size) for offset, size, _a, keys in parts for key in keys}


def _round_up(n: int, align: int) -> int:
    return -(-n // align) * align
