"""The checker's expressions (runtime/st/check/checker_exprs.py): literals, names,
members, indices, bit access, direct addresses."""

from __future__ import annotations

from ..conftest import codes, diagnostics, prog


def test_constant_index_out_of_bounds_is_a_compile_error():
    assert codes(prog("a : ARRAY[1..3] OF INT;", "a[4] := 1;")) == ["E051"]


def test_schneider_addresses_need_the_schneider_profile():
    src = prog("x : BOOL;", "x := %MW3250:X0;")
    assert codes(src, "codesys") == ["E080"]
    assert codes(src, "schneider") == []


def test_c_style_hex_only_in_the_schneider_profile():
    src = prog("d : DINT;", "d := 0x00032007;")
    assert codes(src, "codesys") == ["E026"]
    assert codes(src, "schneider") == []


def test_bit_numbers_string_indices_and_members_of_scalars():
    src = prog("i : INT; x : INT; s : STRING; c : BOOL;", "x := i.16;\nx := s[1];\nx := i.q;\nc := i.3;")
    # IEC strings are not indexed (CODESYS and TwinCAT read s[1] as a byte: test_string_index.py)
    assert [(d.code, d.message, d.pos.line) for d in diagnostics(src, "iec")] == [
        ("E053", "bit number must be a constant 0..15 for INT", 5),
        ("E050", "strings are not indexed", 6),
        ("E013", "INT has no members", 7),
    ]
