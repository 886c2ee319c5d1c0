"""TwinCAT 3 files (runtime/st/importers/twincat.py): a .plcproj with a
POU using methods, a property, an action and an interface, DUTs and a
qualified-only GVL runs as the same code in plain ST; diagnostics point
into the .TcPOU; problems are named."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from softplc.runtime.program import check_files, compile_files
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.importers import st_export, st_views

HERE = Path(__file__).parent
PROJECT = HERE / "twincat" / "Demo.plcproj"
TWIN = [HERE / "twincat_twin" / "GVL.st", HERE / "twincat_twin" / "Demo.st"]
WATCHED = ["fbMotor.stStatus.eState", "fbMotor.stStatus.nStarts", "fbMotor.nRamp", "bStarted", "nRunning", "nCycles"]


def values(paths: list, cycles: int) -> dict:
    r = compile_files([str(p) for p in paths]).runner("MAIN", cycle_time_ms=10)
    r.run(cycles)
    return {v: r.get(v) for v in WATCHED}


@pytest.mark.parametrize("cycles", [2, 5, 8, 12])
def test_the_twincat_project_runs_as_its_plain_st_twin(cycles):
    got = values([PROJECT], cycles)
    assert got == values(TWIN, cycles)
    if cycles == 5:  # started in cycle 2 (the interface's method), ramped 3 cycles
        assert got["fbMotor.stStatus.eState"] == 2 and got["nRunning"] == 1
    if cycles == 12:  # disabled from cycle 8 on: the action Reset stops it, the restart fails
        assert got["fbMotor.stStatus.nStarts"] == 2 and got["nRunning"] == 3 and got["nCycles"] == 12


def _copy_project(tmp_path: Path) -> Path:
    dst = tmp_path / "twincat"
    shutil.copytree(HERE / "twincat", dst)
    return dst


def test_an_error_in_a_method_points_into_the_tcpou(tmp_path):
    dst = _copy_project(tmp_path)
    pou = dst / "POUs" / "FB_Motor.TcPOU"
    text = pou.read_text().replace("stStatus.rSpeed := rSpeed;", "stStatus.rSpeed := rSpeeed;")
    pou.write_text(text)
    diags, sources = check_files([str(dst / "Demo.plcproj")])
    [d] = [d for d in diags if d.is_error]
    before = text[: text.index("rSpeeed")]
    assert d.code == "E010" and d.pos.file == str(pou)
    assert (d.pos.line, d.pos.col) == (before.count("\n") + 1, len(before) - before.rfind("\n"))
    assert "stStatus.rSpeed := rSpeeed;" in d.format(sources)


def test_a_file_the_project_lists_but_lacks_is_named(tmp_path):
    dst = _copy_project(tmp_path)
    (dst / "DUTs" / "ST_Status.TcDUT").unlink()
    diags, _ = check_files([str(dst / "Demo.plcproj")])
    errors = [d for d in diags if d.is_error]
    assert errors[0].code == "E000" and errors[0].pos.file.endswith("ST_Status.TcDUT")


def test_an_implementation_in_another_language_is_named():
    text = (HERE / "twincat" / "POUs" / "MAIN.TcPOU").read_text()
    start, end = text.index("<ST>"), text.index("</ST>") + len("</ST>")
    diags = DiagnosticBag()
    st_views("MAIN.TcPOU", text[:start] + "<FBD />" + text[end:], diags)
    [d] = diags.items
    assert d.code == "E182" and d.message == "POU MAIN is written in FBD: only ST is imported"


def test_a_dtd_in_a_twincat_file_is_refused():
    diags = DiagnosticBag()
    text = (
        '<?xml version="1.0"?>\n<!DOCTYPE x [<!ENTITY e SYSTEM "file:///etc/passwd">]>\n<TcPlcObject>&e;</TcPlcObject>'
    )
    assert st_views("evil.TcPOU", text, diags) == []
    assert [d.code for d in diags.items] == ["E181"]


def test_export_st_of_a_pou_reads_as_twincat_text_export():
    diags = DiagnosticBag()
    st = st_export("FB_Motor.TcPOU", (HERE / "twincat" / "POUs" / "FB_Motor.TcPOU").read_text(), diags)
    assert diags.items == []
    lines = [line for line in st.splitlines() if line and not line.startswith(("\t", " "))]
    assert lines[:3] == ["FUNCTION_BLOCK FB_Motor IMPLEMENTS I_Motor", "VAR_INPUT", "END_VAR"]
    assert "END_FUNCTION_BLOCK" in lines and lines.index("END_FUNCTION_BLOCK") < lines.index("METHOD Start : BOOL")
    assert st.endswith(
        "ACTION FB_Motor.Reset:\nstStatus.eState := E_State.Stopped;\nstStatus.rSpeed := 0;\nnRamp := 0;\nEND_ACTION\n"
    )


def test_the_testing_api_takes_the_twincat_project():
    from softplc.testing import PLC

    with PLC.from_st([str(PROJECT)], cycle="10ms") as plc:
        plc.run_for("120ms")
        assert plc.read("MAIN.nRunning") == 3 and plc.read("MAIN.fbMotor.stStatus.nStarts") == 2


SEMICOLONS = """<?xml version="1.0" encoding="utf-8"?>
<TcPlcObject Version="1.1.0.1">
  <POU Name="FB_Sum" Id="{1}" SpecialFunc="None">
    <Declaration><![CDATA[// TwinCAT takes a ';' after a header
FUNCTION_BLOCK FB_Sum;
VAR
    nTotal : DINT;
END_VAR]]></Declaration>
    <Implementation>
      <ST><![CDATA[nTotal := Add(nTotal, 2);]]></ST>
    </Implementation>
    <Method Name="Add" Id="{2}">
      <Declaration><![CDATA[METHOD PUBLIC Add : DINT; // the sum
VAR_INPUT
    a : DINT;
    b : DINT;
END_VAR]]></Declaration>
      <Implementation>
        <ST><![CDATA[Add := a + b;]]></ST>
      </Implementation>
    </Method>
  </POU>
</TcPlcObject>
"""


def test_a_semicolon_after_a_header_is_taken_as_twincat_takes_it(tmp_path):
    pou = tmp_path / "FB_Sum.TcPOU"
    pou.write_text(SEMICOLONS)
    main = tmp_path / "main.st"
    main.write_text("PROGRAM Main\nVAR fb : FB_Sum; END_VAR\nfb();\nEND_PROGRAM\n")
    r = compile_files([str(pou), str(main)], profile="twincat").runner("Main", cycle_time_ms=10)
    r.run(4)
    assert r.get("fb.nTotal") == 8
    # the column of what follows stays: an error there points at the .TcPOU's own column
    broken = SEMICOLONS.replace("Add := a + b;", "Add := a + c;")
    pou.write_text(broken)
    diags, _ = check_files([str(pou), str(main)], profile="twincat")
    [d] = [d for d in diags if d.is_error]
    line = broken.split("Add := a + c;")[0].count("\n") + 1
    assert (d.code, d.pos.line, d.pos.col) == ("E010", line, len("        <ST><![CDATA[Add := a + ") + 1)


def test_a_declaration_of_blanks_is_named_at_once():
    """Blanks or '//' runs before no keyword: named (E183), not tried every way."""
    for lead in (" " * 5000, "\n" * 5000, "//" * 5000):
        text = SEMICOLONS.replace("// TwinCAT takes a ';' after a header\nFUNCTION_BLOCK FB_Sum;", lead)
        diags = DiagnosticBag()
        st_views("FB_Sum.TcPOU", text, diags)
        assert [d.code for d in diags.items] == ["E183"]
