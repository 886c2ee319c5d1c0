"""The process image: %I, %Q and %M areas in memory, with both addressing
models of DESIGN.md (chosen by the profile's ``addressing``):

  'iec'       byte offsets (CODESYS): %MB5 = byte 5, %MW1 = bytes 2-3,
              %MD1 = bytes 4-7, %ML1 = bytes 8-15, %MX2.3 = bit 3 of byte 2.
  'schneider' word indices (Unity/Control Expert): %MW3250 = word 3250,
              %MD3200 = words 3200 (low) and 3201 (high), %MW3250:X0 = bit 0
              of that word, %MW3250:4 = the 4-word table 3250..3253; %M100
              is bit 100 of a separate bit area, as on a Premium PLC.

Words are little-endian in the image; drivers convert to bus byte order.
Code generated for a located variable binds an accessor pair (get, set) once
at load time, so an access is one call with no address arithmetic. Beside
that hot path: region() gives a driver the bytes an address covers, read()
and write() reach one value by address string (--watch, forcing, tests), and
outputs_view() is the image drivers see while outputs are held safe. Address
syntax and default types are in address.py.
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from typing import Any

from ..st import types as T
from ..st.ast import LocatedAddress
from .address import SIZE_BITS as _SIZE_BITS
from .address import AddressError, check_address, check_type, default_type, parse_address

_FORMATS = {
    (8, True): "<b",
    (8, False): "<B",
    (16, True): "<h",
    (16, False): "<H",
    (32, True): "<i",
    (32, False): "<I",
    (64, True): "<q",
    (64, False): "<Q",
}

__all__ = ["AREA_SIZE", "AddressError", "ProcessImage", "WordTable"]

#: bytes of each area (%I, %Q, %M) of an image of the default size: 64 KiB
AREA_SIZE = 1 << 16


class ProcessImage:
    #: this is the engine's safe-output view (outputs_view): the drivers are
    #: handed it while a task is faulted and at the stop
    held_safe = False

    def __init__(self, addressing: str = "iec", size: int = AREA_SIZE) -> None:
        if addressing not in ("iec", "schneider"):
            raise ValueError(f"unknown addressing model {addressing!r}")
        self.addressing = addressing
        self.size = size
        self.areas = {"I": bytearray(size), "Q": bytearray(size), "M": bytearray(size)}
        # Schneider %Mi bits live apart from the %MW words.
        self.mbits = bytearray(size)

    # ------------------------------------------------------------ layout

    def _bit_location(self, addr: LocatedAddress) -> tuple:
        """(buffer, byte offset, bit) of a bit address."""
        buf = self.areas[addr.area]
        if addr.bit is not None:  # %MW3250:X0 -- bit of a word
            word = addr.indices[0]
            off = self._word_offset(word, 16)
            return buf, off + addr.bit // 8, addr.bit % 8
        if self.addressing == "schneider" and addr.area == "M" and len(addr.indices) == 1:
            return self.mbits, addr.indices[0], None
        if len(addr.indices) >= 2:
            byte, bit = addr.indices[-2], addr.indices[-1]
        else:
            byte, bit = divmod(addr.indices[0], 8)
        if not 0 <= bit <= 7:
            raise AddressError(f"{addr.text}: bit number {bit} is not 0..7")
        return buf, byte, bit

    def _word_offset(self, index: int, bits: int) -> int:
        if self.addressing == "schneider":
            return 2 * index
        return index * (bits // 8)

    def byte_offset(self, addr: LocatedAddress) -> int:
        bits = _SIZE_BITS[addr.size]
        if self.addressing == "iec":
            return addr.indices[-1] * (bits // 8) if len(addr.indices) == 1 else addr.indices[-1]
        return 2 * addr.indices[-1] if bits >= 16 else addr.indices[-1]

    def _check(self, offset: int, nbytes: int, addr: LocatedAddress) -> None:
        if offset < 0 or offset + nbytes > self.size:
            span = f"byte {offset}" if nbytes == 1 else f"bytes {offset}..{offset + nbytes - 1}"
            raise AddressError(f"{addr.text} ({span}) is outside the {self.size}-byte %{addr.area} area")

    # ------------------------------------------------------------ access

    def accessor(self, addr: LocatedAddress, ty: T.ElementaryType) -> tuple:
        """(get, set) closures for a scalar at addr read as type ty."""
        if addr.size in ("", "X") or addr.bit is not None:
            buf, byte, bit = self._bit_location(addr)
            self._check(byte, 1, addr)
            if bit is None:  # a whole-byte Schneider bit cell

                def get_cell(buf=buf, i=byte):
                    return buf[i] != 0

                def set_cell(v, buf=buf, i=byte):
                    buf[i] = 1 if v else 0

                return get_cell, set_cell
            mask = 1 << bit

            def get_bit(buf=buf, i=byte, m=mask):
                return buf[i] & m != 0

            def set_bit(v, buf=buf, i=byte, m=mask):
                if v:
                    buf[i] |= m
                else:
                    buf[i] &= ~m & 0xFF

            return get_bit, set_bit
        bits = _SIZE_BITS[addr.size]
        buf = self.areas[addr.area]
        off = self.byte_offset(addr)
        self._check(off, bits // 8, addr)
        if ty.is_real:
            fmt = "<f" if bits == 32 else "<d"
            if struct.calcsize(fmt) != bits // 8:
                raise AddressError(f"{addr.text}: {ty.name} does not fit a {bits}-bit address")
        else:
            signed = ty.category in (T.SIGNED, T.DURATION)
            fmt = _FORMATS[(bits, signed)]
        codec = struct.Struct(fmt)
        unpack_from, pack_into = codec.unpack_from, codec.pack_into
        mask = (1 << bits) - 1
        half = 1 << (bits - 1)

        if ty.is_real:

            def get_real(buf=buf, off=off):
                return unpack_from(buf, off)[0]

            def set_real(v, buf=buf, off=off):
                pack_into(buf, off, v)

            return get_real, set_real

        def get_int(buf=buf, off=off):
            return unpack_from(buf, off)[0]

        if fmt[1].islower():  # signed: wrap into range before packing

            def set_int(v, buf=buf, off=off):
                pack_into(buf, off, ((int(v) + half) & mask) - half)
        else:

            def set_int(v, buf=buf, off=off):
                pack_into(buf, off, int(v) & mask)

        return get_int, set_int

    def table(self, addr: LocatedAddress, signed: bool = True) -> WordTable:
        """The Schneider word table %MWi:n as a list-like view."""
        length = addr.table or 1
        off = self._word_offset(addr.indices[-1], 16)
        self._check(off, 2 * length, addr)
        return WordTable(self.areas[addr.area], off, length, signed)

    def region(self, addr: LocatedAddress) -> tuple:
        """(area letter, byte offset, byte count) covered by a byte, word,
        double or long word address or a ``:n`` word table: what a driver
        copies. Bit addresses are refused, as drivers move whole bytes."""
        check_address(addr, self.addressing)
        if addr.bit is not None or addr.size in ("", "X"):
            raise AddressError(
                f"{addr.text} is a bit; drivers copy whole bytes: give the byte or "
                f"word that holds it (e.g. %{addr.area}B0, %{addr.area}W0)"
            )
        if addr.table is not None:
            off, nbytes = self._word_offset(addr.indices[0], 16), 2 * addr.table
        else:
            off, nbytes = self.byte_offset(addr), _SIZE_BITS[addr.size] // 8
        self._check(off, nbytes, addr)
        return addr.area, off, nbytes

    # ------------------------------------------------------------ views and watching

    def outputs_view(self, q_bytes: bytearray) -> ProcessImage:
        """An image sharing this one's %I and %M areas (and %M bits) whose %Q
        area is q_bytes: the engine hands it to the drivers' write_outputs
        while the outputs are held at their safe values."""
        if len(q_bytes) != self.size:
            raise ValueError(f"the %Q area of a view must have {self.size} bytes, not {len(q_bytes)}")
        view = object.__new__(ProcessImage)
        view.addressing = self.addressing
        view.size = self.size
        view.areas = {"I": self.areas["I"], "Q": q_bytes, "M": self.areas["M"]}
        view.mbits = self.mbits
        view.held_safe = True
        return view

    def _resolve(self, where) -> LocatedAddress:
        if isinstance(where, LocatedAddress):
            check_address(where, self.addressing)
            return where
        key = (where, self.addressing)
        addr = _PARSED.get(key)
        if addr is None:  # drivers and simulators read the same few addresses every cycle
            if len(_PARSED) >= 4096:
                _PARSED.clear()
            addr = _PARSED[key] = parse_address(where, self.addressing)
        return addr

    def read(self, where, ty: T.ElementaryType | None = None):
        """The value at an address ('%QW0', '%MW3250:X0' or a LocatedAddress)
        read as ty (default: address.default_type; pass T.REAL for a float
        in a %MD). A ``:n`` table reads as a list of n words."""
        addr = self._resolve(where)
        ty = ty or default_type(addr)
        check_type(addr, ty)
        if addr.table is not None:
            return list(self.table(addr, signed=ty.category == T.SIGNED))
        return self.accessor(addr, ty)[0]()

    def reader(self, where, ty: T.ElementaryType | None = None) -> Callable[[], Any]:
        """A callable giving read(where, ty), checked once here (AddressError
        as read gives it): what reads the same address every scan uses."""
        addr = self._resolve(where)
        ty = ty or default_type(addr)
        check_type(addr, ty)
        if addr.table is not None:
            return lambda: self.read(addr, ty)
        return self.accessor(addr, ty)[0]

    def writer(self, where, ty: T.ElementaryType | None = None) -> Callable[[Any], None]:
        """A callable doing write(where, value, ty), the address checked once
        here (AddressError as write gives it), the value at each call
        (ValueError as write gives it): what writes the same address every scan uses."""
        addr = self._resolve(where)
        ty = ty or default_type(addr)
        check_type(addr, ty)
        if addr.table is not None:
            return lambda value: self.write(addr, value, ty)
        store = self.accessor(addr, ty)[1]

        def write(value, addr=addr, ty=ty, store=store) -> None:
            store(_checked_value(addr, ty, value))

        return write

    def write(self, where, value, ty: T.ElementaryType | None = None) -> None:
        """Store value at an address (see read). Integers must fit the
        address's size, signed or unsigned (-1 or 16#FFFF into a word);
        a ``:n`` table takes a sequence of n words."""
        addr = self._resolve(where)
        ty = ty or default_type(addr)
        check_type(addr, ty)
        if addr.table is not None:
            values = _word_list(addr, value)
            table = self.table(addr, signed=ty.category == T.SIGNED)
            for i, v in enumerate(values):
                table[i] = v
            return
        self.accessor(addr, ty)[1](_checked_value(addr, ty, value))


#: (address text, addressing) -> its LocatedAddress, for read() and write() by text
_PARSED: dict[tuple[str, str], LocatedAddress] = {}


def _checked_value(addr: LocatedAddress, ty: T.ElementaryType, value):
    """value if it is of the kind ty stores; a clear ValueError if not, so a
    forced value is never silently truncated or wrapped."""
    if ty.is_bool:
        if isinstance(value, bool) or value in (0, 1):
            return bool(value)
        raise ValueError(f"{addr.text} is a BOOL: write TRUE/FALSE or 1/0, not {value!r}")
    if ty.is_real:
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            return float(value)
        raise ValueError(f"{addr.text} holds a {ty.name}: write a number, not {value!r}")
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"{addr.text} holds a {ty.name}: write an integer, not {value!r}")
    return _fits(addr, ty.bits, value)


def _fits(addr: LocatedAddress, bits: int, value: int) -> int:
    lo, hi = -(1 << (bits - 1)), (1 << bits) - 1
    if not lo <= value <= hi:
        raise ValueError(f"{addr.text}: {value} does not fit {bits} bits ({lo}..{hi})")
    return value


def _word_list(addr: LocatedAddress, value) -> list:
    try:
        values = list(value)
    except TypeError:
        raise ValueError(
            f"{addr.text} is a table of {addr.table} words: write a list of {addr.table} integers, not {value!r}"
        ) from None
    if len(values) != addr.table:
        raise ValueError(f"{addr.text} is a table of {addr.table} words, not {len(values)}")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, int):
            raise ValueError(f"{addr.text}: table words are integers, not {v!r}")
        _fits(addr, 16, v)
    return values


class WordTable:
    """A view on n consecutive 16-bit words of the image, indexed 0..n-1,
    behaving like the Python list an ARRAY value is."""

    __slots__ = ("buf", "offset", "length", "_codec")

    def __init__(self, buf: bytearray, offset: int, length: int, signed: bool = True) -> None:
        self.buf = buf
        self.offset = offset
        self.length = length
        self._codec = struct.Struct("<h" if signed else "<H")

    def __len__(self) -> int:
        return self.length

    def _at(self, i: int) -> int:
        if not 0 <= i < self.length:
            raise IndexError(f"word table index {i} outside 0..{self.length - 1}")
        return self.offset + 2 * i

    def __getitem__(self, i: int) -> int:
        return self._codec.unpack_from(self.buf, self._at(i))[0]

    def __setitem__(self, i: int, v: int) -> None:
        bits = 0x8000 if self._codec.format == "<h" else 0
        self._codec.pack_into(self.buf, self._at(i), ((int(v) + bits) & 0xFFFF) - bits)

    def __iter__(self):
        return (self[i] for i in range(self.length))

    def __repr__(self) -> str:
        return f"WordTable({list(self)})"
