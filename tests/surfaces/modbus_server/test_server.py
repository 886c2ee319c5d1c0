"""The Modbus TCP server as an HMI sees it: a real pymodbus client on
127.0.0.1 reads what the program writes and writes what the program reads,
in OpenPLC's mapping (runtime/surfaces/modbus_server/mapping.py)."""

from __future__ import annotations

import logging
import multiprocessing
import socket

import pytest
from pymodbus.client import ModbusTcpClient
from pymodbus.exceptions import ConnectionException, ModbusIOException

from softplc.runtime.surfaces.host import SurfaceError, Surfaces
from softplc.runtime.surfaces.modbus_server import Mapping

from ...engine.conftest import make_engine, task, wait_until

ILLEGAL_DATA_ADDRESS = 2


def test_an_hmi_reads_the_outputs_inputs_and_markers_of_the_image(plc):
    p = plc()
    p.test.write("%IX0.2", True, surface="test")  # as a driver would set an input
    p.test.write("%IW4", 41, surface="test")
    client = p.client
    wait_until(lambda: client.read_holding_registers(2).registers == [1000], "the count reaches 1000 in %QW2")
    # the count may have reached 1000 before the writes: a snapshot after them is a period away
    expected = [False, False, True] + [False] * 5
    wait_until(lambda: client.read_discrete_inputs(0, count=8).bits[:8] == expected, "discrete input 2 = %IX0.2")
    wait_until(lambda: client.read_input_registers(4).registers == [41], "input register 4 = %IW4")
    wait_until(lambda: client.read_holding_registers(10).registers == [42], "%QW10 = %IW4 + 1")
    assert client.read_coils(0, count=8).bits == [False] * 5 + [True, False, False]  # coil 5 = %QX0.5 = sensor
    # holding 1023 is %QW1023, 1024 is %MW0: one read across both
    assert client.read_holding_registers(1020, count=8).registers == [0] * 8


def test_a_coil_and_a_holding_register_written_by_the_hmi_reach_the_program(plc):
    p = plc()
    client = p.client
    assert not client.write_coil(3, True).isError()
    assert client.read_coils(3).bits[0] is True  # the answer comes after a snapshot holding the write
    wait_until(lambda: client.read_coils(8).bits[0], "coil 8 (%QX1.0) follows coil 3 (%QX0.3)")
    assert p.engine.get("Main.start") is True
    assert not client.write_register(1029, 21).isError()  # %MW5, the setpoint
    assert client.read_holding_registers(1029).registers == [21]
    wait_until(lambda: client.read_holding_registers(1030).registers == [42], "holding 1030 (%MW6) = 2 x setpoint")
    assert not client.write_registers(1031, [7, 65535]).isError()  # %MW7, %MW8: a word takes 0..65535
    assert client.read_holding_registers(1031, count=2).registers == [7, 65535]
    assert not client.write_coils(16, [True, False, True]).isError()  # %QX2.0 .. %QX2.2
    assert client.read_coils(16, count=3).bits[:3] == [True, False, True]


def test_a_write_outside_writable_is_refused_with_exception_02_naming_the_address(plc, caplog):
    p = plc(writable=["%MW*"])
    client = p.client
    with caplog.at_level(logging.WARNING, logger="softplc.surfaces.modbus_server"):
        reply = client.write_coil(3, True)
        assert reply.isError() and reply.exception_code == ILLEGAL_DATA_ADDRESS
        reply = client.write_registers(1030, [1, 2], device_id=1)  # %MW6, %MW7: allowed
        assert not reply.isError()
        reply = client.write_register(10, 5)  # %QW10
        assert reply.isError() and reply.exception_code == ILLEGAL_DATA_ADDRESS
    assert p.engine.get("Main.start") is False
    messages = [r.getMessage() for r in caplog.records]
    assert any(
        "coils 3 refused" in m and "%QX0.3: modbus_server may not write it" in m and "[modbus_server] writable" in m
        for m in messages
    ), messages
    # an input cannot be written at all: discrete inputs and input registers have no write function,
    # and no coil or holding register reaches %I
    mapping = Mapping(len(p.surfaces.hub.current().image["Q"]))
    assert all(not path.startswith("%I") for path in mapping.paths("holding registers", 0, 2000))


def test_an_address_outside_the_mapping_gets_exception_02(plc):
    client = plc().client
    for reply in (
        client.read_holding_registers(1024 + 32767, count=2),  # past %MW32767
        client.read_input_registers(32768),  # past %IW32767
        client.write_register(1024 + 32768, 1),
        client.read_holding_registers(65535),
    ):
        assert reply.isError() and reply.exception_code == ILLEGAL_DATA_ADDRESS, reply
    assert client.read_holding_registers(1024 + 32767).registers == [0]  # the last %MW
    assert client.read_coils(65528, count=8).bits == [False] * 8  # the last coils: %QX8191.0..7


def test_a_configured_unit_answers_only_its_own_id(plc):
    p = plc(unit=7)
    assert p.client.read_holding_registers(2, device_id=7).registers[0] >= 1
    quick = ModbusTcpClient("127.0.0.1", port=p.port, timeout=0.5, retries=0)
    assert quick.connect()
    try:
        with pytest.raises(ModbusIOException):  # no answer, as from a unit missing on a serial line
            quick.read_holding_registers(2, device_id=3)
    finally:
        quick.close()


def test_any_unit_id_is_answered_by_default(plc):
    client = plc().client
    assert [client.read_coils(0, device_id=unit).isError() for unit in (0, 1, 99, 255)] == [False] * 4


def test_stop_closes_the_listener_and_the_connections_and_ends_the_servers_process(plc):
    p = plc()
    assert not p.client.read_coils(0).isError()
    port = p.port
    p.surfaces.stop()
    with pytest.raises(OSError):
        socket.create_connection(("127.0.0.1", port), timeout=2).close()
    assert not [c for c in multiprocessing.active_children() if c.name == "softplc-servers"]
    with pytest.raises(ConnectionException):  # the server closed the connection
        p.client.read_coils(0)


def test_a_port_in_use_is_reported_naming_the_section_and_port(plc):
    from .conftest import server_config

    p = plc()
    engine = make_engine("PROGRAM Main VAR n : INT; END_VAR n := n + 1; END_PROGRAM", [task("Main", 10, "Main")])
    try:
        other = Surfaces(engine, {"modbus_server": server_config(port=p.port)})
        with pytest.raises(SurfaceError, match=rf"\[modbus_server\] cannot listen on 127.0.0.1:{p.port}: "):
            other.start()
        # no servers' process left behind: only the first PLC's runs
        assert len([c for c in multiprocessing.active_children() if c.name == "softplc-servers"]) == 1
    finally:
        engine.stop()
