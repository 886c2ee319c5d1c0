"""A string never exceeds its declared length (IEC 61131-3 ed.3 6.4.2,
CODESYS: the string is cut): CONCAT, INSERT and REPLACE give a result as
long as their strings together (conversions.string_result), so every store
of one cuts it; a reference declared longer than its variable cuts what is
stored through it (refs.CutRef). Issue 31: `h := CONCAT(h, 'abc')` in a
STRING[10] grew to 600,000 characters in 100,000 cycles."""

from __future__ import annotations

import pytest

from .conftest import prog, run_st


@pytest.mark.parametrize("decl", ["STRING[5]", "STRING(5)"])
def test_insert_and_replace_are_cut_at_the_declared_length(decl):
    src = prog(
        f"d : {decl}; r : {decl}; w : WSTRING[5];",
        "d := INSERT('abc', 'XYZW', 1);\nr := REPLACE('abcde', 'XYZW', 1, 2);\nw := WINSERT(\"abc\", \"XYZW\", 1);",
    )
    r = run_st(src)
    assert (r.get("d"), r.get("r"), r.get("w")) == ("aXYZW", "aXYZW", "aXYZW")


def test_a_string_grown_every_cycle_stops_at_its_length():
    src = prog(
        "h : STRING[10]; d : STRING; w : WSTRING;",
        "h := CONCAT(h, 'abc');\nd := CONCAT(d, 'abc');\nw := CONCAT(w, \"ab\");",
    )
    r = run_st(src, cycles=200)
    assert r.get("h") == "abcabcabca"
    assert len(r.get("d")) == 80 and len(r.get("w")) == 80  # the default length


def test_a_loop_of_concats_in_one_cycle_is_bounded():
    src = prog("h : STRING[10]; i : DINT;", "FOR i := 1 TO 10000 DO h := CONCAT(h, 'abc', h); END_FOR")
    assert run_st(src).get("h") == "abcabcabca"


_STORES = """
TYPE R : STRUCT s : STRING[4]; END_STRUCT END_TYPE
FUNCTION F : STRING[3]
VAR_INPUT a : STRING; END_VAR
F := CONCAT(a, a);
END_FUNCTION
FUNCTION H : INT
VAR_OUTPUT o : STRING[10]; END_VAR
o := CONCAT('abcde', 'fghij');
END_FUNCTION
FUNCTION G : INT
VAR_IN_OUT io : STRING; END_VAR
io := CONCAT(io, 'rrrrrrrr');
END_FUNCTION
FUNCTION_BLOCK B
VAR_INPUT i : STRING[4]; END_VAR
VAR_OUTPUT o : STRING[6]; END_VAR
VAR_IN_OUT io : STRING[5]; END_VAR
VAR seen : STRING; END_VAR
seen := i;
o := CONCAT(i, 'zzzzzzzz');
io := CONCAT(io, 'qqqqqqqq');
END_FUNCTION_BLOCK
PROGRAM main
VAR
  long : STRING := 'abcdefghij';
  r : R; arr : ARRAY[1..2] OF STRING[2]; b : B;
  out3, io3, fr, fo : STRING[3]; io4 : STRING[4]; s2 : STRING[2]; s6 : STRING[6];
  p : POINTER TO STRING; rf : REFERENCE TO STRING;
END_VAR
r.s := CONCAT(long, long);
arr[1] := CONCAT(long, 'x');
b(i := CONCAT(long, 'y'), o => out3, io := io3);
fr := F(long);
H(o => fo);
G(io4);
p := ADR(s2); p^ := long;
rf REF= s6; rf := CONCAT(long, long);
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "matiec"])
def test_every_kind_of_store_cuts_at_the_declared_length(profile):
    r = run_st(_STORES, cycles=2, profile=profile)
    assert (r.get("r.s"), r.get("arr")[0], r.get("fr"), r.get("fo")) == ("abcd", "ab", "abc", "abc")
    assert r.get("b.seen") == "abcd" and r.get("b.o") == "abcdzz" and r.get("out3") == "abc"
    # through references declared longer than the variable: VAR_IN_OUT, POINTER, REFERENCE
    assert (r.get("io3"), r.get("io4"), r.get("s2"), r.get("s6")) == ("qqq", "rrrr", "ab", "abcdef")
