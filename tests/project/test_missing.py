"""The errors a missing library causes, one line per library
(runtime/project/missing.py): by the table of what vendor libraries
declare, by a qualified name, through a variable or a parameter whose type
is the library's; the rest stay errors of their own."""

from __future__ import annotations

import shutil

from softplc.runtime.project import open_projects
from softplc.runtime.project.analysis import analyse
from softplc.runtime.project.missing import NOT_FOUND, group, group_analysis, vendor_table
from tests.project.builders import BROKEN, HERE, LOGGER, line_of, twincat


def _grouped(root, libraries=()):
    [project] = open_projects([str(root)])
    analysis = analyse(project, subset=False)
    return analysis, *group(analysis.diagnostics, analysis.units, project.libraries, frozenset(libraries))


def test_a_referenced_library_is_one_line_at_its_reference(tmp_path):
    root = twincat(tmp_path, ("FB_Logger", LOGGER), ("FB_Broken", BROKEN))
    analysis, groups, rest = _grouped(root)
    [g] = groups
    d = g.diagnostic()
    plcproj = root / "Plant" / "Plc" / "Plc.plcproj"
    assert (d.code, d.pos.file, d.pos.line) == ("E223", str(plcproj), line_of(plcproj, 'Include="Tc3_JsonXml"'))
    # SJsonValue once as a type, twice through sLine; FB_JsonSaxWriter once
    # as a type, once through fbJson's method call
    assert d.message == "needs Tc3_JsonXml (SJsonValue, FB_JsonSaxWriter: 5 references): not installed"
    assert dict(g.names) == {"SJsonValue": 3, "FB_JsonSaxWriter": 2}
    assert {x.code for x in g.replaced} == {"E012", "E010"}
    # the broken block's own error (a near name is declared) is not the library's
    assert [(x.code, x.message) for x in rest if x.is_error] == [("E010", "unknown name 'nCuont'")]
    assert len(analysis.errors) == len(g.replaced) + 1


def test_a_library_given_to_the_compiler_is_not_missing(tmp_path):
    root = twincat(tmp_path, ("FB_Logger", LOGGER))
    _analysis, groups, rest = _grouped(root, {"Tc3_JsonXml"})
    assert groups == [] and {x.code for x in rest if x.is_error} == {"E010", "E012"}


def test_a_qualified_name_names_its_library_and_the_standard_one_is_there(tmp_path):
    pou = (
        "FUNCTION_BLOCK FB_Files\nVAR\n    tWait : Tc2_Standard.TON;\n    hFile : SysFile.RTS_IEC_HANDLE;\nEND_VAR\n",
        "tWait(IN := TRUE, PT := T#1S);",
    )
    _analysis, [g], rest = _grouped(twincat(tmp_path, ("FB_Files", pou)))
    # SysFile is not referenced by the project: the qualified name says it
    # (its two errors, E019 and E012, are at one place: one reference);
    # softplc ships SysFile (unavailable: no file system), so it says so
    assert g.diagnostic().message.startswith("needs SysFile (RTS_IEC_HANDLE: 1 reference), which softplc ships")
    assert "does not reference it" in g.diagnostic().message
    assert not [x for x in rest if x.is_error]  # Tc2_Standard.TON is softplc's own TON


def test_a_parameter_whose_type_is_missing_is_the_library_s_too(tmp_path):
    """The declaration of sText fails; the call that sets it then says 'has
    no parameter sText': one more reference to the library, not an error."""
    writer = (
        "FUNCTION_BLOCK FB_Writer\nVAR_INPUT\n    sText : SJsonValue;\n    nMode : INT;\nEND_VAR\n",
        "nMode := nMode + 1;",
    )
    user = ("PROGRAM P_Write\nVAR fbW : FB_Writer; END_VAR\n", "fbW(sText := 'abc', nMode := 2);")
    _analysis, [g], rest = _grouped(twincat(tmp_path, ("FB_Writer", writer), ("P_Write", user)))
    assert g.name == "Tc3_JsonXml" and g.names["SJsonValue"] == 2
    assert "E040" in {x.code for x in g.replaced} and not [x for x in rest if x.is_error]


def test_unknown_names_in_a_project_that_lacks_libraries_are_names_not_found(tmp_path):
    user = ("FUNCTION_BLOCK FB_Alarm\nVAR fbRaise : FB_SpecialAlarm; END_VAR\n", "fbRaise(bTrigger := TRUE);")
    _analysis, groups, _rest = _grouped(twincat(tmp_path, ("FB_Alarm", user)))
    [g] = groups
    assert g.name == NOT_FOUND and g.maybe == ("Tc3_JsonXml",)
    assert g.diagnostic().code == "E224"
    # the declaration and the call of the instance whose type is unknown
    assert g.diagnostic().message == "names not found (FB_SpecialAlarm: 2 references), maybe from Tc3_JsonXml"


def test_without_libraries_referenced_an_unknown_name_is_an_error_of_its_own(tmp_path):
    src = tmp_path / "p.st"
    src.write_text("PROGRAM P\nVAR x : INT; END_VAR\nx := y;\nMEMCPY(ADR(x), ADR(x), 2);\nEND_PROGRAM\n")
    _analysis, groups, rest = _grouped(src)
    # MEMCPY is Tc2_System's (which softplc ships, not chosen); y is nobody's
    assert [g.name for g in groups] == ["Tc2_System"]
    assert [x.message for x in rest if x.is_error] == ["unknown name 'y'"]


def test_the_table_of_vendor_libraries_is_well_formed():
    table = vendor_table()
    names = [lib.name for lib in table]
    assert len(names) == len(set(names)) and {"Tc3_JsonXml", "Util", "OSCAT BASIC", "Python"} <= set(names)
    for lib in table:
        assert all(n.replace("_", "a").isalnum() for n in lib.names), lib.name


def test_the_table_offers_the_libraries_of_the_project_s_tool(tmp_path):
    """PID is a function block of Beremiz's additional library and of
    CODESYS's Util: a Beremiz project needs the first."""
    plc = (HERE / "beremiz" / "plc.xml").read_text()
    folder = tmp_path / "beremiz"
    shutil.copytree(HERE / "beremiz", folder)
    (folder / "plc.xml").write_text(plc.replace('<derived name="TON"/>', '<derived name="PID"/>'))
    _analysis, groups, _rest = _grouped_analysis(folder)
    assert [g.name for g in groups] == ["Additional function blocks"]
    (folder / "beremiz.xml").unlink()  # now a PLCopen file of no known tool: any library's
    xml = folder / "plc.xml"
    xml.write_text(
        xml.read_text().replace('companyName="Beremiz" productName="Beremiz"', 'companyName="x" productName="y"')
    )
    _analysis, groups, _rest = _grouped_analysis(xml)
    assert [g.name for g in groups] == ["Util"]


def _grouped_analysis(path):
    [project] = open_projects([str(path)])
    analysis = analyse(project, subset=False)
    return analysis, *group_analysis(analysis)


def test_what_follows_from_a_missing_type_is_the_library_s_too(tmp_path):
    """A FUNCTION's result, a method's inputs, a base block, a property:
    declared with a missing library's types, they fail, and so does each
    use of them; all of it is the library's."""
    text = (
        "FUNCTION F_Text : SJsonValue\n",
        "F_Text := 'x';",
    )
    sender = (
        "FUNCTION_BLOCK FB_Sender\nVAR n : INT; END_VAR\n",
        "n := n + 1;",
    )
    uses = (
        "PROGRAM P_Use\nVAR fb : FB_Sender; s : STRING; END_VAR\n",
        "fb.Send('hello');\nF_Text();",
    )
    root = twincat(tmp_path, ("F_Text", text), ("FB_Sender", sender), ("P_Use", uses))
    pou = root / "Plant" / "Plc" / "POUs" / "FB_Sender.TcPOU"
    method = (
        '    <Method Name="Send" Id="{1}">\n      <Declaration><![CDATA[METHOD Send : BOOL\n'
        "VAR_INPUT\n    sMsg : SJsonValue;\nEND_VAR]]></Declaration>\n"
        "      <Implementation>\n        <ST><![CDATA[Send := TRUE;]]></ST>\n      </Implementation>\n    </Method>\n"
    )
    pou.write_text(pou.read_text().replace("  </POU>", method + "  </POU>"))
    analysis, groups, rest = _grouped(root)
    assert [g.name for g in groups] == ["Tc3_JsonXml"]
    codes = {d.code for d in groups[0].replaced}
    assert {"E012", "E010", "E041"} <= codes  # the type, F_Text := ..., Send('hello')
    assert not [d for d in rest if d.is_error], [d.message for d in rest if d.is_error]


def test_a_pou_of_the_project_that_did_not_import_is_no_library_s(tmp_path):
    """A block in a language the importer does not read is the project's
    own: its uses stay errors, not 'names not found, maybe from Native'."""
    folder = tmp_path / "beremiz"
    shutil.copytree(HERE / "beremiz", folder)
    xml = folder / "plc.xml"
    ghost = (
        '      <pou name="ghost" pouType="functionBlock">\n'
        '        <interface><localVars><variable name="n"><type><INT/></type></variable></localVars></interface>\n'
        "        <body><CFC/></body>\n      </pou>\n"
    )
    text = xml.read_text().replace("    </pous>", ghost + "    </pous>")
    use = '<variable name="g"><type><derived name="ghost"/></type></variable>\n            '
    xml.write_text(text.replace('<variable name="toggles">', use + '<variable name="toggles">'))
    analysis, groups, rest = _grouped_analysis(folder)
    assert groups == [] and analysis.lost == {str(xml): [("ghost", line_of(xml, 'pou name="ghost"'))]}
    assert [d.message for d in rest if d.is_error and d.code == "E012"] == ["unknown type 'ghost'"]


def test_a_library_softplc_ships_but_the_program_did_not_choose_says_how_to_choose_it(tmp_path):
    (tmp_path / "tests.st").write_text(
        "FUNCTION_BLOCK FB_T EXTENDS TcUnit.FB_TestSuite\nTEST('t');\nTEST_FINISHED();\nEND_FUNCTION_BLOCK\n"
    )
    [project] = open_projects([str(tmp_path / "tests.st")])
    analysis = analyse(project, subset=False)
    [g], _rest = group_analysis(analysis, frozenset())
    d = g.diagnostic()
    assert d.message.startswith("needs TcUnit (") and "which softplc ships: not chosen" in d.message
    assert d.hint.startswith('add it: [plc] libraries = ["TcUnit"] or --library TcUnit')
