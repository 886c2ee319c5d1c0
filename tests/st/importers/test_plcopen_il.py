"""IL bodies in PLCopen XML (st/importers/bodies.py puts them into the view,
the parser lowers them: st/syntax/il.py): a Beremiz-style project whose POUs and
action are IL runs as its ST twin; export-st writes the lowered ST, which
runs the same; problems point into the XML."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.faults import STFault
from softplc.runtime.st.importers import st_export, st_views
from softplc.runtime.st.syntax.parser import parse_source

HERE = Path(__file__).parent
XML = HERE / "il_project.xml"
ST = HERE / "il_project.st"
WATCHED = ["n", "t.Total", "t.Full", "full", "rises", "m"]


def values(path: Path, cycles: int, profile: str = "codesys") -> list:
    r = compile_files([str(path)], profile).runner("Main", cycle_time_ms=10)
    rows = []
    for _ in range(cycles):
        r.run(1)
        rows.append({v: r.get(v) for v in WATCHED})
    return rows


@pytest.mark.parametrize("profile", ["codesys", "matiec"])
def test_the_il_project_runs_as_its_st_twin(profile):
    got = values(XML, 15, profile)
    assert got == values(ST, 15, profile)
    # Tally adds n and clears every 7th cycle; Full (>= Limit 12) rises at n = 5, 9, 15
    assert [r["t.Total"] for r in got][:8] == [1, 3, 6, 10, 15, 21, 0, 8]
    assert got[-1]["rises"] == 3 and {r["full"] for r in got} == {True, False}


def test_every_il_body_of_the_xml_is_lowered():
    diags = DiagnosticBag()
    lowered = [r for v in st_views(str(XML), XML.read_text(), diags) for r in parse_source(v.text, "x", diags).lowered]
    assert not diags.items
    assert len(lowered) == 4  # Mean3, Tally, its action Check, Main


def test_export_st_writes_the_lowered_st_which_runs_the_same(tmp_path):
    diags = DiagnosticBag()
    text = st_export(str(XML), XML.read_text(), diags)
    assert not diags.items
    assert "Total := Total + Step;" in text and "IF NOT edge.Q THEN JMP no_rise; END_IF;" in text
    assert "(* clear, or add the step *)" in text
    assert "JMPC" not in text and "\nLD " not in text
    out = tmp_path / "exported.st"
    out.write_text(text)
    assert values(out, 15) == values(XML, 15)


def _position_of(text: str, needle: str) -> tuple:
    before = text[: text.index(needle)]
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def test_a_problem_in_an_il_body_points_into_the_xml(tmp_path):
    text = XML.read_text().replace("ADD Step\n", "ADD Stepp\n").replace("GE Limit\n", "GE\n")
    path = tmp_path / "bad.xml"
    path.write_text(text)
    diags, _ = check_files([str(path)])
    got = sorted((d.code, d.pos.line, d.pos.col) for d in diags if d.is_error)
    assert got == [("E010", *_position_of(text, "Stepp")), ("E191", *_position_of(text, "GE\n"))]


def test_a_division_by_zero_in_il_faults_at_its_line_in_the_xml(tmp_path):
    text = XML.read_text().replace("DIV 3\n", "DIV c\n").replace("Mean3 t.Total, 4", "Mean3 t.Total, 0")
    path = tmp_path / "div.xml"
    path.write_text(text)
    r = compile_files([str(path)]).runner("Main")
    with pytest.raises(STFault) as err:
        r.run(1)
    assert err.value.kind == "division"
    assert (err.value.pos.file, err.value.pos.line) == (str(path), _position_of(text, "DIV c")[0])
