"""CODESYS 2.3 text exports (runtime/st/importers/codesys23.py): an export in
the style of OSCAT's (marker comments, FUNCTIONBLOCK, array values without
brackets, a LIBRARY section) runs as its plain ST twin; positions are the
export's; a .TXT is read as one by its content; a graphical body is named."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.importers import st_export, st_views

from ..fuzz_support import assert_well_formed

HERE = Path(__file__).parent / "codesys23"
EXP = HERE / "project.EXP"
WATCHED = ["tick", "total", "name", "third", "steps", "s.i"]


def values(path: Path, cycles: int, name: str | None = None, text: str | None = None) -> dict:
    paths, texts = ([], {name: text}) if name else ([str(path)], None)
    r = compile_files(paths, texts=texts).runner("Main", cycle_time_ms=10)
    r.run(cycles)
    return {v: r.get(v) for v in WATCHED}


@pytest.mark.parametrize("cycles", [1, 4, 9])
def test_the_export_runs_as_its_plain_st_twin(cycles):
    got = values(EXP, cycles)
    assert got == values(HERE / "project_twin.st", cycles)
    if cycles == 9:
        # four rising edges of UP (ticks 2, 4, 6, 8) add seq = [2, 5, 5, 9]: the
        # values in brackets, 2(5) twice; the constant's fields too
        assert got == {"tick": 9, "total": 21, "name": "one", "third": "three", "steps": 38, "s.i": 1}


def _position(text: str, needle: str) -> tuple:
    before = text[: text.index(needle)]
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def test_a_position_after_a_bracket_put_in_is_the_exports():
    text = EXP.read_text().replace("2, 2(5), 9;", "2, 2(5), nine;")
    diags, sources = check_files([], texts={"broken.exp": text})
    [d] = [d for d in diags if d.is_error]
    assert d.code == "E010" and "nine" in d.message
    assert (d.pos.line, d.pos.col) == _position(text, "nine;")
    assert "seq : ARRAY[1..4] OF INT := 2, 2(5), nine;" in d.format(sources)  # the export's line


def test_a_position_after_functionblock_is_the_exports():
    text = EXP.read_text().replace("FUNCTIONBLOCK STEPPER", "FUNCTIONBLOCK STEPPER EXTENDS NOPE")
    diags, _ = check_files([], texts={"broken.exp": text})
    [d] = [d for d in diags if d.is_error]
    assert "NOPE" in d.message and (d.pos.line, d.pos.col) == _position(text, "NOPE")


def test_a_txt_is_read_as_an_export_by_its_markers_only():
    text = EXP.read_text()
    assert values(EXP, 9) == values(EXP, 9, "OSCAT_LIKE.TXT", text)
    # a .txt without the markers is ST as before: FUNCTIONBLOCK is no keyword there
    plain = text.replace("(* @", "(* ")
    diags, _ = check_files([], texts={"notes.txt": plain})
    assert any(d.code == "E001" for d in diags)


def test_a_graphical_body_is_named_and_the_rest_imported():
    text = EXP.read_text().replace(
        "(* @NESTEDCOMMENTS := 'Yes' *)\n(* @PATH := '' *)",
        "(* @NESTEDCOMMENTS := 'Yes' *)\n(* @PATH := '' *)\n(* @OBJECTFLAGS := '0, 8' *)\n"
        "FUNCTION_BLOCK Drawn\nVAR_INPUT x : BOOL; END_VAR\n(* @END_DECLARATION := '0' *)\n"
        "_FBD_BODY\n_NETWORKS : 1\n_NETWORK\n_COMMENT\n''\n_END_COMMENT\nEND_FUNCTION_BLOCK\n\n"
        "(* @NESTEDCOMMENTS := 'Yes' *)\n(* @PATH := '' *)",
        1,
    )
    diags, _ = check_files([], texts={"drawn.exp": text})
    [d] = [d for d in diags if d.is_error]
    assert d.code == "E182" and d.message.startswith("POU Drawn is written in FBD")
    assert (d.pos.line, d.pos.col) == _position(text, "_FBD_BODY")  # the only error: the rest compiles


def test_export_st_writes_what_later_st_reads():
    diags = DiagnosticBag()
    st = st_export("project.EXP", EXP.read_text(), diags)
    assert diags.items == []
    assert "\nFUNCTION_BLOCK STEPPER\n" in st and "\nFUNCTIONBLOCK" not in st
    assert "seq : ARRAY[1..4] OF INT := [2, 2(5), 9];" in st
    assert "NAMES : ARRAY[1..3] OF STRING(10) := ['one', 'two;2',\n" in st and "'three'];" in st
    assert "LIBRARY" not in st and "Standard.lib" not in st
    assert compile_files([], texts={"export.st": st}).runner("Main").ns is not None


def test_the_library_section_is_no_st():
    views = st_views("project.EXP", EXP.read_text(), DiagnosticBag())
    assert "NumOfPOUs" not in views[0].text and "END_LIBRARY" not in views[0].text


_SNIPPETS = ["FUNCTIONBLOCK ", ":= 1, 2", "LIBRARY\n", "END_LIBRARY\n", "'", "(*", "*)", "_FBD_BODY\n", "\r", "["]


@settings(max_examples=60, deadline=None, derandomize=True, database=None)
@given(
    st.lists(
        st.tuples(st.integers(0, 3000), st.integers(0, 40), st.sampled_from(_SNIPPETS + [""])), min_size=1, max_size=4
    )
)
def test_a_mangled_export_gives_coded_diagnostics(edits):
    # cut a piece out here and there, and put in what the importer looks for
    text = EXP.read_text()
    for at, cut, put in edits:
        at %= len(text) + 1
        text = text[:at] + put + text[at + cut :]
    diags, _ = check_files([], texts={"mangled.exp": text})
    assert_well_formed(diags, user_files=("mangled.exp",))
    assert not any(d.code == "E009" for d in diags)
    assert isinstance(st_export("mangled.exp", text, DiagnosticBag()), str)
