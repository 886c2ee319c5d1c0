"""`softplc check`, `exec`, `run` and `export-st` on projects
(runtime/cli_project.py): a TwinCAT solution, a CODESYS export, a Beremiz
folder, a folder; the table, the line per missing library, the part that
compiles, the project's own tasks."""

from __future__ import annotations

import json
import re
import shutil

import pytest

from tests.project.builders import BROKEN, HERE, LOGGER, USES_BROKEN, line_of, twincat
from tests.test_cli import no_traceback, softplc

SYNTAX = ("FUNCTION_BLOCK FB_Syntax\nVAR nCount : INT; END_VAR\n", "nCount := ;")


def _table(stderr: str) -> dict:
    """label -> the cells of its row in a check's table."""
    lines = stderr[stderr.index("file / POU") :].splitlines()[1:]
    return {line.split()[0]: line.split()[1:] for line in lines if not line.startswith(("total:", "most frequent"))}


def test_check_of_a_twincat_solution_prints_the_table_and_one_line_per_library(tmp_path):
    root = twincat(tmp_path, ("FB_Logger", LOGGER), ("FB_Broken", BROKEN), ("FB_UsesBroken", USES_BROKEN))
    r = softplc("check", root / "Plant.sln")
    no_traceback(r)
    assert r.returncode == 1
    plcproj = root / "Plant" / "Plc" / "Plc.plcproj"
    assert r.stderr.startswith("TwinCAT PLC project Plc: 7 source files\n")
    at = line_of(plcproj, 'Include="Tc3_JsonXml"')
    assert (
        f"{plcproj}:{at}:5: error E223: needs Tc3_JsonXml (SJsonValue, FB_JsonSaxWriter: 5 references): not installed"
    ) in r.stderr
    assert "unknown type 'FB_JsonSaxWriter'" not in r.stderr and "error E012" not in r.stderr
    assert "error E010: unknown name 'nCuont'" in r.stderr  # the broken block's own error
    rows = _table(r.stderr)
    assert rows["POUs/FB_Tank.TcPOU"] == ["yes", "0", "0", "0"]
    assert rows["POUs/MAIN.TcPOU"] == ["yes", "0", "0", "0"]
    assert rows["POUs/FB_Logger.TcPOU"] == ["no", "0", "5", "0", "needs", "Tc3_JsonXml"]
    assert rows["POUs/FB_Broken.TcPOU"] == ["no", "1", "0", "0"]
    assert rows["POUs/FB_UsesBroken.TcPOU"] == [
        "no",
        "0",
        "0",
        "0",
        "uses",
        "FB_Broken,",
        "which",
        "does",
        "not",
        "compile",
    ]
    assert "total: 7 files, 5 POUs, 2 compiled (40 %); 1 error, 5 from 1 missing library; 0 warnings" in r.stderr
    assert "profile: twincat (the project's)\n1 error, 5 more from 1 missing library, 0 warnings\n" in r.stderr


def test_a_pou_that_does_not_become_st_is_a_row_of_its_own(tmp_path):
    root = twincat(tmp_path, ("FB_Bad", ("FUNCTION_BLOCK FB_Bad\n", "")))
    bad = root / "Plant" / "Plc" / "POUs" / "FB_Bad.TcPOU"
    bad.write_text(bad.read_text().replace("</Implementation>", ""))  # not well-formed any more
    r = softplc("check", root)
    rows = _table(r.stderr)
    assert rows["POUs/FB_Bad.TcPOU"] == ["0/1", "1", "0", "0"]
    assert rows["FB_Bad"] == ["no", "1", "0", "0", "not", "imported"]
    assert "total: 5 files, 3 POUs, 2 compiled (67 %); 1 error; 0 warnings" in r.stderr


def test_check_all_errors_shows_each_use_of_the_missing_library(tmp_path):
    root = twincat(tmp_path, ("FB_Logger", LOGGER))
    r = softplc("check", "--all-errors", root)
    assert r.returncode == 1 and "E223" not in r.stderr
    assert "error E012: unknown type 'FB_JsonSaxWriter'" in r.stderr and "unknown type 'SJsonValue'" in r.stderr
    assert "\n5 errors, 0 warnings\n" in r.stderr


@pytest.mark.parametrize(
    ("given", "head", "profile"),
    [
        ("twincat", "TwinCAT PLC project Plc: 4 source files", "profile: twincat (the project's)"),
        ("codesys/Line.xml", "CODESYS export Line: 1 source file", "profile: codesys"),
        ("beremiz", "Beremiz project beremiz: 1 source file", "profile: matiec (the project's)"),
        ("folder", "folder folder: 2 source files", "profile: codesys"),
    ],
)
def test_check_of_each_kind_of_project(given, head, profile):
    r = softplc("check", HERE / given)
    assert r.returncode == 0, r.stderr
    assert r.stderr.startswith(head + "\n") and f"\n{profile}\n0 errors, 0 warnings" in r.stderr
    assert "total:" in r.stderr and "(100 %)" in r.stderr


def test_a_beremiz_project_names_the_extensions_softplc_does_not_run():
    r = softplc("check", HERE / "beremiz")
    assert "extensions softplc does not run: py_ext_0 (py_ext)" in r.stderr


def test_a_profile_given_overrides_the_project_s(tmp_path):
    r = softplc("check", "--profile", "iec", HERE / "twincat")
    assert "profile: iec\n" in r.stderr


def test_check_of_an_empty_folder_and_a_folder_without_sources_is_a_usage_error(tmp_path):
    (tmp_path / "notes.xml").write_text("<notes/>")
    r = softplc("check", tmp_path)
    assert r.returncode == 2 and "no ST sources" in r.stderr


# ---------------------------------------------------------------- exec


def test_exec_of_a_project_runs_the_program_its_task_calls(tmp_path):
    r = softplc("exec", HERE / "codesys" / "Line.xml", "--cycles", "7")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["cycles"] == 7
    root = twincat(tmp_path, ("P_Other", ("PROGRAM P_Other\nVAR n : INT; END_VAR\n", "n := n + 1;")))
    r = softplc("exec", root, "--cycles", "3")  # two PROGRAMs: the .TcTTO calls MAIN
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["nCycles"] == 3


def test_exec_of_a_project_with_errors_runs_its_part_that_compiles_with_partial(tmp_path):
    root = twincat(tmp_path, ("FB_Logger", LOGGER), ("FB_Broken", BROKEN))
    r = softplc("exec", root, "--cycles", "3")
    assert r.returncode == 1 and "hint: --partial runs the part of the project that compiles" in r.stderr
    r = softplc("exec", root, "--cycles", "3", "--partial")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["nCycles"] == 3
    assert "left out, they do not compile (softplc check lists why): FB_Logger, FB_Broken" in r.stderr


def test_exec_takes_one_project(tmp_path):
    r = softplc("exec", HERE / "folder", HERE / "beremiz")
    assert r.returncode == 2 and "exec runs one project; these are 2" in r.stderr


# ---------------------------------------------------------------- run


def _scans(stderr: str) -> int:
    return int(re.search(r"stopped after (\d+) scans", stderr).group(1))


def test_run_of_a_twincat_project_takes_the_cycle_time_of_its_task(tmp_path):
    r = softplc("run", HERE / "twincat", "--virtual-time", "--duration", "1s", "--final-json", "-")
    assert r.returncode == 0, r.stderr
    assert "task PlcTask: every 10 ms, priority 20" in r.stderr
    assert json.loads(r.stdout)["MAIN"]["nCycles"] == _scans(r.stderr) == 100
    root = tmp_path / "twincat"
    shutil.copytree(HERE / "twincat", root)
    tto = root / "Plant" / "Plc" / "PlcTask.TcTTO"
    tto.write_text(tto.read_text().replace("<CycleTime>10000</CycleTime>", "<CycleTime>25000</CycleTime>"))
    r = softplc("run", root / "Plant.sln", "--virtual-time", "--duration", "1s", "--final-json", "-")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["MAIN"]["nCycles"] == _scans(r.stderr) == 40


@pytest.mark.parametrize(
    ("given", "program", "period_ms"),
    [("codesys/Line.xml", "PLC_PRG", 20), ("beremiz", "blink", 50), ("folder", "Main", 10)],
)
def test_run_of_a_project_takes_the_tasks_of_its_configuration(given, program, period_ms):
    r = softplc("run", HERE / given, "--virtual-time", "--duration", "1s", "--final-json", "-")
    assert r.returncode == 0, r.stderr
    assert _scans(r.stderr) == 1000 // period_ms
    assert program in json.loads(r.stdout)


def test_run_partial_leaves_out_what_does_not_compile(tmp_path):
    root = twincat(tmp_path, ("FB_Logger", LOGGER))
    r = softplc("run", root, "--virtual-time", "--cycles", "5")
    assert r.returncode == 1 and "E223" in r.stderr
    r = softplc("run", root, "--virtual-time", "--cycles", "5", "--partial", "--final-json", "-")
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["MAIN"]["nCycles"] == 5


def test_run_of_a_task_calling_no_program_that_compiled_is_a_usage_error(tmp_path):
    root = twincat(tmp_path)
    main = root / "Plant" / "Plc" / "POUs" / "MAIN.TcPOU"
    main.write_text(main.read_text().replace("nCycles := nCycles + 1;", "nCycles := nCycles + nMissing;"))
    r = softplc("run", root, "--virtual-time", "--cycles", "5", "--partial")
    no_traceback(r)
    assert r.returncode == 2 and "the project's tasks call MAIN: no PROGRAM that compiled" in r.stderr


# ---------------------------------------------------------------- export-st


def test_export_st_writes_what_imports_and_lists_the_rest(tmp_path):
    root = twincat(tmp_path, ("FB_Syntax", SYNTAX), ("FB_Logger", LOGGER))
    out = tmp_path / "plant.st"
    r = softplc("export-st", root, "-o", out)
    no_traceback(r)
    assert r.returncode == 1  # something did not import
    assert "not exported from POUs/FB_Syntax.TcPOU: FB_Syntax" in r.stderr and "error E001" in r.stderr
    st = out.read_text()
    assert "FB_Syntax" not in st and "FUNCTION_BLOCK FB_Tank" in st and "PROGRAM MAIN" in st
    assert "(* not compiled by softplc: needs Tc3_JsonXml *)\nFUNCTION_BLOCK FB_Logger" in st
    assert "CONFIGURATION Plc\n" in st and "TASK PlcTask (INTERVAL := T#10ms, PRIORITY := 20);" in st
    # one file holds the list GVL_Plant, which MAIN names as GVL_Plant.x: say so
    assert "note: the global variable lists of GVLs/GVL_Plant.TcGVL are named by their files" in r.stderr


def test_the_export_to_a_folder_runs_as_the_project_does(tmp_path):
    root = twincat(tmp_path, ("FB_Syntax", SYNTAX), ("FB_Logger", LOGGER))
    out = tmp_path / "st"
    r = softplc("export-st", root, "-o", f"{out}/")
    assert r.returncode == 1 and not (out / "POUs" / "FB_Syntax.st").exists()
    (out / "POUs" / "FB_Logger.st").unlink()  # it needs Tc3_JsonXml
    a = softplc("run", HERE / "twincat", "--virtual-time", "--duration", "1s", "--final-json", "-")
    b = softplc("run", out, "--virtual-time", "--duration", "1s", "--final-json", "-")
    assert a.returncode == b.returncode == 0, b.stderr
    assert json.loads(a.stdout)["MAIN"] == json.loads(b.stdout)["MAIN"]
    assert _scans(a.stderr) == _scans(b.stderr) == 100  # the task came along as a CONFIGURATION


def test_export_st_to_a_folder_writes_one_file_per_source(tmp_path):
    out = tmp_path / "st"
    r = softplc("export-st", HERE / "twincat", "-o", f"{out}/")
    assert r.returncode == 0, r.stderr
    written = sorted(p.relative_to(out).as_posix() for p in out.rglob("*.st"))
    assert written == ["DUTs/E_TankState.st", "GVLs/GVL_Plant.st", "POUs/FB_Tank.st", "POUs/MAIN.st", "Plc_tasks.st"]
    r = softplc("check", out)
    assert r.returncode == 0 and "0 errors, 0 warnings" in r.stderr


def test_export_st_of_several_sources_marks_each(tmp_path):
    r = softplc("export-st", HERE / "folder" / "src" / "counter.st", HERE / "beremiz")
    assert r.returncode == 0, r.stderr
    # the file given beside the Beremiz project is exported with it, after its own
    assert r.stdout.startswith("(* from plc.xml *)\nPROGRAM blinker\n")
    assert "counter.st *)\nFUNCTION_BLOCK Counter" in r.stdout


def test_a_label_cannot_end_the_comment_it_is_written_in(tmp_path):
    odd = tmp_path / "a*)b(*c.st"
    odd.write_text("PROGRAM P\nEND_PROGRAM\n")
    other = tmp_path / "other.st"
    other.write_text("PROGRAM Q\nEND_PROGRAM\n")
    r = softplc("export-st", odd, other)
    assert r.returncode == 0, r.stderr
    assert "(* from a__b__c.st *)" in r.stdout


def test_no_traceback_on_broken_project_files(tmp_path):
    root = tmp_path / "p"
    root.mkdir()
    (root / "x.sln").write_text('Project("{1}") = "x", "x\\x.tsproj", "{2}"\n')
    (root / "x").mkdir()
    (root / "x" / "x.tsproj").write_text(
        "<TcSmProject><Project><Plc><Project File='x.xti'/></Plc></Project></TcSmProject>"
    )
    for command in (["check"], ["exec"], ["export-st"], ["run", "--virtual-time", "--cycles", "1"]):
        r = softplc(*command, root)
        no_traceback(r)
        assert r.returncode in (1, 2) and "E220" in r.stderr + "no ST sources", (command, r.stderr)


def test_an_importer_that_fails_on_a_file_loses_no_project(tmp_path):
    """A string whose length is a constant of a list (CODESYS writes
    length="GVL.LEN"): whatever the importer makes of it, the project is
    checked and exported, and nothing ends in exit 4."""
    xml = (HERE / "codesys" / "Line.xml").read_text()
    xml = xml.replace(
        '<variable name="pulse"><type><BOOL /></type></variable>',
        (
            '<variable name="pulse"><type><BOOL /></type></variable>\n'
            '            <variable name="topic"><type><string length="GVL.TOPIC_LEN" /></type></variable>'
        ),
    )
    odd = tmp_path / "Line.xml"
    odd.write_text(xml)
    for command in (["check"], ["export-st", "-o", f"{tmp_path}/out/"], ["exec", "--partial"]):
        r = softplc(*command, odd)
        no_traceback(r)
        assert r.returncode in (0, 1, 2) and "internal error: ValueError" not in r.stderr, (command, r.stderr)


def test_a_task_calling_what_is_no_program_is_e222_at_its_line(tmp_path):
    root = tmp_path / "twincat"
    shutil.copytree(HERE / "twincat", root)
    tto = root / "Plant" / "Plc" / "PlcTask.TcTTO"
    tto.write_text(tto.read_text().replace("<Name>MAIN</Name>", "<Name>FB_Tank</Name>"))
    r = softplc("check", root)
    at = line_of(tto, "<Name>FB_Tank")
    assert r.returncode == 1
    assert f"{tto}:{at}:7: error E222: task PlcTask calls FB_Tank, which is a FUNCTION_BLOCK" in r.stderr
    r = softplc("run", root, "--virtual-time", "--cycles", "1")
    assert r.returncode == 1 and "E222" in r.stderr
