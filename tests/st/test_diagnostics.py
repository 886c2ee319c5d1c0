"""Diagnostics as the user sees them: coded, located, with a hint; all
errors of a file in one run; never a Python traceback. The checks behind
each code are tested with the checker's parts (test_checker_*.py)."""

from __future__ import annotations

from softplc.runtime.st.diagnostics import SourceSet

from .conftest import codes, diagnostics, prog


def test_unknown_name_has_location_and_a_did_you_mean_hint():
    src = prog("counter : INT;", "countr := 1;")
    [d] = diagnostics(src)
    assert (d.code, d.pos.line, d.pos.col) == ("E010", 5, 1)
    assert "countr" in d.message and "counter" in d.hint
    sources = SourceSet()
    sources.add("test.st", src)
    text = d.format(sources)
    assert text.splitlines()[0].startswith("test.st:5:1: error E010")
    assert "countr := 1;" in text and "^" in text and "hint:" in text


def test_all_errors_of_a_file_are_reported_in_one_run():
    src = prog("a : INT; b : BOOL; c : CONSTANT_NOT_A_TYPE;", "a := TRUE;\nb := 5;\nzz := 1;\nEXIT;")
    found = codes(src)
    assert found.count("E020") == 2 and "E012" in found and "E010" in found and "E070" in found


def test_duplicate_declarations_and_case_labels():
    src = prog("a : INT; a : INT; x : INT;", "CASE x OF 1: ; 0..2: ; END_CASE")
    assert codes(src) == ["E011", "E061"]


def test_nesting_beyond_the_python_compilers_limits_is_e006_at_the_st_location():
    body = "WHILE FALSE DO\n" * 21 + "x := 1;\n" + "END_WHILE\n" * 21
    ds = diagnostics(prog("x : INT;", body))
    assert [d.code for d in ds] == ["E006"]
    assert ds[0].pos.line >= 5 and "FUNCTION" in ds[0].hint
