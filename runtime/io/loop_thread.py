"""An asyncio server in a daemon thread of its own, the one way softplc
runs one (the simulated Modbus line's server, the Modbus TCP server, the
OPC UA server):

    runner = LoopThread("softplc-modbus-server")
    runner.start(self._serve, timeout_s=10)   # returns once _serve called ready()
    ...
    runner.call_soon(stopping.set)            # from any thread, into the loop
    runner.join(5)

start() runs serve(ready) in a new event loop and returns once serve has
called ready() (its server listens), raising what serve raised before that,
or TimeoutError. An error after ready() goes to on_error (the thread ends
with it). When serve returns, the tasks it left are cancelled and the loop
is closed, its default executor's thread too (asyncua resolves host names
in it): nothing outlives the server.
"""

from __future__ import annotations

import asyncio
import threading
from collections.abc import Awaitable, Callable, Coroutine
from typing import Any


class LoopThread:
    def __init__(self, name: str, on_error: Callable[[BaseException], None] | None = None) -> None:
        self.name = name
        self.loop: asyncio.AbstractEventLoop | None = None
        self._on_error = on_error
        self._thread: threading.Thread | None = None
        self._ready = threading.Event()
        self._error: BaseException | None = None

    @property
    def alive(self) -> bool:
        return self._thread is not None and self._thread.is_alive()

    def start(self, serve: Callable[[Callable[[], None]], Awaitable[None]], timeout_s: float) -> None:
        loop = self.loop = asyncio.new_event_loop()

        def run() -> None:
            asyncio.set_event_loop(loop)
            try:
                loop.run_until_complete(serve(self._ready.set))
            except BaseException as exc:  # to start(), or to on_error once it listened
                if not self._ready.is_set():
                    self._error = exc
                elif self._on_error is not None:
                    self._on_error(exc)
            finally:
                _finish(loop)
                self._ready.set()

        self._thread = threading.Thread(target=run, name=self.name, daemon=True)
        self._thread.start()
        if not self._ready.wait(timeout_s):
            raise TimeoutError(f"{self.name}: the server did not start within {timeout_s:g} s")
        if self._error is not None:
            self._thread.join()
            raise self._error

    def call_soon(self, callback: Callable[..., Any], *args: Any) -> None:
        """callback(*args) in the loop, from any thread; nothing once the loop has ended."""
        loop = self.loop
        if loop is not None and self.alive and not loop.is_closed():
            loop.call_soon_threadsafe(callback, *args)

    def run(self, coroutine: Coroutine[Any, Any, Any], timeout_s: float) -> Any:
        """The coroutine's result, run in the loop, from another thread."""
        assert self.loop is not None
        return asyncio.run_coroutine_threadsafe(coroutine, self.loop).result(timeout=timeout_s)

    def join(self, timeout_s: float | None = None) -> None:
        if self._thread is not None:
            self._thread.join(timeout_s)


def _finish(loop: asyncio.AbstractEventLoop) -> None:
    """Cancel what the server left running (a request waiting for a scan),
    then close the loop: no task, no executor thread outlives it."""
    pending = asyncio.all_tasks(loop)
    for task in pending:
        task.cancel()
    loop.run_until_complete(asyncio.gather(*pending, return_exceptions=True))
    loop.run_until_complete(loop.shutdown_asyncgens())
    loop.run_until_complete(loop.shutdown_default_executor())
    loop.close()
