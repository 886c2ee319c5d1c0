"""The Modbus TCP server's thread (in the servers' process:
surfaces/process.py): an asyncio server on its own event loop whose data
is the PLC (the snapshot's image for reads, Access for writes). The
protocol itself is protocol.py.

What an HMI sees:
  * a read answers from the latest snapshot (taken at the end of a scan at
    most [modbus_server] period ago): the scan never waits for a client;
  * a write is checked at once against [modbus_server] writable (refused:
    exception 02), carried out at the start of the next scan (the registers
    of one request in the same scan: a REAL in two registers is never seen
    half written), and answered after the snapshot that follows it, so a
    read after the answer sees the value written (unless the program wrote
    over it in that scan);
  * a request outside the mapping gets exception 02 (ILLEGAL DATA ADDRESS),
    a write the engine does not carry out within WRITE_TIMEOUT_S (a stopped
    engine) exception 04 (SERVER DEVICE FAILURE), a read before the first
    snapshot exception 06 (SERVER DEVICE BUSY);
  * unit = 0 answers every unit id; another unit answers only its own, and
    requests to other ids get no answer (as on a serial line);
  * requests sent one after the other without waiting (pipelined) are
    answered in order, each with its own transaction id: a connection's
    requests are read one at a time, the next once the last is answered, so
    what a client sends ahead waits in the socket's buffers (TCP's own
    back-pressure), never in the server's memory.

Limits: at most [modbus_server] max_connections connections (one more is
taken when the oldest idle one has been quiet IDLE_S: it is closed; else
the newcomer is), a request's rest within FRAME_TIMEOUT_S of its header,
an answer the client reads within SEND_TIMEOUT_S; a header whose length
cannot be a Modbus request (the framing is lost) closes the connection.
What a peer makes the server log is rate limited (io/ratelog.py).
"""

from __future__ import annotations

import asyncio
import logging
import struct
import time
from collections.abc import Callable

from ...config.values import cut
from ...engine.access import AccessDenied, denied
from ...engine.places import PathError
from ...io.loop_thread import LoopThread
from ...io.ratelog import RateLimitedLog
from . import protocol as P
from .mapping import COILS, DISCRETE_INPUTS, HOLDING_REGISTERS, INPUT_REGISTERS, Mapping, OutOfRange

log = logging.getLogger("softplc.surfaces.modbus_server")

SURFACE = "modbus_server"
#: how long a write may wait for its scan (and the snapshot after it) before exception 04
WRITE_TIMEOUT_S = 2.0
#: how long a read may wait for the first snapshot before exception 06
FIRST_SNAPSHOT_S = 1.0
#: how often a waiting request looks at the snapshot hub
POLL_S = 0.002
#: connections at once unless [modbus_server] max_connections says otherwise
MAX_CONNECTIONS = 32
#: a connection quiet this long gives its place to a new one when all are taken
IDLE_S = 10.0
#: the rest of a request is due this long after its header
FRAME_TIMEOUT_S = 5.0
#: an answer the client does not read within this long closes the connection
SEND_TIMEOUT_S = 10.0

_MBAP = struct.Struct(">HHHB")  # transaction id, protocol id (0), length (unit id + PDU), unit id
_TABLES = {
    P.READ_COILS: COILS,
    P.READ_DISCRETE_INPUTS: DISCRETE_INPUTS,
    P.READ_HOLDING: HOLDING_REGISTERS,
    P.READ_INPUT: INPUT_REGISTERS,
    P.READ_WRITE: HOLDING_REGISTERS,
    P.WRITE_COIL: COILS,
    P.WRITE_COILS: COILS,
}


class PlcDatastore:
    """The requests' data: the PLC's snapshots for reads, Access for writes."""

    def __init__(self, surfaces, limited: RateLimitedLog) -> None:
        self.hub = surfaces.hub
        self.access = surfaces.access
        self.limited = limited
        self.mapping: Mapping | None = None  # from the first snapshot's image size

    async def execute(self, pdu: bytes) -> bytes:
        """The answer PDU to a request PDU (an exception answer included)."""
        try:
            request = P.parse(pdu)
            return P.answer(request, pdu, await self._carry_out(request))
        except P.ModbusError as exc:
            return P.exception(pdu[0] if pdu else 0, exc.code)

    async def _carry_out(self, request: P.Request) -> list | None:
        f = request.function
        if f == P.MASK_WRITE:
            snap = await self._snapshot()
            current = self._read(snap, HOLDING_REGISTERS, request.write_address, 1)[0]
            value = P.masked(current, request.and_mask, request.or_mask)
            await self._write(HOLDING_REGISTERS, request.write_address, [value])
            return None
        if request.values:
            await self._write(_TABLES.get(f, HOLDING_REGISTERS), request.write_address, list(request.values))
        if not request.reads:
            return None
        return self._read(await self._snapshot(), _TABLES[f], request.address, request.count)

    # ------------------------------------------------------------ reads

    async def _snapshot(self):
        hub = self.hub
        waited = 0.0
        while hub.latest is None and waited < FIRST_SNAPSHOT_S:
            await asyncio.sleep(POLL_S)
            waited += POLL_S
        snap = hub.latest
        if snap is None:
            raise P.ModbusError(P.SERVER_DEVICE_BUSY, "no snapshot yet")
        if self.mapping is None:
            self.mapping = Mapping(len(snap.image["Q"]))
        return snap

    def _read(self, snap, table: str, address: int, count: int) -> list:
        assert self.mapping is not None
        try:
            return self.mapping.read(snap.image, table, address, count)
        except OutOfRange as exc:
            raise P.ModbusError(P.ILLEGAL_DATA_ADDRESS, str(exc)) from None

    # ------------------------------------------------------------ writes

    async def _write(self, table: str, address: int, values: list) -> None:
        if self.mapping is None:
            await self._snapshot()
        assert self.mapping is not None
        try:
            paths = self.mapping.paths(table, address, len(values))
        except OutOfRange as exc:
            raise P.ModbusError(P.ILLEGAL_DATA_ADDRESS, str(exc)) from None
        permission = self.access.permissions.get(SURFACE)
        for offset, path in enumerate(paths):  # Access.check's verdict, asked here: no call to the PLC
            refusal = denied("write", path, SURFACE, permission)
            if refusal is not None:
                self.limited.warning(
                    ("refused", table, address + offset),
                    "modbus_server: %s %d refused: %s",
                    table,
                    address + offset,
                    refusal,
                )
                raise P.ModbusError(P.ILLEGAL_DATA_ADDRESS)
        try:  # a call to the PLC (a pipe's round trip): in a thread, the other connections go on
            future = await asyncio.to_thread(
                self.access.submit_many, "write", list(zip(paths, values)), surface=SURFACE
            )
        except (PathError, AccessDenied) as exc:  # an online change in between
            self.limited.warning(("refused", table), "modbus_server: %s %d: %s", table, address, exc)
            raise P.ModbusError(P.ILLEGAL_DATA_ADDRESS) from None
        except ValueError as exc:
            self.limited.warning(("value", table), "modbus_server: %s %d: %s", table, address, exc)
            raise P.ModbusError(P.ILLEGAL_DATA_VALUE) from None
        except Exception as exc:  # the PLC is gone, or does not answer
            self.limited.warning(("failed", table), "modbus_server: %s %d: %s", table, address, cut(str(exc)))
            raise P.ModbusError(P.SERVER_DEVICE_FAILURE) from None
        await self._applied(future)

    async def _applied(self, future) -> None:
        """Once the writes are in the image and a snapshot was taken after
        them; exception 04 if the engine did not get there."""
        hub = self.hub
        seen: list = []  # the snapshot sequence when the writes landed (the scan thread)

        def landed(_future) -> None:
            latest = hub.latest
            seen.append(latest.sequence if latest is not None else 0)
            hub.request()

        future.add_done_callback(landed)
        try:
            await asyncio.wait_for(asyncio.wrap_future(future), WRITE_TIMEOUT_S)
        except TimeoutError:
            self.limited.warning("timeout", "modbus_server: no scan carried out a write within %.1f s", WRITE_TIMEOUT_S)
            raise P.ModbusError(P.SERVER_DEVICE_FAILURE) from None
        except Exception as exc:  # a write that faulted in the scan
            self.limited.warning("fault", "modbus_server: write refused: %s", cut(str(exc)))
            raise P.ModbusError(P.SERVER_DEVICE_FAILURE) from None
        if not hub.scanning:
            return  # carried out at once (no scan running): no snapshot to wait for
        waited = 0.0
        while waited < WRITE_TIMEOUT_S and (hub.latest is None or not seen or hub.latest.sequence <= seen[0]):
            await asyncio.sleep(POLL_S)
            waited += POLL_S


class _Connection:
    def __init__(self, writer: asyncio.StreamWriter) -> None:
        self.writer = writer
        self.task = asyncio.current_task()
        self.quiet_since = time.monotonic()
        self.busy = False


class ModbusServer:
    """The handle ``start`` returns: ``url``, ``port``, ``stop()``."""

    def __init__(self, surfaces, config) -> None:
        self.config = config
        self.limited = RateLimitedLog(log)
        self.datastore = PlcDatastore(surfaces, self.limited)
        self.unit = int(config.options.get("unit", 0))
        self.max_connections = int(config.options.get("max_connections") or MAX_CONNECTIONS)
        self.host = config.host
        self.port = config.port
        self.connections: list[_Connection] = []
        self.refused = 0  # connections closed at once: all places taken
        self._runner: LoopThread | None = None
        self._server: asyncio.Server | None = None
        self._stopping: asyncio.Event | None = None

    @property
    def url(self) -> str:
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"modbus-tcp://{host}:{self.port}"

    def start(self) -> ModbusServer:
        """Listening (OSError when it cannot: the port taken, a start that
        timed out)."""
        runner = self._runner = LoopThread("softplc-modbus-server")
        try:
            runner.start(self._serve, timeout_s=10)
        except OSError:
            runner.join(timeout_s=5)
            raise
        except Exception as exc:
            raise OSError(f"the Modbus server did not start: {exc}") from exc
        return self

    async def _serve(self, ready: Callable[[], None]) -> None:
        self._stopping = asyncio.Event()
        server = await asyncio.start_server(self._client, self.host, self.port, limit=P.MAX_PDU + _MBAP.size)
        self._server = server
        self.port = server.sockets[0].getsockname()[1]
        ready()
        async with server:
            await self._stopping.wait()
        for conn in list(self.connections):
            conn.writer.close()

    # ------------------------------------------------------------ connections

    async def _client(self, reader: asyncio.StreamReader, writer: asyncio.StreamWriter) -> None:
        if len(self.connections) >= self.max_connections and not self._make_room():
            self.refused += 1
            self.limited.warning(
                "full", "modbus_server: %d connections already: one more refused", self.max_connections
            )
            writer.close()
            return
        conn = _Connection(writer)
        self.connections.append(conn)
        try:
            await self._requests(conn, reader)
        except (asyncio.IncompleteReadError, ConnectionError, TimeoutError, asyncio.CancelledError):
            pass  # the client went, stalled or was closed to make room
        except Exception as exc:  # never a traceback from a peer's request
            self.limited.error("error", "modbus_server: a connection ended: %s: %s", type(exc).__name__, cut(str(exc)))
        finally:
            if conn in self.connections:  # else closed to make room
                self.connections.remove(conn)
            writer.close()

    def _make_room(self) -> bool:
        """Close the connection quiet longest, if it has been IDLE_S; True if one was."""
        idle = [c for c in self.connections if not c.busy]
        if not idle:
            return False
        oldest = min(idle, key=lambda c: c.quiet_since)
        if time.monotonic() - oldest.quiet_since < IDLE_S:
            return False
        self.limited.info("evicted", "modbus_server: the connection idle longest closed for a new one")
        oldest.writer.close()
        if oldest.task is not None:
            oldest.task.cancel()
        self.connections.remove(oldest)
        return True

    async def _requests(self, conn: _Connection, reader: asyncio.StreamReader) -> None:
        """One request after the other, each answered before the next is read."""
        writer = conn.writer
        while True:
            header = await reader.readexactly(_MBAP.size)
            transaction, protocol, length, unit = _MBAP.unpack(header)
            if not 2 <= length <= P.MAX_PDU + 1:  # no function code, or more than an ADU holds
                self.limited.warning("framing", "modbus_server: a header of length %d: connection closed", length)
                return
            conn.busy = True
            pdu = await asyncio.wait_for(reader.readexactly(length - 1), FRAME_TIMEOUT_S)
            if protocol == 0 and (not self.unit or unit == self.unit):  # others: no answer
                reply = await self.datastore.execute(pdu)
                writer.write(_MBAP.pack(transaction, 0, len(reply) + 1, unit) + reply)
                await asyncio.wait_for(writer.drain(), SEND_TIMEOUT_S)
            conn.busy = False
            conn.quiet_since = time.monotonic()
            self.limited.flush()

    def stop(self) -> None:
        """Close the listener and every client connection, end the thread
        (what the connections left running is cancelled: LoopThread)."""
        runner, stopping = self._runner, self._stopping
        if runner is not None:
            if stopping is not None:
                runner.call_soon(stopping.set)
            runner.join(timeout_s=5)
        self._server = self._runner = None
