"""Projects that reference libraries softplc ships get them without being
told: a CODESYS export whose libraries name Standard, Util and CAA Types,
and a TwinCAT project with a PlaceholderReference to Tc2_EtherCAT. Each
runs as the same logic written in ST and compiled with the libraries
chosen by hand."""

from __future__ import annotations

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.program.shipped import shipped_named
from softplc.runtime.project import open_projects
from softplc.runtime.project.analysis import analyse
from tests.project.builders import twincat

# PLC_PRG of the CODESYS export and of its ST twin: CODESYS names throughout
DECLS = """blink : Util.BLINK; scale : Util.LIN_TRAFO; count : Standard.CTU; size : CAA.SIZE;
    level : REAL; lamp : BOOL; flashes : WORD; bytes : CAA.SIZE; n : INT;"""
BODY = """n := n + 1;
blink(ENABLE := TRUE, TIMELOW := T#40ms, TIMEHIGH := T#20ms);
lamp := blink.OUT;
count(CU := blink.OUT, RESET := n = 50, PV := 3);
flashes := count.CV;
scale(IN := INT_TO_REAL(n), IN_MIN := 0, IN_MAX := 200, OUT_MIN := 4, OUT_MAX := 20);
level := scale.OUT;
bytes := SIZEOF(size);"""

EXPORT = """<?xml version="1.0" encoding="utf-8"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0200">
  <fileHeader companyName="" productName="CODESYS" productVersion="CODESYS V3.5 SP19"
              creationDateTime="2026-11-28T10:00:00" />
  <contentHeader name="Lamp.project" modificationDateTime="2026-11-28T10:00:00">
    <coordinateInfo>
      <fbd><scaling x="1" y="1" /></fbd><ld><scaling x="1" y="1" /></ld><sfc><scaling x="1" y="1" /></sfc>
    </coordinateInfo>
  </contentHeader>
  <types>
    <dataTypes />
    <pous>
      <pou name="PLC_PRG" pouType="program">
        <interface>
          <localVars>
            <variable name="blink"><type><derived name="Util.BLINK" /></type></variable>
            <variable name="scale"><type><derived name="Util.LIN_TRAFO" /></type></variable>
            <variable name="count"><type><derived name="Standard.CTU" /></type></variable>
            <variable name="size"><type><derived name="CAA.SIZE" /></type></variable>
            <variable name="level"><type><REAL /></type></variable>
            <variable name="lamp"><type><BOOL /></type></variable>
            <variable name="flashes"><type><WORD /></type></variable>
            <variable name="bytes"><type><derived name="CAA.SIZE" /></type></variable>
            <variable name="n"><type><INT /></type></variable>
          </localVars>
        </interface>
        <body>
          <ST>
            <xhtml xmlns="http://www.w3.org/1999/xhtml">BODY</xhtml>
          </ST>
        </body>
      </pou>
    </pous>
  </types>
  <instances>
    <configurations>
      <configuration name="Device">
        <resource name="Application">
          <task name="MainTask" interval="T#20ms" priority="1">
            <pouInstance name="PLC_PRG" typeName="PLC_PRG" />
          </task>
        </resource>
      </configuration>
    </configurations>
  </instances>
  <addData>
    <data name="http://www.3s-software.com/plcopenxml/libraries" handleUnknown="implementation">
      <Libraries>
        <Library Name="#Standard" Namespace="Standard" SystemLibrary="false" DefaultResolution="Standard, * (System)" />
        <Library Name="#Util" Namespace="Util" SystemLibrary="false" DefaultResolution="Util, * (System)" />
        <Library Name="#CAA Types" Namespace="CAA" SystemLibrary="true"
                 DefaultResolution="CAA Types, * (CAA Technical Workgroup)" />
      </Libraries>
    </data>
  </addData>
</project>
"""


def test_a_codesys_export_gets_standard_util_and_caa_types_and_runs_as_its_st_twin(tmp_path):
    export = tmp_path / "Lamp.xml"
    export.write_text(EXPORT.replace("BODY", BODY.replace("<", "&lt;").replace(">", "&gt;")))
    [project] = open_projects([str(export)])
    analysis = analyse(project)
    assert [d for d in analysis.diagnostics if d.is_error] == []
    assert {lib.namespace for lib in analysis.libraries} >= {"Standard", "Util", "CAA Types"}
    twin = compile_files(
        [],
        texts={"twin.st": f"PROGRAM PLC_PRG\nVAR\n{DECLS}\nEND_VAR\n{BODY}\nEND_PROGRAM\n"},
        libraries=[shipped_named(n) for n in ("Standard", "Util", "CAA Types")],
    )
    a, b = analysis.program.runner("PLC_PRG", cycle_time_ms=20), twin.runner("PLC_PRG", cycle_time_ms=20)
    seen = []
    for _ in range(60):
        a.run(1)
        b.run(1)
        seen.append(a.get("lamp"))
        for var in ("lamp", "flashes", "level", "bytes"):
            assert a.get(var) == b.get(var), var
    # BLINK: 40 ms low, 20 ms high at 20 ms a cycle; CTU counts the flashes until its RESET
    assert seen[:6] == [False, False, True, False, False, True]
    # after the RESET of cycle 50: the flashes of cycles 51, 54, 57 and 60
    assert a.get("bytes") == 8 and a.get("flashes") == 4 and a.get("level") == pytest.approx(4.0 + 16.0 * 60 / 200)


ECDIAG = (
    """PROGRAM DIAG
VAR
    fbStates : FB_EcGetAllSlaveStates;
    astStates : ARRAY[0..9] OF ST_EcSlaveState;
    bFailed : BOOL;
    nErrId : UDINT;
    nFailures : INT;
    bExecute : BOOL;
END_VAR
""",
    """bExecute := NOT bExecute;
fbStates(sNetId := '', pStateBuf := ADR(astStates), cbBufLen := SIZEOF(astStates), bExecute := bExecute);
IF NOT fbStates.bBusy AND fbStates.bError AND bExecute THEN
    bFailed := TRUE;
    nErrId := fbStates.nErrId;
    nFailures := nFailures + 1;
END_IF""",
)


def test_a_twincat_project_referencing_tc2_ethercat_compiles_and_its_error_handling_runs(tmp_path):
    root = twincat(tmp_path, ("DIAG", ECDIAG))
    plcproj = root / "Plant" / "Plc" / "Plc.plcproj"
    reference = (
        '    <PlaceholderReference Include="Tc2_EtherCAT">\n'
        "      <DefaultResolution>Tc2_EtherCAT, * (Beckhoff Automation GmbH)</DefaultResolution>\n"
        "      <Namespace>Tc2_EtherCAT</Namespace>\n    </PlaceholderReference>\n"
    )
    plcproj.write_text(
        plcproj.read_text().replace("  </ItemGroup>\n</Project>", reference + "  </ItemGroup>\n</Project>")
    )
    [project] = open_projects([str(root)])
    analysis = analyse(project)
    units = {u.name: analysis.compiled(u) for u in analysis.units.all if u.is_pou}
    assert units["DIAG"] is True
    warned = [d for d in analysis.diagnostics if d.code == "W230"]
    assert len(warned) == 1 and warned[0].message.startswith("Tc2_EtherCAT is declared but not available here")
    r = analysis.program.runner("DIAG", cycle_time_ms=10)
    r.run(6)
    # each rising edge of bExecute fails at once: ADSERR_DEVICE_SRVNOTSUPP
    assert (r.get("bFailed"), r.get("nErrId"), r.get("nFailures")) == (True, 0x701, 3)
