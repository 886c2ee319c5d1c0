"""Dialect rules of declarations met in real CODESYS and TwinCAT code (issue
30): initial values computed when a variable is initialised, and the names a
global variable list's initial values use; seen from a program a user
compiles and runs."""

from __future__ import annotations

import pytest

from softplc.runtime.program import check_files, compile_files

from .conftest import diagnostics, run_st

FROM_INPUT = """
VAR_GLOBAL
    gBase : STRING := 'home';
    gTopic : STRING := CONCAT(gBase, '/status');
END_VAR
FUNCTION_BLOCK FB_Limit
VAR_INPUT
    LowerLimit : INT := 5;
END_VAR
VAR
    nVal : INT := LowerLimit;
    nNext : INT := nVal * 2 + 1;
    sTopic : STRING := CONCAT(gTopic, '/limit');
END_VAR
VAR_OUTPUT
    q : INT;
END_VAR
nVal := nVal + 1;
q := nVal;
END_FUNCTION_BLOCK
FUNCTION Tenfold : INT
VAR_INPUT
    a : INT;
END_VAR
VAR
    b : INT := a * 10;
END_VAR
Tenfold := b;
END_FUNCTION
PROGRAM main
VAR
    f : FB_Limit;
    g : FB_Limit := (LowerLimit := 20);
    k : INT := Tenfold(4);
    first, next, firstG : INT;
    topic : STRING;
END_VAR
f(LowerLimit := 100, q => first);
g(q => firstG);
next := f.nNext;
topic := f.sTopic;
END_PROGRAM
"""


@pytest.mark.parametrize("profile", ["codesys", "twincat"])
def test_an_initial_value_is_computed_when_the_variable_is_initialised(profile):
    # CODESYS "Variable Initialization": any ST expression, computed in
    # declaration order when the instance is initialised: nVal takes
    # LowerLimit's own initial value (5), not what the first call passes, and
    # the instance's declaration values (LowerLimit := 20) are set after its
    # initial values, so g's nVal is 5 too
    r = run_st(FROM_INPUT, cycles=1, profile=profile)
    assert (r.get("first"), r.get("next"), r.get("firstG")) == (6, 11, 6)
    assert (r.get("f.LowerLimit"), r.get("g.LowerLimit")) == (100, 20)
    assert r.get("topic") == "home/status/limit"
    assert r.get("k") == 40  # a FUNCTION's local: computed at every call, from its input


def test_a_later_variable_is_not_read_before_it_is_initialised():
    src = FROM_INPUT.replace(
        "    nVal : INT := LowerLimit;\n    nNext : INT := nVal * 2 + 1;",
        "    nNext : INT := nVal * 2 + 1;\n    nVal : INT := LowerLimit;",
    )
    ds = diagnostics(src)
    assert [(d.code, d.message) for d in ds if d.is_error] == [
        ("E024", "the initial value of 'nNext' reads 'nVal', which is initialised after it")
    ]


@pytest.mark.parametrize("profile", ["iec", "matiec", "schneider"])
def test_the_strict_profiles_want_a_constant(profile):
    ds = [d for d in diagnostics(FROM_INPUT, profile) if d.code == "E024"]
    assert len(ds) == 6
    assert ds[0].message == "the initial value of 'gTopic' is not a constant expression"
    assert "the codesys and twincat profiles compute a variable's at start-up" in ds[0].hint


def test_a_constant_still_wants_a_constant():
    src = "VAR_GLOBAL\n    g : INT := 1;\nEND_VAR\nVAR_GLOBAL CONSTANT\n    c : INT := g + 1;\nEND_VAR\n"
    assert [d.code for d in diagnostics(src) if d.is_error] == ["E024"]


QUALIFIED_LIST = """
{attribute 'qualified_only'}
VAR_GLOBAL
    MqttMain : STRING(16) := 'Devices/';
    MqttKind : STRING(16) := 'PLC/';
    MqttBase : STRING(100) := CONCAT(MqttMain, MqttKind);
    Ready : BOOL := MqttBase <> '';
END_VAR
"""


def test_a_qualified_only_lists_initial_values_name_its_variables_bare():
    # a CODESYS export's GVL_MQTT builds its topics from its own variables,
    # unqualified, under {attribute 'qualified_only'}
    main = (
        "PROGRAM main\nVAR\n    topic : STRING(100);\n    ok : BOOL;\nEND_VAR\n"
        "topic := GVL_MQTT.MqttBase;\nok := GVL_MQTT.Ready;\nEND_PROGRAM\n"
    )
    prog = compile_files([], texts={"GVL_MQTT.st": QUALIFIED_LIST, "main.st": main})
    r = prog.runner("main", cycle_time_ms=10)
    r.run(1)
    assert (r.get("topic"), r.get("ok")) == ("Devices/PLC/", True)
    bare = main.replace("GVL_MQTT.MqttBase", "MqttBase")
    diags, _ = check_files([], texts={"GVL_MQTT.st": QUALIFIED_LIST, "main.st": bare})
    assert [d.code for d in diags] == ["E018"]  # elsewhere they stay qualified
