"""A WSTRING counts UTF-16 code units (IEC 61131-3 ed.3 6.3.3; CODESYS works
on them): a WSTRING[4] holds 4 units, a character beyond U+FFFF ($D83D$DE00,
U+1F600) counts 2 in the declared length, in LEN and in every position of
the string functions. Issue 31: a WSTRING[1] held "$D83D$DE00", LEN of it
was 1, and a WSTRING[4] held 'a😀bc' (5 units). A cut or a position inside
a pair never splits it (runtime/st/rtlib/rt_strings.py). A STRING counts
characters, as before."""

from __future__ import annotations

import pytest

from softplc.testing import PLC

from .conftest import prog, run_st

FACE = "\U0001f600"  # $D83D$DE00: 2 UTF-16 units


def units(s: str) -> int:
    """The definition: a string's length in UTF-16 code units."""
    return len(s.encode("utf-16-le")) // 2


def test_the_issues_inputs_are_cut_at_the_declared_units():
    src = prog(
        "w1 : WSTRING[1]; w2 : WSTRING[2]; w4 : WSTRING[4]; n1, n2, n4 : INT;",
        'w1 := "$D83D$DE00";\nw2 := "$D83D$DE00";\nw4 := "a$D83D$DE00bc";\n'
        "n1 := LEN(w1); n2 := LEN(w2); n4 := LEN(w4);",
    )
    r = run_st(src)
    # the character does not fit one unit: cut before it, never half of it
    assert (r.get("w1"), r.get("w2"), r.get("w4")) == ("", FACE, "a" + FACE + "b")
    assert (r.get("n1"), r.get("n2"), r.get("n4")) == (0, units(FACE), units("a" + FACE + "b")) == (0, 2, 4)


def test_len_counts_units_of_a_wstring_and_characters_of_a_string():
    src = prog(
        "w : WSTRING := \"a$D83D$DE00b\"; s : STRING := 'a$E9b'; lw, lc, ls, lwf : INT;",
        'lw := LEN(w); lc := LEN("a$D83D$DE00b"); ls := LEN(s); lwf := WLEN(w);',
    )
    r = run_st(src)
    assert (r.get("lw"), r.get("lc"), r.get("lwf")) == (units("a" + FACE + "b"),) * 3 == (4, 4, 4)
    assert r.get("ls") == 3


W = "a" + FACE + "bc"  # units: a=1, the face 2..3, b=4, c=5
# MID(IN, L, P), DELETE(IN, L, P), REPLACE(IN1, IN2, L, P), INSERT(IN1, IN2, P)

# (the call, its value by the definition: positions in UTF-16 units)
CALLS = [
    ("LEFT(w, 3)", "a" + FACE),
    ("LEFT(w, 2)", "a"),  # half the face: left out
    ("RIGHT(w, 3)", "bc"),  # the low half only: left out
    ("RIGHT(w, 4)", FACE + "bc"),
    ("MID(w, 2, 2)", FACE),
    ("MID(w, 2, 3)", "b"),  # from the low half: left out
    ("MID(w, 3, 3)", "bc"),
    ("INSERT(w, 'X', 3)", "a" + FACE + "Xbc"),
    ("INSERT(w, 'X', 2)", "aX" + FACE + "bc"),  # inside the pair: before it
    ("DELETE(w, 2, 2)", "abc"),
    ("DELETE(w, 1, 3)", "abc"),  # half the face: all of it
    ("DELETE(w, 1, 4)", "a" + FACE + "c"),
    ("REPLACE(w, 'X', 2, 2)", "aXbc"),
    ("REPLACE(w, 'X', 1, 3)", "aXbc"),  # half the face: all of it
    ("REPLACE(w, 'X', 0, 3)", "aX" + FACE + "bc"),  # 0 units inside the pair: before it
    ("REPLACE(w, 'X', 1, 4)", "a" + FACE + "Xc"),
]


@pytest.mark.parametrize("folded", [False, True], ids=["run", "folded"])
def test_positions_of_the_string_functions_are_utf16_units(folded):
    """The same calls on a variable (run time) and on a constant (folded)."""
    w = '"a$D83D$DE00bc"' if folded else "w"
    decls = 'w : WSTRING := "a$D83D$DE00bc"; f1, f2, f3 : INT; '
    decls += " ".join(f"r{i} : WSTRING;" for i in range(len(CALLS)))
    body = "\n".join(f"r{i} := {call.replace('w,', w + ',')};" for i, (call, _) in enumerate(CALLS))
    body = body.replace("'X'", '"X"')
    body += f'\nf1 := FIND({w}, "b"); f2 := FIND({w}, "$D83D$DE00"); f3 := FIND({w}, "z");'
    r = run_st(prog(decls, body))
    got = [r.get(f"r{i}") for i in range(len(CALLS))]
    assert got == [want for _, want in CALLS]
    assert (r.get("f1"), r.get("f2"), r.get("f3")) == (units("a" + FACE) + 1, 2, 0)


def test_the_w_functions_and_the_standard_library_count_units():
    src = prog(
        'w : WSTRING := "$D83D$DE00$D83D$DE00x"; a, b : WSTRING; n, m : INT;',
        'a := WLEFT(w, 3); b := WMID(w, 1, 5); n := WLEN(w); m := WFIND(w, "x");',
    )
    r = run_st(src)
    assert (r.get("a"), r.get("b"), r.get("n"), r.get("m")) == (FACE, "x", 5, 5)


def test_string_positions_stay_characters():
    src = prog("s : STRING := 'a$E9bc'; l : STRING; n : INT;", "l := LEFT(s, 2); n := FIND(s, 'b');")
    r = run_st(src)
    assert (r.get("l"), r.get("n")) == ("a\u00e9", 3)


_STORES = """
TYPE R : STRUCT s : WSTRING[4]; END_STRUCT END_TYPE
FUNCTION F : WSTRING[3]
VAR_INPUT a : WSTRING; END_VAR
F := a;
END_FUNCTION
FUNCTION G : INT
VAR_IN_OUT io : WSTRING; END_VAR
io := CONCAT(io, "$D83D$DE00$D83D$DE00");
END_FUNCTION
FUNCTION_BLOCK B
VAR_INPUT i : WSTRING[2]; END_VAR
VAR_OUTPUT o : WSTRING[3]; END_VAR
VAR seen : WSTRING; END_VAR
seen := i;
o := CONCAT(i, "$D83D$DE00");
END_FUNCTION_BLOCK
PROGRAM main
VAR
  long : WSTRING := "a$D83D$DE00bc$D83D$DE00";
  init : WSTRING[3] := "ab$D83D$DE00";
  r : R; arr : ARRAY[1..2] OF WSTRING[2]; b : B;
  fr, out3 : WSTRING[3]; io3 : WSTRING[3] := "a"; s2 : WSTRING[2]; s4 : WSTRING[4];
  p : POINTER TO WSTRING; rf : REFERENCE TO WSTRING;
END_VAR
r.s := long;
arr[1] := long;
b(i := long, o => out3);
fr := F(long);
G(io3);
p := ADR(s2); p^ := "$D83D$DE00$D83D$DE00";
rf REF= s4; rf := CONCAT("abc", long);
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "matiec"])
def test_every_kind_of_store_cuts_a_wstring_at_its_units(profile):
    r = run_st(_STORES, cycles=2, profile=profile)
    long = "a" + FACE + "bc" + FACE
    # cut at n units, before a character that would be split
    assert r.get("init") == "ab"  # an initial value
    assert (r.get("r.s"), r.get("arr")[0], r.get("fr")) == ("a" + FACE + "b", "a", "a" + FACE)
    assert (r.get("b.seen"), r.get("b.o"), r.get("out3")) == ("a", "a" + FACE, "a" + FACE)
    # through references declared longer than the variable: VAR_IN_OUT, POINTER, REFERENCE
    assert (r.get("io3"), r.get("s2"), r.get("s4")) == ("a" + FACE, FACE, "abca")
    for name in ("r.s", "fr", "out3", "io3", "s2", "s4", "init"):
        assert units(r.get(name)) <= {"r.s": 4, "s2": 2, "s4": 4}.get(name, 3)
    assert units(long) == 7


def test_a_write_from_outside_is_checked_in_units():
    """The one write API of the test PLC and the servers (engine/values.py)."""
    src = "PROGRAM Main\nVAR w : WSTRING[4]; s : STRING[4]; END_VAR\nEND_PROGRAM\n"
    with PLC.from_st(src) as plc:
        plc.write("Main.w", "a" + FACE + "b")  # 4 units
        with pytest.raises(ValueError, match=r"WSTRING\[4\]: write a str of at most 4 UTF-16 units"):
            plc.write("Main.w", "a" + FACE + "bc")  # 5 units
        assert plc["Main.w"] == "a" + FACE + "b"
        plc.write("Main.s", "a" + FACE + "bc")  # a STRING counts characters: 4
        assert plc["Main.s"] == "a" + FACE + "bc"


def test_a_word_pointer_sees_the_surrogate_pair_of_a_wstring():
    """A WSTRING's memory is UTF-16 (2 bytes a unit): U+1F600 is 16#D83D 16#DE00."""
    src = prog(
        'w : WSTRING(4) := "a$D83D$DE00"; pw : POINTER TO WORD; hi, lo, after : WORD;',
        "pw := ADR(w) + 2; hi := pw^; pw := pw + 2; lo := pw^; pw := pw + 2; after := pw^; pw^ := 16#62;",
    )
    r = run_st(src)
    pair = FACE.encode("utf-16-le")
    assert (r.get("hi"), r.get("lo")) == (int.from_bytes(pair[:2], "little"), int.from_bytes(pair[2:], "little"))
    assert (r.get("after"), r.get("w")) == (0, "a" + FACE + "b")
