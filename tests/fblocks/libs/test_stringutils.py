"""CODESYS's StringUtils library (fblocks/libs/stringutils) against the
CODESYS online help (libs/StringUtils, Public Parts/Ansi): the functions
walk the string a pointer points to, called as `Stu.<name>` or bare."""

from __future__ import annotations

import pytest

from softplc.runtime.st.faults import STFault

from .bench import runner

STRINGS = """hello : STRING := 'hello'; empty : STRING; abcdef : STRING := 'abcdef'; de : STRING := 'de';
    buf : STRING(10) := 'xxxxxxx'; joined : STRING(80) := 'foo'; tight : STRING(80) := 'foo'; tail : STRING := 'bar';"""


def run_once(decls: str, body: str):
    r = runner(STRINGS + decls, body, "StringUtils")
    r.run(1)
    return r


def test_length_and_copy_count_as_the_help_says():
    r = run_once(
        "n : DINT; nul : DINT; copied : DINT; whole : DINT; all : STRING(10);",
        """n := Stu.StrLenA(ADR(hello)); nul := StrLenA(0);
        copied := StrCpyA(ADR(buf), 4, ADR(hello)); whole := Stu.StrCpyA(pBuffer := ADR(all), iBufferSize := 11,
        pStr := ADR(hello));""",
    )
    # "-1 if the given pointer to String is equal NULL"; StrCpyA counts the terminating 0
    assert (r.get("n"), r.get("nul")) == (5, -1)
    assert (r.get("buf"), r.get("copied"), r.get("all"), r.get("whole")) == ("hel", 4, "hello", 6)


def test_concat_appends_while_the_buffer_holds_it_and_refuses_else():
    r = run_once(
        "ok : BOOL; bad : BOOL;",
        """ok := Stu.StrConcatA(pstFrom := ADR(tail), pstTo := ADR(joined), iBufferSize := 80);
        bad := StrConcatA(ADR(tail), ADR(tight), 6);""",
    )
    assert (r.get("ok"), r.get("joined"), r.get("bad"), r.get("tight")) == (True, "foobar", False, "foo")


def test_find_is_the_standard_find_from_a_start_position():
    r = run_once(
        "f : INT; later : INT; none : INT; nul : INT; caseless : INT; twice : STRING := 'ababab'; ab : STRING := 'AB';",
        """f := StrFindA(ADR(abcdef), ADR(de), 1); later := StrCaseFindA(ADR(twice), ADR(ab), 2);
        none := StrFindA(ADR(hello), ADR(de), 1); nul := StrFindA(0, ADR(de), 1);
        caseless := StrFindA(ADR(twice), ADR(ab), 1);""",
    )
    # FIND('abcdef', 'de') = 4 (Standard, FIND); "A null pointer will lead to a return of -1"
    assert [r.get(n) for n in ("f", "later", "none", "nul", "caseless")] == [4, 3, 0, -1, 0]


def test_compares_answer_minus_one_zero_one():
    r = run_once(
        "lt : INT; eq : INT; gt : INT; ci : INT; st : INT; nst : INT; en : INT; cen : INT; e1 : BOOL; e2 : BOOL;"
        " abc : STRING := 'abc'; abd : STRING := 'abd'; ab : STRING := 'ab'; up : STRING := 'ABC';"
        " llo : STRING := 'LLO';",
        """lt := StrCmpA(ADR(abc), ADR(abd)); eq := StrCmpA(ADR(abc), ADR(abc)); gt := StrCmpA(ADR(abc), ADR(ab));
        ci := StrCaseCmpA(ADR(abc), ADR(up)); st := StrCmpStartA(ADR(abc), ADR(ab));
        nst := StrCmpStartA(ADR(ab), ADR(abc));
        en := StrCmpEndA(ADR(hello), ADR(llo)); cen := StrCaseCmpEndA(ADR(hello), ADR(llo));
        e1 := StrIsNullOrEmptyA(ADR(empty)); e2 := StrIsNullOrEmptyA(ADR(hello));""",
    )
    assert [r.get(n) for n in ("lt", "eq", "gt", "ci", "st", "nst", "en", "cen")] == [-1, 0, 1, 0, 0, -1, -1, 0]
    assert (r.get("e1"), r.get("e2")) == (True, False)


def test_delete_replace_and_case_edit_the_string_in_place():
    # the Standard library's examples: DELETE('SUXYSI', 2, 3) = 'SUSI', REPLACE('SUXYSI', 'K', 2, 2) = 'SKYSI'
    r = run_once(
        "d : STRING := 'SUXYSI'; rp : STRING(20) := 'SUXYSI'; k : STRING := 'K'; u : STRING := 'Hello World 1';"
        " l : STRING := 'ABC def'; c : BYTE; far : STRING := 'SUSI';",
        """StrDeleteA(ADR(d), 2, 3); Stu.StrReplaceA(pstInput := ADR(rp), uiInputBufferSize := 21,
        pstReplaceWith := ADR(k), iLengthInput := 6, iLengthToReplace := 2, iLengthToReplaceWith := 1, iPosition := 2);
        StrToUpperA(ADR(u)); StrToLowerA(ADR(l)); c := CharToUpper(16#61); StrDeleteA(ADR(far), 1, 9);""",
    )
    assert [r.get(n) for n in ("d", "rp", "u", "l", "c", "far")] == [
        "SUSI",
        "SKYSI",
        "HELLO WORLD 1",
        "abc def",
        0x41,
        "SUSI",
    ]


def test_pad_fills_to_the_size_and_refuses_a_longer_source():
    r = run_once(
        "l : STRING(10); rt : STRING(10); no : STRING(10) := 'zz'; a : BOOL; b : BOOL; c : BOOL; abc : STRING := 'abc';"
        " long : STRING := 'abcdefgh';",
        """a := StrPadLeftA(16#2A, ADR(abc), ADR(l), 6); b := StrPadRightA(16#2E, ADR(abc), ADR(rt), 6);
        c := StrPadLeftA(16#2A, ADR(long), ADR(no), 6);""",
    )
    assert [r.get(n) for n in ("l", "rt", "a", "b", "no", "c")] == ["***abc", "abc...", True, True, "zz", False]


def test_a_copy_past_the_destination_is_a_reference_fault_not_a_quiet_overwrite():
    r = runner(STRINGS + "small : STRING(3); n : DINT;", "n := StrCpyA(ADR(small), 80, ADR(hello));", "StringUtils")
    with pytest.raises(STFault, match="StrCpyA"):
        r.run(1)
