"""The servers' process's side of the pipe to the PLC (surfaces/child.py)."""

from __future__ import annotations

import multiprocessing

import pytest

from softplc.runtime.surfaces.child import _Link
from softplc.runtime.surfaces.pipe import PlcBusy


def test_a_call_the_plc_does_not_answer_in_time_says_so():
    """The web page's online change waited 30 s for a PLC busy compiling on
    a loaded host: a bare TimeoutError reached the page as a 500 with
    "TimeoutError: " and nothing after it. Now a PlcBusy (a TimeoutError:
    the page answers 504) that says what happened; the call is forgotten."""
    plc_end, servers_end = multiprocessing.Pipe()
    link = _Link(servers_end)
    with pytest.raises(PlcBusy, match=r"^the PLC did not answer within 0.2 s: busy, or stopping$"):
        link.call("request", timeout=0.2)
    assert plc_end.recv()[:3] == ("call", 1, "request")  # it was asked, and nobody answered
    assert not link._waiting and not link._done
    plc_end.close()
    servers_end.close()


def test_a_page_asking_a_plc_that_is_gone_gets_503_not_500():
    """The live soak: a GET /api/tree in the half second after a kill -9 of
    the PLC, before its servers' process saw the pipe end, answered 500
    Internal Server Error. The same request over a pipe whose PLC end is
    closed: 503 with why."""
    import asyncio

    import httpx

    from softplc.runtime.surfaces.child import RemoteSurfaces
    from softplc.runtime.surfaces.web.app import make_app
    from softplc.runtime.surfaces.web.stream import Broadcaster

    from .web.conftest import web_config

    plc_end, servers_end = multiprocessing.Pipe()
    plc_end.close()  # the PLC's process is gone
    surfaces = RemoteSurfaces(_Link(servers_end), {}, 0.1)
    app = make_app(surfaces, web_config(), Broadcaster(surfaces, period_s=0.1, logs=surfaces.logs))

    async def ask() -> httpx.Response:
        async with httpx.AsyncClient(transport=httpx.ASGITransport(app=app), base_url="http://127.0.0.1") as client:
            return await client.get("/api/tree", params={"path": "NoSuch.thing", "offset": 0})

    answer = asyncio.run(ask())
    assert answer.status_code == 503
    assert answer.json()["error"].startswith("the PLC is gone")
    servers_end.close()
