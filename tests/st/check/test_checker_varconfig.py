"""VAR_CONFIG (runtime/st/check/checker_varconfig.py): instance paths through a
RESOURCE, a program instance and FB instances to a variable; addresses for
variables declared with incomplete ones (AT %QX*), initial values."""

from __future__ import annotations

import pytest

from ...test_cli import softplc
from ..conftest import diagnostics

VALVES = """\
FUNCTION_BLOCK Valve
VAR
  open AT %QX* : BOOL;
  level AT %IW* : INT;
  limit : INT := 10;
END_VAR
END_FUNCTION_BLOCK
PROGRAM Line
VAR
  v1 : Valve;
  n : INT;
END_VAR
END_PROGRAM
CONFIGURATION Plant
  RESOURCE Cpu ON PLC
    TASK Main (INTERVAL := T#10ms, PRIORITY := 1);
    PROGRAM line1 WITH Main : Line;
  END_RESOURCE
  VAR_CONFIG
    Cpu.line1.v1.open AT %QX0.1 : BOOL;
    line1.v1.level AT %IW2 : INT;
{more}  END_VAR
END_CONFIGURATION
"""


def test_dotted_paths_through_the_resource_and_fb_instances_resolve():
    assert diagnostics(VALVES.format(more="    Cpu.line1.v1.limit : INT := 50;\n    line1.n : INT := 3;\n")) == []


@pytest.mark.parametrize(
    "line,code,message",
    [
        (
            "Cpu.line9.v1.open AT %QX0.1 : BOOL;",
            "E094",
            "VAR_CONFIG 'Cpu.line9.v1.open': RESOURCE Cpu has no program instance 'line9'",
        ),
        (
            "Cpux.line1.n : INT;",
            "E094",
            "VAR_CONFIG 'Cpux.line1.n': 'Cpux' is neither a RESOURCE nor a program instance of this CONFIGURATION",
        ),
        (
            "line1.v1.nope : INT;",
            "E094",
            "VAR_CONFIG 'line1.v1.nope': FUNCTION_BLOCK Valve has no variable 'nope' to configure",
        ),
        (
            "line1.n.x : INT;",
            "E094",
            "VAR_CONFIG 'line1.n.x': 'n' in Line is INT, not a function block instance",
        ),
        ("line1.v1.limit AT %QW4 : INT;", "E094", "'line1.v1.limit' has no incomplete address to complete"),
        ("line1.v1.limit : DINT;", "E020", "'line1.v1.limit' is INT, not DINT"),
        ("Cpu.line1.v1.open AT %QX0.2 : BOOL;", "E094", "'Cpu.line1.v1.open' is configured twice"),
        ("line1.v1.open AT %IX0.2 : BOOL;", "E083", "%IX0.2 does not complete %QX*"),
    ],
)
def test_what_a_path_cannot_reach_is_a_coded_error_at_its_line(line, code, message):
    found = [(d.code, d.pos.line, d.message) for d in diagnostics(VALVES.format(more=f"    {line}\n"))]
    assert found == [(code, 22, message)]


def test_an_incomplete_address_needs_an_address_in_every_instance():
    src = VALVES.replace("    line1.v1.level AT %IW2 : INT;\n", "").format(more="")
    [d] = diagnostics(src)
    assert (d.code, d.pos.line, d.message) == ("E083", 4, "%IW* of instance line1.v1.level has no address")
    assert d.hint == "give it one in the CONFIGURATION: VAR_CONFIG line1.v1.level AT %IW0 : INT; END_VAR"
    # without a CONFIGURATION nothing can give one
    [d] = diagnostics("PROGRAM main\nVAR x AT %I* : BOOL; END_VAR\nEND_PROGRAM\n")
    assert (d.code, d.message) == ("E083", "%I* of main.x has no address: there is no CONFIGURATION")


def test_instances_a_path_cannot_name_cannot_hold_incomplete_addresses():
    src = VALVES.format(more="").replace("  n : INT;\n", "  n : INT;\n  spare : ARRAY[1..2] OF Valve;\n")
    src += "VAR_GLOBAL g AT %QX* : BOOL; END_VAR\n"
    found = [(d.code, d.pos.line, d.message) for d in diagnostics(src)]
    assert found == [
        ("E083", 12, "'spare' holds Valve, whose incomplete addresses VAR_CONFIG cannot reach in an ARRAY or STRUCT"),
        ("E083", 25, "%QX* is an incomplete address; a global variable needs a full one"),
    ]


def test_var_config_through_the_command_line_is_checked_not_a_crash(tmp_path):
    good = tmp_path / "good.st"
    good.write_text(VALVES.format(more=""))
    proc = softplc("check", good)
    assert (proc.returncode, proc.stderr.strip()) == (0, "profile: codesys\n0 errors, 0 warnings")
    bad = tmp_path / "bad.st"
    bad.write_text(VALVES.format(more="    Cpu.line1.v1.limit AT %QX0.4 : INT;\n"))
    for command in ("check", "compile"):
        proc = softplc(command, bad)
        assert proc.returncode == 1 and "Traceback" not in proc.stderr
        assert f"{bad}:22:5: error E094: 'Cpu.line1.v1.limit' has no incomplete address to complete" in proc.stderr
