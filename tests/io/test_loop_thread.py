"""An asyncio server in a thread of its own (io/loop_thread.py), as the
simulated Modbus line, the Modbus TCP server and the OPC UA server run
theirs: start() returns once it listens, raises what stopped it before,
stop leaves no task and no thread behind."""

from __future__ import annotations

import asyncio
import socket

import pytest

from softplc.runtime.io.loop_thread import LoopThread


class EchoServer:
    def __init__(self, port: int = 0) -> None:
        self.port = port
        self.stopping: asyncio.Event | None = None
        self.cancelled = False

    async def serve(self, ready) -> None:
        self.stopping = asyncio.Event()
        server = await asyncio.start_server(self._client, "127.0.0.1", self.port)
        self.port = server.sockets[0].getsockname()[1]
        asyncio.get_running_loop().create_task(self._forever())  # left running when it stops
        ready()
        async with server:
            await self.stopping.wait()

    async def _forever(self) -> None:
        try:
            await asyncio.sleep(3600)
        except asyncio.CancelledError:
            self.cancelled = True
            raise

    async def _client(self, reader, writer) -> None:
        writer.write(await reader.readline())
        await writer.drain()
        writer.close()


def test_it_listens_once_start_returns_and_stop_leaves_nothing_running():
    server, runner = EchoServer(), LoopThread("test-echo")
    runner.start(server.serve, timeout_s=10)
    with socket.create_connection(("127.0.0.1", server.port), timeout=10) as s:
        s.sendall(b"ping\n")
        assert s.makefile().readline() == "ping\n"
    assert server.stopping is not None
    runner.call_soon(server.stopping.set)
    runner.join(10)
    assert not runner.alive
    assert server.cancelled  # the task it left was cancelled, not abandoned
    assert runner.loop is not None and runner.loop.is_closed()
    runner.call_soon(server.stopping.set)  # after the end: nothing, no error


def test_what_stops_it_before_it_listens_is_raised_by_start():
    taken = socket.socket()
    taken.bind(("127.0.0.1", 0))
    taken.listen()
    try:
        runner = LoopThread("test-taken")
        with pytest.raises(OSError):
            runner.start(EchoServer(taken.getsockname()[1]).serve, timeout_s=10)
        assert not runner.alive
    finally:
        taken.close()


def test_a_server_that_never_listens_is_a_timeout():
    stop = asyncio.Event()

    async def never(ready) -> None:
        await stop.wait()

    runner = LoopThread("test-never")
    with pytest.raises(TimeoutError, match="test-never: the server did not start within 0.2 s"):
        runner.start(never, timeout_s=0.2)
    runner.call_soon(stop.set)
    runner.join(10)
    assert not runner.alive


def test_an_error_after_it_listened_goes_to_on_error():
    seen: list = []

    async def fails_later(ready) -> None:
        ready()
        await asyncio.sleep(0)
        raise RuntimeError("the server broke")

    runner = LoopThread("test-later", on_error=seen.append)
    runner.start(fails_later, timeout_s=10)
    runner.join(10)
    assert [str(e) for e in seen] == ["the server broke"]
