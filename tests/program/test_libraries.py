"""The user's libraries (runtime/program/libraries.py): a folder of POUs in
OSCAT's style (global constant structures, EN/ENO, FBs calling FBs, array
functions through pointers) used plain and in its namespace; unused files
cost nothing; parses are kept by content hash; [plc] libraries = [...]."""

from __future__ import annotations

import pickle
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from softplc.runtime.program import Library, check_files, compile_files, libraries
from softplc.runtime.st.diagnostics import CompileError

LIB = Library(Path(__file__).parent / "oscat_style", "OSCAT")

MAIN = """
PROGRAM Main
VAR
    area : LREAL;
    cc : OSCAT.CYCLE_COUNT;        (* a type in the namespace *)
    level : REAL;
    up : BOOL := TRUE;
    checked : INT;
    ok : BOOL := TRUE;
    inside : INT;
    ok2 : BOOL;
    width : INT;
    values : ARRAY[1..5] OF REAL := [1.5, 2.5, 3.0, 4.0, 5.0];
    total : REAL;
END_VAR
area := OSCAT.CIRCLE_AREA(2.0);   (* MATH.PI, a global constant of the library *)
IF up THEN level := level + 15.0; ELSE level := level - 15.0; END_IF
IF level >= 100.0 THEN up := FALSE; ELSIF level <= 0.0 THEN up := TRUE; END_IF
cc(IN := level);
checked := LIMIT_CHECK(x := 120, lo := 0, hi := 100, ENO => ok);
inside := LIMIT_CHECK(x := 50, lo := 0, hi := 100, ENO => ok2);
width := OSCAT.STRING_LENGTH;
total := OSCAT.ARRAY_SUM(pt := ADR(values), size := UDINT_TO_UINT(SIZEOF(values)));  (* a pointer to ARRAY[0..32000] *)
END_PROGRAM
"""


@pytest.fixture(autouse=True)
def _own_cache(tmp_path, monkeypatch):
    """A cache folder of the test's own, and no parses kept from other tests."""
    monkeypatch.setenv("SOFTPLC_CACHE", str(tmp_path / "cache"))
    monkeypatch.setattr(libraries, "_PARSES", {})


def run(cycles: int, source: str = MAIN, libraries=(LIB,)):
    prog = compile_files([], texts={"main.st": source}, libraries=libraries)
    r = prog.runner("Main")
    r.run(cycles)
    return prog, r


def test_a_program_uses_the_library_plain_and_in_its_namespace():
    _, r = run(20)
    assert r.get("area") == pytest.approx(3.14159265358979 * 4)
    # level: 15, 30 ... 105 (cycle 7), down to 0 (cycle 14), up again: HYST_1's Q rises
    # above 80 in cycles 6 and 19, so the FB inside the FB counts two edges
    assert r.get("cc.COUNT") == 2
    assert (r.get("checked"), r.get("ok"), r.get("inside"), r.get("ok2")) == (100, False, 50, True)
    assert r.get("width") == 254
    assert r.get("total") == 16.0  # ARRAY_SUM reads the 5 REALs SIZEOF gives through its large array pointer


def test_unused_library_files_are_not_compiled():
    prog, _ = run(1)
    src = prog.python_source.upper()
    assert "HYST_1" in src and "CYCLE_COUNT" in src  # CYCLE_COUNT needs HYST_1
    assert "NEVER_USED" not in src


def test_an_unused_broken_file_costs_nothing_and_a_used_one_is_reported(tmp_path):
    lib = tmp_path / "lib"
    lib.mkdir()
    (lib / "good.st").write_text("FUNCTION GOOD : INT\nGOOD := 7;\nEND_FUNCTION\n")
    (lib / "broken.st").write_text("FUNCTION BROKEN : INT\nBROKEN := nothing;\nEND_FUNCTION\n")
    src = "PROGRAM Main\nVAR x : INT; END_VAR\nx := LIBX.GOOD();\nEND_PROGRAM\n"
    _, r = run(1, src, (Library(lib, "LIBX"),))
    assert r.get("x") == 7
    with pytest.raises(CompileError) as exc:
        run(1, src.replace("LIBX.GOOD()", "BROKEN()"), (Library(lib, "LIBX"),))
    [d] = exc.value.diagnostics
    assert d.code == "E010" and d.pos.file == str(lib / "broken.st") and d.pos.line == 2


def test_a_name_the_library_lacks_is_e019_with_a_suggestion():
    diags, _ = check_files(
        [], texts={"main.st": MAIN.replace("OSCAT.CIRCLE_AREA", "OSCAT.CIRCLE_AREAS")}, libraries=(LIB,)
    )
    d = next(d for d in diags if d.is_error)
    assert d.code == "E019" and d.message == "the library OSCAT has no 'CIRCLE_AREAS'"
    assert "CIRCLE_AREA" in (d.hint or "")


def test_a_user_pou_of_the_same_name_replaces_the_librarys():
    src = MAIN + "FUNCTION CIRCLE_AREA : LREAL\nVAR_INPUT r : LREAL; END_VAR\nCIRCLE_AREA := r;\nEND_FUNCTION\n"
    _, r = run(1, src)
    assert r.get("area") == 2.0


def test_parses_are_kept_by_content_hash(tmp_path):
    cache = tmp_path / "cache" / "st"
    # without a library: the parses of softplc's own library files (every one is indexed)
    run(1, "PROGRAM Main\nVAR t : TON; END_VAR\nt(IN := TRUE, PT := T#1s);\nEND_PROGRAM\n", libraries=())
    standard = {p.name for p in cache.glob("*.pickle")} if cache.exists() else set()
    run(1)
    first = sorted(p.name for p in cache.glob("*.pickle"))
    # every file of the library was parsed once (to know what it declares), then kept
    assert len(set(first) - standard) == len(LIB.files()) == 7
    # a damaged entry is parsed again and rewritten, not an error
    victim = cache / sorted(set(first) - standard)[0]
    victim.write_bytes(b"not a pickle")
    libraries._PARSES.clear()  # (as a new process)
    _, r = run(20)
    assert r.get("cc.COUNT") == 2
    assert pickle.loads(victim.read_bytes())
    # a second process reads the library's entries: none is written again
    mine = sorted(set(first) - standard)
    written = {name: (cache / name).stat().st_mtime_ns for name in mine}
    code = (
        "from pathlib import Path; from softplc.runtime.program import compile_files, Library;"
        f"compile_files([], texts={{'main.st': {MAIN!r}}}, libraries=[Library(Path({str(LIB.path)!r}), 'OSCAT')])"
    )
    env_run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert env_run.returncode == 0, env_run.stderr
    assert {name: (cache / name).stat().st_mtime_ns for name in mine} == written


def test_a_changed_library_file_is_parsed_again(tmp_path):
    lib = tmp_path / "lib"
    lib.mkdir()
    f = lib / "k.st"
    f.write_text("FUNCTION K : INT\nK := 1;\nEND_FUNCTION\n")
    src = "PROGRAM Main\nVAR x : INT; END_VAR\nx := K();\nEND_PROGRAM\n"
    assert run(1, src, (Library(lib, "L"),))[1].get("x") == 1
    f.write_text("FUNCTION K : INT\nK := 2;\nEND_FUNCTION\n")
    assert run(1, src, (Library(lib, "L"),))[1].get("x") == 2


def test_a_librarys_generated_and_hidden_folders_are_no_sources(tmp_path):
    # a Beremiz project as a library (OSCAT's port): build/ holds matiec's
    # input, a copy of every POU; .git and the like hold nothing to compile
    lib = tmp_path / "lib"
    for sub, name, value in (("", "K", 1), ("build", "K", 2), (".git", "K", 3), ("more", "M", 4)):
        (lib / sub).mkdir(parents=True, exist_ok=True)
        (lib / sub / f"{name.lower()}.st").write_text(f"FUNCTION {name} : INT\n{name} := {value};\nEND_FUNCTION\n")
    assert [p.relative_to(lib).as_posix() for p in Library(lib, "L").files()] == ["k.st", "more/m.st"]
    src = "PROGRAM Main\nVAR x : INT; END_VAR\nx := K() + M();\nEND_PROGRAM\n"
    assert run(1, src, (Library(lib, "L"),))[1].get("x") == 5


def test_the_config_names_libraries(tmp_path):
    from softplc.testing import PLC

    (tmp_path / "main.st").write_text(MAIN)
    lib = Path(__file__).parent / "oscat_style"
    (tmp_path / "plant.toml").write_text(
        f'[plc]\nprograms = ["main.st"]\nlibraries = [{{ path = "{lib}", namespace = "OSCAT" }}]\n'
    )
    with PLC.from_config(tmp_path / "plant.toml") as plc:
        plc.run_for("200ms")
        assert plc.read("Main.cc.COUNT") == 2 and plc.read("Main.width") == 254


def test_a_library_folder_that_does_not_exist_names_the_key(tmp_path):
    from softplc.runtime.config import ConfigError, load_config

    (tmp_path / "main.st").write_text(MAIN)
    (tmp_path / "plant.toml").write_text('[plc]\nprograms = ["main.st"]\nlibraries = ["nowhere"]\n')
    with pytest.raises(ConfigError) as exc:
        load_config(tmp_path / "plant.toml")
    assert "plc.libraries[0]" in str(exc.value) and "no such folder" in str(exc.value)


def test_a_parse_is_kept_no_longer_than_the_importer_that_made_it(tmp_path, monkeypatch):
    """A cached parse of an imported file is what its importer wrote: a
    softplc whose importers read more (FBD bodies) must parse again."""
    st = tmp_path / "st"
    shutil.copytree(Path(libraries.__file__).resolve().parents[1] / "st", st)
    monkeypatch.setattr(libraries, "_ST", st)
    before = libraries._version_salt()
    assert libraries._version_salt() == before
    plcopen = st / "importers" / "plcopen.py"
    plcopen.write_text(plcopen.read_text() + "\n# reads more now\n")
    assert libraries._version_salt() != before


SUITE_LIB = {
    "GVL_Param_Suite.st": """
        {attribute 'gvl_name' := 'GVL_Param_Suite'}
        {attribute 'qualified_only'}
        VAR_GLOBAL CONSTANT
            BufferSize : UDINT := 16;
        END_VAR
    """,
    "params_unnamed.st": "VAR_GLOBAL CONSTANT Unlisted : INT := 7; END_VAR",
    "FB_Suite.st": """
        FUNCTION_BLOCK FB_Suite
        VAR calls : INT; END_VAR
        METHOD PUBLIC Count : INT
        calls := calls + 1;
        Count := calls;
        END_METHOD
        END_FUNCTION_BLOCK
    """,
    "I_Named.st": "INTERFACE I_Named METHOD Name : STRING END_METHOD END_INTERFACE",
}


def _suite_lib(tmp_path) -> Library:
    folder = tmp_path / "SuiteLib"
    folder.mkdir(exist_ok=True)
    for name, text in SUITE_LIB.items():
        (folder / name).write_text(text)
    return Library(folder, "SuiteLib")


def test_a_block_extends_and_implements_names_of_a_library_in_its_namespace(tmp_path):
    src = """
    FUNCTION_BLOCK FB_Mine EXTENDS SuiteLib.FB_Suite IMPLEMENTS SuiteLib.I_Named
    VAR n : INT; END_VAR
    METHOD Name : STRING
    Name := 'mine';
    END_METHOD
    n := Count();
    END_FUNCTION_BLOCK
    PROGRAM Main
    VAR fb : FB_Mine; who : STRING; itf : SuiteLib.I_Named; END_VAR
    fb();
    itf := fb;
    who := itf.Name();
    END_PROGRAM
    """
    _, r = run(3, src, libraries=(_suite_lib(tmp_path),))
    assert r.get("fb.n") == 3 and r.get("who") == "mine"


def test_extending_what_the_library_lacks_is_e019(tmp_path):
    src = "FUNCTION_BLOCK FB_Mine EXTENDS SuiteLib.FB_Nope END_FUNCTION_BLOCK"
    diags, _ = check_files([], texts={"main.st": src}, libraries=[_suite_lib(tmp_path)])
    assert ("E019", "the library SuiteLib has no 'FB_Nope'") in [(d.code, d.message) for d in diags]


def test_a_library_names_a_global_list_that_programs_qualify_with_and_without_its_namespace(tmp_path):
    src = """
    PROGRAM Main
    VAR
        a : ARRAY[0..SuiteLib.GVL_Param_Suite.BufferSize - 1] OF BYTE;
        size : UDINT := GVL_Param_Suite.BufferSize;
        top : DINT;
    END_VAR
    top := UPPER_BOUND(a, 1);
    END_PROGRAM
    """
    _, r = run(1, src, libraries=(_suite_lib(tmp_path),))
    assert r.get("size") == 16 and r.get("top") == 15
    # qualified_only, as TcUnit's GVL_Param_TcUnit: a bare name is E018
    diags, _ = check_files(
        [],
        texts={"main.st": src.replace("GVL_Param_Suite.BufferSize;", "BufferSize;")},
        libraries=[_suite_lib(tmp_path)],
    )
    assert [d.code for d in diags if d.is_error] == ["E018"]


def test_a_library_file_that_names_no_list_keeps_its_globals_unlisted(tmp_path):
    src = "PROGRAM Main VAR n : INT; END_VAR n := Unlisted; END_PROGRAM"
    _, r = run(1, src, libraries=(_suite_lib(tmp_path),))
    assert r.get("n") == 7
    bad = "PROGRAM Main VAR n : INT; END_VAR n := params_unnamed.Unlisted; END_PROGRAM"
    diags, _ = check_files([], texts={"main.st": bad}, libraries=[_suite_lib(tmp_path)])
    assert any(d.is_error for d in diags)
