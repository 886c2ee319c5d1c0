"""Runtime library, the IEC string functions: LEN, LEFT, RIGHT, MID, CONCAT,
INSERT, DELETE, REPLACE, FIND, and their WSTRING forms.

A STRING counts characters. A WSTRING counts UTF-16 code units (IEC
61131-3 ed.3 6.3.3: a WSTRING[4] holds 4 of them; CODESYS works on them):
a character beyond U+FFFF (U+1F600, written $D83D$DE00) counts 2, in the
declared length, LEN and every position. The code generator and the folding
take the W forms (WIDE) for a WSTRING argument; STRING keeps the plain ones.
A position inside such a pair never splits it (softplc holds no lone
surrogate it can avoid): LEFT, RIGHT and MID leave out a character they
would take half of, DELETE and REPLACE remove all of a character they would
remove half of, INSERT (and REPLACE of 0 units) goes before the character;
a store cuts before it (wcut)."""

from __future__ import annotations

import re

# ---------------------------------------------------------------- strings
# IEC 61131-3 Table 29 / CODESYS Standard library, positions 1-based.
# Out-of-range arguments never raise; the rule for each is in its docstring.


def LEN(s: str) -> int:
    return len(s)


def LEFT(s: str, n: int) -> str:
    """The first n characters; n <= 0 -> '', n > LEN -> s."""
    return s[:n] if n > 0 else ""


def RIGHT(s: str, n: int) -> str:
    """The last n characters; n <= 0 -> '', n > LEN -> s."""
    return s[-n:] if n > 0 else ""


def MID(s: str, n: int, p: int) -> str:
    """n characters from position p: MID('SUSI', 2, 2) = 'US'. p < 1 or
    p > LEN, or n <= 0 -> ''; n past the end -> up to the end."""
    if p < 1 or n <= 0:
        return ""
    return s[p - 1 : p - 1 + n]


def CONCAT(*parts: str) -> str:
    return "".join(parts)


def INSERT(s1: str, s2: str, p: int) -> str:
    """s2 inserted after position p of s1: INSERT('SUSI', 'XY', 2) =
    'SUXYSI'. p <= 0 -> in front; p > LEN(s1) -> appended."""
    if p < 0:
        p = 0
    return s1[:p] + s2 + s1[p:]


def DELETE(s: str, n: int, p: int) -> str:
    """Delete n characters from position p: DELETE('SUXYSI', 2, 3) = 'SUSI'.
    p < 1 or p > LEN, or n <= 0 -> s unchanged; n past the end deletes to the
    end."""
    if p < 1 or n <= 0 or p > len(s):
        return s
    return s[: p - 1] + s[p - 1 + n :]


def REPLACE(s1: str, s2: str, n: int, p: int) -> str:
    """Replace n characters of s1 from position p by s2:
    REPLACE('SUXYSI', 'K', 2, 2) = 'SKYSI'. p is clamped to 1..LEN(s1)+1
    (so p past the end appends s2), n < 0 counts as 0."""
    if p < 1:
        p = 1
    elif p > len(s1) + 1:
        p = len(s1) + 1
    if n < 0:
        n = 0
    return s1[: p - 1] + s2 + s1[p - 1 + n :]


def FIND(s1: str, s2: str) -> int:
    """Position of the first s2 in s1, 0 if absent (also for an empty s2:
    there is nothing to find)."""
    if not s2:
        return 0
    return s1.find(s2) + 1


# ---------------------------------------------------------------- WSTRING: UTF-16 units

#: a character beyond U+FFFF: 2 UTF-16 code units (a surrogate pair)
_ASTRAL = re.compile("[\U00010000-\U0010ffff]")


def units(s: str) -> int:
    """The length of s in UTF-16 code units (LEN of a WSTRING)."""
    if s.isascii():
        return len(s)
    return len(s) + sum(1 for _ in _ASTRAL.finditer(s))


def _at(s: str, u: int, after: bool = False) -> int:
    """The index in s of the UTF-16 unit offset u >= 0 (past the end: more
    than len(s)); an offset inside a surrogate pair gives the index of its
    character, or the one after it when after."""
    if s.isascii():
        return u
    extra = 0
    for m in _ASTRAL.finditer(s):
        start = m.start() + extra  # the character's first unit
        if start >= u:
            break
        if start + 1 == u:
            return m.start() + 1 if after else m.start()
        extra += 1
    return u - extra


def wcut(s: str, n: int) -> str:
    """s cut to at most n UTF-16 units, before a character it would split
    (a WSTRING[n] store)."""
    if s.isascii():
        return s[:n]
    if len(s) <= n and units(s) <= n:
        return s
    return s[: _at(s, n)]


def WLEN(s: str) -> int:
    return units(s)


def WLEFT(s: str, n: int) -> str:
    return s[: _at(s, n)] if n > 0 else ""


def WRIGHT(s: str, n: int) -> str:
    if n <= 0:
        return ""
    start = units(s) - n
    return s if start <= 0 else s[_at(s, start, True) :]


def WMID(s: str, n: int, p: int) -> str:
    if p < 1 or n <= 0:
        return ""
    return s[_at(s, p - 1, True) : _at(s, p - 1 + n)]


def WINSERT(s1: str, s2: str, p: int) -> str:
    i = _at(s1, p) if p > 0 else 0
    return s1[:i] + s2 + s1[i:]


def WDELETE(s: str, n: int, p: int) -> str:
    if p < 1 or n <= 0 or p > units(s):
        return s
    return s[: _at(s, p - 1)] + s[_at(s, p - 1 + n, True) :]


def WREPLACE(s1: str, s2: str, n: int, p: int) -> str:
    p = min(max(p, 1), units(s1) + 1)
    i = _at(s1, p - 1)
    return s1[:i] + s2 + s1[_at(s1, p - 1 + n, True) if n > 0 else i :]


def WFIND(s1: str, s2: str) -> int:
    if not s2:
        return 0
    i = s1.find(s2)
    return units(s1[:i]) + 1 if i >= 0 else 0


#: the function a WSTRING argument calls in place of each (CONCAT is the same)
WIDE = {
    LEN: WLEN,
    LEFT: WLEFT,
    RIGHT: WRIGHT,
    MID: WMID,
    INSERT: WINSERT,
    DELETE: WDELETE,
    REPLACE: WREPLACE,
    FIND: WFIND,
}


def cut_string(s: str, n: int, wide: bool) -> str:
    """s as a STRING[n] (characters) or WSTRING[n] (UTF-16 units) holds it."""
    return wcut(s, n) if wide else s[:n]


def string_length(s: str, wide: bool) -> int:
    """LEN of s as a STRING or a WSTRING."""
    return units(s) if wide else len(s)
