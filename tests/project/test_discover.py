"""Finding a project's files, libraries and tasks (runtime/project/discover.py,
twincat.py, plcopen_project.py): a TwinCAT solution through its system
project and .xti to the PLC project, a CODESYS export, a Beremiz folder, a
plain folder; and the problems of the project files at their lines."""

from __future__ import annotations

import shutil
from pathlib import Path

from softplc.runtime.project import open_projects

HERE = Path(__file__).parent
TWINCAT = HERE / "twincat"
PLC = TWINCAT / "Plant" / "Plc"


def line_of(path: Path, needle: str) -> int:
    """The line of path that holds needle (one-based)."""
    return path.read_text().split(needle)[0].count("\n") + 1


def _copy(tmp_path: Path, name: str) -> Path:
    shutil.copytree(HERE / name, tmp_path / name)
    return tmp_path / name


def test_a_solution_leads_through_the_system_project_to_the_plc_project():
    [p] = open_projects([str(TWINCAT / "Plant.sln")])
    assert (p.kind, p.name, p.profile) == ("twincat", "Plc", "twincat")
    assert [Path(f).relative_to(PLC).as_posix() for f in p.files] == [
        "DUTs/E_TankState.TcDUT",
        "GVLs/GVL_Plant.TcGVL",
        "POUs/FB_Tank.TcPOU",
        "POUs/MAIN.TcPOU",
    ]  # the .TcTTO is a task, the .TcVis a visualisation: neither is compiled
    assert [(r.name, r.namespace) for r in p.libraries] == [
        ("Tc2_Standard", "Tc2_Standard"),
        ("Tc3_JsonXml", "Tc3_JsonXml"),
    ]
    [task] = p.tasks
    assert (task.name, task.interval_ns, task.priority) == ("PlcTask", 10_000_000, 20)
    assert [name for name, _pos in task.programs] == ["MAIN"]
    assert task.programs[0][1].file == str(PLC / "PlcTask.TcTTO")
    assert task.programs[0][1].line == line_of(PLC / "PlcTask.TcTTO", "<Name>MAIN")
    assert not p.diags.items


def test_the_folder_the_tsproj_and_the_plcproj_are_the_same_project():
    expected = open_projects([str(PLC / "Plc.plcproj")])[0].files
    for given in (TWINCAT, TWINCAT / "Plant", TWINCAT / "Plant" / "Plant.tsproj"):
        [p] = open_projects([str(given)])
        assert p.files == expected, given  # _Boot's stale copy of MAIN is not read


def test_a_codesys_export_brings_the_libraries_it_lists():
    [p] = open_projects([str(HERE / "codesys" / "Line.xml")])
    assert (p.kind, p.profile) == ("codesys", "codesys")
    assert [(r.name, r.namespace) for r in p.libraries] == [
        ("Standard", "Standard"),
        ("Util", "Util"),
        ("CAA Types", "CAA"),
    ]
    assert p.libraries[1].pos.line == line_of(HERE / "codesys" / "Line.xml", 'Name="#Util"')


def test_a_beremiz_folder_is_plc_xml_with_its_libraries_and_extensions():
    for given in (HERE / "beremiz", HERE / "beremiz" / "plc.xml"):
        [p] = open_projects([str(given)])
        assert (p.kind, p.profile, p.files) == ("beremiz", "matiec", [str(HERE / "beremiz" / "plc.xml")])
        # beremiz.xml turns the Python library off; Native is on by default
        assert [r.name for r in p.libraries] == ["Native"]
        assert p.extensions == [("py_ext_0", "py_ext")]


def test_a_folder_of_sources_leaves_out_xml_that_is_not_plcopen():
    [p] = open_projects([str(HERE / "folder")])
    assert p.kind == "folder" and [Path(f).name for f in p.files] == ["counter.st", "main.st"]


def test_a_folder_holding_projects_is_each_of_them(tmp_path):
    shutil.copytree(TWINCAT, tmp_path / "twincat")
    shutil.copytree(HERE / "beremiz", tmp_path / "beremiz")
    shutil.copytree(HERE / "folder" / "src", tmp_path / "loose")
    (tmp_path / "tools").mkdir()  # a C# solution beside the PLC code is no project
    (tmp_path / "tools" / "Tool.sln").write_text('Project("{FAE04EC0}") = "Tool", "Tool\\Tool.csproj", "{1}"\n')
    kinds = [(p.kind, p.name, len(p.files)) for p in open_projects([str(tmp_path)])]
    assert kinds == [("twincat", "Plc", 4), ("beremiz", "beremiz", 1), ("folder", tmp_path.name, 2)]


def test_files_given_beside_a_project_are_compiled_with_it(tmp_path):
    extra = tmp_path / "extra.st"
    extra.write_text("PROGRAM Extra\nEND_PROGRAM\n")
    [p] = open_projects([str(PLC / "Plc.plcproj"), str(extra)])
    assert p.files[-1] == str(extra) and len(p.files) == 5


def _codes(project) -> list:
    return [(d.code, Path(d.pos.file).name, d.pos.line) for d in project.diags.items]


def test_a_solution_naming_a_missing_project_is_e220_at_its_line(tmp_path):
    root = _copy(tmp_path, "twincat")
    shutil.rmtree(root / "Plant")
    [p] = open_projects([str(root / "Plant.sln")])
    assert (
        _codes(p) == [("E220", "Plant.sln", line_of(root / "Plant.sln", "Project("))]
        and "Plant\\Plant.tsproj" in p.diags.items[0].message
    )
    (root / "Plant.sln").write_text("Microsoft Visual Studio Solution File, Format Version 12.00\n")
    [p] = open_projects([str(root / "Plant.sln")])
    assert _codes(p) == [("E220", "Plant.sln", 1)] and "names no TwinCAT project" in p.diags.items[0].message


def test_a_missing_xti_and_a_broken_tsproj_are_named(tmp_path):
    root = _copy(tmp_path, "twincat")
    (root / "Plant" / "_Config" / "PLC" / "Plc.xti").unlink()
    [p] = open_projects([str(root / "Plant.sln")])
    assert _codes(p) == [("E220", "Plant.tsproj", line_of(root / "Plant" / "Plant.tsproj", "Plc.xti"))]
    (root / "Plant" / "Plant.tsproj").write_text("<TcSmProject><Project>")
    [p] = open_projects([str(root / "Plant.sln")])
    assert [c for c, _f, _l in _codes(p)] == ["E180"]  # not well-formed XML, at its line


def test_a_file_the_plc_project_lists_but_lacks_is_e221(tmp_path):
    root = _copy(tmp_path, "twincat")
    (root / "Plant" / "Plc" / "POUs" / "FB_Tank.TcPOU").unlink()
    [p] = open_projects([str(root)])
    listed = line_of(root / "Plant" / "Plc" / "Plc.plcproj", "FB_Tank")
    assert _codes(p) == [("E221", "Plc.plcproj", listed)] and len(p.files) == 3


def test_a_task_object_that_cannot_run_is_e222(tmp_path):
    root = _copy(tmp_path, "twincat")
    tto = root / "Plant" / "Plc" / "PlcTask.TcTTO"
    good = tto.read_text()
    tto.write_text(good.replace("<CycleTime>10000</CycleTime>", "<CycleTime>fast</CycleTime>"))
    [p] = open_projects([str(root)])
    assert _codes(p) == [("E222", "PlcTask.TcTTO", line_of(tto, "<CycleTime>"))] and p.tasks == []
    tto.write_text(good.replace("<Name>MAIN</Name>", "<Name>MAIN; x := 1</Name>"))
    [p] = open_projects([str(root)])
    assert _codes(p) == [("E222", "PlcTask.TcTTO", line_of(tto, "<Name>"))] and p.tasks[0].programs == ()


PYFILE = """<?xml version='1.0' encoding='utf-8'?>
<PyFile xmlns:xhtml="http://www.w3.org/1999/xhtml">
  <variables>
    <variable name="Setpoint" type="INT" initial="42"/>
    <variable name="Label" type="STRING" initial="'tank'"/>
    <variable name="Evil" type="INT; END_VAR PROGRAM X" initial="1"/>
    <variable name="Worse" type="INT" initial="1; (* "/>
  </variables>
  <globals>
    <xhtml:p><![CDATA[
def Poll():
    PLCGlobals.Setpoint += 1
]]></xhtml:p>
  </globals>
</PyFile>
"""


def test_the_variables_of_a_beremiz_python_extension_are_global_variables(tmp_path):
    from softplc.runtime.project.analysis import analyse

    folder = _copy(tmp_path, "beremiz")
    pyfile = folder / "py_ext_0@py_ext" / "pyfile.xml"
    pyfile.write_text(PYFILE)
    xml = folder / "plc.xml"
    xml.write_text(
        xml.read_text()
        .replace(
            "<localVars>",
            '<externalVars><variable name="Setpoint"><type><INT/></type></variable></externalVars>\n<localVars>',
            1,
        )
        .replace("toggles := toggles + 1;", "toggles := toggles + Setpoint;")
    )
    [p] = open_projects([str(folder)])
    assert p.files == [str(xml), str(pyfile)]
    # what could end a declaration or open a comment stays out, named at its line
    assert _codes(p) == [("E183", "pyfile.xml", 6), ("E183", "pyfile.xml", 7)]
    analysis = analyse(p)
    assert analysis.clean and [d.code for d in analysis.errors] == ["E183", "E183"]
    # the program adds Setpoint where the project beside it adds 1
    r = analysis.program.runner("blinker", cycle_time_ms=50)
    plain = analyse(open_projects([str(HERE / "beremiz")])[0]).program.runner("blinker", cycle_time_ms=50)
    r.run(21)
    plain.run(21)
    assert plain.get("toggles") > 1 and r.get("toggles") == 42 * plain.get("toggles")
