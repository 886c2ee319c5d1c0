"""Runtime library, numbers: REAL rounding and the IEEE results of the real
functions, integer division and rounding, bit-string shifts and rotations,
BCD. Nothing here raises for a value an ST program can produce, except
integer division and MOD by zero (see rtlib.py)."""

from __future__ import annotations

import math
import struct
from collections.abc import Callable

_INF = math.inf
_NAN = math.nan

# ---------------------------------------------------------------- REAL

_F32 = struct.Struct("<f")
_f32_pack = _F32.pack
_f32_unpack = _F32.unpack


def f32(x: float, _pack=_f32_pack, _unpack=_f32_unpack) -> float:
    """Round to IEEE binary32 (round to nearest even), like a C float cast:
    NaN and inf pass through, a finite value beyond FLT_MAX becomes +-inf.

    The generated code calls this after every REAL operation, so it is the
    fastest correct form measured in CPython 3.11 (docs/architecture.md):
    a precompiled struct.Struct with its methods bound as default arguments
    (locals, ~150 ns a call). A shared array('f') or memoryview cast to 'f'
    is ~30 % faster but not thread-safe (write, then read back); ctypes
    c_float(x).value is twice as slow."""
    try:
        return _unpack(_pack(x))[0]
    except (OverflowError, struct.error):
        # beyond FLT_MAX after rounding (or an int beyond any float): the C
        # cast gives inf; struct refuses instead
        return _INF if x > 0 else -_INF


_EXACT53 = 1 << 53


def int_to_f32(v: int) -> float:
    """int -> REAL rounded once (int -> double -> float would round twice
    for values beyond 2**53)."""
    if -_EXACT53 <= v <= _EXACT53:
        return f32(float(v))
    a = -v if v < 0 else v
    shift = a.bit_length() - 24
    q = a >> shift
    r = a & ((1 << shift) - 1)
    half = 1 << (shift - 1)
    if r > half or (r == half and q & 1):  # ties to even
        q += 1
    x = float(q << shift)  # <= 25 significant bits: exact
    return f32(-x if v < 0 else x)


def rdiv(a: float, b: float) -> float:
    """Real division, IEEE 754: x/0 = +-inf (sign of x times sign of the
    zero), 0/0 = NaN. Never raises."""
    try:
        return a / b
    except ZeroDivisionError:
        if a != a or a == 0:
            return _NAN
        return math.copysign(_INF, a) * math.copysign(1.0, b)
    except OverflowError:  # huge int / int
        return math.copysign(_INF, a) * math.copysign(1.0, b)


def _is_odd_integer(y: float) -> bool:
    return math.isfinite(y) and y == math.floor(y) and math.fmod(y, 2.0) != 0.0


def expt(a, b) -> float:
    """a ** b as float with C pow() results: negative base with a non-integer
    exponent -> NaN, 0 ** negative -> inf, overflow -> +-inf. Never raises."""
    try:
        return math.pow(a, b)
    except ValueError:  # pole or domain error
        if a == 0:
            return math.copysign(_INF, a) if _is_odd_integer(b) else _INF
        return _NAN
    except OverflowError:
        if a < 0 and _is_odd_integer(b):
            return -_INF
        return _INF


# Real functions: the IEEE result instead of Python's ValueError.


def sqrt(x) -> float:
    try:
        return math.sqrt(x)
    except ValueError:
        return _NAN


def ln(x) -> float:
    try:
        return math.log(x)
    except ValueError:
        return -_INF if x == 0 else _NAN


def log(x) -> float:
    """LOG is base 10 (IEC)."""
    try:
        return math.log10(x)
    except ValueError:
        return -_INF if x == 0 else _NAN


def exp(x) -> float:
    try:
        return math.exp(x)
    except OverflowError:
        return _INF


def _nan_on_domain(fn: Callable) -> Callable:
    def f(x):
        try:
            return fn(x)
        except ValueError:  # sin(inf), asin(2) ...
            return _NAN

    f.__name__ = fn.__name__
    f.__doc__ = f"{fn.__name__}(x); NaN outside the domain."
    return f


sin = _nan_on_domain(math.sin)
cos = _nan_on_domain(math.cos)
tan = _nan_on_domain(math.tan)
asin = _nan_on_domain(math.asin)
acos = _nan_on_domain(math.acos)
atan = math.atan
atan2 = math.atan2  # (y, x); defined for every pair incl. (0, 0)


# ---------------------------------------------------------------- integers


def idiv(a: int, b: int) -> int:
    """Integer division truncating toward zero (IEC / CODESYS: -7 / 2 = -3;
    Python's // floors). b == 0 raises ZeroDivisionError."""
    q = a // b
    if q < 0 and q * b != a:
        q += 1
    return q


def imod(a: int, b: int) -> int:
    """Remainder with the sign of the dividend (a - idiv(a, b) * b):
    -7 MOD 2 = -1, 7 MOD -2 = 1. b == 0 raises ZeroDivisionError (a fault
    in CODESYS too)."""
    r = a % b
    if r and (a ^ b) < 0:  # signs differ: Python's % took the divisor's sign
        r -= b
    return r


def round_half_away(x: float) -> int:
    """REAL -> integer rounding: to nearest, halves away from zero
    (CODESYS: REAL_TO_INT(1.5) = 2, (1.4) = 1, (-1.5) = -2). NaN and inf
    give 0 (C leaves them undefined; we choose a value that does not crash)."""
    try:
        r = int(x)  # truncates
    except (OverflowError, ValueError):
        return 0
    d = x - r  # exact: the fraction of a double is representable
    if d >= 0.5:
        return r + 1
    if d <= -0.5:
        return r - 1
    return r


def trunc(x: float) -> int:
    """TRUNC: toward zero; NaN and inf give 0."""
    try:
        return int(x)
    except (OverflowError, ValueError):
        return 0


# ---------------------------------------------------------------- bit strings
# IEC: SHL/SHR fill with zeros; ROL/ROR rotate within the width of IN.
# CODESYS leaves n >= width target dependent; we give 0 for shifts (what its
# static analysis SA0053 says: "a constant 0 is generated") and take n MOD
# width for rotations. A negative n shifts/rotates the other way.


def shl(width: int, x: int, n: int) -> int:
    if n < 0:
        return shr(width, x, -n)
    if n >= width:
        return 0
    return (x << n) & ((1 << width) - 1)


def shr(width: int, x: int, n: int) -> int:
    """Logical shift right of the width-bit pattern of x (zeros shifted in,
    also for signed operands)."""
    if n < 0:
        return shl(width, x, -n)
    if n >= width:
        return 0
    return (x & ((1 << width) - 1)) >> n


def rol(width: int, x: int, n: int) -> int:
    mask = (1 << width) - 1
    n %= width
    x &= mask
    return ((x << n) | (x >> (width - n))) & mask


def ror(width: int, x: int, n: int) -> int:
    return rol(width, x, -n)


# ---------------------------------------------------------------- BCD


def bcd_to_int(x: int, width: int) -> int:
    """Decode the width-bit BCD pattern x. A nibble above 9 gives -1
    (CODESYS Util BCD_TO_INT: "if the byte is not in BCD format the output
    is -1"; stored into an unsigned type that wraps to its maximum)."""
    x &= (1 << width) - 1
    r = 0
    mul = 1
    while x:
        d = x & 15
        if d > 9:
            return -1
        r += d * mul
        mul *= 10
        x >>= 4
    return r


def int_to_bcd(v: int, width: int) -> int:
    """Encode v as BCD in width bits. Negative or too many digits gives all
    ones (CODESYS Util INT_TO_BCD: 255 when the value does not fit a BCD
    byte)."""
    mask = (1 << width) - 1
    if v < 0:
        return mask
    r = 0
    shift = 0
    while v:
        v, d = divmod(v, 10)
        r |= d << shift
        shift += 4
    if shift > width:
        return mask
    return r
