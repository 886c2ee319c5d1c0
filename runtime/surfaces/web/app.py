"""The web monitor's ASGI application (Starlette): the page, its files and
its JSON API. Every read goes through the SnapshotHub (stream.py), every
change through the one Access with the [web] permissions.

    GET  /                     the page (static/index.html, app.js, style.css: no CDN, no build)
    GET  /api/info             what the page needs to know once: writable patterns, online change ...
    GET  /api/tree?path=&offset=   one level of the variable tree (tree.py)
    POST /api/watch            {"client", "paths"}: the values that client's stream sends
    GET  /api/events?client=   its server-sent events (stream.py)
    POST /api/write            {"path", "value"}   once, at the next scan
    POST /api/force            {"path", "value"}   held until unforced
    POST /api/unforce          {"path"}
    POST /api/restart          restart the tasks a runtime fault stopped
    POST /api/online-change    compile the ST files and swap them in (softplc run only)

An error is {"error": message} with the status saying what kind: 400 a
value the type cannot hold, 403 a variable [web] writable does not cover,
404 no such variable, 409 unforce of a variable not forced (or an online
change under way), 413 a body over guard.MAX_BODY or a watch of more than
MAX_WATCHED paths, 429 watches asked faster than WATCH_RATE, 503 more than
MAX_CLIENTS event streams (or MAX_CONNECTIONS requests at once: uvicorn's
limit, or the PLC's process gone: killed, or stopping, child.PlcGone),
504 no scan took the change in time, or the PLC did not answer
a call in time (pipe.PlcBusy: busy, or stopping); restart and online-change
answer 403 when [web] control is false (a page that watches and writes,
and no more). A value echoed in a message is cut. A POST must be JSON
(Content-Type application/json): a page of another site cannot send one
without the browser asking first (a CORS preflight, which this server does
not grant).
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import re
from pathlib import Path
from typing import Any

from starlette.applications import Starlette
from starlette.middleware import Middleware
from starlette.middleware.trustedhost import TrustedHostMiddleware
from starlette.requests import Request
from starlette.responses import FileResponse, JSONResponse, Response, StreamingResponse
from starlette.routing import Mount, Route
from starlette.staticfiles import StaticFiles

from ...config.servers import ServerConfig
from ...config.values import cut
from ...engine.access import AccessDenied
from ...engine.places import PathError
from ...engine.values import shown, without_lone_surrogates
from ...io.ratelog import RateLimitedLog
from ..pipe import CALL_TIMEOUT_S
from . import plc
from .guard import Guard, Rate
from .stream import MAX_CLIENTS, Broadcaster, log

STATIC = Path(__file__).parent / "static"
SURFACE = "web"
#: how long a write, force or unforce waits for the scan that applies it
APPLY_TIMEOUT_S = 5.0
#: how long the page waits for an online change's report: a big project's compile on a slow host
ONLINE_CHANGE_TIMEOUT_S = 300.0
_CLIENT = re.compile(r"^[A-Za-z0-9_-]{1,64}$")
#: paths one watch may name (the page watches what it shows: a level of the tree, 100 elements
#: of an array at a time, and its trend)
MAX_WATCHED = 2000
#: watches a second over all pages (and WATCH_BURST at once): each makes the snapshots'
#: layout again and asks for a snapshot, and a client posting them in a loop loaded the scan
WATCH_RATE, WATCH_BURST = 20.0, 40


def make_app(surfaces, config: ServerConfig, broadcaster: Broadcaster) -> Guard:
    """The application uvicorn serves: the routes inside the Guard (guard.py)."""
    api = _Api(surfaces, config, broadcaster)

    @contextlib.asynccontextmanager
    async def lifespan(_app):
        broadcaster.start(asyncio.get_running_loop())
        try:
            yield
        finally:
            broadcaster.stop()

    routes = [
        Route("/", api.index),
        Route("/api/info", api.info),
        Route("/api/tree", api.tree),
        Route("/api/watch", api.watch, methods=["POST"]),
        Route("/api/events", api.events),
        Route("/api/{op:str}", api.change, methods=["POST"]),
        Mount("/static", app=StaticFiles(directory=STATIC), name="static"),
    ]
    middleware = []
    if not config.public:  # a page of another site reaching 127.0.0.1 by a name of its own (DNS rebinding)
        middleware.append(Middleware(TrustedHostMiddleware, allowed_hosts=["127.0.0.1", "localhost"]))
    limited = RateLimitedLog(log, burst=3)

    async def busy(request: Request, exc: Exception) -> Response:
        """A call the PLC did not answer in time (PlcBusy): 504 and why."""
        limited.warning(("busy",), "web: %s %s: %s", request.method, cut(request.url.path), exc)
        return _error(504, str(exc) or "the PLC did not answer in time")

    async def gone(request: Request, exc: Exception) -> Response:
        """The PLC's process ended while a request waited for it (child.PlcGone,
        a ConnectionError: killed, stopping): 503 and why, never a 500."""
        limited.warning(("gone",), "web: %s %s: %s", request.method, cut(request.url.path), exc)
        return _error(503, str(exc) or "the PLC is gone")

    handlers = {TimeoutError: busy, ConnectionError: gone}
    app = Starlette(routes=routes, middleware=middleware, lifespan=lifespan, exception_handlers=handlers)
    guard = Guard(app, limited)
    guard.api = api  # type: ignore[attr-defined]  # the tests reach its rates and limits
    return guard


class _Json(JSONResponse):
    """A JSON answer whose text holds no lone surrogate: U+FFFD in its place,
    as the OPC UA server publishes one. A path a client sent ("\\ud800" in
    its JSON) comes back in the answer's errors, and UTF-8 cannot encode it
    (Starlette's JSONResponse failed: a 500)."""

    def render(self, content: Any) -> bytes:
        text = json.dumps(content, ensure_ascii=False, allow_nan=False, separators=(",", ":"))
        return without_lone_surrogates(text).encode("utf-8")


def _error(status: int, message: str) -> JSONResponse:
    return _Json({"error": cut(message)}, status_code=status)


class _EventStream(StreamingResponse):
    """A page's event stream, whose slot (Broadcaster.open) is given back
    however the response ends, even before its first byte."""

    def __init__(self, broadcaster: Broadcaster, client: str, token: object, headers: dict) -> None:
        super().__init__(broadcaster.events(client), media_type="text/event-stream", headers=headers)
        self.release = lambda: broadcaster.close_stream(client, token)

    async def __call__(self, scope, receive, send) -> None:
        try:
            await super().__call__(scope, receive, send)
        finally:
            self.release()


class _Api:
    """The routes. What they need of the PLC they ask through the surfaces
    (plc.py's functions, the hub, the one Access): the same in the servers'
    process as in the PLC's. A call that waits for the PLC's answer is made
    in a worker thread: the event loop keeps serving the other pages."""

    def __init__(self, surfaces, config: ServerConfig, broadcaster: Broadcaster) -> None:
        self.surfaces = surfaces
        self.config = config
        self.broadcaster = broadcaster
        self.access = surfaces.access
        self.watch_rate = Rate(WATCH_RATE, WATCH_BURST)
        self.changing = False  # an online change asked by a page is under way

    async def _ask(self, function, *args, timeout: float = CALL_TIMEOUT_S) -> Any:
        """function(the PLC's surfaces, *args), run in the PLC's process, from
        a worker thread; PlcBusy (504) when it does not answer within timeout."""
        return await asyncio.to_thread(self.surfaces.call, function, *args, timeout=timeout)

    async def index(self, _request: Request) -> Response:
        return FileResponse(STATIC / "index.html")

    async def info(self, _request: Request) -> Response:
        plc_info = await self._ask(plc.info)
        return _Json(
            {
                "writable": list(self.config.writable),
                "period_s": self.config.period_ns / 1e9,
                "online_change": self.control and plc_info["online_change"],
                "control": self.control,
                "tasks": plc_info["tasks"],
            }
        )

    def tree(self, request: Request) -> Response:  # sync: Starlette runs it in a worker thread
        path = request.query_params.get("path", "")
        try:
            offset = int(request.query_params.get("offset", "0"))
            return _Json(self.surfaces.call(plc.tree_level, path, offset))
        except PathError as exc:
            return _error(404, str(exc))
        except ValueError as exc:
            return _error(400, f"offset: {exc}")

    async def watch(self, request: Request) -> Response:
        body = await _json(request)
        if isinstance(body, Response):
            return body
        client, paths = body.get("client"), body.get("paths")
        if not isinstance(client, str) or not _CLIENT.match(client):
            return _error(400, "client: a name of letters, digits, - and _ (the page makes one)")
        if not isinstance(paths, list) or not all(isinstance(p, str) for p in paths):
            return _error(400, 'paths: a list of variable paths such as ["Motor.state"]')
        if len(paths) > MAX_WATCHED:
            return _error(413, f"{len(paths)} paths: a page watches at most {MAX_WATCHED}")
        if not self.watch_rate.take():
            return _error(429, f"more than {WATCH_RATE:g} watches a second: wait and send it again")
        good, errors = await self.broadcaster.watch(client, paths)
        return _Json({"paths": good, "errors": errors})

    async def events(self, request: Request) -> Response:
        client = request.query_params.get("client", "")
        if not _CLIENT.match(client):
            return _error(400, "client: a name of letters, digits, - and _ (the page makes one)")
        token = self.broadcaster.open(client)  # the slot taken now: a thousand at once do not all pass
        if token is None:
            return _error(503, f"{MAX_CLIENTS} pages are open already; close one")
        headers = {"Cache-Control": "no-store", "X-Accel-Buffering": "no"}
        return _EventStream(self.broadcaster, client, token, headers)

    async def change(self, request: Request) -> Response:
        op = request.path_params["op"]
        if op == "restart":
            return await self.restart(request)
        if op == "online-change":
            return await self.online_change(request)
        if op not in ("write", "force", "unforce"):
            return _error(404, f"no operation {shown(op)} (write, force, unforce, restart, online-change)")
        body = await _json(request)
        if isinstance(body, Response):
            return body
        path = body.get("path")
        try:
            if not isinstance(path, str):
                raise PathError(f"path: a variable path such as 'Motor.Auto', not {shown(path)}")
            # a refusal first, whatever the value
            declared, value = await self._ask(plc.checked, op, path, SURFACE, "value" in body, body.get("value"))
            future = await asyncio.to_thread(self.access.submit, op, declared, value, surface=SURFACE)
            # shielded: a page that goes away does not cancel a change the scan is to apply
            done = await asyncio.wait_for(asyncio.shield(asyncio.wrap_future(future)), APPLY_TIMEOUT_S)
        except AccessDenied as exc:
            return _error(403, str(exc))
        except PathError as exc:
            return _error(404, str(exc))
        except plc.NotForced as exc:
            return _error(409, str(exc))
        except (ValueError, TypeError) as exc:
            return _error(400, str(exc))
        except TimeoutError:
            return _error(
                504,
                f"{path}: no scan took the {op} within {APPLY_TIMEOUT_S:g} s (is the PLC running?); "
                "it waits for the next",
            )
        except Exception as exc:  # the scan refused it (a fault while storing): tell the page, keep serving
            return _error(422, f"{path}: {exc}")
        return _Json({"path": done, "op": op})

    @property
    def control(self) -> bool:
        return bool(self.config.options.get("control", True))

    async def _refused(self, request: Request, what: str) -> Response | None:
        """The answer to a restart or an online change that may not go on
        (not JSON, or [web] control = false), None when it may."""
        body = await _json(request)
        if isinstance(body, Response):
            return body
        if not self.control:
            return _error(403, f"the page may not {what}: [web] control = false")
        return None

    async def restart(self, request: Request) -> Response:
        refused = await self._refused(request, "restart tasks")
        if refused is not None:
            return refused
        faulted = await self._ask(plc.restart)
        if not faulted:
            return _error(409, "no task is stopped by a fault")
        return _Json({"restarting": faulted})

    async def online_change(self, request: Request) -> Response:
        refused = await self._refused(request, "make an online change")
        if refused is not None:
            return refused
        if self.changing:  # one at a time: a compile is work of the PLC's process
            return _error(409, "an online change is under way: wait for its report")
        self.changing = True
        try:  # compiling takes a while: in a worker thread, the event loop keeps serving
            report = await self._ask(plc.online_change, "web page", timeout=ONLINE_CHANGE_TIMEOUT_S)
        except plc.OnlineChangeOff as exc:
            return _error(404, str(exc))
        finally:
            self.changing = False
        return _Json(report)


async def _json(request: Request) -> Any:
    """The request's JSON object, or the error response to send."""
    if not request.headers.get("content-type", "").split(";")[0].strip().lower() == "application/json":
        return _error(415, "send JSON (Content-Type: application/json)")
    try:
        body = await request.json()
    except ValueError as exc:
        return _error(400, f"not JSON: {exc}")
    except RecursionError:  # [[[[... 100,000 deep
        return _error(400, "not JSON this server reads: nested too deep")
    if not isinstance(body, dict):
        return _error(400, "send a JSON object")
    return body
