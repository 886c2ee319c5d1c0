"""Runtime library, the IEC string functions: LEN, LEFT, RIGHT, MID, CONCAT,
INSERT, DELETE, REPLACE, FIND."""

from __future__ import annotations

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
