"""The checker's CONFIGURATION (runtime/st/check/checker_config.py): tasks and
program instances, checked and exposed for the engine."""

from __future__ import annotations

from softplc.runtime.program import compile_files

from ..conftest import codes

CONFIG = """
PROGRAM Fast
VAR_INPUT limit : INT; END_VAR
VAR n : INT; END_VAR
n := n + 1; IF n > limit THEN n := 0; END_IF
END_PROGRAM
PROGRAM Slow
END_PROGRAM
CONFIGURATION Plant
  VAR_GLOBAL g_limit : INT := 3; END_VAR
  RESOURCE Cpu ON PLC
    TASK T_fast (INTERVAL := T#10ms, PRIORITY := 1);
    TASK T_slow (INTERVAL := T#100ms, PRIORITY := 5);
    PROGRAM fast1 WITH T_fast : Fast (limit := g_limit);
    PROGRAM slow1 WITH T_slow : Slow;
  END_RESOURCE
END_CONFIGURATION
"""


def test_configuration_tasks_and_program_instances_are_checked_and_exposed():
    prog = compile_files([], texts={"cfg.st": CONFIG})
    [cfg] = prog.checked.configurations
    assert cfg.name == "Plant"
    assert [(t["name"], t["interval_ms"], t["priority"]) for t in cfg.tasks] == [
        ("T_fast", 10.0, 1),
        ("T_slow", 100.0, 5),
    ]
    assert [(p["name"], p["type"].name, p["task"]) for p in cfg.programs] == [
        ("fast1", "Fast", "T_fast"),
        ("slow1", "Slow", "T_slow"),
    ]
    assert [p.name for p, _ in cfg.programs[0]["binding"].inputs] == ["limit"]


def test_configuration_errors():
    bad = (
        CONFIG.replace("WITH T_slow : Slow", "WITH T_none : Slow")
        .replace("PRIORITY := 5", "PRIORITY := 300")
        .replace("Fast (limit", "Fats (limit")
    )
    assert sorted(codes(bad)) == ["E091", "E092", "E093"]


def test_a_trailing_comma_in_a_program_configuration_is_the_profiles_choice():
    trailing = CONFIG.replace("(limit := g_limit)", "(limit := g_limit,)")
    assert codes(trailing, "iec") == ["E044"]
    assert codes(trailing, "codesys") == codes(trailing, "twincat") == []
