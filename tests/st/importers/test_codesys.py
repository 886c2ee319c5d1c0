"""A CODESYS V3 PLCopen XML export (runtime/st/importers/plcopen.py and
codesys.py): codesys/project.xml is written the way CODESYS writes one,
with EXTENDS/IMPLEMENTS in the interface's addData, an INTERFACE in the
project's addData, methods (of a program too), a property, FB_init inputs
(named and positional), a named qualified_only GVL split by its
mixedattrsvarlist, constants as array bounds and string lengths, XSD task
intervals, the application's POUs in the resource's addData, the device
tree as discard data and typeName="" instances. It runs in virtual time
as codesys_twin/ (the same project in plain ST) does."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from softplc.runtime.program import check_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.importers import st_export
from softplc.runtime.st.importers.plcopen import LibraryRef, plcopen_libraries
from softplc.testing import PLC

HERE = Path(__file__).parent
XML = HERE / "codesys" / "project.xml"
TWIN = [HERE / "codesys_twin" / "GVL_Cfg.st", HERE / "codesys_twin" / "project.st"]
WATCHED = [
    "PRG_Main.fbA.nTotal",
    "PRG_Main.fbA.doubled",
    "PRG_Main.fbA.state",
    "PRG_Main.fbB.nTotal",
    "PRG_Main.fbC.nTotal",
    "PRG_Main.sum",
    "PRG_Main.win",
    "PRG_Main.sample",
    "PRG_Main.label",
    "PRG_Main.url",
    "PRG_Slow.ticks",
    "PRG_Slow.last",
    "GVL_Cfg.gTicks",
    "GVL_Cfg.gUrl",
]


def values(sources: list, duration: str) -> dict:
    with PLC.from_st(sources) as plc:
        plc.run_for(duration)
        return {path: plc[path] for path in WATCHED}


@pytest.mark.parametrize("duration", ["30ms", "200ms", "1s"])
def test_the_codesys_export_runs_as_its_plain_st_twin(duration):
    got = values([XML], duration)
    assert got == values(TWIN, duration)
    if duration == "1s":
        # MainTask (PT0.01S) ran 100 times, SlowTask (PT0.05S) 20 times
        assert got["GVL_Cfg.gTicks"] == 100 and got["PRG_Slow.ticks"] == 20
        # FB_init: fbB started at 100 (a positional input), fbC at 20 (positional, FB_init inherited)
        assert got["PRG_Main.fbB.nTotal"] == 250 and got["PRG_Main.fbC.nTotal"] == 753
        assert got["PRG_Main.win"] == [26, 27, 28, 29]  # ARRAY[0..GVL_Cfg.N - 1], 100 cycles over 4
        assert got["PRG_Main.sample"]["id"] == 12 and got["PRG_Main.sample"]["label"] == "none"  # ST_Base's member
        assert got["PRG_Main.url"] == "http://x//y" and got["GVL_Cfg.gUrl"] == "http://plc.local//x"


@pytest.mark.parametrize("layout", ["CRLF and a BOM", "no line breaks between tags"])
def test_the_same_export_laid_out_otherwise_runs_the_same(layout, tmp_path):
    text = XML.read_text()
    if layout == "CRLF and a BOM":
        data = ("\ufeff" + text.replace("\n", "\r\n")).encode()
    else:  # what shares a line is written in the order of the file
        data = re.sub(r">\s+<", "><", text).encode()
    path = tmp_path / "project.xml"
    path.write_bytes(data)
    diags, _ = check_files([str(path)])
    assert diags == []
    assert values([path], "200ms") == values([XML], "200ms")


def test_the_export_imports_without_a_diagnostic():
    diags, _ = check_files([str(XML)])
    assert [(d.code, d.message) for d in diags] == []


def test_export_st_is_the_same_program(tmp_path):
    diags = DiagnosticBag()
    st = st_export(str(XML), XML.read_text(), diags)
    assert diags.items == []
    assert "FUNCTION_BLOCK FB_Derived EXTENDS FB_Base IMPLEMENTS I_Counter" in st
    assert "INTERFACE I_Counter\nMETHOD Step : INT\n" in st and "METHOD PROTECTED Bump" in st
    assert "{attribute 'qualified_only'} {attribute 'gvl_name' := 'GVL_Cfg'}\nVAR_GLOBAL CONSTANT\n" in st
    assert "    fbB : FB_Base(nStart_in := 100);\n" in st
    assert "PROGRAM PRG_Main WITH MainTask : PRG_Main;" in st and "LocalBus" not in st
    exported = tmp_path / "export.st"
    exported.write_text(st)
    assert values([exported], "1s") == values([XML], "1s")


def test_the_libraries_it_references():
    assert plcopen_libraries(XML.read_text()) == [
        LibraryRef("Standard, 3.5.18.0 (System)", "Standard", "Standard"),
        LibraryRef("Util", "Util", "Util"),
        LibraryRef("NETWORK, 1.3.5.3 (OSCAT)", "OSCAT_NETWORK", ""),
    ]
    assert plcopen_libraries("<project") == [] and plcopen_libraries("<other/>") == []


def test_an_error_in_a_method_of_the_resource_points_into_the_xml():
    text = XML.read_text().replace("last := GVL_Cfg.gTicks;", "last := GVL_Cfg.gTick;")
    diags, sources = check_files([], texts={"p.xml": text})
    [d] = diags
    before = text[: text.index("gTick;")]
    assert d.code == "E019" and "gTick" in d.message
    assert (d.pos.file, d.pos.line, d.pos.col) == (
        "p.xml",
        before.count("\n") + 1,
        len(before) - before.rfind("\n") - 8,
    )
    assert "last := GVL_Cfg.gTick;" in d.format(sources)
