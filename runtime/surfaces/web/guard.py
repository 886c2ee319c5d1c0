"""The web server's outer layer: what no request may do, whatever its
route (an ASGI wrapper around the Starlette app, app.py).

  * a body is read here, whole, before the app sees the request, and
    refused with 413 beyond MAX_BODY (from its Content-Length at once, or
    as it comes): a 200 MB POST no longer stalls the scan;
  * a client that goes away while sending its body is no error: nothing is
    answered, nothing logged (it gave a ClientDisconnect traceback);
  * an exception of a request's handling never reaches the log as a
    traceback: one line, rate limited, and a 500 {"error"} to the client
    if nothing was sent yet;
  * ``Rate`` is a token bucket, for what a client may ask only so often.

uvicorn's own loggers get an io/ratelog.py PeerLogFilter (server.py):
their lines about malformed requests are rate limited and one line each.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable

from ...config.values import cut
from ...io.ratelog import RateLimitedLog

#: the largest body taken: a watch of 2,000 paths of 30 characters fits (the page watches
#: what it shows: a hundred or two), and a write of the longest STRING (65,535 characters)
MAX_BODY = 256 * 1024


class Guard:
    def __init__(self, app, limited: RateLimitedLog) -> None:
        self.app = app
        self.limited = limited
        self.dropped = 0  # requests whose client went while sending the body
        self.refused = 0  # bodies refused: too big

    async def __call__(self, scope, receive, send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        sent: list = []

        async def tracked(message) -> None:
            if message["type"] == "http.response.start":
                sent.append(message["status"])
            await send(message)

        body = await _body(scope, receive, tracked)
        if body is None:  # answered already (413, 400), or nobody to answer
            if sent:
                self.refused += 1
            else:
                self.dropped += 1
            return
        replayed: list = []

        async def replay():
            if not replayed:
                replayed.append(True)
                return {"type": "http.request", "body": body, "more_body": False}
            return await receive()  # then what the server says: the client went (http.disconnect)

        try:
            await self.app(scope, replay, tracked)
        except Exception as exc:  # no traceback into the PLC's log: one line, and a 500
            what = " ".join(f"{type(exc).__name__}: {exc}".split())  # one line
            path = scope.get("path", "")
            self.limited.error(None, "web: %s %s: %s", scope.get("method", ""), cut(path), cut(what))
            if not sent:
                await _answer(tracked, 500, f"internal error: {cut(what)}")


async def _body(scope, receive, send) -> bytes | None:
    """The request's body, or None once it was refused (413) or the client went."""
    headers = dict(scope.get("headers") or ())
    length = headers.get(b"content-length")
    if length is not None:
        try:
            declared = int(length)
        except ValueError:
            await _answer(send, 400, "Content-Length: not a number")
            return None
        if declared > MAX_BODY:
            await _answer(send, 413, f"a body of {declared} bytes: at most {MAX_BODY}")
            return None
    chunks: list = []
    size = 0
    while True:
        message = await receive()
        if message["type"] == "http.disconnect":
            return None
        chunk = message.get("body", b"")
        size += len(chunk)
        if size > MAX_BODY:
            await _answer(send, 413, f"a body of more than {MAX_BODY} bytes")
            return None
        chunks.append(chunk)
        if not message.get("more_body", False):
            return b"".join(chunks)


async def _answer(send, status: int, message: str) -> None:
    body = json.dumps({"error": message}).encode()
    headers = [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode())]
    if status == 413:
        headers.append((b"connection", b"close"))  # the rest of the body is not read
    await send({"type": "http.response.start", "status": status, "headers": headers})
    await send({"type": "http.response.body", "body": body})


class Rate:
    """A token bucket: take() is True at most `burst` times at once and
    `per_s` times a second after that. clock: seconds (time.monotonic)."""

    def __init__(self, per_s: float, burst: int, clock: Callable[[], float] = time.monotonic) -> None:
        self.per_s = per_s
        self.burst = burst
        self.clock = clock
        self._tokens = float(burst)
        self._last = clock()
        self.refused = 0

    def take(self) -> bool:
        now = self.clock()
        self._tokens = min(self.burst, self._tokens + max(now - self._last, 0.0) * self.per_s)
        self._last = now
        if self._tokens >= 1:
            self._tokens -= 1
            return True
        self.refused += 1
        return False
