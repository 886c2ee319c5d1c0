"""Starting and stopping the servers of a configuration ([web], [opcua],
[modbus_server], config/servers.py) around one SnapshotHub and one Access.

    surfaces = Surfaces(engine, {"web": cfg.sections["web"], ...})
    surfaces.start()      # each server in its own thread; the scan never waits for one
    surfaces.urls         # {"web": "http://127.0.0.1:8080/", ...}
    surfaces.stop()

A server module (surfaces/<key>/ or surfaces/<key>.py) offers
``start(surfaces, config) -> handle``: the handle has ``url`` and
``stop()``. Modules are imported only when their section is present, so a
PLC without a web page does not load a web framework.

The servers run in a process of their own (process.py, child.py): they
publish, poll and encode thousands of values a second, and in the PLC's
process that work would hold the interpreter lock the scan needs. A server
reaches the PLC only through ``hub`` (snapshots), ``access`` (writes) and
``call`` (a function of its own run with the PLC's surfaces, such as the
OPC UA server's walk of the program or the web page's restart and online
change), which work the same in both processes: ``own_process`` names the
servers started in the servers' process (by default all of them; a test
that reaches into a server's state starts it in the PLC's).
"""

from __future__ import annotations

import importlib
import logging
from typing import Any

from ..config.servers import ServerConfig
from ..engine.access import Access, Permission
from ..engine.snapshot import SnapshotHub
from .pipe import OWN_PROCESS, SERVERS, start_failure
from .process import ProcessError, SurfaceProcess

log = logging.getLogger("softplc.surfaces")


class SurfaceError(Exception):
    """A server could not start (its port taken, a bad certificate ...): the message says which and why."""


class Surfaces:
    def __init__(self, engine, servers: dict, period_s: float = 0.1, own_process=OWN_PROCESS) -> None:
        self.engine = engine
        self.own_process = frozenset(own_process)
        self.configs: dict[str, ServerConfig] = {k: v for k, v in servers.items() if v is not None}
        periods = [c.period_ns / 1e9 for c in self.configs.values()]
        self.hub = SnapshotHub(engine, period_s=min([period_s, *periods]))
        self.access = Access(engine, {k: Permission(tuple(c.writable), where=c.where) for k, c in self.configs.items()})
        self.handles: dict[str, Any] = {}
        #: softplc run's OnlineChange, if on: what the web page's "Online change" button calls
        self.online_change: Any = None
        self.process: SurfaceProcess | None = None  # the servers' process, when one runs

    @property
    def urls(self) -> dict:
        return {key: handle.url for key, handle in self.handles.items()}

    def call(self, function, *args, timeout: float | None = None) -> Any:
        """function(self, *args): a server's function run with the PLC's
        surfaces (child.py's RemoteSurfaces sends it here; in this process
        it is called at once, and timeout means nothing)."""
        return function(self, *args)

    def start(self) -> None:
        for key, config in self.configs.items():
            if config.public:
                log.warning("%s listens on %s:%d, reachable from the network", key, config.host, config.port)
        apart = {k: c for k, c in self.configs.items() if k in self.own_process}
        if apart:
            self.process = SurfaceProcess(self, apart)
            try:
                self.handles.update(self.process.start())
            except ProcessError as exc:
                self.process.stop()  # its threads too
                self.process = None
                raise SurfaceError(str(exc)) from None
            for key, handle in self.handles.items():
                log.info("%s: %s", key, handle.url)
        for key, config in self.configs.items():
            if key in apart:
                continue
            module = importlib.import_module(SERVERS[key], __package__)
            try:
                self.handles[key] = module.start(self, config)
            except OSError as exc:
                self.stop()
                raise SurfaceError(f"[{key}] {start_failure(config.host, config.port, exc)}") from None
            log.info("%s: %s", key, self.handles[key].url)

    def stop(self) -> None:
        for key, handle in reversed(list(self.handles.items())):
            try:
                handle.stop()
            except Exception as exc:  # one server's trouble does not keep the others running
                log.error("%s: stopping: %s", key, exc)
        self.handles.clear()
        if self.process is not None:
            self.process.stop()
            self.process = None
