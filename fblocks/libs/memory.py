"""Memory through pointers, for the vendor functions that take an address
and a size (Tc2_System MEMCPY, Tc2_Utilities F_CRC16_CCITT ...).

softplc has no flat memory: a pointer stays bound to the variable it points
into (runtime/st/rtlib/refs.py), and a function parameter written ``POINTER TO
BYTE`` (fblocks/iec/functions.py) receives any pointer as a byte view of
its target, laid out as CODESYS and TwinCAT lay it out on x64
(runtime/st/rtlib/rt_bytes.py: little-endian, IEEE 754, structures padded as
runtime/st/sizes.py says). So MEMCPY(ADR(st), ADR(arr), SIZEOF(st)) copies
a structure's bytes into an array of bytes and back, as on the PLC.

What a PLC would do with a wrong address or size (read or overwrite the
variables beside it, or crash) is a 'reference' fault here, naming the
function and the sizes: n bytes from a byte offset past the end of the
variable the pointer points into.

    data = read(p, n, "MEMCPY")      # bytes; p: what the function received
    write(p, data, "MEMCPY")
"""

from __future__ import annotations

from softplc.runtime.st.faults import RangeFault
from softplc.runtime.st.rtlib import rt_bytes
from softplc.runtime.st.rtlib.refs import BytePtr

_BYTE = rt_bytes.IntLeaf(1, False)


def view(p) -> BytePtr | None:
    """p (a pointer a POINTER TO BYTE parameter received) as a byte view;
    None for NULL. The checker made every other pointer a byte view
    already; a POINTER TO BYTE arrives as it is (into an ARRAY OF BYTE, on
    a BYTE variable)."""
    if p is None:
        return None
    if type(p) is BytePtr:
        return p
    return rt_bytes.byte_view(p, _BYTE, _BYTE, None)


def _span(p: BytePtr, n: int, fn: str) -> None:
    size = p.layout.size
    if p.offset < 0 or p.offset + n > size:
        raise RangeFault(
            "reference",
            f"{fn}: {n} byte(s) from byte offset {p.offset} of a {size}-byte variable",
        )


def read(p, n: int, fn: str) -> bytes:
    """n bytes from where p points (a 'reference' fault past its variable)."""
    v = view(p)
    if v is None:
        raise RangeFault("reference", f"{fn}: NULL pointer")
    _span(v, n, fn)
    return v.layout.read(v.holder, v.offset, n)


def write(p, data: bytes, fn: str) -> None:
    """data stored where p points (a 'reference' fault past its variable)."""
    v = view(p)
    if v is None:
        raise RangeFault("reference", f"{fn}: NULL pointer")
    _span(v, len(data), fn)
    v.layout.write(v.holder, v.offset, data)
