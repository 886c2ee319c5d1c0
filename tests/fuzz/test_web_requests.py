"""Requests into the web monitor (runtime/surfaces/web), as a careless or
hostile client sends them (issue 31): any method and path (a long one, a
percent-encoded one), any Content-Type, bodies that are JSON of the API's
shape with drawn paths and values (a lone surrogate, 1e999, "nan", an
integer of 400 digits, a string past its length), JSON nested deep, bytes,
a body past the size limit. Every request gets an answer below 500 (an
exception of a request's handling is a 500: a crash in disguise), an error
answer small (a value is echoed cut, never whole), nothing is logged with
a traceback, and the server serves on after all of them.
"""

from __future__ import annotations

import json

import httpx
from hypothesis import given
from hypothesis import strategies as st

from softplc.runtime.surfaces.web.guard import MAX_BODY
from softplc.testing import PLC

from ..surfaces.web.conftest import PLANT, Web, web_config
from .support import LogWatch, assert_no_tracebacks, bounded, fuzz, long, short

#: the variables of the tests' plant (not G_crash: a write of it faults the PLC on purpose)
PATHS = [
    "Main.n",
    "Main.setpoint",
    "Main.enable",
    "Main.mode",
    "Main.point",
    "Main.point.x",
    "Main.point.y",
    "Main.locked",
    "Main.timer.ET",
    "Main.scratch",
    "G_count",
    "G_big[3]",
    "G_big[1000]",
    "G_big",
    "Nope.x",
    "Main..n",
    "Main.n[1]",
]
#: an error answer holds one cut message: far less than what was sent
MAX_ERROR_ANSWER = 2_000

texts = st.text(max_size=40) | st.sampled_from(["\ud800", "a\udfffb", "x" * 300, "", " ", "nan", "1e999", "T#2s"])
values = (
    st.none()
    | st.booleans()
    | st.integers(-(2**70), 2**70)
    | st.sampled_from([10**400, -(10**400), 1e308, float("inf"), float("-inf"), float("nan")])
    | st.floats()
    | texts
    | st.lists(st.integers(-5, 5), max_size=4)
    | st.dictionaries(st.sampled_from(["x", "y", "z"]), st.integers(-5, 5), max_size=3)
)


def _json(obj) -> bytes:
    """JSON as a client sends it: a lone surrogate as its \\uXXXX escape,
    NaN and infinities as JavaScript's own writers do."""
    return json.dumps(obj, allow_nan=True).encode()


@st.composite
def api_bodies(draw) -> bytes:
    kind = draw(st.sampled_from(["change", "watch", "object", "deep", "bytes", "big", "number"]))
    if kind == "change":
        body: dict = {}
        if draw(st.booleans()):
            body["path"] = draw(st.sampled_from(PATHS) | texts | values)
        if draw(st.booleans()):
            body["value"] = draw(values)
        return _json(body)
    if kind == "watch":
        paths = draw(st.lists(st.sampled_from(PATHS) | texts, max_size=6))
        many = draw(st.sampled_from([0, 0, 0, 2_001]))  # past the paths a page may watch
        return _json(
            {
                "client": draw(st.sampled_from(["page", "p-1", "", "a b", "x" * 200]) | texts),
                "paths": paths + ["Main.n"] * many,
            }
        )
    if kind == "object":
        return _json(draw(st.dictionaries(texts, values, max_size=4)))
    if kind == "deep":
        depth = draw(st.sampled_from([2, 100, 1_000, 30_000]))
        opener, closer = draw(st.sampled_from([("[", "]"), ('{"a":', "}")]))
        return (opener * depth + "1" + closer * depth).encode()
    if kind == "big":
        return b'{"path": "' + b"x" * (MAX_BODY + draw(st.integers(1, 1_000))) + b'"}'
    if kind == "number":
        return draw(st.sampled_from([b"1e999", b"-1e999", b"NaN", b"Infinity", b"9" * 5_000, b'"\\ud800"']))
    return draw(st.binary(max_size=200))


@st.composite
def web_requests(draw) -> tuple:
    """(method, path, headers, body)"""
    method = draw(st.sampled_from(["GET", "POST", "POST", "POST", "PUT", "DELETE", "OPTIONS", "HEAD", "PATCH"]))
    route = draw(
        st.sampled_from(
            ["/", "/api/info", "/api/tree", "/api/watch", "/api/write", "/api/force", "/api/unforce", "/api/restart"]
            + ["/api/online-change", "/api/nothing", "/static/app.js", "/static/../../etc/passwd", "/nowhere"]
        )
    )
    tail = draw(st.sampled_from(["", "", "", "?path=Main", "?path=Main.point&offset=x", "?offset=-1"]))
    if draw(st.integers(0, 9)) == 0:
        route = "/" + "x" * draw(st.sampled_from([1_000, 60_000]))  # a long path, to be cut in the 404
    elif draw(st.integers(0, 9)) == 0:
        route = "/api/" + "".join(f"%{b:02X}" for b in draw(st.binary(min_size=1, max_size=20)))
    content_type = draw(
        st.sampled_from(["application/json", "application/json", "application/json; charset=utf-8"])
        | st.sampled_from(["text/plain", "", "application/JSON"])
    )
    body = draw(api_bodies()) if method not in ("GET", "HEAD") or draw(st.integers(0, 4)) == 0 else b""
    headers = {"Content-Type": content_type} if content_type else {}
    return method, route + tail, headers, body


def check_request(web: Web, case: tuple) -> int:
    """The status of one request, judged."""
    method, path, headers, body = case
    what = f"{method} {path[:80]!r} ({len(path)} characters), {headers}, body {body[:80]!r} ({len(body)} bytes)"
    with bounded("a web request"):
        try:
            response = web.http.request(method, path, headers=headers, content=body)
        except httpx.RemoteProtocolError:  # the server closed a request it would not read (uvicorn's own refusal)
            return 0
    status = response.status_code
    assert status < 500, f"{what}: {status} {response.text[:300]}"
    if status >= 400:
        assert len(response.content) <= MAX_ERROR_ANSWER, f"{what}: an error of {len(response.content)} bytes"
    return status


def _serve(examples_run) -> None:
    """Run the examples against one PLC and its web server; then the server still serves."""
    web = Web(PLC.from_st(PLANT), web_config(), pause_s=0.002)
    try:
        with LogWatch() as watch:
            examples_run(web)
            assert web.http.get("/api/info").status_code == 200
            assert web.post("write", path="Main.n", value=5).status_code == 200
        assert_no_tracebacks(watch, "web requests")
        assert not [r for r in watch.records if "Traceback" in r.getMessage()]
    finally:
        web.close()


def test_web_requests_are_answered_without_a_server_error():
    def examples(web: Web) -> None:
        @short(60)
        @given(web_requests())
        def run(case):
            check_request(web, case)

        run()

    _serve(examples)


@fuzz
def test_long_web_requests(tally, shard):
    counts = tally("requests")

    def examples(web: Web) -> None:
        @long("requests", 0.5, shard)
        @given(web_requests())
        def run(case):
            counts.add(str(check_request(web, case)))

        run()

    _serve(examples)
