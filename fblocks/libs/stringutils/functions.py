"""CODESYS StringUtils' Ansi functions written in Python (namespace Stu):
each walks the zero-terminated string a pointer points to (fblocks/libs/
memory.py: a pointer stays bound to its variable, reading past it is a
'reference' fault). The CODESYS online help page of each (content.
helpme-codesys.com, libs/StringUtils, Public Parts/Ansi/<name>) is quoted
at its definition; where a page leaves a case open the comment says what
softplc chose. The helpers STU_* serve ansi.st's in-place functions.
"""

from __future__ import annotations

from softplc.fblocks.iec.functions import StdFunc
from softplc.fblocks.libs import memory
from softplc.runtime.st.rtlib import rt_strings as S

_PTR = "POINTER TO BYTE"

FUNCTIONS: dict[str, StdFunc] = {}


def _def(name: str, params, ret: str, impl) -> None:
    FUNCTIONS[name] = StdFunc(name, tuple(params), ret, impl)


def _cstr(p, fn: str) -> bytes | None:
    """The characters p points to up to their terminating 0 (or the end of
    the variable); None for NULL."""
    v = memory.view(p)
    if v is None:
        return None
    data = memory.read(v, max(0, v.layout.size - v.offset), fn)
    end = data.find(0)
    return data if end < 0 else data[:end]


def _text(p, fn: str) -> str:
    data = _cstr(p, fn)
    return "" if data is None else data.decode("latin-1")


def _put(p, data: bytes, fn: str) -> None:
    memory.write(p, data + b"\x00", fn)


def _sign(a: str, b: str) -> int:
    return (a > b) - (a < b)


# StrLenA: "determines the length of a string by searching for a terminating
# zero character ... It will return -1 if the given pointer to String is
# equal NULL" (StrLenA : DINT, pstData : CharBufferPtr).
def _len(p) -> int:
    data = _cstr(p, "StrLenA")
    return -1 if data is None else len(data)


_def("STRLENA", (("pstData", _PTR),), "DINT", _len)


# StrIsNullOrEmptyA: TRUE for a NULL pointer or an empty string.
_def("STRISNULLOREMPTYA", (("pString", _PTR),), "BOOL", lambda p: not _cstr(p, "StrIsNullOrEmptyA"))


# StrCpyA: "Copies the content of pStr to pBuffer ... The return value is the
# number of copied characters including the terminating '\0'"; iBufferSize is
# "The size of the destination in bytes" (StrCpyA : DINT). A source longer
# than the buffer is cut to iBufferSize - 1 characters; the page says the
# pointers "must not be NULL": with one, nothing is copied and 0 returned.
def _cpy(buf, size: int, src) -> int:
    data = _cstr(src, "StrCpyA")
    if buf is None or data is None or size <= 0:
        return 0
    data = data[: size - 1]
    _put(buf, data, "StrCpyA")
    return len(data) + 1


_def("STRCPYA", (("pBuffer", _PTR), ("iBufferSize", "DINT"), ("pStr", _PTR)), "DINT", _cpy)


# StrConcatA (pstFrom, pstTo, iBufferSize) : BOOL appends pstFrom to pstTo
# when the result and its terminating 0 fit in iBufferSize bytes: TRUE;
# else it leaves pstTo as it was: FALSE (code stops concatenating on FALSE).
def _concat(src, dst, size: int) -> bool:
    a, b = _cstr(dst, "StrConcatA"), _cstr(src, "StrConcatA")
    if a is None or b is None or len(a) + len(b) + 1 > size:
        return False
    _put(dst, a + b, "StrConcatA")
    return True


_def("STRCONCATA", (("pstFrom", _PTR), ("pstTo", _PTR), ("iBufferSize", "DINT")), "BOOL", _concat)


# StrCmpA: "Does a case sensitive comparison of two strings. Return values:
# 0 -> the strings are equal, -1 -> pwd1 is less than pwd2, 1 -> pwd1 is
# larger than pwd2" (pby1, pby2 : POINTER TO BYTE). StrCaseCmpA: the same
# without regard to case. A NULL pointer compares as an empty string.
def _cmp(fold: bool):
    def impl(p1, p2) -> int:
        a, b = _text(p1, "StrCmpA"), _text(p2, "StrCmpA")
        return _sign(a.upper(), b.upper()) if fold else _sign(a, b)

    return impl


_def("STRCMPA", (("pby1", _PTR), ("pby2", _PTR)), "INT", _cmp(False))
_def("STRCASECMPA", (("pby1", _PTR), ("pby2", _PTR)), "INT", _cmp(True))


# StrCmpStartA / StrCmpEndA (and StrCaseCmp...): 0 when the first string
# starts (ends) with the second, else -1 (the pages give no more than the
# names: softplc's reading).
def _edge(end: bool, fold: bool):
    def impl(p1, p2) -> int:
        a, b = _text(p1, "StrCmpStartA"), _text(p2, "StrCmpStartA")
        if fold:
            a, b = a.upper(), b.upper()
        return 0 if (a.endswith(b) if end else a.startswith(b)) else -1

    return impl


for _name, _end, _fold in (
    ("STRCMPSTARTA", False, False),
    ("STRCMPENDA", True, False),
    ("STRCASECMPSTARTA", False, True),
    ("STRCASECMPENDA", True, True),
):
    _def(_name, (("pby1", _PTR), ("pby2", _PTR)), "INT", _edge(_end, _fold))


# StrFindA: "Similar semantics as Find from the standard.library. A null
# pointer will lead to a return of -1"; uiSearchStart: "a position relative
# to 1, where the search starts" (pst1, pst2 : POINTER TO STRING(255)).
# The position found counts from the start of pst1; 0: not found.
# StrCaseFindA: the same without regard to case.
def _find(fold: bool):
    def impl(p1, p2, start: int) -> int:
        a, b = _cstr(p1, "StrFindA"), _cstr(p2, "StrFindA")
        if a is None or b is None:
            return -1
        s1, s2 = a.decode("latin-1"), b.decode("latin-1")
        if fold:
            s1, s2 = s1.upper(), s2.upper()
        skip = max(start, 1) - 1
        found = S.FIND(s1[skip:], s2)
        return found + skip if found else 0

    return impl


_def("STRFINDA", (("pst1", _PTR), ("pst2", _PTR), ("uiSearchStart", "UINT")), "INT", _find(False))
_def("STRCASEFINDA", (("pst1", _PTR), ("pst2", _PTR), ("uiSearchStart", "UINT")), "INT", _find(True))


# StrPadLeftA / StrPadRightA (byPadChar, pstFrom, pstTo, diBufferSize) : BOOL:
# pstFrom filled up with byPadChar on the left (right) to diBufferSize
# characters, into pstTo; FALSE and nothing written when pstFrom is longer
# (the pages name the parameters only: softplc's reading).
def _pad(left: bool):
    def impl(pad: int, src, dst, size: int) -> bool:
        data = _cstr(src, "StrPadLeftA")
        if data is None or dst is None or len(data) > size:
            return False
        fill = bytes((pad & 0xFF,)) * (size - len(data))
        _put(dst, fill + data if left else data + fill, "StrPadLeftA")
        return True

    return impl


for _name, _left in (("STRPADLEFTA", True), ("STRPADRIGHTA", False)):
    _def(
        _name,
        (("byPadChar", "BYTE"), ("pstFrom", _PTR), ("pstTo", _PTR), ("diBufferSize", "DINT")),
        "BOOL",
        _pad(_left),
    )


# CharToUpper: one character (a byte) in upper case, a..z only.
_def("CHARTOUPPER", (("byChar", "BYTE"),), "BYTE", lambda c: c - 32 if 0x61 <= c <= 0x7A else c)


# ---------------------------------------------------------------- helpers of ansi.st
def _delete(p, n: int, pos: int) -> bool:
    data = _cstr(p, "StrDeleteA")
    if data is None or n <= 0 or not 1 <= pos <= len(data):
        return False
    _put(p, data[: pos - 1] + data[pos - 1 + n :], "StrDeleteA")
    return True


def _replace(p, size: int, q, n: int, m: int, pos: int) -> bool:
    data, new = _cstr(p, "StrReplaceA"), _cstr(q, "StrReplaceA")
    if data is None or new is None or not 1 <= pos <= len(data) + 1 or n < 0 or m < 0 or size <= 0:
        return False
    out = data[: pos - 1] + new[:m] + data[pos - 1 + n :]
    _put(p, out[: size - 1], "StrReplaceA")
    return True


def _case(p, upper: bool) -> bool:
    data = _cstr(p, "StrToUpperA")
    if data is None:
        return False
    text = data.decode("latin-1")
    conv = "".join(
        c.upper() if upper and "a" <= c <= "z" else c.lower() if not upper and "A" <= c <= "Z" else c for c in text
    )
    _put(p, conv.encode("latin-1"), "StrToUpperA")
    return True


_def("STU_DELETE", (("p", _PTR), ("n", "INT"), ("pos", "INT")), "BOOL", _delete)
_def(
    "STU_REPLACE",
    (("p", _PTR), ("size", "UINT"), ("q", _PTR), ("n", "INT"), ("m", "INT"), ("pos", "INT")),
    "BOOL",
    _replace,
)
_def("STU_CASE", (("p", _PTR), ("upper", "BOOL")), "BOOL", _case)
