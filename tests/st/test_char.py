"""CHAR and WCHAR (runtime/st/types.py, rt_convert.py, checker_exprs.py).

IEC 61131-3 ed.3 6.4.2 (Table 10: CHAR is a single-byte, WCHAR a
double-byte character; initial value '$00' / "$0000"), Table 6 (typed
literals CHAR#'A', WCHAR#"A"), Table 23 and 27 (BYTE_TO_CHAR,
CHAR_TO_BYTE, WORD_TO_WCHAR, CHAR_TO_STRING, STRING_TO_CHAR, CHAR_TO_WCHAR,
WCHAR_TO_CHAR ...). A CHAR holds its character's code; it compares with a
character of its own type and takes no arithmetic.
"""

from __future__ import annotations

from .conftest import codes, diagnostics, prog, run_st


def test_char_literals_conversions_and_comparisons():
    src = prog(
        "c : CHAR := CHAR#'A'; d : CHAR := 'z'; w : WCHAR := WCHAR#\"\u00e9\"; z : CHAR;"
        "b : BYTE; s : STRING; ws : WSTRING; up : BOOL; digit : BOOL; c2 : CHAR; w2 : WCHAR;"
        "e : CHAR; i : INT; dollar : CHAR := '$24';",
        "b := CHAR_TO_BYTE(c);\n"
        "c2 := BYTE_TO_CHAR(b + 1);\n"
        "s := CONCAT(CHAR_TO_STRING(c), CHAR_TO_STRING(c2));\n"
        "ws := WCHAR_TO_WSTRING(w);\n"
        "up := c >= CHAR#'A' AND c <= CHAR#'Z';\n"
        "digit := d = CHAR#'0';\n"
        "w2 := CHAR_TO_WCHAR(d);\n"
        "e := STRING_TO_CHAR('xyz');\n"
        "i := CHAR_TO_INT(dollar);",
    )
    r = run_st(src)
    assert (r.get("b"), r.get("c2"), r.get("s"), r.get("ws")) == (65, ord("B"), "AB", "\u00e9")
    assert (r.get("up"), r.get("digit"), r.get("w2"), r.get("e"), r.get("i")) == (True, False, 122, 120, 36)
    assert r.get("z") == 0  # '$00', the initial value of a CHAR


def test_wide_characters_narrow_to_a_question_mark():
    src = prog(
        'w : WCHAR := WCHAR#"\u20ac"; c : CHAR; s : STRING; n : WORD;',
        "c := WCHAR_TO_CHAR(w);\ns := WCHAR_TO_STRING(w);\nn := WCHAR_TO_WORD(w);",
    )
    r = run_st(src)
    assert (r.get("c"), r.get("s"), r.get("n")) == (ord("?"), "?", 0x20AC)


def test_char_errors_are_coded():
    src = prog(
        "c : CHAR; i : INT; w : WCHAR;",
        "c := CHAR#'AB';\nc := c + 1;\ni := c;\nc := w;\nc := 'AB';\nw := WCHAR#\"\u20ac\";\nc := CHAR#'\u20ac';",
    )
    found = [(d.code, d.pos.line) for d in diagnostics(src)]
    assert [f for f in found if f[0] != "E023"][:2] == [("E028", 5), ("E020", 7)]
    assert ("E023", 6) in found  # no arithmetic on CHAR
    assert ("E020", 8) in found and ("E020", 9) in found and ("E028", 11) in found
    assert not any(line == 10 for _c, line in found)
    e028 = next(d for d in diagnostics(src) if d.code == "E028")
    assert e028.hint == "write CHAR#'A'" and (e028.pos.line, e028.pos.col) == (5, 6)


def test_a_char_conversion_that_does_not_exist_is_refused():
    """No CHAR_TO_REAL, TIME_TO_CHAR ... (ed.3 Table 23, 27 convert CHAR
    with bit strings and strings; integers here too, by code)."""
    assert codes(prog("c : CHAR; r : REAL;", "r := CHAR_TO_REAL(c);")) == ["E043"]
    assert codes(prog("c : CHAR; r : REAL;", "r := TO_REAL(c);")) == ["E020"]
    assert codes(prog("c : CHAR; i : INT;", "i := TO_INT(c);\nc := INT_TO_CHAR(i);")) == []
