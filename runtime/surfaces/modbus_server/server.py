"""The Modbus TCP server's thread (in the servers' process:
surfaces/process.py): a pymodbus ModbusTcpServer on its own event loop
whose datastore is the PLC (the snapshot's image for reads, Access for
writes).

What an HMI sees:
  * a read answers from the latest snapshot (taken at the end of a scan at
    most [modbus_server] period ago): the scan never waits for a client;
  * a write is checked at once against [modbus_server] writable (refused:
    exception 02), carried out at the start of the next scan, and answered
    after the snapshot that follows it, so a read after the answer sees the
    value written (unless the program wrote over it in that scan);
  * a request outside the mapping gets exception 02 (ILLEGAL DATA ADDRESS),
    a write the engine does not carry out within WRITE_TIMEOUT_S (a stopped
    engine) exception 04 (SERVER DEVICE FAILURE), a read before the first
    snapshot exception 06 (SERVER DEVICE BUSY);
  * unit = 0 answers every unit id; another unit answers only its own, and
    requests to other ids get no answer (as on a serial line).
"""

from __future__ import annotations

import asyncio
import logging
import socket
import threading
from typing import Any

from pymodbus.constants import ExcCodes
from pymodbus.datastore import ModbusServerContext
from pymodbus.exceptions import NoSuchIdException
from pymodbus.server import ModbusTcpServer

from ...engine.access import AccessDenied
from ...engine.places import PathError
from .mapping import TABLE_OF_FUNCTION, Mapping, OutOfRange

log = logging.getLogger("softplc.surfaces.modbus_server")

SURFACE = "modbus_server"
#: how long a write may wait for its scan (and the snapshot after it) before exception 04
WRITE_TIMEOUT_S = 2.0
#: how long a read may wait for the first snapshot before exception 06
FIRST_SNAPSHOT_S = 1.0
#: how often a waiting request looks at the snapshot hub
POLL_S = 0.002
#: write single coil / register: the answer echoes the value written
_ECHO_FUNCTIONS = (5, 6)


class PlcDatastore(ModbusServerContext):
    """pymodbus's datastore interface, answered by the PLC's snapshots and Access."""

    def __init__(self, surfaces, unit: int) -> None:  # no super(): no pymodbus datastore of its own
        self.old_simulator = True  # pymodbus then calls async_getValues/async_setValues itself
        self.simdevices = []
        self.surfaces = surfaces
        self.hub = surfaces.hub
        self.access = surfaces.access
        self.unit = unit
        self.mapping: Mapping | None = None  # from the first snapshot's image size
        self._echo: dict = {}
        self._refused: set = set()  # addresses whose refusal was logged

    def device_ids(self) -> list:
        return [self.unit]

    def _check_unit(self, device_id: int) -> None:
        if self.unit and device_id != self.unit:
            raise NoSuchIdException(f"unit {device_id}: this PLC answers unit {self.unit}")

    async def _snapshot(self):
        hub = self.hub
        waited = 0.0
        while hub.latest is None and waited < FIRST_SNAPSHOT_S:
            await asyncio.sleep(POLL_S)
            waited += POLL_S
        snap = hub.latest
        if snap is not None and self.mapping is None:
            self.mapping = Mapping(len(snap.image["Q"]))
        return snap

    # ------------------------------------------------------------ reads

    async def async_getValues(self, device_id: int, func_code: int, address: int, count: int = 1):
        self._check_unit(device_id)
        echo = self._echo.pop((device_id, func_code, address), None)
        if echo is not None and func_code in _ECHO_FUNCTIONS:
            return echo
        table = TABLE_OF_FUNCTION.get(func_code)
        if table is None:
            return ExcCodes.ILLEGAL_FUNCTION
        snap = await self._snapshot()
        if snap is None or self.mapping is None:
            return ExcCodes.DEVICE_BUSY
        try:
            return self.mapping.read(snap.image, table, address, count)
        except OutOfRange as exc:
            log.debug("%s", exc)
            return ExcCodes.ILLEGAL_ADDRESS

    # ------------------------------------------------------------ writes

    async def async_setValues(self, device_id: int, func_code: int, address: int, values):
        self._check_unit(device_id)
        table = TABLE_OF_FUNCTION.get(func_code)
        if table is None:
            return ExcCodes.ILLEGAL_FUNCTION
        values = list(values)
        if self.mapping is None and await self._snapshot() is None:
            return ExcCodes.DEVICE_BUSY
        assert self.mapping is not None
        try:
            paths = self.mapping.paths(table, address, len(values))
        except OutOfRange as exc:
            log.debug("%s", exc)
            return ExcCodes.ILLEGAL_ADDRESS
        refusal = self._refuse(table, address, paths)
        if refusal is not None:
            return refusal
        try:
            futures = [self.access.submit("write", p, v, surface=SURFACE) for p, v in zip(paths, values)]
        except (PathError, AccessDenied, ValueError) as exc:  # checked above; an online change in between
            log.warning("modbus_server: %s %d: %s", table, address, exc)
            return ExcCodes.ILLEGAL_VALUE if isinstance(exc, ValueError) else ExcCodes.ILLEGAL_ADDRESS
        code = await self._applied(futures)
        if code is None and func_code in _ECHO_FUNCTIONS:
            self._echo[(device_id, func_code, address)] = values
        return code

    def _refuse(self, table: str, address: int, paths: list):
        """Exception 02 if the surface may not write one of paths (logged once per address)."""
        for offset, path in enumerate(paths):
            try:
                self.access.check("write", path, SURFACE)
            except (PathError, AccessDenied) as exc:
                key = (table, address + offset)
                if key not in self._refused:
                    self._refused.add(key)
                    log.warning("modbus_server: %s %d refused: %s", table, address + offset, exc)
                return ExcCodes.ILLEGAL_ADDRESS
        return None

    async def _applied(self, futures: list):
        """None once every write is in the image and a snapshot was taken
        after it; an exception code if the engine did not get there."""
        hub = self.hub
        seen: list = []  # the snapshot sequence when the last write landed (the scan thread)

        def landed(_future) -> None:
            latest = hub.latest
            seen.append(latest.sequence if latest is not None else 0)
            hub.request()

        futures[-1].add_done_callback(landed)
        try:
            await asyncio.wait_for(asyncio.gather(*(asyncio.wrap_future(f) for f in futures)), WRITE_TIMEOUT_S)
        except TimeoutError:
            log.warning("modbus_server: no scan carried out a write within %.1f s", WRITE_TIMEOUT_S)
            return ExcCodes.DEVICE_FAILURE
        except Exception as exc:  # a write that faulted in the scan
            log.warning("modbus_server: write refused: %s", exc)
            return ExcCodes.ILLEGAL_VALUE
        if not hub.scanning:
            return None  # carried out at once (no scan running): no snapshot to wait for
        waited = 0.0
        while waited < WRITE_TIMEOUT_S and (hub.latest is None or not seen or hub.latest.sequence <= seen[0]):
            await asyncio.sleep(POLL_S)
            waited += POLL_S
        return None


class ModbusServer:
    """The handle ``start`` returns: ``url``, ``port``, ``stop()``."""

    def __init__(self, surfaces, config) -> None:
        self.config = config
        self.datastore = PlcDatastore(surfaces, int(config.options.get("unit", 0)))
        self.host = config.host
        self.port = config.port
        self._loop: asyncio.AbstractEventLoop | None = None
        self._server: ModbusTcpServer | None = None
        self._thread: threading.Thread | None = None

    @property
    def url(self) -> str:
        host = f"[{self.host}]" if ":" in self.host else self.host
        return f"modbus-tcp://{host}:{self.port}"

    def start(self) -> ModbusServer:
        started = threading.Event()
        failure: list = []

        def run() -> None:
            loop = asyncio.new_event_loop()
            self._loop = loop
            asyncio.set_event_loop(loop)
            try:
                loop.run_until_complete(self._serve(started))
            except Exception as exc:  # reported by start() below
                failure.append(exc)
                started.set()
            finally:
                _finish(loop)

        self._thread = threading.Thread(target=run, name="softplc-modbus-server", daemon=True)
        self._thread.start()
        if not started.wait(10) or failure:
            self._thread.join(timeout=5)
            self._thread = None
            if failure and isinstance(failure[0], OSError):
                raise failure[0]
            raise OSError(f"the Modbus server did not start{': ' + str(failure[0]) if failure else ''}")
        return self

    async def _serve(self, started: threading.Event) -> None:
        server = ModbusTcpServer(self.datastore, address=(self.host, self.port), ignore_missing_devices=True)
        self._server = server
        try:
            await server.serve_forever(background=True)
        except RuntimeError:  # pymodbus logs the OSError and says only "could not listen"
            raise _why_not(self.host, self.port) from None
        listener: Any = server.transport
        self.port = listener.sockets[0].getsockname()[1]
        started.set()
        await server.serving

    def stop(self) -> None:
        """Close the listener and every client connection, end the thread."""
        loop, server, thread = self._loop, self._server, self._thread
        if loop is not None and server is not None and thread is not None and thread.is_alive():
            future = asyncio.run_coroutine_threadsafe(server.shutdown(), loop)
            try:
                future.result(timeout=5)
            except Exception as exc:  # already down
                log.debug("modbus_server: shutdown: %s", exc)
        if thread is not None:
            thread.join(timeout=5)
        self._server = self._thread = None


def _finish(loop: asyncio.AbstractEventLoop) -> None:
    """Cancel what the connections left running (a request waiting for a
    scan), then close the loop: no task outlives the server."""
    pending = asyncio.all_tasks(loop)
    for task in pending:
        task.cancel()
    loop.run_until_complete(asyncio.gather(*pending, return_exceptions=True))
    loop.run_until_complete(loop.shutdown_asyncgens())
    loop.close()


def _why_not(host: str, port: int) -> OSError:
    """The OSError binding host:port gives (pymodbus keeps it to its log)."""
    try:
        with socket.create_server((host, port)):
            pass
    except OSError as exc:
        return exc
    return OSError(f"pymodbus could not listen on {host}:{port}")
