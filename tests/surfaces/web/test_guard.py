"""The web server's outer layer (surfaces/web/guard.py) around an
application that fails, served by a real uvicorn: an exception of a
request's handling is a 500 {"error"} and one rate-limited line in the
log, never a traceback (issue 31: an ASGI traceback reached the PLC's log)."""

from __future__ import annotations

import logging
import socket
import threading
import time

import httpx
import pytest
import uvicorn

from softplc.runtime.io.ratelog import RateLimitedLog
from softplc.runtime.surfaces.web.guard import Guard, Rate


async def failing(scope, receive, send) -> None:
    """An ASGI application whose every request fails, some after their answer began."""
    if scope["type"] != "http":
        return
    body = (await receive())["body"]
    if scope["path"] == "/late":
        await send({"type": "http.response.start", "status": 200, "headers": []})
    raise RuntimeError("broken\n" + body.decode() * 1000)


def serve(app) -> tuple:
    sock = socket.socket()
    sock.bind(("127.0.0.1", 0))
    sock.listen(8)
    server = uvicorn.Server(uvicorn.Config(app, log_config=None, lifespan="off", log_level="warning"))
    thread = threading.Thread(target=server.run, kwargs={"sockets": [sock]}, daemon=True)
    thread.start()
    while not server.started:
        time.sleep(0.01)
    return server, thread, f"http://127.0.0.1:{sock.getsockname()[1]}"


def test_a_failing_request_is_a_500_and_one_line_never_a_traceback(caplog):
    logger = logging.getLogger("softplc.web.test")
    server, thread, url = serve(Guard(failing, RateLimitedLog(logger, lambda: 0, burst=3)))
    try:
        with caplog.at_level(logging.INFO), httpx.Client(base_url=url, timeout=10) as http:
            replies = [http.post("/api/x", content=b"x" * 100) for _ in range(30)]
            with pytest.raises(httpx.RemoteProtocolError):  # begun, then failed: the answer is cut
                http.get("/late")
        assert {r.status_code for r in replies} == {500}
        error = replies[0].json()["error"]
        assert error.startswith("internal error: RuntimeError: broken") and len(error) <= 1100
        lines = [r for r in caplog.records if r.levelno >= logging.WARNING]
        ours = [r for r in lines if r.name == "softplc.web.test"]
        assert len(ours) == 3  # the burst, then held back (counted)
        # uvicorn says once that /late's answer did not end (the web server rate limits its lines too)
        assert all(r.exc_info is None and "\n" not in r.getMessage() for r in lines)
    finally:
        server.should_exit = True
        thread.join(10)


def test_a_rate_gives_its_burst_then_its_rate():
    now = [0.0]
    rate = Rate(per_s=2.0, burst=3, clock=lambda: now[0])
    assert [rate.take() for _ in range(5)] == [True, True, True, False, False]
    now[0] = 1.0
    assert [rate.take() for _ in range(3)] == [True, True, False]
    now[0] = 0.5  # a clock that went back gives nothing
    assert rate.take() is False and rate.refused == 4
