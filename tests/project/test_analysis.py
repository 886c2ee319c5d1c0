"""The part of a project that compiles (runtime/project/analysis.py): a POU
with an error, one that needs a missing library and one that uses a broken
one do not compile; their neighbours do, and the part that compiles runs
as the whole project runs without them."""

from __future__ import annotations

import pytest

from softplc.runtime.program import compile_files
from softplc.runtime.project import open_projects
from softplc.runtime.project.analysis import analyse
from tests.project.builders import BROKEN, HERE, LOGGER, USES_BROKEN, twincat


def _compiled(analysis) -> dict:
    return {u.name: analysis.compiled(u) for u in analysis.units.all if u.is_pou}


@pytest.fixture
def mixed(tmp_path):
    root = twincat(tmp_path, ("FB_Logger", LOGGER), ("FB_Broken", BROKEN), ("FB_UsesBroken", USES_BROKEN))
    [project] = open_projects([str(root)])
    return analyse(project)


def test_the_broken_the_library_user_and_their_user_are_left_out(mixed):
    assert mixed.errors and mixed.clean
    assert _compiled(mixed) == {
        "FB_Tank": True,
        "MAIN": True,
        "FB_Logger": False,  # SJsonValue, FB_JsonSaxWriter: Tc3_JsonXml
        "FB_Broken": False,  # nStep is declared nowhere
        "FB_UsesBroken": False,  # no error of its own: it uses FB_Broken
    }
    [uses] = [u for u in mixed.units.all if u.name == "FB_UsesBroken"]
    assert mixed.because[uses.id] == "FB_Broken"


def test_the_part_that_compiles_runs_as_the_project_without_the_rest(mixed):
    plc = HERE / "twincat" / "Plant" / "Plc"
    alone = compile_files(
        [
            str(plc / f)
            for f in ("DUTs/E_TankState.TcDUT", "GVLs/GVL_Plant.TcGVL", "POUs/FB_Tank.TcPOU", "POUs/MAIN.TcPOU")
        ]
    )
    a, b = mixed.program.runner("MAIN", cycle_time_ms=10), alone.runner("MAIN", cycle_time_ms=10)
    a.run(57)
    b.run(57)
    for var in ("nCycles", "rLeft", "fbTank.rLevel", "fbTank.eState"):
        assert a.get(var) == b.get(var), var


def test_a_project_without_errors_compiles_in_one_check():
    [project] = open_projects([str(HERE / "twincat")])
    analysis = analyse(project)
    assert analysis.clean and analysis.rounds == 0 and not analysis.dropped
    assert set(analysis.program.pous) == {"FB_Tank", "MAIN"}


def test_a_global_variable_of_a_missing_type_leaves_out_its_users_only(tmp_path):
    """A GVL is split by variable: one of a missing type takes the POUs
    that use it along, not the POUs that use the list's other variables."""
    root = twincat(
        tmp_path,
        ("FB_Clock", ("FUNCTION_BLOCK FB_Clock\nVAR nTicks : UDINT; END_VAR\n", "nTicks := GVL_Time.nNow;")),
    )
    gvl = root / "Plant" / "Plc" / "GVLs" / "GVL_Time.TcGVL"
    gvl.write_text(
        (root / "Plant" / "Plc" / "GVLs" / "GVL_Plant.TcGVL")
        .read_text()
        .replace("GVL_Plant", "GVL_Time")
        .replace("bAuto : BOOL := TRUE;\n    rCapacity : REAL := 100.0;", "nNow : UDINT;\n    stSys : T_SystemInfo;")
    )
    plcproj = root / "Plant" / "Plc" / "Plc.plcproj"
    plcproj.write_text(
        plcproj.read_text().replace(
            '<Compile Include="POUs', '<Compile Include="GVLs\\GVL_Time.TcGVL" />\n    <Compile Include="POUs', 1
        )
    )
    [project] = open_projects([str(root)])
    analysis = analyse(project)
    assert analysis.clean and _compiled(analysis) == {"FB_Tank": True, "MAIN": True, "FB_Clock": True}
    kept = {u.name for u in analysis.units.all if u.kind == "VAR_GLOBAL" and u.id not in analysis.dropped}
    assert kept == {"bAuto", "rCapacity", "nNow"}


def test_a_configuration_keeps_the_program_instances_that_compile(tmp_path):
    src = tmp_path / "plant.st"
    src.write_text(
        "PROGRAM Good\nVAR n : INT; END_VAR\nn := n + 1;\nEND_PROGRAM\n"
        "PROGRAM Bad\nVAR n : INT; END_VAR\nn := missing;\nEND_PROGRAM\n"
        "CONFIGURATION Cell\n  RESOURCE R ON PLC\n    TASK T (INTERVAL := T#10ms, PRIORITY := 1);\n"
        "    PROGRAM g WITH T : Good;\n    PROGRAM b WITH T : Bad;\n  END_RESOURCE\nEND_CONFIGURATION\n"
    )
    [project] = open_projects([str(tmp_path)])
    analysis = analyse(project)
    assert analysis.clean and _compiled(analysis) == {"Good": True, "Bad": False}
    [config] = analysis.program.checked.configurations
    assert [p["name"] for p in config.programs] == ["g"]


def test_a_project_s_sources_keep_one_entry_each_in_the_cache_folder(tmp_path, monkeypatch):
    """They change with every edit: each version kept would fill the cache
    (an entry per file holds the parse of its last text; the libraries
    they use are kept, once)."""
    monkeypatch.setenv("SOFTPLC_CACHE", str(tmp_path / "cache"))
    root = twincat(tmp_path)
    main = root / "Plant" / "Plc" / "POUs" / "MAIN.TcPOU"
    counts = []
    for step in (1, 2, 3):
        main.write_text(main.read_text().replace("]]></ST>", f"\n// edit {step}]]></ST>", 1))
        [project] = open_projects([str(root)])
        assert analyse(project).clean
        counts.append(len(list((tmp_path / "cache").rglob("*.pickle"))))
    assert counts[0] == counts[1] == counts[2]


def test_a_check_only_analysis_reports_what_a_full_one_does_without_a_program(tmp_path):
    root = twincat(tmp_path, ("FB_Logger", LOGGER), ("FB_Broken", BROKEN), ("FB_UsesBroken", USES_BROKEN))
    [project] = open_projects([str(root)])
    full, checked = analyse(project), analyse(project, check_only=True)
    assert [d.format() for d in checked.diagnostics] == [d.format() for d in full.diagnostics]
    assert _compiled(checked) == _compiled(full) and checked.clean and checked.rounds == full.rounds
    assert full.program is not None and checked.program is None


def test_plain_files_find_their_units_when_asked_as_a_folder_does(tmp_path):
    # files given one by one: their units found only when asked (for the
    # errors), from a fresh parse; the same as the folder's, found at once
    (tmp_path / "good.st").write_text(
        "FUNCTION_BLOCK FB_Count\nVAR_INPUT go : BOOL; END_VAR\nVAR_OUTPUT n : INT; END_VAR\n"
        "IF go THEN n := n + 1; END_IF\nEND_FUNCTION_BLOCK\n"
        "PROGRAM Main\nVAR c : FB_Count; ton : TON; END_VAR\nc(go := TRUE);\nEND_PROGRAM\n"
    )
    (tmp_path / "bad.st").write_text(
        "PROGRAM Broken\nVAR x : INT; END_VAR\nx := nStep;\nEND_PROGRAM\n"
        "PROGRAM UsesCounter\nVAR c : FB_Count; END_VAR\nc();\nEND_PROGRAM\n"
    )
    [files] = open_projects([str(tmp_path / "bad.st"), str(tmp_path / "good.st")])  # (the folder's order)
    [folder] = open_projects([str(tmp_path)])
    assert (files.kind, folder.kind) == ("files", "folder")
    by_files, by_folder = analyse(files), analyse(folder)

    def units(a) -> list:
        return [(u.file, u.kind, u.name, u.spans, u.uses) for u in a.units.all]

    assert units(by_files) == units(by_folder)
    assert [d.format() for d in by_files.diagnostics] == [d.format() for d in by_folder.diagnostics]
    assert (
        _compiled(by_files)
        == _compiled(by_folder)
        == {
            "FB_Count": True,
            "Main": True,
            "Broken": False,  # nStep is declared nowhere
            "UsesCounter": True,
        }
    )
