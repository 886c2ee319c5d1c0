"""The Modbus TCP server against raw sockets: each request of issue 31 as
bytes on the wire, the answer as bytes back (Modbus Application Protocol
Specification V1.1b3: the exception code per function, pipelined requests
answered in order with their own transaction ids, limits on connections and
framing), the log lines a flood leaves counted."""

from __future__ import annotations

import logging
import socket
import struct

import pytest

from softplc.runtime.engine.access import Permission
from softplc.runtime.surfaces.host import Surfaces
from softplc.runtime.surfaces.modbus_server import server as modbus_server
from softplc.runtime.surfaces.modbus_server.protocol import ModbusError, parse

from ...engine.conftest import Scanning, make_engine, task, wait_until
from .conftest import server_config

MBAP = struct.Struct(">HHHB")


def adu(pdu: bytes, transaction: int = 1, unit: int = 1, protocol: int = 0) -> bytes:
    return MBAP.pack(transaction, protocol, len(pdu) + 1, unit) + pdu


def recv_exactly(sock: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        if not chunk:
            raise ConnectionError(f"closed after {len(data)} of {n} bytes")
        data += chunk
    return data


def answer(sock: socket.socket) -> tuple:
    """(transaction id, PDU) of the next answer."""
    transaction, _protocol, length, _unit = MBAP.unpack(recv_exactly(sock, MBAP.size))
    return transaction, recv_exactly(sock, length - 1)


class Raw:
    def __init__(self, port: int) -> None:
        self.sock = socket.create_connection(("127.0.0.1", port), timeout=10)

    def ask(self, pdu: bytes, transaction: int = 1) -> bytes:
        self.sock.sendall(adu(pdu, transaction))
        got, reply = answer(self.sock)
        assert got == transaction
        return reply

    def closed(self) -> bool:
        """True once the server closed the connection (b'' or a reset)."""
        try:
            return self.sock.recv(1) == b""
        except ConnectionResetError:
            return True

    def close(self) -> None:
        self.sock.close()


@pytest.fixture
def raw(plc):
    opened: list[Raw] = []

    def connect(p) -> Raw:
        r = Raw(p.port)
        opened.append(r)
        return r

    yield connect
    for r in opened:
        r.close()


def read(function: int, address: int, count: int) -> bytes:
    return struct.pack(">BHH", function, address, count)


@pytest.mark.parametrize(
    ("pdu", "expected"),
    [
        (read(3, 0, 126), b"\x83\x03"),  # more registers than an answer holds
        (read(3, 0, 0), b"\x83\x03"),
        (read(1, 0, 2001), b"\x81\x03"),  # more coils than an answer holds
        (read(4, 0, 126), b"\x84\x03"),
        (read(2, 0, 0), b"\x82\x03"),
        (struct.pack(">BHH", 5, 3, 0x1234), b"\x85\x03"),  # a coil is FF00h or 0000h
        (struct.pack(">BHHB", 16, 1024, 124, 2) + bytes(2), b"\x90\x03"),  # 124 registers: too many
        (struct.pack(">BHHB", 16, 1024, 2, 3) + bytes(3), b"\x90\x03"),  # byte count not 2 x quantity
        (struct.pack(">BHHB", 15, 0, 9, 1) + b"\xff", b"\x8f\x03"),  # 9 coils in 1 byte
        (struct.pack(">BHHHHB", 23, 0, 126, 1024, 1, 2) + bytes(2), b"\x97\x03"),
        (b"\x03\x00", b"\x83\x03"),  # a request cut short
        (b"\x18\x00\x00", b"\x98\x01"),  # read FIFO queue: the PLC has none, no made-up data
        (b"\x11", b"\x91\x01"),  # report server id: serial line only, names no stack
        (b"\x2b\x0e\x01\x00", b"\xab\x01"),  # device identification
        (b"\x08\x00\x00\x12\x34", b"\x88\x01"),  # diagnostics: serial line only
        (b"\x41", b"\xc1\x01"),  # a code no function has
        (b"\x07", b"\x87\x01"),
        (read(3, 65535, 1), b"\x83\x02"),  # a good request outside the mapping: its address
    ],
)
def test_a_bad_request_gets_the_exception_code_the_specification_gives(plc, raw, pdu, expected):
    p = plc()
    client = raw(p)
    assert client.ask(pdu) == expected
    assert client.ask(read(3, 2, 1))[:2] == b"\x03\x02"  # and the connection goes on


def test_a_coil_written_with_1234h_stays_off(plc, raw):
    p = plc()
    client = raw(p)
    assert client.ask(struct.pack(">BHH", 5, 3, 0x1234)) == b"\x85\x03"
    assert client.ask(struct.pack(">BHH", 5, 3, 0xFF00)) == struct.pack(">BHH", 5, 3, 0xFF00)  # the echo
    assert p.engine.get("Main.start") is True
    assert client.ask(struct.pack(">BHH", 5, 3, 0x0000)) == struct.pack(">BHH", 5, 3, 0)
    assert p.engine.get("Main.start") is False


def test_pipelined_requests_are_each_answered_in_order_with_their_own_ids(plc, raw):
    p = plc()
    client = raw(p)
    # two in one segment: a write (which waits for a scan) and a read of what it wrote
    client.sock.sendall(adu(struct.pack(">BHH", 6, 1029, 77), 10) + adu(read(3, 1029, 1), 11))
    assert answer(client.sock) == (10, struct.pack(">BHH", 6, 1029, 77))
    assert answer(client.sock) == (11, b"\x03\x02\x00\x4d")
    # 200 in one segment, reads and writes mixed
    burst = b""
    for i in range(200):
        pdu = struct.pack(">BHH", 6, 1031, i) if i % 2 else read(3, 1031, 1)
        burst += adu(pdu, 1000 + i)
    client.sock.sendall(burst)
    answers = [answer(client.sock) for _ in range(200)]
    assert [t for t, _pdu in answers] == list(range(1000, 1200))
    assert all(pdu == struct.pack(">BHH", 6, 1031, i) for i, (_t, pdu) in enumerate(answers) if i % 2)
    # each read sees the write before it: a write is answered after the snapshot that holds it
    assert all(pdu == b"\x03\x02" + struct.pack(">H", i - 1) for i, (_t, pdu) in enumerate(answers) if i and not i % 2)


def test_the_registers_of_one_write_land_in_the_same_scan(plc, raw):
    source = """
PROGRAM Main
VAR
    low AT %MW0 : WORD;     (* holding register 1024 *)
    high AT %MW1 : WORD;    (* holding register 1025: always written with 1024 *)
    torn AT %QW0 : WORD;    (* holding register 0: scans that saw one without the other *)
END_VAR
IF low <> high THEN torn := torn + 1; END_IF
END_PROGRAM
"""
    p = plc(source)
    client = raw(p)
    for value in range(1, 101):
        pdu = struct.pack(">BHHB", 16, 1024, 2, 4) + struct.pack(">HH", value, value)
        assert client.ask(pdu) == struct.pack(">BHH", 16, 1024, 2)
    assert p.engine.get("Main.low") == p.engine.get("Main.high") == 100
    assert p.engine.get("Main.torn") == 0


def test_mask_write_and_read_write_registers(plc, raw):
    p = plc()
    client = raw(p)
    client.ask(struct.pack(">BHH", 6, 1029, 0x0012))
    # (0012h AND 00F2h) OR (0025h AND NOT 00F2h) = 0017h, the specification's example
    assert client.ask(struct.pack(">BHHH", 22, 1029, 0x00F2, 0x0025)) == struct.pack(">BHHH", 22, 1029, 0xF2, 0x25)
    assert client.ask(read(3, 1029, 1)) == b"\x03\x02\x00\x17"
    # 23: the write first, then the read, in one request
    pdu = struct.pack(">BHHHHB", 23, 1029, 3, 1031, 1, 2) + struct.pack(">H", 9)
    assert client.ask(pdu) == b"\x17\x06" + struct.pack(">HHH", 0x17, 2 * 0x17, 9)  # 1030: the program's double


def test_a_request_to_another_protocol_is_dropped_and_the_connection_goes_on(plc, raw):
    client = raw(plc())
    client.sock.sendall(adu(read(3, 2, 1), 5, protocol=1) + adu(read(3, 2, 1), 6))
    assert answer(client.sock)[0] == 6  # no answer to 5


@pytest.mark.parametrize("length", [0, 1, 255, 65535])
def test_a_header_whose_length_no_request_has_closes_the_connection(plc, raw, length):
    client = raw(plc())
    client.sock.sendall(MBAP.pack(1, 0, length, 1) + b"\x03\x00\x02\x00\x01")
    assert client.closed()


def test_a_flood_of_bad_connections_leaves_a_bounded_number_of_log_lines(plc, raw, caplog):
    p = plc(writable=["%MW5"])
    with caplog.at_level(logging.WARNING, logger="softplc.surfaces.modbus_server"):
        for _ in range(100):
            client = raw(p)
            client.sock.sendall(MBAP.pack(1, 0, 0, 1))
            assert client.closed()
            client.close()
        refused = raw(p)  # 100 refused writes too, each to another address
        for address in range(100):
            assert refused.ask(struct.pack(">BHH", 6, 2000 + address, 1)) == b"\x86\x02"
        # a write that goes through: the servers' log lines before it have reached this process
        assert refused.ask(struct.pack(">BHH", 6, 1029, 1)) == struct.pack(">BHH", 6, 1029, 1)
    lines = [r for r in caplog.records if r.name == "softplc.surfaces.modbus_server"]
    assert 2 <= len(lines) <= 20, [r.getMessage() for r in lines]  # 200 events; the budget of a limiter
    assert all(r.exc_info is None and "Traceback" not in r.getMessage() for r in lines)


def test_connections_beyond_the_limit_are_closed_and_the_others_served(plc, raw):
    p = plc(max_connections=4)  # the fixture's pymodbus client has one
    first = [raw(p) for _ in range(3)]
    for client in first:
        assert client.ask(read(3, 2, 1))[:2] == b"\x03\x02"
    extra = raw(p)
    assert extra.closed()
    assert all(client.ask(read(3, 2, 1))[:2] == b"\x03\x02" for client in first)
    first[0].close()
    wait_until(lambda: _serves(p.port), "a place is free again")


def _serves(port: int) -> bool:
    client = Raw(port)
    try:
        return client.ask(read(3, 2, 1))[:2] == b"\x03\x02"
    except (ConnectionError, OSError):
        return False
    finally:
        client.close()


def test_when_every_place_is_taken_the_connection_idle_longest_makes_room(monkeypatch):
    """In this process, with IDLE_S at 0: a dead HMI's connection does not lock the others out."""

    monkeypatch.setattr(modbus_server, "IDLE_S", 0.0)
    engine = make_engine(
        "PROGRAM Main VAR n AT %QW2 : INT; END_VAR n := n + 1; END_PROGRAM", [task("Main", 10, "Main")]
    )
    surfaces = Surfaces(engine, {})
    surfaces.access.allow("modbus_server", Permission(("%Q*", "%M*")))
    scanning = Scanning(engine, pause_s=0.001).start()
    server = modbus_server.ModbusServer(surfaces, server_config(max_connections=2)).start()
    try:
        surfaces.hub.wait_fresh(timeout=10)
        old, older = Raw(server.port), Raw(server.port)
        assert old.ask(read(3, 2, 1))[:2] == older.ask(read(3, 2, 1))[:2] == b"\x03\x02"
        newcomer = Raw(server.port)
        assert newcomer.ask(read(3, 2, 1))[:2] == b"\x03\x02"
        assert old.closed()  # quiet longest
        assert older.ask(read(3, 2, 1))[:2] == b"\x03\x02"
        for client in (old, older, newcomer):
            client.close()
    finally:
        server.stop()
        scanning.stop()
        engine.stop()


def test_parse_refuses_what_the_specification_refuses_before_the_address():
    """The order of the checks: the function, then the quantity, then (server.py) the address."""
    with pytest.raises(ModbusError) as bad_function:
        parse(b"\x18" + bytes(4))
    assert bad_function.value.code == 1
    with pytest.raises(ModbusError) as bad_count:
        parse(read(3, 65535, 200))  # outside the mapping too, but the quantity comes first
    assert bad_count.value.code == 3
