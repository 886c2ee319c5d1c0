"""FB_FormatString's formatting (Beckhoff Information System, Tc2_Utilities
> "Format specification" and "Format error codes"): up to ten arguments
(T_Arg: a type, a size and a pointer to the value, made by F_DINT,
F_LREAL, F_STRING ...) written into a format string as fprintf does.

    %[flags][width][.precision]type

  type   b B  binary        o O  octal          u U  unsigned decimal
         d D  signed decimal (also i)           c C  a character (BYTE)
         x X  hexadecimal, lower / upper case   s S  a string
         f F  [-]ddd.ddd    e E  [-]d.ddde+dd    g G  the shorter of f and e
  flags  -  left-aligned    +  a sign always     0  zero-padded
         ' ' a blank for the sign of a positive number
         #  0, 0x, 0X before o, x, X; a decimal point always for f, e, g
  width  the least number of characters, or * (the next argument)
  precision  digits after the point (f, e: 6 by default), the least digits
         of an integer, the most characters of a string, or *

An integer type field of a signed argument shows its bits at its width
(%x of INT#-1 is ffff); b, o and x take a REAL's bits too. %% is a percent
sign. An error leaves sOut empty and answers its code plus the argument's
number: 16#10 a percent sign at an invalid position, 16#40 an invalid
width, 16#80 an invalid precision, 16#800 an unsupported type field,
16#1000 a type field the argument's type does not take, 16#2000 a missing
argument, 16#4000 more arguments in the format than given, 16#8000 an
output longer than 255 characters.
"""

from __future__ import annotations

import struct

# E_ArgType (Tc2_Utilities): the value's type, and how its bytes read
ARG_BYTE, ARG_WORD, ARG_DWORD, ARG_REAL, ARG_LREAL = 1, 2, 3, 4, 5
ARG_SINT, ARG_INT, ARG_DINT, ARG_USINT, ARG_UINT, ARG_UDINT = 6, 7, 8, 9, 10, 11
ARG_STRING, ARG_BOOL, ARG_BIGTYPE = 12, 13, 14
ARG_ULARGE, ARG_UHUGE, ARG_LARGE, ARG_HUGE = 15, 16, 17, 18
ARG_LWORD, ARG_ULINT, ARG_LINT = 19, 20, 21

# (bits, signed) of the integer argument types
_INTS = {
    ARG_BYTE: (8, False),
    ARG_WORD: (16, False),
    ARG_DWORD: (32, False),
    ARG_SINT: (8, True),
    ARG_INT: (16, True),
    ARG_DINT: (32, True),
    ARG_USINT: (8, False),
    ARG_UINT: (16, False),
    ARG_UDINT: (32, False),
    ARG_ULARGE: (64, False),
    ARG_LARGE: (64, True),
    ARG_LWORD: (64, False),
    ARG_ULINT: (64, False),
    ARG_LINT: (64, True),
    ARG_BOOL: (8, False),
}
_REALS = {ARG_REAL: "<f", ARG_LREAL: "<d"}

E_PERCENT, E_WIDTH, E_PRECISION = 0x10, 0x40, 0x80
E_TYPE, E_MISMATCH, E_MISSING, E_TOO_MANY, E_OVERFLOW = 0x800, 0x1000, 0x2000, 0x4000, 0x8000
MAX_LENGTH = 255


class FormatError(Exception):
    def __init__(self, code: int) -> None:
        super().__init__(code)
        self.code = code


def decode(kind: int, data: bytes):
    """The value of an argument: int, float or str (None: not a value)."""
    if kind in _INTS:
        bits, signed = _INTS[kind]
        return int.from_bytes(data[: bits // 8].ljust(bits // 8, b"\0"), "little", signed=signed)
    if kind in _REALS:
        size = struct.calcsize(_REALS[kind])
        return struct.unpack(_REALS[kind], data[:size].ljust(size, b"\0"))[0]
    if kind == ARG_STRING:
        return data.split(b"\0", 1)[0].decode("latin-1")
    return None


def _bits(kind: int, value) -> int:
    """The bit pattern of an integer or REAL argument, as unsigned."""
    if kind in _REALS:
        fmt = _REALS[kind]
        return int.from_bytes(struct.pack(fmt, value), "little")
    bits, _signed = _INTS[kind]
    return value & ((1 << bits) - 1)


def _radix(n: int, base: int, upper: bool) -> str:
    digits = "0123456789ABCDEF" if upper else "0123456789abcdef"
    out = ""
    while n:
        n, r = divmod(n, base)
        out = digits[r] + out
    return out or "0"


def _pad(body: str, sign: str, flags: str, width: int, numeric: bool) -> str:
    text = sign + body
    if width <= len(text):
        return text
    if "-" in flags:
        return text.ljust(width)
    if "0" in flags and numeric:
        return sign + body.rjust(width - len(sign), "0")
    return text.rjust(width)


def _integer(t: str, kind: int, value, flags: str, width: int, prec: int | None) -> str:
    lo = t.lower()
    if lo == "c":
        if kind not in (ARG_BYTE, ARG_USINT, ARG_SINT):
            raise FormatError(E_MISMATCH)
        return _pad(chr(value & 0xFF), "", flags, width, False)
    if kind in _REALS and lo not in "box":
        raise FormatError(E_MISMATCH)
    if lo in ("d", "i"):
        n, sign = abs(value), "-" if value < 0 else "+" if "+" in flags else " " if " " in flags else ""
        body = str(n)
    elif lo == "u":
        n, sign, body = _bits(kind, value), "", ""
        body = str(n)
    else:
        base = {"b": 2, "o": 8, "x": 16}[lo]
        n, sign = _bits(kind, value), ""
        body = _radix(n, base, t == "X")
    if prec is not None:
        body = "" if prec == 0 and n == 0 else body.rjust(prec, "0")
    if "#" in flags and n:
        body = {"o": "0", "x": "0x" if t == "x" else "0X"}.get(lo, "") + body
    if prec is not None:
        flags = flags.replace("0", "")  # a precision makes the 0 flag void, as in C
    return _pad(body, sign, flags, width, True)


def _real(t: str, value, flags: str, width: int, prec: int | None) -> str:
    spec = "%" + "".join(f for f in "-+ #0" if f in flags) + (str(width) if width else "")
    spec += f".{6 if prec is None else prec}" + ("f" if t in "fF" else t)
    return spec % value


def format_args(fmt: str, args: list) -> tuple[str, int]:
    """(output, 0) or ('', error code). args: (E_ArgType, value) per
    argument given (value from decode), in order."""
    out: list[str] = []
    i, used = 0, 0

    def take() -> tuple:
        nonlocal used
        if used >= len(args):
            raise FormatError(E_TOO_MANY)
        used += 1
        return args[used - 1]

    try:
        while i < len(fmt):
            ch = fmt[i]
            i += 1
            if ch != "%":
                out.append(ch)
                continue
            if i < len(fmt) and fmt[i] == "%":
                out.append("%")
                i += 1
                continue
            flags = ""
            while i < len(fmt) and fmt[i] in "-+0 #":
                flags += fmt[i]
                i += 1
            width, prec = 0, None
            if i < len(fmt) and fmt[i] == "*":
                kind, value = take()
                if kind not in _INTS or value < 0:
                    raise FormatError(E_WIDTH)
                width, i = value, i + 1
            else:
                start = i
                while i < len(fmt) and fmt[i].isdigit():
                    i += 1
                width = int(fmt[start:i]) if i > start else 0
            if i < len(fmt) and fmt[i] == ".":
                i += 1
                if i < len(fmt) and fmt[i] == "*":
                    kind, value = take()
                    if kind not in _INTS or value < 0:
                        raise FormatError(E_PRECISION)
                    prec, i = value, i + 1
                else:
                    start = i
                    while i < len(fmt) and fmt[i].isdigit():
                        i += 1
                    prec = int(fmt[start:i]) if i > start else 0
            if i >= len(fmt):
                raise FormatError(E_PERCENT)
            t = fmt[i]
            i += 1
            if t not in "bBoOuUcCdDixXfFeEgGsS":
                raise FormatError(E_TYPE)
            kind, value = take()
            if value is None:
                raise FormatError(E_MISMATCH)
            if t in "sS":
                if kind != ARG_STRING:
                    raise FormatError(E_MISMATCH)
                out.append(_pad(value if prec is None else value[:prec], "", flags, width, False))
            elif t in "fFeEgG":
                if kind not in _REALS:
                    raise FormatError(E_MISMATCH)
                out.append(_real(t, value, flags, width, prec))
            else:
                if kind == ARG_STRING:
                    raise FormatError(E_MISMATCH)
                out.append(_integer(t, kind, value, flags, width, prec))
            if sum(map(len, out)) > MAX_LENGTH:
                raise FormatError(E_OVERFLOW)
    except FormatError as e:  # + the number of the argument at hand
        return "", e.code + max(used + (e.code == E_TOO_MANY), 1)
    return "".join(out), 0
