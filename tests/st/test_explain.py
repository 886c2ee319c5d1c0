"""The pages of ``softplc check --explain`` (runtime/st/explain): one per
code the compiler emits, none for a code nobody emits, and each page's
example still draws its code, so a page cannot drift from the compiler.

A page's first fenced ```st (or ```xml) block is its example; the blocks
under "## How to fix" are fixes, which must check without that code and
without errors. ``<!-- profile: iec -->`` chooses the profile (codesys
otherwise), ``<!-- file: x.TcPOU -->`` the file name (an imported kind).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

from softplc.runtime.program import check_files
from softplc.runtime.st import explain

RUNTIME = Path(__file__).resolve().parents[2] / "runtime"
_CODE = re.compile(r"[EW]\d{3}")
_BLOCK = re.compile(r"```(st|xml)\n(.*?)```", re.S)


def emitted_codes() -> set:
    """Every code a string literal of the runtime spells on its own ("E030"):
    what diags.error/warning and report(...) are given."""
    found = set()
    for path in RUNTIME.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and _CODE.fullmatch(node.value):
                found.add(node.value)
    return found


def test_every_emitted_code_has_a_page_and_every_page_a_code():
    emitted, pages = emitted_codes(), set(explain.codes())
    assert len(emitted) > 90  # the scan sees the codes (97 when written)
    assert sorted(emitted - pages) == [], "codes without a page in runtime/st/explain/"
    assert sorted(pages - emitted) == [], "pages for codes nothing emits"


def _setting(text: str, key: str, default: str) -> str:
    m = re.search(rf"<!-- {key}: (\S+) -->", text)
    return m.group(1) if m else default


def _check(code: str, src: str, text: str) -> list:
    profile = _setting(text, "profile", "codesys")
    name = _setting(text, "file", "example.st")
    diags, _sources = check_files([], texts={name: src}, profile=profile)
    return diags


@pytest.mark.parametrize("code", explain.codes())
def test_a_page_says_what_its_code_is(code):
    text = explain.page(code)
    assert text is not None and text.startswith(f"# {code}: ")
    assert "## How to fix" in text and "## Profiles" in text


@pytest.mark.parametrize("code", explain.codes())
def test_the_example_draws_the_code_and_the_fix_does_not(code):
    text = explain.page(code)
    assert text is not None
    before, _, fix = text.partition("## How to fix")
    examples = _BLOCK.findall(before)
    if not examples:  # E000, E006-E009: no program draws them; the page says so in prose
        # E220-E229 are drawn by projects of several files: tests/project/test_codes.py;
        # E230-W239 by programs with a library softplc ships: tests/program/test_shipped.py
        assert code in ("E000", "E006", "E007", "E008", "E009") or "E220" <= code <= "E229" or code[1:3] == "23"
        return
    found = [d.code for d in _check(code, examples[0][1], text)]
    assert code in found, f"{code}'s example gives {found}"
    for _lang, src in _BLOCK.findall(fix):
        diags = _check(code, src, text)
        assert not any(d.code == code or d.is_error for d in diags), [(d.code, d.message) for d in diags]


def test_page_takes_any_case_and_refuses_what_is_no_code():
    assert explain.page("e030") == explain.page("E030") is not None
    assert explain.page("E999") is None and explain.page("../pyproject") is None


def test_near_codes_are_the_numerically_closest_of_the_same_kind():
    assert explain.near("E034", 3) == ["E032", "E031", "E030"]
    assert explain.near("W101", 2) == ["W102", "W103"]
    assert explain.near("E30", 1) == ["E030"]  # a digit left out
    assert explain.near("EO30", 1) == ["E030"]  # a letter O for a zero: by spelling


def test_the_last_line_of_a_check_names_the_most_frequent_code():
    assert explain.more_line(["W130", "E010", "E010"]) == "for more on a code: softplc check --explain E010"
    assert explain.more_line(["E020", "E010"]).endswith("--explain E020")  # a tie: the first found
