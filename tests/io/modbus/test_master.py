"""MODBUS_REQUEST from ST and the channels' triggers and statistics, against
simulated drives over TCP (several units on one connection)."""

from __future__ import annotations

import re

import pytest

from softplc.runtime.devices.eaton import registers as eaton
from softplc.runtime.io.modbus.link import ModbusError

from .plant import REPO, WIRES, plant_config

REQUESTS = """
PROGRAM P
VAR
    go : BOOL;
    fc : USINT := 3;
    unit : BYTE := 1;
    connection : STRING[32] := 'drives';
    offset : UINT := 16;            (* ID 17 *)
    count : UINT := 1;
    req : MODBUS_REQUEST;
    done, failed : BOOL;
    errorId : WORD;
    first : WORD;
    received : UINT;
END_VAR
req(EXECUTE := go, CONNECTION := connection, UNIT := unit, FUNCTION_CODE := fc,
    READ_OFFSET := offset, READ_COUNT := count, WRITE_OFFSET := offset, WRITE_COUNT := count);
IF req.DONE THEN
    done := TRUE;
    first := req.RECEIVE[0];
    received := req.RECEIVED;
END_IF
IF req.ERROR THEN
    failed := TRUE;
    errorId := req.ERRORID;
END_IF
END_PROGRAM
"""


def request(plants, tmp_path, **values):
    plant = plants(
        plant_config(tmp_path, REQUESTS, program="P", sims=[{"type": "da1", "unit": 1}, {"type": "de1", "unit": 2}])
    )
    for name, value in values.items():
        plant.engine.set(f"P.{name}", value)
    plant.engine.set("P.go", True)
    plant.run_until(lambda: plant["P.done"] or plant["P.failed"], 500)
    return plant


@pytest.mark.parametrize("unit, id17", [(1, 5632), (2, 8)])
def test_read_reaches_each_unit_of_the_connection(plants, tmp_path, unit, id17):
    plant = request(plants, tmp_path, unit=unit)
    assert plant["P.done"] and plant["P.first"] == id17 and plant["P.received"] == 1
    assert not plant["P.req.BUSY"]


@pytest.mark.parametrize(
    "values, code",
    [
        ({"offset": 4}, ModbusError.ILLEGAL_DATA_ADDRESS),  # ID 5 does not exist
        ({"count": 12, "offset": 5}, ModbusError.ILLEGAL_DATA_VALUE),  # more than 11 registers (L667)
        ({"fc": 4}, ModbusError.ILLEGAL_FUNCTION),  # the drive knows 03, 06, 16, 23 only
        ({"unit": 9}, ModbusError.RESPONSE_TIMEOUT),  # nobody answers to unit 9
        ({"connection": "pumps"}, ModbusError.REQUEST_FAILED_TO_SEND),
        ({"fc": 7}, ModbusError.INVALID_REQUEST),
        ({"fc": 3, "count": 0}, ModbusError.INVALID_REQUEST),
    ],
)
def test_errors(plants, tmp_path, values, code):
    plant = request(plants, tmp_path, **values)
    assert plant["P.failed"] and not plant["P.done"]
    assert plant["P.errorId"] == code
    assert plant.engine.faults == []


def test_write_single_register_changes_the_drive(plants, tmp_path):
    plant = request(plants, tmp_path, fc=6, offset=1, count=1)  # ID 2: setpoint
    assert plant["P.done"]
    assert plant.drive(1).register(eaton.REG_SPEED_SETPOINT) == 0  # SEND[0] was 0
    plant.engine.set("P.go", False)
    plant.run_ms(20)
    holder, attr, _ty = plant.engine.variable("P.req.SEND")
    getattr(holder, attr)[0] = 355  # 35.5 Hz
    plant.engine.set("P.done", False)
    plant.engine.set("P.go", True)
    plant.run_until(lambda: plant["P.done"], 500)
    assert plant.drive(1).register(eaton.REG_SPEED_SETPOINT) == 355


def test_error_codes_match_the_st_constants():
    text = (REPO / "fblocks" / "comm" / "modbus.st").read_text()
    constants = dict(re.findall(r"MODBUS_ERR_(\w+) : WORD := 16#([0-9A-F]+);", text))
    assert constants
    for name, value in constants.items():
        assert ModbusError[name] == int(value, 16), name


TRIGGERS = """
PROGRAM T
VAR
    n : INT;
    setpoint AT %QW10 : WORD;
    pulse AT %QX40.0 : BOOL;
    ok : BOOL;
END_VAR
n := n + 1;
IF n = 20 THEN setpoint := 250; END_IF      (* 200 ms: 25.0 Hz *)
IF n = 60 THEN setpoint := 300; END_IF
pulse := (n MOD 50) = 10;                   (* a rising edge every 500 ms *)
ok := MODBUS_CHANNEL[0].Ok;
END_PROGRAM
"""


def test_channel_triggers(plants, tmp_path):
    channels = [
        {"name": "cyclic", "unit": 1, "function": 3, "offset": 5, "count": 6, "read_to": "%IW0", "period": "50ms"},
        {
            "name": "change",
            "unit": 1,
            "function": 16,
            "offset": 1,
            "count": 1,
            "write_from": "%QW10",
            "trigger": "change",
        },
        {
            "name": "edge",
            "unit": 2,
            "function": 3,
            "offset": 16,
            "count": 1,
            "read_to": "%IW20",
            "trigger": "edge",
            "edge": "%QX40.0",
        },
        {
            "name": "both",
            "unit": 2,
            "function": 23,
            "offset": 5,
            "count": 2,
            "read_to": "%IW30",
            "write_offset": 1,
            "write_count": 1,
            "write_from": "%QW10",
            "period": "100ms",
        },
    ]
    plant = plants(
        plant_config(
            tmp_path,
            TRIGGERS,
            program="T",
            channels=channels,
            sims=[{"type": "da1", "unit": 1}, {"type": "dc1", "unit": 2}],
        )
    )
    plant.run_ms(1000)
    cyclic, change, edge, both = plant.master.channels
    assert cyclic.stats.requests == 20  # every 50 ms for 1 s
    assert change.stats.requests == 3  # at start (0), then 250, then 300
    assert plant.drive(1).register(eaton.REG_SPEED_SETPOINT) == 300
    assert edge.stats.requests == 2  # the edges at 100 ms and 600 ms
    assert plant["%IW20"] == 10  # DC1's ID 17
    assert both.stats.requests == 10
    assert plant.drive(2).register(eaton.REG_SPEED_SETPOINT) == 300
    assert plant["%IW0"] == plant.drive(1).status()  # ID 6 of unit 1
    assert all(ch.stats.errors == 0 and ch.stats.ok for ch in plant.master.channels)
    assert [plant.channel(i, "Requests") for i in range(4)] == [20, 3, 2, 10]


@pytest.mark.parametrize("wire", WIRES)
def test_a_failing_channel_does_not_disturb_the_others(plants, tmp_path, wire):
    """In memory the absent unit's timeouts (30 ms) take virtual time: the
    line is busy meanwhile and the absent channel tries again one period
    (50 ms) after each timeout ends; the good one is late by at most a
    timeout, never skipped."""
    channels = [
        {"name": "good", "unit": 1, "function": 3, "offset": 5, "count": 1, "read_to": "%IW0", "period": "50ms"},
        {"name": "absent", "unit": 7, "function": 3, "offset": 5, "count": 1, "read_to": "%IW2", "period": "50ms"},
    ]
    source = "PROGRAM T\nVAR ok : BOOL; END_VAR\nok := MODBUS_CHANNEL[1].Error;\nEND_PROGRAM\n"
    # on a port the answers cross a pty in real time: the default (long) timeout, so a loaded
    # machine's slow answer is no timeout; in memory a 30 ms timeout is 30 ms of virtual time
    extra = {"timeout": "30ms"} if wire == "memory" else {}
    plant = plants(plant_config(tmp_path, source, program="T", channels=channels, transport="rtu", wire=wire, **extra))
    plant.run_ms(500)
    good, absent = plant.master.channels
    assert good.stats.requests == 10 and good.stats.errors == 0
    # memory: sent at 0, 80, ... 400 ms (the one at 480 still waits at 500); port: every 50 ms
    tries = 6 if wire == "memory" else 10
    assert absent.stats.requests == tries and absent.stats.errors == tries
    assert plant.channel(1, "LastError") == ModbusError.RESPONSE_TIMEOUT
    assert plant.channel(1, "Error") and plant.channel(0, "Ok")
    assert "no answer from unit 7" in plant.channel(1, "Message")
    assert not plant.master.status().ok and "absent" in plant.master.status().message


def test_a_simulated_drive_refuses_a_register_it_does_not_have(tmp_path):
    from softplc.runtime.config import config_from_dict
    from softplc.runtime.engine.build import build_engine
    from softplc.runtime.plugin.driver import DriverError

    data = plant_config(
        tmp_path, "PROGRAM T\nEND_PROGRAM\n", program="T", sims=[{"type": "da1", "unit": 1, "registers": {"5": 3}}]
    )
    with pytest.raises(DriverError, match=r"plant.toml: sim\[0\].registers: DA1 has no register 5"):
        build_engine(config_from_dict(data, tmp_path / "plant.toml"), virtual_time=True)
