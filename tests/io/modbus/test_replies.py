"""Every reply is checked against its request (runtime/io/modbus/replies.py):
function code, exception code, unit, byte count and item count, and a
write's echo. A bad reply is a channel error with its reason (the status
line, MODBUS_CHANNEL[i], MODBUS_REQUEST.ERRORID) and the image keeps its
last good values.

The bad replies are crafted by the test and framed by pymodbus's own framers
(RTU with its CRC, TCP with its MBAP header): on the in-memory wire the
simulated line's end answers them instead of the drive's answer; on TCP a raw
asyncio server on 127.0.0.1 sends them over a real socket to pymodbus's client."""

from __future__ import annotations

import asyncio
import logging
import re
import threading

import pytest
from pymodbus.framer import FramerRTU, FramerSocket
from pymodbus.pdu import DecodePDU

from softplc.runtime.config import config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.engine.monitor import status_line
from softplc.runtime.io.modbus.link import LinkSettings, ModbusError, ModbusLink, Transaction
from softplc.runtime.io.modbus.master import ModbusDriver

from .plant import plant_config

PROGRAM = """
PROGRAM P
VAR
    ok : BOOL;
    lastError : WORD;
    message : STRING[120];
    status AT %IW0 : WORD;
    after AT %IW1 : WORD;
    command AT %QW2 : WORD;
END_VAR
ok := MODBUS_CHANNEL[0].Ok;
lastError := MODBUS_CHANNEL[0].LastError;
message := MODBUS_CHANNEL[0].Message;
END_PROGRAM
"""

READ_ID6 = {"name": "status", "unit": 1, "function": 3, "offset": 5, "count": 1, "read_to": "%IW0", "period": "20ms"}
IDLE = 0x00A1  # ID 6 of a DA1 at rest with its STO closed (manual 002: ready, zero speed)


def _framer(transport: str, server: bool = True):
    """pymodbus's framer of a server (it reads requests) or of a client (it reads replies)."""
    return (FramerRTU if transport == "rtu" else FramerSocket)(DecodePDU(server))


def _split(transport: str, frame: bytes) -> tuple[int, int, bytes]:
    """(unit, transaction id, PDU) of a request frame, as pymodbus's server framer reads it."""
    _used, unit, tid, pdu = _framer(transport).decode(frame)
    return unit, tid, pdu


def _frame(transport: str, unit: int, pdu: bytes, tid: int) -> bytes:
    """A reply framed by pymodbus: RTU address, PDU, CRC-16; TCP MBAP header, PDU."""
    return _framer(transport).encode(pdu, unit, tid)


def crafting(plant, transport: str, craft):
    """From now on the simulated line's end answers craft(unit, request PDU,
    the drive's own reply PDU or None) -> (unit, reply PDU), framed by pymodbus."""
    server = plant.line.server
    genuine = server.exchange

    def exchange(frame: bytes):
        answer = genuine(frame)
        unit, tid, request = _split(transport, frame)
        own = _framer(transport, server=False).decode(answer)[3] if answer else None
        reply_unit, pdu = craft(unit, request, own)
        return _frame(transport, reply_unit, pdu, tid)

    server.exchange = exchange


# (what, reply PDU crafted for "read ID 6 of unit 1", error, words of the message)
BAD_READS = [
    ("exception code 0", lambda u, req, own: (u, b"\x83\x00"), ModbusError.RESPONSE_INVALID_DATA, "exception code 0"),
    (
        "exception code 7 (not defined)",
        lambda u, req, own: (u, b"\x83\x07"),
        ModbusError.RESPONSE_INVALID_DATA,
        "exception code 7",
    ),
    (
        "function 4 for 3",
        lambda u, req, own: (u, b"\x04\x02\x12\x34"),
        ModbusError.RESPONSE_WRONG_FUNCTIONCODE,
        "function 4 to a function 3 request",
    ),
    (
        "an exception of function 4",
        lambda u, req, own: (u, b"\x84\x02"),
        ModbusError.RESPONSE_WRONG_FUNCTIONCODE,
        "function 4 (exception 2) to a function 3 request",
    ),
    ("unit 2 for 1", lambda u, req, own: (2, own), ModbusError.RESPONSE_WRONG_SLAVE, "unit 2 answered"),
    (
        "an odd byte count",
        lambda u, req, own: (u, b"\x03\x03\x12\x34\x56"),
        ModbusError.RESPONSE_INVALID_DATA,
        "byte count 3 for 1 register",
    ),
    (
        "two registers for one",
        lambda u, req, own: (u, b"\x03\x04\x12\x34\x56\x78"),
        ModbusError.RESPONSE_INVALID_DATA,
        "byte count 4 for 1 register",
    ),
]


@pytest.mark.parametrize("transport", ["rtu", "tcp"])
@pytest.mark.parametrize("what, craft, code, words", BAD_READS, ids=[b[0] for b in BAD_READS])
def test_a_bad_read_reply_is_a_channel_error_and_the_image_keeps_its_values(
    plants, tmp_path, transport, what, craft, code, words
):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport=transport, channels=[READ_ID6]))
    plant.engine.set("%IW1", 0x5555)  # the word after the channel's
    plant.run_ms(30)
    assert plant["%IW0"] == IDLE and plant["P.ok"]
    crafting(plant, transport, craft)
    plant.run_ms(150)  # a reply from another unit is skipped: it costs the timeout (100 ms)
    channel = plant.master.channels[0]
    assert not channel.stats.ok and channel.stats.last_error == code, channel.stats.message
    assert words in channel.stats.message
    # the program sees it, and the operator
    assert not plant["P.ok"] and plant["P.lastError"] == code and words in plant["P.message"]
    assert words in status_line(plant.engine)
    # the image keeps the last good value, and nothing else moved
    assert plant["%IW0"] == IDLE and plant["%IW1"] == 0x5555
    assert len(plant.engine.image.areas["I"]) == plant.engine.image.size


def test_in_rtu_a_reply_with_data_beyond_its_byte_count_fails_its_crc(plants, tmp_path):
    """RTU frames a reply by its byte count: the byte after it is taken for
    the CRC, which then does not match."""
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu", channels=[READ_ID6]))
    plant.run_ms(30)
    crafting(plant, "rtu", lambda u, req, own: (u, b"\x03\x02\x12\x34\x56"))
    plant.run_ms(150)  # pymodbus drops a frame with a bad CRC and waits for the timeout (100 ms)
    stats = plant.master.channels[0].stats
    assert stats.last_error == ModbusError.RESPONSE_CRC_FAIL and "CRC" in stats.message
    assert plant["%IW0"] == IDLE


def test_in_tcp_a_reply_with_data_beyond_its_byte_count_is_refused(plants, tmp_path):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="tcp", channels=[READ_ID6]))
    plant.run_ms(30)
    crafting(plant, "tcp", lambda u, req, own: (u, b"\x03\x02\x12\x34\x56"))
    plant.run_ms(50)
    stats = plant.master.channels[0].stats
    assert stats.last_error == ModbusError.RESPONSE_INVALID_DATA and "3 data bytes after a byte count of 2" in (
        stats.message
    )
    assert plant["%IW0"] == IDLE


def test_a_good_exception_reply_is_still_the_slaves_exception(plants, tmp_path):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu", channels=[READ_ID6]))
    crafting(plant, "rtu", lambda u, req, own: (u, b"\x83\x02"))
    plant.run_ms(30)
    stats = plant.master.channels[0].stats
    assert stats.last_error == ModbusError.ILLEGAL_DATA_ADDRESS and "exception 2" in stats.message


WRITE_ID1 = {"name": "control", "unit": 1, "function": 6, "offset": 0, "write_from": "%QW2", "period": "20ms"}
WRITE_ID1_2 = {
    "name": "control",
    "unit": 1,
    "function": 16,
    "offset": 0,
    "count": 2,
    "write_from": "%QW2",
    "period": "20ms",
}


@pytest.mark.parametrize(
    "transport, channel, reply, words",
    [
        ("rtu", WRITE_ID1, b"\x06\x00\x01\x00\x00", "echoed address 1 for 0"),
        ("rtu", WRITE_ID1, b"\x06\x00\x00\x00\x07", "echoed value 7 for 0"),
        ("tcp", WRITE_ID1, b"\x06\x00\x00", "a reply of 3 bytes to a function 6 write"),
        ("rtu", WRITE_ID1, b"\x06\x00\x00", "a reply of 6 bytes that does not frame"),  # RTU: too short to frame
        ("rtu", WRITE_ID1_2, b"\x10\x00\x00\x00\x01", "echoed count 1 for 2"),
        ("tcp", WRITE_ID1_2, b"\x03\x02\x00\x00", "function 3 to a function 16 request"),
    ],
)
def test_a_write_whose_echo_does_not_match_is_a_channel_error(plants, tmp_path, transport, channel, reply, words):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport=transport, channels=[channel]))
    crafting(plant, transport, lambda u, req, own: (u, reply))
    plant.run_ms(150)  # an RTU frame too short to frame costs the timeout (100 ms)
    stats = plant.master.channels[0].stats
    assert not stats.ok and words in stats.message
    assert stats.last_error in (ModbusError.RESPONSE_INVALID_DATA, ModbusError.RESPONSE_WRONG_FUNCTIONCODE)


COILS = {"name": "coils", "unit": 1, "function": 1, "offset": 0, "count": 3, "read_to": "%IB2", "period": "20ms"}


def test_coils_with_a_byte_count_for_more_coils_are_refused(plants, tmp_path):
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu", channels=[COILS]))
    crafting(plant, "rtu", lambda u, req, own: (u, b"\x01\x01\x05"))
    plant.run_ms(30)
    assert plant.master.channels[0].stats.ok and plant["%IB2"] == 0x05  # three coils: one byte
    crafting(plant, "rtu", lambda u, req, own: (u, b"\x01\x02\x02\x00"))
    plant.run_ms(40)
    stats = plant.master.channels[0].stats
    assert stats.last_error == ModbusError.RESPONSE_INVALID_DATA and "byte count 2 for 3 coils" in stats.message
    assert plant["%IB2"] == 0x05


REQUEST = """
PROGRAM R
VAR
    go : BOOL;
    req : MODBUS_REQUEST;
    failed : BOOL;
    errorId : WORD;
END_VAR
req(EXECUTE := go, CONNECTION := 'drives', UNIT := 1, FUNCTION_CODE := 3, READ_OFFSET := 5, READ_COUNT := 1);
IF req.ERROR THEN
    failed := TRUE;
    errorId := req.ERRORID;
END_IF
END_PROGRAM
"""


def test_modbus_request_takes_nothing_from_a_bad_reply(plants, tmp_path):
    plant = plants(plant_config(tmp_path, REQUEST, program="R", transport="rtu"))
    holder, attr, _ty = plant.engine.variable("R.req.RECEIVE")
    getattr(holder, attr)[0] = 77
    crafting(plant, "rtu", lambda u, req, own: (u, b"\x04\x02\x12\x34"))
    plant.engine.set("R.go", True)
    plant.run_until(lambda: plant["R.failed"] or plant["R.req.DONE"], 200)
    assert plant["R.failed"] and plant["R.errorId"] == ModbusError.RESPONSE_WRONG_FUNCTIONCODE
    assert getattr(holder, attr)[0] == 77


# ---------------------------------------------------------------------------- TCP over a real socket


class CraftedTcpSlave:
    """A raw asyncio server on 127.0.0.1 that answers each request frame with
    craft(unit, request PDU, transaction id) -> (unit, reply PDU), framed by
    pymodbus's socket framer with the request's transaction id, or the bytes
    of a whole frame, sent as they are."""

    def __init__(self, craft) -> None:
        self.craft = craft
        self.requests = 0
        self._loop = asyncio.new_event_loop()
        self._ready = threading.Event()
        self._thread = threading.Thread(target=self._run, name="crafted slave", daemon=True)
        self._thread.start()
        assert self._ready.wait(5)

    def _run(self) -> None:
        asyncio.set_event_loop(self._loop)
        self._server = self._loop.run_until_complete(asyncio.start_server(self._serve, "127.0.0.1", 0))
        self.port = self._server.sockets[0].getsockname()[1]
        self._ready.set()
        self._loop.run_forever()
        self._server.close()
        tasks = asyncio.all_tasks(self._loop)
        for task in tasks:
            task.cancel()
        self._loop.run_until_complete(asyncio.gather(*tasks, return_exceptions=True))
        self._loop.close()

    async def _serve(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        try:
            while True:
                header = await reader.readexactly(6)
                body = await reader.readexactly(int.from_bytes(header[4:6], "big"))
                self.requests += 1
                unit, tid, pdu = _split("tcp", header + body)
                reply = self.craft(unit, pdu, tid)
                writer.write(reply if isinstance(reply, bytes) else _frame("tcp", reply[0], reply[1], tid))
                await writer.drain()
        except (asyncio.IncompleteReadError, ConnectionError, asyncio.CancelledError):
            pass
        finally:
            writer.close()

    def close(self) -> None:
        self._loop.call_soon_threadsafe(self._loop.stop)
        self._thread.join(5)


@pytest.fixture
def slave():
    made = []

    def make(craft) -> CraftedTcpSlave:
        made.append(CraftedTcpSlave(craft))
        return made[-1]

    yield make
    for s in made:
        s.close()


def _link(port: int) -> ModbusLink:
    return ModbusLink(LinkSettings("crafted", "tcp", port=port, timeout_s=0.3, retries=0))


def test_tcp_a_good_reply_over_a_socket_is_taken(slave):
    s = slave(lambda unit, pdu, tid: (unit, b"\x03\x04\x12\x34\x56\x78"))
    link = _link(s.port)
    try:
        outcome = link.transact(Transaction(unit=1, function=3, offset=5, count=2), 0)
    finally:
        link.close()
    assert outcome.error == ModbusError.OK and outcome.values == [0x1234, 0x5678]


@pytest.mark.parametrize(
    "reply, code, words",
    [
        ((1, b"\x83\x00"), ModbusError.RESPONSE_INVALID_DATA, "exception code 0"),
        ((1, b"\x04\x02\x12\x34"), ModbusError.RESPONSE_WRONG_FUNCTIONCODE, "function 4 to a function 3 request"),
        ((1, b"\x03\x04\x12\x34\x56\x78"), ModbusError.RESPONSE_INVALID_DATA, "byte count 4 for 1 register"),
        ((1, b"\x03\x02\x12\x34\x56"), ModbusError.RESPONSE_INVALID_DATA, "3 data bytes after a byte count of 2"),
        ((1, b"\x03\x04\x12\x34"), ModbusError.RESPONSE_INVALID_DATA, "byte count 4 for 1 register"),
        ((7, b"\x03\x02\x12\x34"), ModbusError.RESPONSE_WRONG_SLAVE, "unit 7 answered a request to unit 1"),
        (
            lambda tid: (tid + 1).to_bytes(2, "big") + bytes.fromhex("0000 0005 01 03 02 1234"),
            ModbusError.RESPONSE_INVALID_HEADER,
            "in the reply to transaction",
        ),
        (
            lambda tid: tid.to_bytes(2, "big") + bytes.fromhex("0001 0005 01 03 02 1234"),
            ModbusError.RESPONSE_INVALID_PROTOCOL,
            "protocol id 1",
        ),
        (
            lambda tid: tid.to_bytes(2, "big") + bytes.fromhex("0000 0009 01 03 02 1234"),
            ModbusError.RESPONSE_INVALID_HEADER,
            "shorter than its header's length 9",
        ),
    ],
)
def test_tcp_a_bad_reply_over_a_socket_is_an_error_with_its_reason(slave, reply, code, words):
    s = slave(lambda unit, pdu, tid: reply(tid) if callable(reply) else reply)
    link = _link(s.port)
    try:
        outcome = link.transact(Transaction(unit=1, function=3, offset=5, count=1), 0)
    finally:
        link.close()
    assert outcome.error == code and words in outcome.message, outcome.message
    assert outcome.values == []


def test_tcp_a_channel_to_a_slave_that_lies_keeps_its_last_good_values(slave, tmp_path):
    answers = iter([b"\x03\x02\x00\x2a"] + [b"\x83\x00"] * 100)
    s = slave(lambda unit, pdu, tid: (unit, next(answers)))
    st = tmp_path / "p.st"
    st.write_text(PROGRAM)
    cfg = config_from_dict(
        {
            "plc": {"programs": [str(st)]},
            "task": [{"name": "Main", "interval": "10ms", "programs": ["P"]}],
            "modbus": [
                {
                    "name": "crafted",
                    "transport": "tcp",
                    "host": "127.0.0.1",
                    "port": s.port,
                    "timeout": "300ms",
                    "channel": [{**READ_ID6, "unit": 1}],
                }
            ],
        },
        tmp_path / "plant.toml",
    )
    engine = build_engine(cfg, virtual_time=True)
    engine.start()
    try:
        engine.run(duration_ns=15_000_000)
        assert engine.get("%IW0") == 42 and engine.get("P.ok")
        engine.run(duration_ns=50_000_000)
        master = next(d for d in engine.drivers if isinstance(d, ModbusDriver))
        assert master.channels[0].stats.requests >= 3
        assert engine.get("%IW0") == 42
        assert not engine.get("P.ok") and engine.get("P.lastError") == ModbusError.RESPONSE_INVALID_DATA
        assert "exception code 0" in status_line(engine)
    finally:
        engine.stop()


def test_a_slave_that_keeps_lying_is_logged_once_per_interval(plants, tmp_path, caplog):
    """Every failure with a new reason is a log line, rate limited per channel:
    a slave that answers nonsense every 20 ms writes two lines per 10 s."""
    caplog.set_level(logging.INFO, logger="softplc.runtime.io.modbus")
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport="rtu", channels=[READ_ID6]))
    plant.run_ms(30)
    counts = (2 * (k % 5 + 2) for k in range(1_000_000))  # byte counts 4, 6 ... 12 for one register, in turn

    def lie(unit, request, own):
        n = next(counts)
        return unit, bytes([0x03, n]) + bytes(n)

    crafting(plant, "rtu", lie)
    plant.run_ms(12_000)
    failures = plant.master.channels[0].stats.errors
    lines = [r.getMessage() for r in caplog.records if "channel status" in r.getMessage()]
    assert failures > 500 and 2 <= len(lines) <= 4
    assert lines[0].startswith("modbus drives: channel status: unit 1 sent byte count")
    held = sum(int(m.group(1)) for line in lines if (m := re.match(r"suppressed (\d+) ", line)))
    assert held > 0


@pytest.mark.parametrize("transport, code", [("rtu", ModbusError.RESPONSE_CRC_FAIL), ("tcp", None)])
@pytest.mark.parametrize("around", ["after", "before"])
def test_a_good_frame_with_bytes_around_it_is_not_taken(plants, tmp_path, transport, code, around):
    """pymodbus's framer takes a frame out of what came and ignores the rest;
    everything that came is the reply: in RTU the CRC is over all of it (a
    master frames by the line's silence), in TCP the header's length is
    exact (found by the fuzz harness, tests/fuzz/test_modbus.py)."""
    plant = plants(plant_config(tmp_path, PROGRAM, program="P", transport=transport, channels=[READ_ID6]))
    plant.run_ms(30)
    assert plant["%IW0"] == IDLE and plant["P.ok"]
    server = plant.line.server
    genuine = server.exchange
    server.exchange = lambda frame: (b"\x00" + genuine(frame)) if around == "before" else (genuine(frame) + b"\x00")
    plant.run_ms(150)
    stats = plant.master.channels[0].stats
    assert not stats.ok, "a reply with a stray byte was taken"
    if code is not None:
        assert stats.last_error == code
    assert "bytes around a" in stats.message or "header" in stats.message or "CRC" in stats.message, stats.message
    assert plant["%IW0"] == IDLE
