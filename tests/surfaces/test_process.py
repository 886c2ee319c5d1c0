"""The servers' process (surfaces/process.py, surfaces/child.py): the OPC UA
and Modbus servers run apart from the PLC, their log lines reach the PLC's
log, and when the process dies the PLC goes on scanning, says so, and
starts a new one that serves again."""

from __future__ import annotations

import logging
import multiprocessing

from pymodbus.client import ModbusTcpClient

from softplc.runtime.surfaces.host import Surfaces
from softplc.runtime.surfaces.pipe import start_failure

from ..engine.conftest import Scanning, make_engine, task, wait_until
from .modbus_server.conftest import server_config

SRC = """
PROGRAM Main
VAR count AT %QW2 : INT; END_VAR
count := count + 1;
IF count > 30000 THEN count := 0; END_IF
END_PROGRAM
"""


def _count(port: int) -> int | None:
    client = ModbusTcpClient("127.0.0.1", port=port, timeout=2, retries=0)
    try:
        if not client.connect():
            return None
        reply = client.read_holding_registers(2)
        return None if reply.isError() else reply.registers[0]
    finally:
        client.close()


def test_a_killed_servers_process_is_reported_and_replaced(caplog):
    engine = make_engine(SRC, [task("Main", 10, "Main")])
    surfaces = Surfaces(engine, {"modbus_server": server_config()})
    surfaces.start()
    scan = Scanning(engine).start()
    try:
        handle = surfaces.handles["modbus_server"]
        children = [p for p in multiprocessing.active_children() if p.name == "softplc-servers"]
        assert len(children) == 1 and children[0].pid != multiprocessing.current_process().pid
        first = wait_until(lambda: _count(handle.port), "the HMI reads the count")
        with caplog.at_level(logging.WARNING, logger="softplc.surfaces"):
            children[0].kill()
            process = surfaces.process
            wait_until(lambda: process is not None and process.restarts == 1, "a new process", timeout=60)
        # the PLC scanned on meanwhile, and the new server (on a new free port: port 0) serves it
        later = wait_until(lambda: (c := _count(handle.port)) is not None and c > first and c, "the count", timeout=60)
        assert later > first
        messages = [r.getMessage() for r in caplog.records]
        assert any("the servers' process ended" in m and "modbus_server" in m for m in messages), messages
        assert any("the servers' process is back: modbus-tcp://127.0.0.1:" in m for m in messages), messages
    finally:
        scan.stop()
        surfaces.stop()
        engine.stop()
    assert not [p for p in multiprocessing.active_children() if p.name == "softplc-servers"]


def test_a_server_start_that_timed_out_says_so_not_cannot_listen():
    """asyncua's start on a host busy with two test suites raised a
    TimeoutError without a message: the PLC said "[opcua] cannot listen on
    127.0.0.1:60421: " and nothing after it."""
    said = start_failure("127.0.0.1", 60421, TimeoutError())
    assert (
        said
        == "did not start on 127.0.0.1:60421 in time: a step of its start timed out (a busy host? start the PLC again)"
    )
    said = start_failure("127.0.0.1", 4840, TimeoutError("opcua: the server did not start within 60.0 s"))
    assert said.startswith("did not start on 127.0.0.1:4840 in time: opcua: the server did not start within 60.0 s")
    assert start_failure("0.0.0.0", 502, OSError(98, "Address already in use")) == (
        "cannot listen on 0.0.0.0:502: Address already in use"
    )
    assert start_failure("::1", 502, OSError()) == "cannot listen on ::1:502: OSError"
