"""`softplc run --web [HOST:]PORT`: the page without a [web] section, with
its defaults (127.0.0.1, everything writable) and softplc run's online
change behind its button."""

from __future__ import annotations

import re
import signal
import subprocess
import sys
import threading
import time

import httpx
import pytest

from softplc.runtime.config.servers import ServerConfig, parse_listen, web_option


@pytest.mark.parametrize(
    ("text", "expected"),
    [("8080", (None, 8080)), ("0", (None, 0)), ("0.0.0.0:80", ("0.0.0.0", 80)), ("[::1]:8080", ("::1", 8080))],
)
def test_the_address_is_an_optional_host_and_a_port(text, expected):
    assert parse_listen(text) == expected


@pytest.mark.parametrize("text", ["", "http", ":8080", "host:", "70000", "a b:80", "localhost:-1"])
def test_a_bad_address_says_what_is_expected(text):
    with pytest.raises(ValueError, match=r"expected \[HOST:\]PORT such as 8080 or 127.0.0.1:8080"):
        parse_listen(text)


def test_the_option_keeps_the_sections_settings_but_the_address():
    section = ServerConfig("web", "127.0.0.1", 8080, ("Main.*",), 500_000_000, where="[web] writable")
    assert web_option("9000", section) == ServerConfig(
        "web", "127.0.0.1", 9000, ("Main.*",), 500_000_000, {}, "[web] writable"
    )
    default = web_option("localhost:0", None)
    assert (default.host, default.port, default.writable, default.period_ns) == ("localhost", 0, ("*",), 250_000_000)


def test_a_bad_option_stops_softplc_run_before_anything_starts():
    proc = subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", "run", "--web", "here:there", "--virtual-time", "--cycles", "1"],
        capture_output=True,
        text=True,
        stdin=subprocess.DEVNULL,
        timeout=120,
    )
    assert proc.returncode == 2
    assert "Invalid value for --web: expected [HOST:]PORT such as 8080" in proc.stderr
    assert "start" not in proc.stderr  # refused before the PLC was built


@pytest.mark.slow
@pytest.mark.realtime  # the real clock runs the PLC; the test waits for log lines and answers, never for a time
def test_softplc_run_web_serves_the_page_with_its_online_change(tmp_path):
    counter = "PROGRAM Main\nVAR n : DINT; {} END_VAR\nn := n + 1;\nEND_PROGRAM\n"
    source = tmp_path / "p.st"
    source.write_text(counter.format(""))
    cfg = tmp_path / "plant.toml"
    cfg.write_text('[plc]\nprograms = ["p.st"]\n')
    proc = subprocess.Popen(
        [sys.executable, "-m", "softplc.runtime.cli", "run", str(cfg), "--web", "127.0.0.1:0"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        stdin=subprocess.DEVNULL,
        text=True,
    )
    try:
        url = _wait_for_url(proc)
        rest: list = []  # read on, so that a full pipe never blocks the PLC's log
        drain = threading.Thread(target=lambda: rest.extend(proc.stderr), daemon=True)
        drain.start()
        with httpx.Client(base_url=url, timeout=30) as http:
            assert http.get("/api/info").json()["online_change"] is True  # softplc run's, on in real time
            assert http.post("/api/write", json={"path": "Main.n", "value": -5}).status_code == 200
            source.write_text(counter.format("added : INT := 7;"))
            report = http.post("/api/online-change", json={}).json()
            # the file watcher may have swapped it in first: then the button's change keeps everything
            assert report["applied"] is True, report
            tree = http.get("/api/tree", params={"path": "Main"}).json()
            assert [c["name"] for c in tree["children"]] == ["n", "added"]
        proc.send_signal(signal.SIGINT)
        assert proc.wait(timeout=60) == 0, "".join(rest)
        drain.join(10)
        assert any("stopped by SIGINT after" in line for line in rest), "".join(rest)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.communicate(timeout=30)


def _wait_for_url(proc) -> str:
    """The page's address from softplc run's log (the limit only stops a broken test from hanging)."""
    deadline = time.monotonic() + 60
    lines = []
    while time.monotonic() < deadline:
        line = proc.stderr.readline()
        if not line:
            break
        lines.append(line)
        found = re.search(r"web: (http://127\.0\.0\.1:\d+/)", line)
        if found:
            return found.group(1)
    raise AssertionError("no web address in the log:\n" + "".join(lines))
