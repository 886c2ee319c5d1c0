"""The libraries softplc ships (runtime/program/shipped.py, fblocks/libs):
chosen by name, with Python functions beside their ST, a warning for one
that cannot do its work here, and an unknown name that says which library
declares it."""

from __future__ import annotations

import textwrap
from pathlib import Path

import pytest

from softplc.runtime.program import Library, check_files, compile_files
from softplc.runtime.program.shipped import catalogue, functions_of, natives_of, shipped, shipped_named

USES = """
PROGRAM Main
VAR s : ST_Slave; n : INT; END_VAR
s.nAddr := 1001;
n := n + 1;
END_PROGRAM
"""


@pytest.fixture
def fieldbus(tmp_path: Path) -> Path:
    lib = tmp_path / "fieldbus"
    lib.mkdir()
    (lib / "types.st").write_text("TYPE ST_Slave : STRUCT nAddr : UINT; END_STRUCT END_TYPE\n")
    (lib / "blocks.st").write_text(
        textwrap.dedent(
            """
            FUNCTION_BLOCK FB_Scan
            VAR_OUTPUT bError : BOOL := TRUE; nErrId : UDINT := 16#701; END_VAR
            END_FUNCTION_BLOCK
            """
        )
    )
    return lib


def test_a_library_that_cannot_work_here_warns_once_when_the_program_uses_it(fieldbus):
    lib = Library(fieldbus, "Fieldbus", unavailable="it needs the EtherCAT master of TwinCAT")
    diags, _ = check_files([], texts={"main.st": USES + USES.replace("Main", "Other")}, libraries=[lib])
    warned = [d for d in diags if d.code == "W230"]
    assert len(warned) == 1 and not [d for d in diags if d.is_error]
    assert warned[0].message.startswith("Fieldbus is declared but not available here: it needs the EtherCAT")
    assert (warned[0].pos.file, warned[0].pos.line) == ("main.st", 1)
    # the program runs: the library's declarations are there
    r = compile_files([], texts={"main.st": USES}, libraries=[lib]).runner("Main", cycle_time_ms=10)
    r.run(3)
    assert r.get("s.nAddr") == 1001 and r.get("n") == 3


def test_a_library_the_program_does_not_use_says_nothing(fieldbus):
    lib = Library(fieldbus, "Fieldbus", unavailable="it needs the EtherCAT master of TwinCAT")
    src = "PROGRAM Main VAR n : INT; END_VAR n := n + 1; END_PROGRAM"
    diags, _ = check_files([], texts={"main.st": src}, libraries=[lib])
    assert diags == []


def test_an_unknown_name_a_vendor_library_declares_says_which():
    src = """
    PROGRAM Main
    VAR s : T_MaxString; ok : BOOL; END_VAR
    ok := MEMCPY(0, 0, 0) = 0;
    END_PROGRAM
    """
    diags, _ = check_files([], texts={"main.st": src}, profile="twincat")
    messages = sorted(d.message for d in diags if d.is_error)
    # Tc2_System: shipped ("add it to libraries") or only catalogued ("softplc does not have")
    assert any(m.startswith("unknown type 'T_MaxString' (Tc2_System") for m in messages), messages
    assert any(m.startswith("unknown function 'MEMCPY' (Tc2_System") for m in messages), messages


def test_a_name_no_library_declares_is_just_unknown():
    diags, _ = check_files([], texts={"main.st": "PROGRAM Main VAR x : INT; END_VAR x := nosuch; END_PROGRAM"})
    assert [d.message for d in diags if d.is_error] == ["unknown name 'nosuch'"]


def test_the_catalogue_and_the_shipped_libraries_are_well_formed():
    names = [lib.name.upper() for lib in catalogue()]
    assert len(names) == len(set(names)) and "TC2_SYSTEM" in names
    for key, spec in shipped().items():
        lib = shipped_named(key)
        assert lib is not None and lib.namespace == spec.name
        assert lib.files(), f"{spec.name}: no ST files in {spec.package}"
        functions_of((lib,))  # its Python functions import
        assert all(fn.name == fn.name.upper() for fn in natives_of((lib,)))  # and its natives


def test_library_on_the_command_line_takes_a_folder_and_refuses_what_is_none(fieldbus, tmp_path):
    from tests.test_cli import softplc

    main = tmp_path / "main.st"
    main.write_text(USES)
    r = softplc("exec", main, "--library", fieldbus, "--cycles", "2")
    assert r.returncode == 0, r.stderr
    assert '"n": 2' in r.stdout
    r = softplc("check", main)
    assert r.returncode == 1 and "unknown type 'ST_Slave'" in r.stderr
    r = softplc("check", main, "--library", "NoSuchLibrary")
    assert r.returncode == 2 and "'NoSuchLibrary' is neither a library softplc ships nor a folder" in r.stderr


def test_a_configuration_names_a_library_by_its_path_or_fails_naming_the_key(fieldbus, tmp_path):
    # (fieldbus is the folder tmp_path/fieldbus)
    from softplc.runtime.config import ConfigError, load_config

    (tmp_path / "main.st").write_text(USES)
    (tmp_path / "plc.toml").write_text(
        '[plc]\nprograms = ["main.st"]\nlibraries = ["fieldbus", "NoSuchLib"]\n'
        '[[task]]\nname = "T"\ninterval = "10ms"\nprograms = ["Main"]\n'
    )
    with pytest.raises(ConfigError) as err:
        load_config(tmp_path / "plc.toml")
    assert "plc.libraries[1]" in str(err.value) and "no such folder" in str(err.value)


def test_a_shipped_library_declares_its_natives_when_chosen_and_names_them_when_not():
    src = "PROGRAM Main VAR ok : BOOL; END_VAR ok := AssertEquals(Expected := 1, Actual := 1); END_PROGRAM"
    diags, _ = check_files([], texts={"main.st": src}, profile="twincat")
    assert [d.message for d in diags if d.is_error] == [
        "unknown function 'AssertEquals' (TcUnit; add it to libraries = [...])"
    ]
    diags, _ = check_files([], texts={"main.st": src}, profile="twincat", libraries=[shipped_named("TcUnit")])
    assert [d for d in diags if d.is_error] == []


# ---------------------------------------------------------------- parts, replacements, namespaces


@pytest.fixture
def partly(tmp_path: Path) -> Path:
    """A library whose ads.st cannot work here and whose math.st can."""
    lib = tmp_path / "partly"
    lib.mkdir()
    (lib / "math.st").write_text("FUNCTION Twice : INT VAR_INPUT x : INT; END_VAR Twice := 2 * x; END_FUNCTION\n")
    (lib / "ads.st").write_text(
        textwrap.dedent(
            """
            FUNCTION_BLOCK ADSREAD
            VAR_INPUT READ : BOOL; END_VAR
            VAR_OUTPUT ERR : BOOL; ERRID : UDINT; END_VAR
            IF READ THEN ERR := TRUE; ERRID := 6; END_IF
            END_FUNCTION_BLOCK
            FUNCTION_BLOCK ADSWRITE
            VAR_INPUT WRITE : BOOL; END_VAR
            END_FUNCTION_BLOCK
            """
        )
    )
    return lib


def test_an_unavailable_part_warns_once_naming_what_the_program_uses(partly):
    lib = Library(partly, "Partly", unavailable_parts=(("ads.st", "it needs an ADS router"),))
    src = """
    PROGRAM Main VAR r1, r2 : ADSREAD; n : INT; END_VAR
    r1(READ := TRUE); r2(READ := FALSE); n := Twice(n + 1);
    END_PROGRAM
    """
    diags, _ = check_files([], texts={"main.st": src}, libraries=[lib])
    assert [(d.code, d.message) for d in diags] == [
        ("W230", "Partly ADSREAD is declared but not available here: it needs an ADS router")
    ]
    r = compile_files([], texts={"main.st": src}, libraries=[lib]).runner("Main")
    r.run(2)
    assert (r.get("r1.ERR"), r.get("r1.ERRID"), r.get("r2.ERR"), r.get("n")) == (True, 6, False, 6)


def test_a_program_that_uses_only_the_working_part_gets_no_warning(partly):
    lib = Library(partly, "Partly", unavailable_parts=(("ads.st", "it needs an ADS router"),))
    src = "PROGRAM Main VAR n : INT; END_VAR n := Twice(3); END_PROGRAM"
    assert check_files([], texts={"main.st": src}, libraries=[lib])[0] == []


def test_a_library_block_replaces_the_standard_block_of_its_name(tmp_path):
    # TwinCAT's Tc2_Standard counts with RESET and a WORD, not IEC's R and INT
    (tmp_path / "counters.st").write_text(
        "FUNCTION_BLOCK CTU VAR_INPUT CU, RESET : BOOL; PV : WORD; END_VAR VAR_OUTPUT Q : BOOL; CV : WORD; END_VAR\n"
        "IF RESET THEN CV := 0; ELSIF CU THEN CV := CV + 1; END_IF Q := CV >= PV;\nEND_FUNCTION_BLOCK\n"
    )
    lib = Library(tmp_path, "Vendor")
    src = "PROGRAM Main VAR c : CTU; END_VAR c(CU := TRUE, RESET := c.CV = 2, PV := 5); END_PROGRAM"
    r = compile_files([], texts={"main.st": src}, libraries=[lib]).runner("Main")
    r.run(4)
    assert r.get("c.CV") == 1  # 1, 2, reset, 1


def test_a_library_function_written_in_python_takes_its_namespace(tmp_path):
    lib = Library(tmp_path, "Probe", functions="tests.program.context_library")
    src = "PROGRAM Main VAR i : DINT; END_VAR i := Probe.TASK_INDEX(); END_PROGRAM"
    r = compile_files([], texts={"main.st": src}, libraries=[lib]).runner("Main")
    r.run(1)
    assert r.get("i") == 1


def test_a_library_global_is_not_the_program_state_exec_prints(tmp_path):
    (tmp_path / "consts.st").write_text("VAR_GLOBAL CONSTANT LIMIT_MAX : INT := 7; END_VAR\n")
    src = "PROGRAM Main VAR n : INT; END_VAR n := LIMIT_MAX; END_PROGRAM"
    prog = compile_files([], texts={"main.st": src}, libraries=[Library(tmp_path, "Consts")])
    assert "LIMIT_MAX" in prog.library_globals and "n" not in prog.library_globals
