"""PLCopen XML import (runtime/st/importers/plcopen.py): a project exported
as TC6 XML (data types, POUs with actions and CODESYS methods, a GVL, the
configuration) compiles, runs, and gives the values of the same project in
plain ST; diagnostics point into the XML; hostile XML is refused."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.importers import st_export, st_views

HERE = Path(__file__).parent
XML = HERE / "project.xml"
ST = HERE / "project.st"
WATCHED = [
    "c.count",
    "c.mode",
    "t.count",
    "t.doubled",
    "p.x",
    "p.y",
    "origin.x",
    "origin.y",
    "scaled",
    "name",
    "gCycles",
]


def values(path: Path, cycles: int) -> dict:
    r = compile_files([str(path)]).runner("Main", cycle_time_ms=10)
    r.run(cycles)
    return {v: r.get(v) for v in WATCHED}


@pytest.mark.parametrize("cycles", [1, 4, 5, 12])
def test_the_xml_project_runs_as_its_plain_st_twin(cycles):
    got = values(XML, cycles)
    assert got == values(ST, cycles)
    if cycles == 12:
        # c counts 1..5, resets at 5 (action Reset), counts again: 12 = 5 + 5 + 2
        assert (got["c.count"], got["c.mode"], got["gCycles"]) == (2, 1, 12)
        # t (EXTENDS FB_Counter) counts every other cycle; Double() is count * 2
        assert (got["t.count"], got["t.doubled"]) == (1, 2)
        # buf's initial value [1, 2(5), 9]: buf[2] = 5 added each cycle
        assert got["p.x"] == 60 and got["origin.x"] == 7 and got["origin.y"] == 2
        assert got["name"] == "pump & fan"  # &amp; in the attribute


def _xml_with_body(body: str) -> str:
    return XML.read_text().replace("Scale := v * k;", body)


def _position_of(text: str, needle: str) -> tuple:
    before = text[: text.index(needle)]
    return before.count("\n") + 1, len(before) - before.rfind("\n")


def test_an_error_in_a_body_points_into_the_xml(tmp_path):
    text = _xml_with_body("Scale := v * kk;")
    path = tmp_path / "broken.xml"
    path.write_text(text)
    diags, sources = check_files([str(path)])
    [d] = [d for d in diags if d.is_error]
    assert d.code == "E010" and "kk" in d.message
    assert (d.pos.file, d.pos.line, d.pos.col) == (str(path), *_position_of(text, "kk;"))
    assert "<xhtml:p><![CDATA[Scale := v * kk;]]>" in d.format(sources)  # the XML line is shown under the message


def test_an_error_in_a_later_line_of_a_body_keeps_its_column(tmp_path):
    text = XML.read_text().replace("    mode := E_Mode.Run;", "    mode := E_Mode.Running;")
    path = tmp_path / "broken.xml"
    path.write_text(text)
    diags, _ = check_files([str(path)])
    [d] = [d for d in diags if d.is_error]
    assert d.code == "E013" and (d.pos.line, d.pos.col) == _position_of(text, "E_Mode.Running")


def test_lone_carriage_returns_end_lines_as_in_the_xml_parser(tmp_path):
    # A Beremiz file edited on several systems mixes CR LF with lone CRs:
    # expat counts each as a line end, and so does the error's position.
    text = _xml_with_body("Scale := v * kk;").replace("\n", "\r\n")
    head, tail = text.split("<pous>", 1)
    text = head.replace("\r\n", "\r") + "<pous>" + tail
    path = tmp_path / "mixed_line_ends.xml"
    path.write_bytes(text.encode())
    diags, sources = check_files([str(path)])
    [d] = [d for d in diags if d.is_error]
    lines = text.splitlines()
    line = next(i for i, s in enumerate(lines, 1) if "kk;" in s)
    assert d.code == "E010" and (d.pos.line, d.pos.col) == (line, lines[line - 1].index("kk;") + 1)
    assert "Scale := v * kk;" in d.format(sources)


def test_a_pou_in_another_language_is_named_and_the_rest_imported(tmp_path):
    text = XML.read_text().replace(
        "    </pous>",
        """      <pou name="Blinker" pouType="functionBlock">
        <interface />
        <body><CFC /></body>
      </pou>
    </pous>""",
    )
    path = tmp_path / "mixed.xml"
    path.write_text(text)
    diags, _ = check_files([str(path)])
    [d] = [d for d in diags if d.is_error]
    assert d.code == "E182" and d.message == "POU Blinker is written in CFC: only ST bodies are imported"
    assert d.pos.line == _position_of(text, "<body><CFC />")[0]


BILLION_LAUGHS = """<?xml version="1.0"?>
<!DOCTYPE lolz [
 <!ENTITY lol "lol">
 <!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">
 <!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">
]>
<project xmlns="http://www.plcopen.org/xml/tc6_0201">&lol3;</project>
"""
EXTERNAL = """<?xml version="1.0"?>
<!DOCTYPE project [<!ENTITY secret SYSTEM "file:///etc/passwd">]>
<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types>&secret;</types></project>
"""


@pytest.mark.parametrize("text", [BILLION_LAUGHS, EXTERNAL], ids=["billion laughs", "external entity"])
def test_hostile_xml_is_refused_with_a_clear_error(text):
    diags = DiagnosticBag()
    assert st_views("hostile.xml", text, diags) == []
    [d] = diags.items
    assert d.code == "E181" and d.message.startswith("refused XML")
    assert "DTD" in d.hint


def test_malformed_xml_is_an_error_at_its_position():
    diags = DiagnosticBag()
    assert st_views("bad.xml", "<project>\n  <types>\n</project>\n", diags) == []
    [d] = diags.items
    assert d.code == "E180" and "mismatched tag" in d.message and d.pos.line == 3


@pytest.mark.parametrize(
    "attr",
    ['name="x; END_VAR VAR y"', 'name="x(*"', 'name="9lives"'],
)
def test_an_attribute_that_is_no_identifier_becomes_no_st(attr):
    text = XML.read_text().replace('name="scaled"', attr)
    diags = DiagnosticBag()
    views = st_views("inject.xml", text, diags)
    assert [d.code for d in diags.items] == ["E183"] and "is not an ST identifier" in diags.items[0].message
    assert not any("END_VAR VAR y" in v.text for v in views)


def test_an_initial_value_cannot_end_its_declaration():
    text = XML.read_text().replace("value=\"'pump &amp; fan'\"", "value=\"'a'; x : INT := 1\"")
    diags = DiagnosticBag()
    st_views("inject.xml", text, diags)
    assert [d.code for d in diags.items] == ["E183"] and "cannot be an ST value" in diags.items[0].message


def test_export_st_writes_the_project_as_plain_st():
    diags = DiagnosticBag()
    st = st_export(str(XML), XML.read_text(), diags)
    assert diags.items == []
    assert st.startswith("TYPE ST_Point : STRUCT\n    x : INT;\n    y : INT := 2;\nEND_STRUCT;\nEND_TYPE\n")
    assert "FUNCTION_BLOCK FB_Twice EXTENDS FB_Counter" in st and "METHOD Double : INT" in st
    assert "IF enable THEN\n    count := count + 1;\n" in st  # a body keeps its indentation
    assert "\nACTION FB_Counter.Reset:\ncount := 0;\nmode := E_Mode.Idle;\nEND_ACTION\n" in st
    assert st.endswith(
        "TASK MainTask(INTERVAL := T#10ms, PRIORITY := 1);\n"
        "        PROGRAM MainInst WITH MainTask : Main;\n    END_RESOURCE\nEND_CONFIGURATION\n"
    )
    # and it compiles to the same program
    assert compile_files([], texts={"export.st": st}).runner("Main").ns is not None


def test_softplc_export_st_and_check_read_the_xml(tmp_path):
    from tests.test_cli import softplc

    out = tmp_path / "project.st"
    r = softplc("export-st", XML, "-o", out)
    assert r.returncode == 0, r.stderr
    assert f"wrote {out}" in r.stderr and "FUNCTION_BLOCK FB_Counter" in out.read_text()
    r = softplc("check", out)
    assert r.returncode == 0 and "0 errors, 0 warnings" in r.stderr
    broken = tmp_path / "broken.xml"
    broken.write_text(_xml_with_body("Scale := v * kk;"))
    r = softplc("check", broken)
    assert r.returncode == 1 and f"{broken}:{_position_of(broken.read_text(), 'kk;')[0]}:" in r.stderr
    hostile = tmp_path / "hostile.xml"
    hostile.write_text(BILLION_LAUGHS)
    r = softplc("export-st", hostile)
    assert r.returncode == 1 and "E181" in r.stderr and "Traceback" not in r.stderr
