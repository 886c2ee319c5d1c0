"""A running PLC with its web monitor, for the web tests: the engine scans
in a thread of its own (virtual time, paced so that it does not take a
whole core, or the real clock), the server listens on a free port of
127.0.0.1, and everything is stopped and checked for leftover threads at
the end."""

from __future__ import annotations

import threading

import httpx
import pytest

from softplc.runtime.config.servers import ServerConfig
from softplc.runtime.surfaces.host import Surfaces
from softplc.runtime.surfaces.pipe import OWN_PROCESS
from softplc.testing import PLC

from ...engine.conftest import Scanning, wait_until

PLANT = """
TYPE E_Mode : (Idle, Run, Hold); END_TYPE
TYPE S_Point : STRUCT x : INT; y : REAL; END_STRUCT END_TYPE

VAR_GLOBAL
    G_count : DINT;
    G_crash : BOOL;
    G_zero : INT;
    G_big : ARRAY[0..999] OF INT;
    {attribute 'hide'}
    G_internal : INT;
END_VAR

PROGRAM Main
VAR
    n : DINT;
    setpoint : REAL := 1.5;
    enable : BOOL := TRUE;
    mode : E_Mode := Idle;
    point : S_Point;
    timer : TON;
    locked : INT := 7;
    quotient : INT;
    {attribute 'hide'}
    scratch : INT;
END_VAR
IF enable THEN n := n + 1; END_IF;
timer(IN := enable, PT := T#1s);
G_count := G_count + 1;
IF G_crash THEN quotient := 10 / G_zero; END_IF;
END_PROGRAM
"""

#: what the web page of the tests may change: not Main.locked
WRITABLE = ("Main.n", "Main.setpoint", "Main.enable", "Main.mode", "Main.point", "G_*")


def web_config(writable=WRITABLE, period_ms: int = 100) -> ServerConfig:
    return ServerConfig("web", "127.0.0.1", 0, tuple(writable), period_ms * 1_000_000, where="[web] writable")


class Web:
    """A PLC, its surfaces with the web server (in the servers' process, or in
    the PLC's for a test that reaches into the server's state), the scan
    thread and an HTTP client."""

    def __init__(self, plc: PLC, config: ServerConfig, pause_s: float, in_process: bool = False) -> None:
        self.plc = plc
        self.engine = plc.engine
        self.surfaces = Surfaces(plc.engine, {"web": config}, own_process=() if in_process else OWN_PROCESS)
        self.surfaces.start()
        self.url = self.surfaces.urls["web"]
        self.scan = Scanning(plc.engine, pause_s).start()
        self.http = httpx.Client(base_url=self.url, timeout=10)

    def post(self, op: str, **body) -> httpx.Response:
        return self.http.post(f"/api/{op}", json=body)

    def wait_for(self, condition, what: str, timeout: float = 10.0):
        """Wait until condition() is true (its value), checking often; fail naming what."""
        return wait_until(condition, what, timeout, poll_s=0.02)

    def close(self) -> None:
        self.http.close()
        try:
            self.scan.stop()
        finally:
            self.surfaces.stop()
            self.plc.stop()


def _no_server_threads() -> list:
    return [t.name for t in threading.enumerate() if t.name.startswith("softplc-web")]


@pytest.fixture
def web_plc():
    """web_plc(plc=None, config=None, pause_s=0.002, in_process=False) -> Web; PLANT in virtual
    time unless plc is given; the web server in the servers' process unless in_process."""
    made: list[Web] = []

    def make(
        plc: PLC | None = None, config: ServerConfig | None = None, pause_s: float = 0.002, in_process: bool = False
    ) -> Web:
        web = Web(plc if plc is not None else PLC.from_st(PLANT), config or web_config(), pause_s, in_process)
        made.append(web)
        return web

    yield make
    for web in made:
        web.close()
    assert _no_server_threads() == [], "the web server left threads running"
