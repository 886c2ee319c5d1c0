"""A scenario's data (config/scenario.py, engine/scenario.py): [init] at the
first scan, [[schedule]] at its times, in virtual time through the testing
API, as a test engineer writes them."""

from __future__ import annotations

from datetime import timedelta

import pytest

from softplc.runtime.config import ConfigError
from softplc.testing import PLC

SRC = """
TYPE Mode : (Off, Auto, Hand); END_TYPE
TYPE Pos : STRUCT x : INT; y : INT; END_STRUCT END_TYPE
PROGRAM Main
VAR
    setpoint : REAL := 10.0;
    auto : BOOL := TRUE;
    mode : Mode;
    delay : TIME := T#1s;
    pos : Pos;
    pair : ARRAY[1..2] OF INT;
    seen : REAL;            (* what the program saw at its last cycle *)
    cycles : INT;
END_VAR
cycles := cycles + 1;
seen := setpoint;
END_PROGRAM
"""


def plc(tables: dict) -> PLC:
    return PLC.from_st(SRC, cycle="10ms", tables=tables)


def test_init_values_are_there_at_the_first_scan_over_the_declared_ones():
    init = {
        "Main": {"setpoint": 40.5, "auto": False, "mode": "Hand", "delay": "T#250ms", "pos": {"x": 3}},
        "Main.pair[2]": 7,
    }
    with plc({"init": init}) as p:
        assert p["Main.setpoint"] == 10.0  # before the first scan: as declared
        p.step()
        assert p["Main.seen"] == 40.5  # the program's first cycle saw it
        assert (p["Main.auto"], p["Main.mode"], p["Main.delay"]) == (False, "Hand", timedelta(milliseconds=250))
        assert p["Main.pos"] == {"x": 3, "y": 0} and p["Main.pair"] == [0, 7]
        p.write("Main.setpoint", 1.0)  # written once: the program and the test own it after
        p.step()
        assert p["Main.seen"] == 1.0


def test_scheduled_writes_land_at_the_first_scan_at_or_after_their_time():
    schedule = [
        {"at": "55ms", "set": "Main.setpoint", "value": 60},
        {"at": "20ms", "set": "Main.setpoint", "value": 20},
        {"at": "55ms", "set": "Main.mode", "value": "Auto"},
    ]
    with plc({"schedule": schedule}) as p:
        p.watch("Main.seen")
        p.run_for("100ms")
        # (a row before the first scan too: the declared 0.0 of seen)
        assert p.trace.changes("Main.seen")[-3:] == [(0, 10.0), (20_000_000, 20.0), (60_000_000, 60.0)]
        assert p["Main.mode"] == "Auto"
        done = [(t, w.key) for t, w in p.engine.scenario.done]
        assert done == [
            (20_000_000, "schedule[1].set"),
            (60_000_000, "schedule[0].set"),
            (60_000_000, "schedule[2].set"),
        ]


@pytest.mark.parametrize(
    ("tables", "key", "message"),
    [
        ({"init": {"Main": {"nope": 1}}}, 'init."Main.nope"', "no variable"),
        ({"init": {"Main.pair[3]": 1}}, 'init."Main.pair[3]"', "Main.pair[3]"),
        ({"init": {"Main": {"auto": 2}}}, 'init."Main.auto"', "Main.auto is BOOL"),
        ({"init": {"Main": {"setpoint": "fast"}}}, 'init."Main.setpoint"', "Main.setpoint is REAL"),
        ({"schedule": [{"at": "1s", "set": "Main.nope", "value": 1}]}, "schedule[0].set", "no variable"),
        ({"schedule": [{"at": "1s", "set": "Main.cycles", "value": 99999}]}, "schedule[0].value", "Main.cycles is INT"),
    ],
)
def test_a_wrong_path_or_value_names_the_key(tables, key, message):
    with pytest.raises(ConfigError) as info:
        plc(tables)
    [(where, said)] = info.value.errors
    assert where == key and message in said


@pytest.mark.parametrize(
    ("tables", "key", "message"),
    [
        ({"schedule": [{"at": "0s", "set": "Main.setpoint", "value": 1}]}, "schedule[0].at", "a duration > 0"),
        ({"schedule": [{"at": "1s", "set": "Main.setpoint"}]}, "schedule[0].value", ""),
        ({"schedule": [{"at": "1s", "set": " ", "value": 1}]}, "schedule[0].set", "a variable's path"),
        (
            {"init": {"Main": {"setpoint": 1}, "MAIN.SETPOINT": 2}},
            'init."MAIN.SETPOINT"',
            'the same variable as init."Main.setpoint"',
        ),
    ],
)
def test_the_file_s_own_mistakes_are_found_before_the_program_is(tables, key, message):
    with pytest.raises(ConfigError) as info:
        plc(tables)
    assert any(where == key and message in said for where, said in info.value.errors), info.value.errors
