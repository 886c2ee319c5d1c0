"""SIZEOF (runtime/st/sizes.py): sizes in bytes as CODESYS lays values out
on a 64-bit target, for a variable or a type name.

Sources: CODESYS "Operator: SIZEOF" and "Attribute: pack_mode" (8-byte
mode, the default of the x64 runtimes); TwinCAT 3 "Attribute 'pack_mode'",
whose example structure (BYTE, DINT, BYTE, INT) is 12 bytes when aligned.
"""

from __future__ import annotations

import pytest

from .conftest import diagnostics, run_st

_TYPES = """
TYPE S : STRUCT b1 : BYTE; i : DINT; b2 : BYTE; n : INT; END_STRUCT END_TYPE
TYPE L : STRUCT b : BOOL; x : LREAL; END_STRUCT END_TYPE
TYPE Inner : STRUCT w : WORD; b : BYTE; END_STRUCT END_TYPE
TYPE Outer : STRUCT b : BYTE; inner : Inner; s : STRING(2); d : DWORD; END_STRUCT END_TYPE
TYPE E : (red, green); END_TYPE
"""


@pytest.mark.parametrize(
    "what,size",
    [
        ("BOOL", 1),  # a BOOL takes a byte
        ("SINT", 1),
        ("INT", 2),
        ("WORD", 2),
        ("DINT", 4),
        ("REAL", 4),
        ("TIME", 4),
        ("LREAL", 8),
        ("LTIME", 8),
        ("str", 21),  # STRING(20): n + 1
        ("wstr", 22),  # WSTRING(10): 2 (n + 1)
        ("arr", 20),  # ARRAY[1..10] OF INT
        ("arr[1]", 2),
        ("m", 24),  # ARRAY[1..2, 1..3] OF DINT
        ("S", 12),  # BYTE pad3 DINT BYTE pad1 INT
        ("s", 12),
        ("L", 16),  # BOOL pad7 LREAL
        ("ls", 32),  # two L: the size includes the tail padding
        ("Inner", 4),  # WORD BYTE pad1: aligned to 2
        ("Outer", 16),  # BYTE pad1, Inner (4 at 2), STRING(2) (3 at 6, strings at any byte), pad3, DWORD at 12
        ("E", 2),  # an enumeration is an INT
        ("p", 8),  # a pointer on a 64-bit target
        ("r", 8),
    ],
)
def test_sizeof_in_bytes(what, size):
    src = (
        _TYPES + "PROGRAM main\nVAR str : STRING(20); wstr : WSTRING(10); arr : ARRAY[1..10] OF INT; "
        "m : ARRAY[1..2, 1..3] OF DINT; s : S; ls : ARRAY[0..1] OF L; p : POINTER TO INT; r : REF_TO LREAL; "
        f"n : UDINT; END_VAR\nn := SIZEOF({what});\nEND_PROGRAM\n"
    )
    assert run_st(src).get("n") == size


def test_sizeof_of_a_function_block_is_an_error():
    # a CODESYS instance holds what the compiler adds (a vtable pointer ...)
    src = (
        "FUNCTION_BLOCK fb VAR x : INT; END_VAR END_FUNCTION_BLOCK\n"
        "PROGRAM main\nVAR f : fb; n : UDINT; END_VAR\nn := SIZEOF(f);\nEND_PROGRAM\n"
    )
    d = [x for x in diagnostics(src) if x.severity == "error"]
    assert [(x.code, x.pos.line, x.pos.col) for x in d] == [("E162", 4, 13)] and d[0].hint
