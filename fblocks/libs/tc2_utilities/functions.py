"""Tc2_Utilities' functions written in Python: numbers as digits, strings,
byte order, checksums over pointers, FB_FormatString's formatting and the
calendar of a FILETIME (the ST files of this folder call the helpers whose
names start with F_TC2_). The Beckhoff Information System page of each is
named at its definition; the numbers are the pages'
infosys.beckhoff.com/content/1033/tcplclib_tc2_utilities/<number>.html.
"""

from __future__ import annotations

import datetime as _dt
import math
import struct
from decimal import ROUND_DOWN, ROUND_HALF_UP, Context, Decimal

from softplc.fblocks.iec.functions import StdFunc
from softplc.fblocks.libs import filetime, memory
from softplc.runtime.st.rtlib import rt_bytes

from . import format_string as F

_PTR = "POINTER TO BYTE"
MAX = 255  # T_MaxString
FMTSTR_MAX = 510  # LREAL_TO_FMTSTR : STRING(510)

FUNCTIONS: dict[str, StdFunc] = {}


def _def(name: str, params, ret: str, impl, context: bool = False) -> None:
    FUNCTIONS[name] = StdFunc(name, tuple(params), ret, impl, context=context)


# ---------------------------------------------------------------- numbers as digits
# BYTE_TO_HEXSTR ... DWORD_TO_DECSTR (the ST declarations are in
# conversions.st): "iPrecision: minimum number of displayed digits ... the
# resulting string is filled with zeros from the left ... not truncated! If
# the iPrecision parameter and the in parameter have the value zero, the
# resulting string is an empty string" (Tc2_Utilities, DWORD_TO_HEXSTR:
# DWORD_TO_HEXSTR(43981, 1, FALSE) = 'ABCD', (15, 4, FALSE) = '000F').


def _radix(value: int, base: int, precision: int, lower: bool) -> str:
    digits = "0123456789abcdef" if lower else "0123456789ABCDEF"
    out = ""
    while value:
        value, r = divmod(value, base)
        out = digits[r] + out
    return out.rjust(max(0, min(precision, MAX)), "0")[-MAX:]


_def("F_TC2_RADIX", (("in", "LWORD"), ("base", "INT"), ("iPrecision", "INT"), ("bLoCase", "BOOL")), "STRING", _radix)


def _lreal_to_fmtstr(x: float, precision: int, rnd: bool) -> str:
    """LREAL_TO_FMTSTR (Tc2_Utilities, LREAL_TO_FMTSTR, 35143691): '[-]dddd.dddd' with
    iPrecision digits after the point, "rounded up" when bRound and "the
    decimal number after the last required decimal place is >= 5", else cut
    off; "the maximum number of significant digits for LREAL variables is
    limited to 15" (the digits beyond are zeros here); '#INF', '-#INF',
    '#QNAN', '-#QNAN'; '#OVF', '-#OVF' beyond the 510 characters of its
    result."""
    neg = math.copysign(1.0, x) < 0
    if math.isnan(x):
        return "-#QNAN" if neg else "#QNAN"
    if math.isinf(x):
        return "-#INF" if neg else "#INF"
    p = max(0, precision)
    if p > FMTSTR_MAX:
        return "-#OVF" if neg else "#OVF"
    digits = Decimal(f"{abs(x):.14e}")  # 15 significant digits
    exact = Context(prec=2 * FMTSTR_MAX)  # every digit of an LREAL's range and of 510 places
    text = f"{digits.quantize(Decimal(1).scaleb(-p), ROUND_HALF_UP if rnd else ROUND_DOWN, exact):f}"
    text = ("-" if x < 0 else "") + text
    if len(text) > FMTSTR_MAX:
        return "-#OVF" if neg else "#OVF"
    return text


_def("F_TC2_LREALFMT", (("in", "LREAL"), ("iPrecision", "INT"), ("bRound", "BOOL")), "STRING", _lreal_to_fmtstr)


# ---------------------------------------------------------------- strings
# F_LTrim, F_RTrim: "removes leading (trailing) spaces" (F_LTrim(' <trim ')
# = '<trim '); F_ToLCase, F_ToUCase: the letters of a string in lower
# (upper) case; F_ToASC: "the ASCII code of the first character" of str;
# F_ToCHR: "the character of an ASCII code".


def _to_asc(s: str) -> int:
    return ord(s[0]) & 0xFF if s else 0


def _to_chr(c: int) -> str:
    return chr(c & 0xFF) if c & 0xFF else ""


def _case(fn):
    # ASCII letters only, as the TwinCAT functions do (no locale)
    def impl(s: str) -> str:
        return "".join(fn(c) if "a" <= c.lower() <= "z" else c for c in s)

    return impl


_def("F_LTRIM", (("in", "STRING"),), "STRING", lambda s: s.lstrip(" "))  # Tc2_Utilities, F_LTrim
_def("F_RTRIM", (("in", "STRING"),), "STRING", lambda s: s.rstrip(" "))  # Tc2_Utilities, F_RTrim
_def("F_TOLCASE", (("in", "STRING"),), "STRING", _case(str.lower))  # Tc2_Utilities, F_ToLCase
_def("F_TOUCASE", (("in", "STRING"),), "STRING", _case(str.upper))  # Tc2_Utilities, F_ToUCase
_def("F_TOASC", (("str", "STRING"),), "BYTE", _to_asc)  # Tc2_Utilities, F_ToASC
_def("F_TOCHR", (("c", "BYTE"),), "STRING", _to_chr)  # Tc2_Utilities, F_ToCHR


# LEN2 (Tc2_Utilities, LEN2, 3483027723): "the number of characters in a string" that
# pSTRING points to, any length; it "stops the checking ... after
# Parameterlist.cMaxCharacters characters": here at the end of the variable
# the pointer points into (a STRING without its terminating zero).


def _len2(p) -> int:
    v = memory.view(p)
    if v is None:
        return 0
    if isinstance(v.layout, rt_bytes.StrLeaf) and v.offset == 0:
        # a POINTER TO STRING (80) may point to a longer STRING: its value
        return len(v.holder.get())
    data = memory.read(v, max(0, v.layout.size - v.offset), "LEN2")
    end = data.find(0)
    return len(data) if end < 0 else end


_def("LEN2", (("pSTRING", _PTR),), "UDINT", _len2)


# GUID_TO_STRING, STRING_TO_GUID (Tc2_Utilities, 35275147, 934149643): a GUID as
# 'xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx' ("without curly brackets"); for a
# string of any other form STRING_TO_GUID gives the GUID of zeros. F_TC2_GUIDFIELD
# answers field k of such a string: 0 Data1, 1 Data2, 2 Data3, 3..10 the
# bytes of Data4 (0 for a string of another form).

_GUID_GROUPS = (8, 4, 4, 4, 12)


def _guid_field(s: str, k: int) -> int:
    groups = s.split("-")
    if [len(g) for g in groups] != list(_GUID_GROUPS) or any(c not in "0123456789abcdefABCDEF" for c in s if c != "-"):
        return 0
    if k < 3:
        return int(groups[k], 16)
    tail = bytes.fromhex(groups[3] + groups[4])
    return tail[k - 3] if k - 3 < len(tail) else 0


_def("F_TC2_GUIDFIELD", (("s", "STRING"), ("k", "INT")), "DWORD", _guid_field)


# ---------------------------------------------------------------- byte order
# HOST_TO_BE16, _BE32, _BE64EX, BE16_TO_HOST ...: "converts host (little
# endian, intel) ... to network (big endian, motorola) format": the bytes
# reversed (HOST_TO_BE16(16#1234) = 16#3412). F_SwapReal: the two 16-bit
# words of a REAL swapped (a value from a device that sends its high word
# first).


def _swap(width: int):
    def impl(x: int) -> int:
        return int.from_bytes((x & ((1 << 8 * width) - 1)).to_bytes(width, "little"), "big")

    return impl


for _name, _width, _ty in ((16, 2, "WORD"), (32, 4, "DWORD"), (64, 8, "LWORD")):
    _ex = "EX" if _width == 8 else ""
    _def(f"HOST_TO_BE{_name}{_ex}", (("in", _ty),), _ty, _swap(_width))  # Tc2_Utilities, HOST_TO_BE16 ...
    _def(f"BE{_name}_TO_HOST{_ex}", (("in", _ty),), _ty, _swap(_width))  # Tc2_Utilities, BE16_TO_HOST ...


def _swap_real(x: float) -> float:
    b = struct.pack("<f", x)
    return struct.unpack("<f", b[2:] + b[:2])[0]


_def("F_SWAPREAL", (("fVal", "REAL"),), "REAL", _swap_real)  # Tc2_Utilities, F_SwapReal


# ---------------------------------------------------------------- data and checksums
# DATA_TO_HEXSTR: "converts binary data into a hexadecimal string ... The
# maximum length of the binary data must not exceed 85 bytes. If the maximum
# length is exceeded, a dot ('.') is added ... In the event of faulty
# function parameters (pData = zero or cbData = zero) the function returns
# an empty string"; the bytes are written 'AB CD EF'. HEXSTR_TO_DATA: "Only
# spaces may be used as separators ... In the event of an error or an
# illegal character the conversion is aborted and a zero length is
# returned"; else the number of bytes written (at most cbData).


def _data_to_hexstr(p, n: int, lower: bool) -> str:
    if p is None or n <= 0:
        return ""
    data = memory.read(p, min(n, 85), "DATA_TO_HEXSTR")
    text = " ".join(f"{b:02x}" if lower else f"{b:02X}" for b in data)
    return text + ("." if n > 85 else "")


def _hexstr_to_data(s: str, p, n: int) -> int:
    if p is None or n <= 0:
        return 0
    out = bytearray()
    for token in s.split(" "):
        if not token:
            continue
        if len(token) % 2 and len(token) > 1 or any(c not in "0123456789abcdefABCDEF" for c in token):
            return 0
        out += bytes.fromhex(token.rjust(2, "0"))
    out = out[:n]
    memory.write(p, bytes(out), "HEXSTR_TO_DATA")
    return len(out)


def _crc16_ccitt(crc: int, data: bytes) -> int:
    """CRC-16 CCITT, polynomial 16#1021 (x^16 + x^12 + x^5 + 1), most
    significant bit first (F_BYTE_TO_CRC16_CCITT)."""
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021 if crc & 0x8000 else crc << 1) & 0xFFFF
    return crc


def _data_crc(p, n: int, crc: int) -> int:
    if p is None or n <= 0:
        return crc & 0xFFFF
    return _crc16_ccitt(crc & 0xFFFF, memory.read(p, n, "F_DATA_TO_CRC16_CCITT"))


def _checksum16(p, n: int, seed: int) -> int:
    """F_CheckSum16 (35109899): "a 16-bit checksum for any data", wChkSum the initial
    value or the last checksum. Beckhoff does not say how it sums; here the
    bytes are added to it modulo 2^16."""
    if p is None or n <= 0:
        return seed & 0xFFFF
    return (seed + sum(memory.read(p, n, "F_CheckSum16"))) & 0xFFFF


_def("DATA_TO_HEXSTR", (("pData", _PTR), ("cbData", "UDINT"), ("bLoCase", "BOOL")), "STRING", _data_to_hexstr)
_def("HEXSTR_TO_DATA", (("sHex", "STRING"), ("pData", _PTR), ("cbData", "UDINT")), "UDINT", _hexstr_to_data)
_def(
    "F_BYTE_TO_CRC16_CCITT", (("value", "BYTE"), ("crc", "WORD")), "WORD", lambda v, c: _crc16_ccitt(c, bytes([v]))
)  # Tc2_Utilities, F_BYTE_TO_CRC16_CCITT
_def("F_DATA_TO_CRC16_CCITT", (("pData", _PTR), ("cbData", "UDINT"), ("crc", "WORD")), "WORD", _data_crc)
_def("F_CHECKSUM16", (("dwSrcAddr", _PTR), ("cbLen", "UDINT"), ("wChkSum", "WORD")), "WORD", _checksum16)


# ---------------------------------------------------------------- FB_FormatString
# format_string.py formats; FB_FormatString (format.st) hands it the ten
# T_Arg's fields (their type, size and pointer) and the address of sOut.


def _format(fmt: str, out, *fields) -> int:
    args = []
    for k in range(0, len(fields), 3):
        kind, size, p = fields[k : k + 3]
        if kind == 0:
            break  # the arguments given come first
        value = None if p is None or size <= 0 else F.decode(kind, memory.read(p, size, "FB_FormatString"))
        args.append((kind, value))
    text, err = F.format_args(fmt, args)
    memory.write(out, text.encode("latin-1", "replace")[:MAX] + b"\0", "FB_FormatString")
    return err


_ARGS = tuple(p for n in range(1, 11) for p in ((f"t{n}", "INT"), (f"n{n}", "UDINT"), (f"p{n}", _PTR)))
_def("F_TC2_FORMAT", (("sFormat", "STRING"), ("pOut", _PTR), *_ARGS), "UDINT", _format)


# ---------------------------------------------------------------- the calendar
# A FILETIME (T_FILETIME, 100 ns since 1601-01-01) in the fields of a
# TIMESTRUCT and back (time.st): part 1 year, 2 month, 3 day of the week
# (0 = Sunday), 4 day, 5 hour, 6 minute, 7 second, 8 millisecond; 0 for
# a FILETIME outside Windows' range. F_TC2_FILETIMEOF is 0 for an invalid date.


def _part(ft: int, part: int) -> int:
    fields = filetime.calendar(ft)
    return fields[part - 1] if fields is not None and 1 <= part <= 8 else 0


def _of(year: int, month: int, day: int, hour: int, minute: int, second: int, ms: int) -> int:
    ft = filetime.from_calendar(year, month, day, hour, minute, second, ms)
    return 0 if ft is None else ft


def _local_now(ctx) -> int:
    return filetime.local(ctx, filetime.now(ctx))


def _utc_offset(ctx) -> int:
    """Minutes UTC is ahead of local time (a TIME_ZONE_INFORMATION's bias)."""
    return -ctx.utc_offset_s(ctx.date_ns() // 1_000_000_000) // 60


_def("F_TC2_FILETIMEPART", (("ft", "ULINT"), ("part", "INT")), "WORD", _part)
_W = "WORD"
_def("F_TC2_FILETIMEOF", tuple((n, _W) for n in ("y", "mo", "d", "h", "mi", "s", "ms")), "ULINT", _of)
_def("F_TC2_LOCALNOW", (), "ULINT", _local_now, context=True)  # the engine's local time (NT_GetTime)
_def("F_TC2_UTCBIAS", (), "DINT", _utc_offset, context=True)  # its zone's bias (FB_GetTimeZoneInformation)


def _iso_week(ft: int) -> int:
    """F_GetWeekOfTheYear (Tc2_Utilities, 35123723): the calendar week "according to
    the DIN 1355 / ISO 8601 standard" (weeks start on Monday; week 1 has four
    days or more of the new year); 0 outside the calendar."""
    fields = filetime.calendar(ft)
    if fields is None:
        return 0
    return _dt.date(fields[0], fields[1], fields[3]).isocalendar()[1]


_def("F_TC2_ISOWEEK", (("ft", "ULINT"),), "WORD", _iso_week)


# ---------------------------------------------------------------- time zones
# Windows' TIME_ZONE_INFORMATION rules (Tc2_Utilities ST_TimeZoneInformation):
# daylight time starts on the wDay-th (1..4, 5: the last) wDayOfWeek of
# wMonth at wHour:wMinute of the zone's standard time and ends at the
# standard date's moment of daylight time; wMonth 0: no daylight time.
# F_TC2_TZID answers E_TimeZoneID for a FILETIME in local time (utc FALSE)
# or in UTC: 0 unknown (no rules), 1 standard, 2 daylight.


def _transition(year: int, month: int, dow: int, week: int, hour: int, minute: int) -> int | None:
    first = filetime.from_calendar(year, month, 1, 0, 0, 0, 0)
    if first is None:
        return None
    fields = filetime.calendar(first)
    if fields is None:
        return None
    first_dow = fields[2]
    day = 1 + (dow - first_dow) % 7 + 7 * (max(1, min(week, 5)) - 1)
    while filetime.from_calendar(year, month, day, 0, 0, 0, 0) is None:
        day -= 7  # week 5: the last one in the month
    return filetime.from_calendar(year, month, day, hour, minute, 0, 0)


def _tz_id(ft: int, utc: bool, bias: int, std_bias: int, dlt_bias: int, *rules: int) -> int:
    std, dlt = rules[:5], rules[5:]
    if std[0] == 0 or dlt[0] == 0:
        return 0
    fields = filetime.calendar(ft)
    if fields is None:
        return 0
    year = fields[0]
    dlt_start, std_start = _transition(year, *dlt), _transition(year, *std)
    if dlt_start is None or std_start is None:
        return 0
    if utc:  # the moments in UTC: local standard (daylight) time + its bias
        dlt_start += (bias + std_bias) * 600_000_000
        std_start += (bias + dlt_bias) * 600_000_000
    if dlt_start < std_start:
        daylight = dlt_start <= ft < std_start
    else:  # the southern hemisphere: daylight time over the new year
        daylight = not std_start <= ft < dlt_start
    return 2 if daylight else 1


_RULE = tuple((f"{w}{f}", "WORD") for w in ("std", "dlt") for f in ("Month", "Dow", "Day", "Hour", "Minute"))
_def(
    "F_TC2_TZID",
    (("ft", "ULINT"), ("utc", "BOOL"), ("bias", "DINT"), ("stdBias", "DINT"), ("dltBias", "DINT"), *_RULE),
    "INT",
    _tz_id,
)
