"""A PLC with its OPC UA server: the engine scans in a background thread on
the virtual clock (paced, so a client sees its values move), the server
listens on 127.0.0.1 on a free port; everything is stopped after the test."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Awaitable, Callable
from dataclasses import dataclass

import pytest

from softplc.runtime.config.servers import ServerConfig
from softplc.runtime.engine.scan import Engine
from softplc.runtime.surfaces.host import Surfaces

from ...engine.conftest import Scanning, make_engine

#: generous: a loaded machine is slow, a condition met is met at once
TIMEOUT_S = 30.0


@dataclass
class Running:
    engine: Engine
    surfaces: Surfaces
    scan: Scanning

    @property
    def server(self):
        return self.surfaces.handles["opcua"]

    @property
    def url(self) -> str:
        return self.server.url

    def stop(self) -> None:
        self.scan.stop(TIMEOUT_S)
        self.surfaces.stop()
        self.engine.stop()


def opcua_config(writable=(), period_ms: int = 20, **options) -> ServerConfig:
    return ServerConfig(
        key="opcua",
        host="127.0.0.1",
        port=0,
        writable=tuple(writable),
        period_ns=period_ms * 1_000_000,
        options=options,
        where="[opcua] writable",
    )


@pytest.fixture
def running():
    """running(source, tasks, writable=..., **options) -> Running, stopped after the test."""
    made: list[Running] = []

    def factory(source, tasks, writable=(), pace_s: float = 0.002, **options) -> Running:
        engine = make_engine(source, tasks)
        surfaces = Surfaces(engine, {"opcua": opcua_config(writable, **options)})
        surfaces.start()
        r = Running(engine, surfaces, Scanning(engine, pace_s))  # virtual time at a pace a client can follow
        made.append(r)
        r.scan.start()
        return r

    yield factory
    for r in made:
        r.stop()


def client(url: str):
    """An asyncua Client for the tests. Its health probe (a read of the
    server's state every watchdog_intervall, failing the connection after
    as long again) waits as long as a request may: a test's own compile
    of an online change holds the test process's interpreter lock for
    seconds on a loaded machine, and the client's event loop with it."""
    from asyncua import Client

    return Client(url, timeout=TIMEOUT_S, watchdog_intervall=TIMEOUT_S)


async def until(condition: Callable[[], Awaitable], what: str, timeout: float = TIMEOUT_S):
    """The first true result of condition(), polled; fails naming what after timeout."""
    deadline = time.monotonic() + timeout
    while True:
        result = await condition()
        if result:
            return result
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out waiting for {what} (last: {result!r})")
        await asyncio.sleep(0.02)


def run(coro):
    """coro in an event loop of its own, failing after three request timeouts."""
    return asyncio.run(asyncio.wait_for(coro, 3 * TIMEOUT_S))


async def value(client, path: str):
    """The value of the PLC variable at path, read by client."""
    return await client.get_node(f"ns=2;s={path}").read_value()


async def greater(read, than):
    """The awaited read when it is greater than than, else None (for until())."""
    got = await read
    return got if got > than else None
