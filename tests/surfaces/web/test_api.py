"""The web monitor over HTTP, against a real uvicorn server on a free port of
127.0.0.1 and a PLC scanning in its own thread (virtual time): the variable
tree, write / force / unforce with the [web] permissions, the live values
as server-sent events, the log, restart of a faulted task, online change,
and a clean stop."""

from __future__ import annotations

import contextlib
import dataclasses
import itertools
import json
import logging
import socket
import threading
from urllib.parse import urlsplit

import httpx
import pytest

from softplc.runtime.config.servers import ServerConfig
from softplc.runtime.engine.online_change import OnlineChange
from softplc.runtime.surfaces.host import SurfaceError, Surfaces
from softplc.runtime.surfaces.web.tree import LIMIT
from softplc.testing import PLC

from .conftest import PLANT, web_config


def states(web, client: str, count: int = 100, until=None) -> list:
    """The state events of client's stream: count of them, or up to the first for which until(state) holds."""
    out = []
    with web.http.stream("GET", "/api/events", params={"client": client}) as stream:
        assert stream.headers["content-type"].startswith("text/event-stream")
        event = None
        for line in stream.iter_lines():
            if line.startswith("event:"):
                event = line[6:].strip()
            elif line.startswith("data:") and event == "state":
                out.append(json.loads(line[5:]))
                if len(out) >= count or (until is not None and until(out[-1])):
                    return out
    raise AssertionError(f"the stream ended after {len(out)} states")


def test_the_tree_shows_programs_fb_instances_and_globals_a_level_at_a_time(web_plc):
    web = web_plc()
    roots = web.http.get("/api/tree").json()["children"]
    assert [(r["name"], r["kind"]) for r in roots] == [
        ("Main", "program"),
        ("Globals", "group"),
        ("Library globals", "group"),
    ]
    main = {c["name"]: c for c in web.http.get("/api/tree", params={"path": "Main"}).json()["children"]}
    assert (main["n"]["kind"], main["n"]["path"], main["n"]["type"]) == ("var", "Main.n", "DINT")
    assert main["mode"]["values"] == ["Idle", "Run", "Hold"]  # an enumeration: the page offers its names
    assert "scratch" not in main  # {attribute 'hide'}: not shown, as in CODESYS's monitoring
    assert web.post("watch", client="t0", paths=["Main.scratch"]).json()["paths"] == ["Main.scratch"]  # typed in
    assert (main["timer"]["kind"], main["timer"]["type"]) == ("struct", "TON")  # an FB instance
    timer = web.http.get("/api/tree", params={"path": "Main.timer"}).json()["children"]
    assert {"Main.timer.Q", "Main.timer.ET"} <= {c["path"] for c in timer}
    point = web.http.get("/api/tree", params={"path": "main.POINT"}).json()  # ST names: any case
    assert [c["path"] for c in point["children"]] == ["Main.point.x", "Main.point.y"]

    globals_ = {c["name"]: c for c in web.http.get("/api/tree", params={"path": "@globals"}).json()["children"]}
    assert set(globals_) == {"G_count", "G_crash", "G_zero", "G_big"}  # the libraries' apart, G_internal hidden
    assert (globals_["G_big"]["kind"], globals_["G_big"]["size"]) == ("array", 1000)
    library = web.http.get("/api/tree", params={"path": "@library"}).json()["children"]
    assert "PLC_DIAG" in [c["name"] for c in library]

    # a big array comes a page at a time
    first = web.http.get("/api/tree", params={"path": "G_big"}).json()
    assert len(first["children"]) == LIMIT and first["more"] == 1000 - LIMIT
    assert first["children"][0] == {"name": "[0]", "path": "G_big[0]", "type": "INT", "kind": "var"}
    last = web.http.get("/api/tree", params={"path": "G_big", "offset": 1000 - LIMIT}).json()
    assert last["children"][-1]["path"] == "G_big[999]" and last["more"] == 0

    missing = web.http.get("/api/tree", params={"path": "Main.nn"})
    assert missing.status_code == 404
    assert missing.json()["error"] == "Main.nn: no variable Main.nn in 'Main' (did you mean 'Main.n'?)"


def test_write_force_and_unforce_go_through_the_web_permissions(web_plc):
    web = web_plc()
    engine = web.engine

    assert web.post("write", path="Main.setpoint", value="2.5").json() == {"path": "Main.setpoint", "op": "write"}
    assert web.post("write", path="Main.mode", value="Run").status_code == 200
    web.wait_for(lambda: engine.get("Main.setpoint") == 2.5 and engine.get("Main.mode") == 1, "the writes landed")

    # force: held against the program in every scan, until unforced
    assert web.post("force", path="Main.enable", value="FALSE").status_code == 200
    n = engine.get("Main.n")
    cycle = engine.cycle
    web.wait_for(lambda: engine.cycle > cycle + 5, "five more scans")
    assert engine.get("Main.n") == n and engine.get("Main.enable") is False
    assert web.post("unforce", path="Main.enable").status_code == 200
    again = web.post("unforce", path="Main.enable")
    assert (again.status_code, again.json()["error"]) == (409, "Main.enable is not forced")

    # refused: a variable the [web] writable patterns do not cover, with where to allow it
    refused = web.post("write", path="Main.locked", value=1)
    assert refused.status_code == 403
    assert refused.json()["error"] == "Main.locked: web may not write it (allow it in [web] writable)"
    assert web.post("force", path="Main.locked", value=1).status_code == 403
    assert engine.get("Main.locked") == 7
    # a value the type cannot hold, a path that is no variable, not JSON
    bad = web.post("write", path="Main.n", value="lots")
    assert bad.status_code == 400 and bad.json()["error"].startswith("Main.n is DINT")
    assert web.post("write", path="Main.nope", value=1).status_code == 404
    no_json = web.http.post("/api/write", content="path=Main.n&value=1")
    assert no_json.status_code == 415  # a form of another site cannot change the PLC


def test_the_event_stream_sends_the_watched_values_the_forces_and_the_log(web_plc):
    web = web_plc()
    watched = web.post("watch", client="t1", paths=["main.n", "Main.mode", "Main.point", "Main.bad"]).json()
    assert watched["paths"] == ["Main.n", "Main.mode", "Main.point"]  # canonical spelling
    assert watched["errors"] == {"Main.bad": "Main.bad: no variable Main.bad in 'Main'"}

    first, second = states(web, "t1", count=2)
    assert second["sequence"] > first["sequence"] and second["cycle"] > first["cycle"]
    assert second["values"]["Main.n"] > first["values"]["Main.n"]  # live: the program counts
    assert second["values"]["Main.mode"] == "Idle"  # an enumeration by name ...
    assert second["numbers"]["Main.mode"] == 0.0  # ... and as a number for the trend
    assert second["values"]["Main.point"] == {"x": 0, "y": 0.0}
    assert [t["name"] for t in second["tasks"]] == ["MainTask"] and second["tasks"][0]["fault"] is None
    assert "Main.n" not in second["forced"]

    web.post("watch", client="t2", paths=["Main.setpoint"])
    web.post("force", path="Main.setpoint", value="3.25")
    logging.getLogger("softplc.test").warning("a line for the page")
    messages: list = []

    def forced_and_logged(state: dict) -> bool:
        # the log reaches the servers' process with a snapshot, maybe a later one than the force's
        messages.extend(r["message"] for r in state["log"])
        return "Main.setpoint" in state["forced"] and "a line for the page" in messages

    seen = states(web, "t2", until=forced_and_logged)
    assert seen[-1]["forced"] == {"Main.setpoint": 3.25} and seen[-1]["values"] == {"Main.setpoint": 3.25}
    log = [r for state in seen for r in state["log"]]  # each record comes once
    assert [r["level"] for r in log if r["message"] == "a line for the page"] == ["WARNING"]
    # the pages went: their streams end and their paths are no longer captured at the end of a scan
    hub = web.surfaces.hub
    web.wait_for(lambda: not [r for r in hub._watched if r.startswith("web:")], "the streams closed")
    assert hub.watch("probe", []) == [] and hub.capture().values == {}


def test_a_page_that_reconnects_keeps_its_watched_values(web_plc):
    web = web_plc(in_process=True)  # its streams counted
    web.post("watch", client="page", paths=["Main.n"])
    broadcaster = web.surfaces.handles["web"].broadcaster
    first = contextlib.ExitStack()
    old = first.enter_context(web.http.stream("GET", "/api/events", params={"client": "page"}))
    old_lines = old.iter_lines()  # held: a dropped iterator would close the connection
    next(line for line in old_lines if line.startswith("data:"))
    # the browser reconnects (EventSource) before the server noticed the old stream was gone
    with httpx.Client(base_url=web.url, timeout=10) as other:
        with other.stream("GET", "/api/events", params={"client": "page"}) as new:
            lines = new.iter_lines()
            next(line for line in lines if line.startswith("data:"))
            first.close()
            web.wait_for(lambda: broadcaster.streams == 1, "the old stream noticed gone")
            later = [json.loads(line[5:]) for line in itertools.islice(lines, 40) if line.startswith("data:")][-1]
            assert "Main.n" in later["values"]  # the old stream's end did not unwatch the page


def test_restart_brings_back_a_task_stopped_by_a_fault(web_plc):
    web = web_plc()
    none = web.post("restart")
    assert (none.status_code, none.json()["error"]) == (409, "no task is stopped by a fault")
    web.post("write", path="G_crash", value=True)
    state = states(web, "t", until=lambda s: s["tasks"][0]["fault"])[-1]
    assert "division by zero" in state["tasks"][0]["fault"] and state["outputs_safe"]
    web.post("write", path="G_crash", value=False)  # refused now: the task is stopped ...
    web.wait_for(lambda: web.engine.get("G_crash") is False, "the cause removed")
    assert web.post("restart").json() == {"restarting": ["MainTask"]}
    state = states(web, "t", until=lambda s: s["tasks"][0]["fault"] is None)[-1]
    assert not state["outputs_safe"]


def test_the_online_change_button_compiles_and_swaps_the_program_in(web_plc, tmp_path):
    source = tmp_path / "plant.st"
    source.write_text(PLANT, encoding="utf-8")
    plc = PLC.from_config(
        {"plc": {"programs": [str(source)]}, "task": [{"name": "T", "interval": "10ms", "programs": ["Main"]}]}
    )
    web = web_plc(plc)
    assert web.http.get("/api/info").json()["online_change"] is False
    off = web.post("online-change")
    assert off.status_code == 404 and "online change is off" in off.json()["error"]

    web.surfaces.online_change = changer = OnlineChange(web.engine, plc.config)  # what softplc run does
    changer.warm()  # its compile process started, as softplc run's start() does
    assert web.http.get("/api/info").json()["online_change"] is True
    source.write_text(
        PLANT.replace("    quotient : INT;", "    quotient : INT;\n    added : INT := 42;"), encoding="utf-8"
    )
    report = web.post("online-change").json()
    assert report["applied"] is True and report["lines"][0] == report["summary"]
    assert "1 initialised" in report["summary"]
    names = [c["name"] for c in web.http.get("/api/tree", params={"path": "Main"}).json()["children"]]
    assert "added" in names  # the tree shows the new program

    source.write_text(PLANT.replace("n := n + 1;", "n := n + ;"), encoding="utf-8")
    broken = web.post("online-change").json()
    assert broken["applied"] is False and "compile error" in broken["summary"]


def test_with_control_off_the_page_neither_restarts_tasks_nor_changes_the_program(web_plc, tmp_path):
    source = tmp_path / "plant.st"
    source.write_text(PLANT, encoding="utf-8")
    plc = PLC.from_config(
        {"plc": {"programs": [str(source)]}, "task": [{"name": "T", "interval": "10ms", "programs": ["Main"]}]}
    )
    config = dataclasses.replace(web_config(), options={"control": False})
    web = web_plc(plc, config)
    web.surfaces.online_change = OnlineChange(web.engine, plc.config)  # what softplc run does
    info = web.http.get("/api/info").json()
    assert info["control"] is False and info["online_change"] is False  # the page shows neither button
    source.write_text(PLANT.replace("    quotient : INT;", "    quotient : INT;\n    added : INT;"), encoding="utf-8")
    refused = web.post("online-change")
    assert (refused.status_code, refused.json()["error"]) == (
        403,
        "the page may not make an online change: [web] control = false",
    )
    web.post("write", path="G_crash", value=True)  # writes are [web] writable's, as before
    states(web, "t", until=lambda s: s["tasks"][0]["fault"])
    refused = web.post("restart")
    message = "the page may not restart tasks: [web] control = false"
    assert (refused.status_code, refused.json()["error"]) == (403, message)
    assert web.engine.faulted_tasks() and "added" not in [
        c["name"] for c in web.http.get("/api/tree", params={"path": "Main"}).json()["children"]
    ]


def test_the_page_and_its_files_are_served_from_the_plc_itself(web_plc):
    web = web_plc()
    page = web.http.get("/")
    assert page.status_code == 200 and page.headers["content-type"].startswith("text/html")
    for asset in ("/static/app.js", "/static/style.css"):
        assert f'"{asset}"' in page.text
        text = web.http.get(asset)
        assert text.status_code == 200
        # works with no internet: nothing is loaded from elsewhere
        assert "http://" not in text.text and "https://" not in text.text and "//cdn" not in text.text
    # a page of another site reaching 127.0.0.1 by a name of its own is refused (DNS rebinding)
    port = urlsplit(web.url).port
    assert web.http.get("/api/info", headers={"Host": f"evil.example:{port}"}).status_code == 400


def test_stop_ends_the_open_streams_and_leaves_no_thread_nor_socket(web_plc):
    web = web_plc()
    web.post("watch", client="open", paths=["Main.n"])
    got: list = []

    def follow() -> None:
        with httpx.stream("GET", web.url + "api/events", params={"client": "open"}, timeout=30) as stream:
            for line in stream.iter_lines():
                got.append(line)

    reader = threading.Thread(target=follow)
    reader.start()
    web.wait_for(lambda: any(line.startswith("data:") for line in got), "a first event")
    web.surfaces.stop()  # while a page is open
    reader.join(10)
    assert not reader.is_alive(), "the open event stream was not ended"
    assert [t.name for t in threading.enumerate() if t.name.startswith("softplc-web")] == []
    address = urlsplit(web.url)
    with pytest.raises(ConnectionRefusedError), socket.create_connection((address.hostname, address.port), timeout=2):
        pass


def test_a_port_in_use_is_an_error_naming_the_section(web_plc):
    web = web_plc()
    port = urlsplit(web.url).port
    other = Surfaces(web.engine, {"web": ServerConfig("web", "127.0.0.1", port, ("*",), 10**8)})
    with pytest.raises(SurfaceError, match=rf"^\[web\] cannot listen on 127.0.0.1:{port}: "):
        other.start()
