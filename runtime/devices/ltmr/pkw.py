"""The LTMR's PKW telegrams: acyclic register access over PDO4 (manual 001
L337-591, digest 001 §2.5).

A request is four 16-bit words in RPDO4 (objects 0x3000:01/02), the response
four words in TPDO4 (0x3000:03/04):

    word 1  register number, or CANopen index            (response: same as request)
    word 2  bit 15 toggle, bits 8-14 function code, bits 0-7 0x00 or sub-index
    word 3  data, 1st word (MSW)
    word 4  data, 2nd word (LSW)

A changed function code or toggle starts a request; the response is ready
when it echoes the toggle and word 1 with the same function code, or 0x4E and
an SDO abort code in words 3-4 (A23). The manual does not say where the words
sit in the 8-byte frame (A6): by default each 32-bit object is
(second word << 16) | first word, little-endian on the wire, so the bytes are
w1lo w1hi w2lo w2hi w3lo w3hi w4lo w4hi; "big" words is the alternative.
"""

from __future__ import annotations

import struct
from dataclasses import dataclass

# Function codes (L404-577). The CANopen-addressing response table prints
# "R_REG_16 Code 0x55": a typo for R_CO_16 0x35 (A10).
R_REG_16 = 0x25
R_REG_32 = 0x26
W_REG_16 = 0x2A
W_REG_32 = 0x2B
R_CO_16 = 0x35
R_CO_32 = 0x36
W_CO_16 = 0x3A
W_CO_32 = 0x3B
ERROR = 0x4E  # "DETECTED ERROR", response only (L519)
NONE = 0x00  # no request: "unless function code [b8...b14] = 0x00"

READS = frozenset({R_REG_16, R_REG_32, R_CO_16, R_CO_32})
WRITES = frozenset({W_REG_16, W_REG_32, W_CO_16, W_CO_32})
IS_32BIT = frozenset({R_REG_32, W_REG_32, R_CO_32, W_CO_32})
BY_OBJECT = frozenset({R_CO_16, R_CO_32, W_CO_16, W_CO_32})
REQUESTS = READS | WRITES

FUNCTION_NAMES = {
    R_REG_16: "R_REG_16",
    R_REG_32: "R_REG_32",
    W_REG_16: "W_REG_16",
    W_REG_32: "W_REG_32",
    R_CO_16: "R_CO_16",
    R_CO_32: "R_CO_32",
    W_CO_16: "W_CO_16",
    W_CO_32: "W_CO_32",
    ERROR: "ERROR",
    NONE: "NONE",
}

TOGGLE_BIT = 0x8000
LAYOUTS = ("little", "big")


@dataclass(frozen=True)
class PkwWords:
    """Four PKW words, request or response."""

    w1: int
    w2: int
    w3: int = 0
    w4: int = 0

    def __post_init__(self):
        for name in ("w1", "w2", "w3", "w4"):
            if not 0 <= getattr(self, name) <= 0xFFFF:
                raise ValueError(f"PKW {name} = {getattr(self, name)} is not a 16-bit word")

    @property
    def toggle(self) -> int:
        return self.w2 >> 15

    @property
    def function(self) -> int:
        return (self.w2 >> 8) & 0x7F

    @property
    def subindex(self) -> int:
        return self.w2 & 0xFF

    @property
    def value32(self) -> int:
        """Words 3 and 4 as one 32-bit value, word 3 the MSW (L404-577)."""
        return (self.w3 << 16) | self.w4

    @property
    def is_error(self) -> bool:
        return self.function == ERROR

    def describe(self) -> str:
        name = FUNCTION_NAMES.get(self.function, f"0x{self.function:02X}")
        return (
            f"PKW {name} T={self.toggle} w1=0x{self.w1:04X} sub=0x{self.subindex:02X} "
            f"data=0x{self.w3:04X} 0x{self.w4:04X}"
        )


def word2(function: int, toggle: int, subindex: int = 0) -> int:
    """Word 2: (toggle << 15) | (function << 8) | sub-index."""
    if not 0 <= function <= 0x7F:
        raise ValueError(f"PKW function code 0x{function:X} does not fit 7 bits")
    if not 0 <= subindex <= 0xFF:
        raise ValueError(f"PKW sub-index {subindex} does not fit 8 bits")
    return (0x8000 if toggle else 0) | (function << 8) | subindex


def request(address: int, function: int, toggle: int, subindex: int = 0, data=(0, 0)) -> PkwWords:
    """A request telegram. `address` is a register number (R_REG/W_REG, whose
    word-2 LSB is 0x00) or a CANopen index (R_CO/W_CO, with `subindex`).
    `data` = (word 3, word 4): the value to write, MSW first."""
    if function not in REQUESTS and function != NONE:
        raise ValueError(f"0x{function:02X} is not a PKW request function code")
    if function not in BY_OBJECT and subindex:
        raise ValueError("register addressing takes no sub-index (word 2 LSB = 0x00)")
    w3, w4 = data
    return PkwWords(address, word2(function, toggle, subindex), w3, w4)


def response(req: PkwWords, data=(0, 0)) -> PkwWords:
    """The successful response to a request: word 1 and word 2 echoed, read data in words 3-4."""
    w3, w4 = data
    return PkwWords(req.w1, req.w2, w3, w4)


def error_response(req: PkwWords, abort_code: int) -> PkwWords:
    """ "function code = toggle bit + 0x4E", the SDO abort code in words 3 (MSW)
    and 4 (LSW) (L337-591); word 1 and the sub-index as in the request."""
    return PkwWords(req.w1, word2(ERROR, req.toggle, req.subindex), (abort_code >> 16) & 0xFFFF, abort_code & 0xFFFF)


def response_ready(req: PkwWords, resp: PkwWords) -> bool:
    """Whether `resp` answers `req` (A23): same toggle, same word 1 and sub-index,
    and the request's function code echoed or ERROR. A request with function
    code 0 (the re-trigger step) is answered only by an echo of 0."""
    if resp.toggle != req.toggle or resp.w1 != req.w1 or resp.subindex != req.subindex:
        return False
    if req.function == NONE:
        return resp.function == NONE
    return resp.function in (req.function, ERROR)


def to_objects(words: PkwWords) -> tuple:
    """The two 32-bit object values (0x3000:01/02 or :03/04), A6 default:
    each object = (second word << 16) | first word."""
    return (words.w2 << 16) | words.w1, (words.w4 << 16) | words.w3


def from_objects(first: int, second: int) -> PkwWords:
    return PkwWords(first & 0xFFFF, (first >> 16) & 0xFFFF, second & 0xFFFF, (second >> 16) & 0xFFFF)


def encode_frame(words: PkwWords, layout: str = "little") -> bytes:
    """The 8 data bytes of the PDO4 frame. "little" (A6 default): the two
    objects as little-endian U32s, i.e. every word little-endian in order;
    "big": every word big-endian in order."""
    return struct.pack(_format(layout), words.w1, words.w2, words.w3, words.w4)


def decode_frame(data: bytes, layout: str = "little") -> PkwWords:
    if len(data) != 8:
        raise ValueError(f"a PKW frame has 8 data bytes, not {len(data)}")
    return PkwWords(*struct.unpack(_format(layout), bytes(data)))


def _format(layout: str) -> str:
    if layout not in LAYOUTS:
        raise ValueError(f"PKW frame layout {layout!r} is not one of {LAYOUTS}")
    return "<4H" if layout == "little" else ">4H"
