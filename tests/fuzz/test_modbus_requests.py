"""Requests into the Modbus TCP server (runtime/surfaces/modbus_server), as
a careless or hostile master sends them (issue 31): every function code,
quantities at and past the specification's limits, coil values other than
FF00h/0000h, byte counts that do not match, PDUs cut short or too long,
bytes at random, several requests pipelined in one segment. Every request
gets its answer, in order, with its own transaction id: the normal answer
or the exception the specification gives for what parse() refuses (01 a
function not served, 03 a quantity or structure), else 02 (an address
outside the mapping) or 04; a read answers the count asked. Nothing is
logged with a traceback and the server serves on.
"""

from __future__ import annotations

import socket
import struct

from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.surfaces.host import Surfaces
from softplc.runtime.surfaces.modbus_server import protocol as P

from ..engine.conftest import Scanning, make_engine, task
from ..surfaces.modbus_server.conftest import SRC, server_config
from .support import LogWatch, assert_no_tracebacks, bounded, fuzz, long, short

MBAP = struct.Struct(">HHHB")
#: the mapped addresses of SRC (coils 0.., registers 0.., 1024.. for %MW) and some outside
ADDRESSES = st.sampled_from([0, 2, 3, 4, 5, 8, 10, 1029, 1030, 1100, 9999, 65535]) | st.integers(0, 65535)
COUNTS = st.sampled_from([0, 1, 2, 8, 123, 124, 125, 126, 1968, 1969, 2000, 2001, 65535]) | st.integers(0, 300)


@st.composite
def pdus(draw) -> bytes:
    kind = draw(st.sampled_from(["read", "write1", "writen", "mask", "readwrite", "other", "bytes"]))
    if kind == "read":
        return struct.pack(">BHH", draw(st.sampled_from([1, 2, 3, 4])), draw(ADDRESSES), draw(COUNTS))
    if kind == "write1":
        value = draw(st.sampled_from([0xFF00, 0x0000, 0x1234, 0x00FF, 1]) | st.integers(0, 65535))
        return struct.pack(">BHH", draw(st.sampled_from([5, 6])), draw(ADDRESSES), value)
    if kind == "writen":
        function, count = draw(st.sampled_from([15, 16])), draw(COUNTS)
        right = (count + 7) // 8 if function == 15 else 2 * count
        size = draw(st.sampled_from([right, right, right + 1, max(0, right - 1)])) % 256
        data = draw(st.binary(min_size=size, max_size=size)) if size < 40 else bytes(size)
        return (struct.pack(">BHHB", function, draw(ADDRESSES), count, size) + data)[: P.MAX_PDU]
    if kind == "mask":
        return struct.pack(">BHHH", 22, draw(ADDRESSES), draw(st.integers(0, 65535)), draw(st.integers(0, 65535)))
    if kind == "readwrite":
        count = draw(st.integers(0, 125))
        size = 2 * count
        head = struct.pack(">BHHHHB", 23, draw(ADDRESSES), draw(COUNTS), draw(ADDRESSES), count, size % 256)
        return (head + bytes(size))[: P.MAX_PDU]
    if kind == "other":  # FIFO queue, server id, diagnostics, device identification, no function at all
        code = draw(st.sampled_from([7, 8, 11, 12, 17, 20, 21, 24, 43, 0, 0x41, 0x80, 0xFF]))
        return bytes([code]) + draw(st.binary(max_size=8))
    return draw(st.binary(min_size=1, max_size=P.MAX_PDU))


def recv_exactly(sock: socket.socket, n: int) -> bytes:
    data = b""
    while len(data) < n:
        chunk = sock.recv(n - len(data))
        assert chunk, f"the server closed the connection after {len(data)} of {n} bytes"
        data += chunk
    return data


def expected(pdu: bytes) -> tuple:
    """(what parse() makes of pdu: a Request or a ModbusError)."""
    try:
        return P.parse(pdu), None
    except P.ModbusError as exc:
        return None, exc.code


def check_pipeline(port: int, batch: list) -> list:
    """Send the batch in one segment; judge each answer; the outcomes."""
    outcomes = []
    with bounded("Modbus requests"), socket.create_connection(("127.0.0.1", port), timeout=10) as sock:
        frames = b"".join(MBAP.pack(7000 + i, 0, len(pdu) + 1, 1) + pdu for i, pdu in enumerate(batch))
        sock.sendall(frames)
        for i, pdu in enumerate(batch):
            transaction, protocol, length, unit = MBAP.unpack(recv_exactly(sock, MBAP.size))
            reply = recv_exactly(sock, length - 1)
            what = f"request {i} of {len(batch)}: {pdu[:20].hex(' ')} ({len(pdu)} bytes) -> {reply[:20].hex(' ')}"
            assert (transaction, protocol, unit) == (7000 + i, 0, 1), what
            request, code = expected(pdu)
            if code is not None:
                assert reply == P.exception(pdu[0], code), what
                outcomes.append(f"exception {code:02X}")
                continue
            assert request is not None
            if reply[0] & 0x80:
                assert reply[0] == pdu[0] | 0x80 and reply[1:] in (b"\x02", b"\x04"), what
                outcomes.append(f"exception {reply[1]:02X}")
                continue
            assert reply[0] == pdu[0], what
            if request.function in (1, 2):
                assert reply[1] == (request.count + 7) // 8 == len(reply) - 2, what
            elif request.function in (3, 4, 23):
                assert reply[1] == 2 * request.count == len(reply) - 2, what
            elif request.function in (5, 6, 22):
                assert reply == pdu, what
            outcomes.append("answered")
    return outcomes


def _serve(examples_run) -> None:
    """Run the examples against one PLC and its server; then the server still serves."""
    engine = make_engine(SRC, [task("Main", 10, "Main")])
    surfaces = Surfaces(engine, {"modbus_server": server_config()})
    try:
        surfaces.start()
        scanning = Scanning(engine, pause_s=0).start()
        try:
            port = surfaces.handles["modbus_server"].port
            with LogWatch() as watch:
                examples_run(port)
                assert check_pipeline(port, [struct.pack(">BHH", 3, 0, 3)]) == ["answered"]
            assert_no_tracebacks(watch, "Modbus requests")
        finally:
            scanning.stop()
    finally:
        surfaces.stop()
        engine.stop()


batches = st.lists(pdus(), min_size=1, max_size=5)


def test_modbus_requests_are_each_answered_as_the_specification_says():
    def examples(port: int) -> None:
        @short(60)
        @given(batches)
        def run(batch):
            check_pipeline(port, batch)

        run()

    _serve(examples)


@fuzz
def test_long_modbus_requests(tally, shard):
    counts = tally("requests")

    def examples(port: int) -> None:
        @long("requests", 0.5, shard, per_example=3)
        @given(batches)
        def run(batch):
            outcomes = check_pipeline(port, batch)
            counts.inputs += len(batch)
            counts.update(outcomes)

        run()

    _serve(examples)
