"""The string functions as the CODESYS Standard library and TwinCAT's
Tc2_Standard name their parameters: CONCAT(STR1, STR2), LEN(STR),
LEFT(STR, SIZE), RIGHT(STR, SIZE), MID(STR, LEN, POS), FIND(STR1, STR2),
INSERT(STR1, STR2, POS), DELETE(STR, LEN, POS), REPLACE(STR1, STR2, L, P),
and their W-prefixed WSTRING variants with the same names.

IEC 61131-3 names them IN1, IN2, L, P (fblocks/iec/functions.py); a program
that chose one of those libraries calls them with the vendor's names
(CONCAT(STR1 := a, STR2 := b)), as the vendor's compiler wants. The
behaviour is the IEC functions' (runtime/st/rtlib/rt_strings.py): the vendors'
documentation gives the same examples (MID('SUSI', 2, 2) = 'US',
REPLACE('SUXYSI', 'K', 2, 2) = 'SKYSI'). CONCAT takes more than two
strings, as softplc's IEC CONCAT does (STR3 ...).

    FUNCTIONS = standard_string_functions()   # name -> StdFunc
"""

from __future__ import annotations

from softplc.fblocks.iec.functions import StdFunc
from softplc.runtime.st.rtlib import rt_strings as S


def standard_string_functions() -> dict:
    """name -> StdFunc of the nine string functions and their W variants."""
    out: dict = {}
    for prefix, s, r in (("", "T:ANY_STRING", "T"), ("W", "WSTRING", "WSTRING")):
        table = (
            ("CONCAT", (("STR1", s), ("STR2", s)), r, S.CONCAT, True),
            ("LEN", (("STR", s),), "INT", S.LEN, False),
            ("LEFT", (("STR", s), ("SIZE", "ANY_INT")), r, S.LEFT, False),
            ("RIGHT", (("STR", s), ("SIZE", "ANY_INT")), r, S.RIGHT, False),
            ("MID", (("STR", s), ("LEN", "ANY_INT"), ("POS", "ANY_INT")), r, S.MID, False),
            ("FIND", (("STR1", s), ("STR2", s)), "INT", S.FIND, False),
            ("INSERT", (("STR1", s), ("STR2", s), ("POS", "ANY_INT")), r, S.INSERT, False),
            ("DELETE", (("STR", s), ("LEN", "ANY_INT"), ("POS", "ANY_INT")), r, S.DELETE, False),
            ("REPLACE", (("STR1", s), ("STR2", s), ("L", "ANY_INT"), ("P", "ANY_INT")), r, S.REPLACE, False),
        )
        for name, params, ret, impl, extensible in table:
            out[prefix + name] = StdFunc(prefix + name, params, ret, impl, extensible)
    return out
