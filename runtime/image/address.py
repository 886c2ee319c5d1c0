"""Direct addresses as a config file or the command line writes them:
``%QX0.0``, ``%IW4``, ``%MD3200``, ``%MW3250:X0``, ``%MW3250:4``, ``%M100``.

This module knows the syntax and the natural type of an address; where the
address lives in the bytes of the image (which depends on the addressing
model) is the business of memory.ProcessImage:

    addr = parse_address("%mw3250:x0")        # LocatedAddress, text '%MW3250:X0'
    default_type(addr)                       # BOOL
    region(image, parse_address("%QW1"))     # ('Q', 2, 2) in an IEC image
"""

from __future__ import annotations

import re

from ..st import types as T
from ..st.ast import LocatedAddress
from ..st.syntax import literals

EXAMPLES = "examples: %QX0.0, %IW2, %MD3200, %MW3250:X0"

# literals._LOCATED accepts '%QX0..3' (the ST lexer never hands it such a
# token); a config string can, so the dotted part is checked once more here.
_INDICES = re.compile(r"\d+(?:\.\d+)*", re.A)

_SIZE_TYPES = {"B": T.BYTE, "W": T.WORD, "D": T.DWORD, "L": T.LWORD}
SIZE_BITS = {"B": 8, "W": 16, "D": 32, "L": 64}


class AddressError(ValueError):
    """A direct address that is malformed, or that the image cannot hold."""


def parse_address(text: str, addressing: str | None = None) -> LocatedAddress:
    """Parse one direct address (case-insensitive, surrounding blanks
    allowed). With ``addressing`` ('iec' or 'schneider') the forms that model
    lacks are refused too (see check_model). Raises AddressError."""
    if not isinstance(text, str):
        raise AddressError(f"a direct address is a string like '%QW0', not {type(text).__name__}")
    s = text.strip().upper()
    m = literals._LOCATED.fullmatch(s)
    if m is None or (m.group(3) is not None and not _INDICES.fullmatch(m.group(3))):
        raise AddressError(f"'{text.strip()}' is not a direct address ({EXAMPLES})")
    if m.group(3) is None:  # %I* / %Q*: a CODESYS placeholder mapped elsewhere
        raise AddressError(f"'{s}' is an unconfigured placeholder; give the full address ({EXAMPLES})")
    try:
        addr = literals.parse_located(s)
    except literals.LiteralError as exc:
        raise AddressError(exc.message) from None
    check_address(addr, addressing)
    return addr


def check_address(addr: LocatedAddress, addressing: str | None = None) -> None:
    """Refuse what no addressing model allows (the checker's E080 rules:
    :Xn and :n only after a word, bits 0..15 of a word, 0..7 of a byte), and
    with ``addressing`` also what that model lacks (check_model)."""
    if not addr.indices:
        raise AddressError(f"{addr.text} is an unconfigured address; give the full address ({EXAMPLES})")
    if addressing is not None:
        check_model(addr, addressing)
    bit_address = addr.size in ("", "X")
    if addr.bit is not None or addr.table is not None:
        what = f":X{addr.bit}" if addr.bit is not None else f":{addr.table}"
        if addr.size != "W" or len(addr.indices) != 1:
            raise AddressError(f"{addr.text}: {what} follows a word address, e.g. %MW3250{what}")
        if addr.bit is not None and not 0 <= addr.bit <= 15:
            raise AddressError(f"{addr.text}: a word has bits 0..15")
        if addr.table is not None and addr.table < 1:
            raise AddressError(f"{addr.text}: a word table has at least 1 word")
    elif bit_address:
        if len(addr.indices) > 2:
            raise AddressError(f"{addr.text}: a bit address is <byte>.<bit>, e.g. %{addr.area}X0.3")
        if len(addr.indices) == 2 and not 0 <= addr.indices[1] <= 7:
            raise AddressError(f"{addr.text}: bit number {addr.indices[1]} is not 0..7")
    elif len(addr.indices) != 1:
        raise AddressError(
            f"{addr.text}: a %{addr.area}{addr.size} address has one number, e.g. %{addr.area}{addr.size}4"
        )


def check_model(addr: LocatedAddress, addressing: str) -> None:
    """Refuse the forms an addressing model lacks, as the checker does for
    located variables (E080, E083): Schneider tables and word bits in the IEC
    model, and IEC bit addresses without <byte>.<bit>."""
    if addressing == "schneider":
        return
    if addr.bit is not None or addr.table is not None:
        raise AddressError(
            f"{addr.text} is Schneider addressing; use the schneider profile "
            f"(IEC addresses a bit as %{addr.area}X<byte>.<bit>)"
        )
    if addr.size == "" and len(addr.indices) < 2:
        raise AddressError(f"{addr.text}: a bit address needs <byte>.<bit>, e.g. %{addr.area}X0.3")


def default_type(addr: LocatedAddress) -> T.ElementaryType:
    """The type of a value at addr when a config gives none: BOOL for a bit,
    BYTE/WORD/DWORD/LWORD by size letter, WORD for the elements of a
    ``:n`` table. REAL and LREAL cannot be inferred; callers pass them."""
    if addr.bit is not None or addr.size in ("", "X"):
        return T.BOOL
    return _SIZE_TYPES[addr.size]


def check_type(addr: LocatedAddress, ty: T.ElementaryType) -> None:
    """Refuse a type whose size differs from the address's (INT at %MD,
    BOOL at %QW, REAL at %MW ...)."""
    bit_address = addr.bit is not None or addr.size in ("", "X")
    if bit_address:
        if ty is not T.BOOL:
            raise AddressError(f"{addr.text} is a bit; it holds a BOOL, not {ty.name}")
        return
    bits = SIZE_BITS[addr.size]
    if not (ty.is_intlike or ty.is_real or ty.is_time) or ty.bits != bits:
        raise AddressError(
            f"{addr.text} holds {bits} bits; {ty.name} does not fit (e.g. {_SIZE_TYPES[addr.size].name})"
        )


def region(image, addr: LocatedAddress) -> tuple:
    """(area letter, byte offset, byte count) of a byte/word/dword/lword
    address or a ``:n`` word table in image; see ProcessImage.region."""
    return image.region(addr)
