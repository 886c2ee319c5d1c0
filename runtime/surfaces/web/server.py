"""Serving the web monitor: uvicorn in a thread of the servers' process (or the PLC's).

    handle = start(surfaces, config)   # returns once the server listens
    handle.url                         # "http://127.0.0.1:8080/"
    handle.stop()                      # event streams ended, server stopped, threads joined

The socket is bound here, in the caller's thread, so a port in use is an
OSError at once (Surfaces.start makes it a SurfaceError naming the section);
uvicorn then serves it in its own daemon thread with its own event loop,
with no signal handlers (the PLC's are softplc run's) and without touching
the process's logging setup.
"""

from __future__ import annotations

import logging
import socket
import threading
import time
from typing import Any

import uvicorn

from ...config.servers import ServerConfig
from ...io.ratelog import PeerLogFilter
from .app import make_app
from .logbuffer import LogBuffer
from .stream import Broadcaster

#: how long start() waits for uvicorn to serve, and stop() for it to end
START_TIMEOUT_S = 10.0
STOP_TIMEOUT_S = 5.0
#: connections and requests at once (the event streams count): more are answered 503 by uvicorn
MAX_CONNECTIONS = 64
#: uvicorn's loggers: what a client's malformed request makes them say is rate limited, one line each
UVICORN_LOGGERS = ("uvicorn", "uvicorn.error", "uvicorn.access", "uvicorn.asgi")


class WebHandle:
    def __init__(self, server: uvicorn.Server, thread: threading.Thread, url: str, broadcaster, logs, quiet) -> None:
        self.quiet: logging.Filter = quiet  # on uvicorn's loggers while the server runs
        self.app: Any = server.config.app  # guard.Guard, its api (app.py _Api) inside
        self.server = server
        self.thread = thread
        self.url = url
        self.broadcaster = broadcaster
        self.logs = logs

    def stop(self) -> None:
        self.broadcaster.close()  # the event streams end: nothing keeps the server up
        for name in UVICORN_LOGGERS:
            logging.getLogger(name).removeFilter(self.quiet)
        self.server.should_exit = True
        self.thread.join(STOP_TIMEOUT_S)
        if self.thread.is_alive():  # a request that will not end: stop waiting for it
            self.server.force_exit = True
            self.thread.join(STOP_TIMEOUT_S)
        self.broadcaster.stop()
        self.logs.detach()


def start(surfaces, config: ServerConfig) -> WebHandle:
    sock = _bind(config.host, config.port)
    # the servers' process has the PLC's records (sent with the snapshots); the PLC's keeps its own
    given: LogBuffer | None = getattr(surfaces, "logs", None)
    own = given is None
    logs = LogBuffer() if given is None else given
    broadcaster = Broadcaster(surfaces, period_s=config.period_ns / 1e9, logs=logs)
    app = make_app(surfaces, config, broadcaster)
    server = uvicorn.Server(
        uvicorn.Config(
            app,
            loop="asyncio",
            http="h11",
            ws="none",
            lifespan="on",
            log_config=None,  # leave the process's logging as softplc run set it
            log_level="warning",
            access_log=False,
            timeout_graceful_shutdown=2,
            limit_concurrency=MAX_CONNECTIONS,
            backlog=MAX_CONNECTIONS,
        )
    )
    quiet = PeerLogFilter()
    for name in UVICORN_LOGGERS:
        logging.getLogger(name).addFilter(quiet)
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, name="softplc-web", daemon=True)
    if own:  # (the servers' process's records reach the PLC's log, and come back from there)
        logs.attach()
    thread.start()
    deadline = time.monotonic() + START_TIMEOUT_S
    while not server.started:
        if not thread.is_alive() or time.monotonic() > deadline:
            server.should_exit = True
            thread.join(STOP_TIMEOUT_S)
            logs.detach()
            for name in UVICORN_LOGGERS:
                logging.getLogger(name).removeFilter(quiet)
            sock.close()
            raise OSError(f"the web server did not start within {START_TIMEOUT_S:g} s")
        time.sleep(0.01)
    port = sock.getsockname()[1]
    host = f"[{config.host}]" if ":" in config.host else config.host
    return WebHandle(server, thread, f"http://{host}:{port}/", broadcaster, logs, quiet)


def _bind(host: str, port: int) -> socket.socket:
    """A listening socket on host:port (0: any free port); OSError when it cannot be had."""
    family, kind, proto, _name, address = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)[0]
    sock = socket.socket(family, kind, proto)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(address)
        sock.listen(MAX_CONNECTIONS)
        sock.setblocking(False)
    except OSError:
        sock.close()
        raise
    return sock
