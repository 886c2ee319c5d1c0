"""The web monitor in a real headless Chromium (Debian's /usr/bin/chromium,
driven by Playwright), against the default plant in virtual time, paced
by a pause after each scan so that a page can follow it: the page shows
the Motor program start the LTMR, a force from the page stops it (the
program reacts, the forced value is marked with a red F) and the unforce
lets it start again. A screenshot of the page is checked:
a PNG of the window's size, the forced marker drawn in the forced red,
no such red on the row of a variable that is not forced, and the trend
chart with its line drawn.

What it proves: the page works from the PLC alone (every request the
browser makes goes to 127.0.0.1; any other would be recorded and refused),
its live values come through the server-sent events, and a user's force
goes through the [web] permissions to the scan and back to the page."""

from __future__ import annotations

import shutil
import struct
import zlib
from urllib.parse import urlsplit

import pytest

from softplc.testing import PLC

from .conftest import web_config

CHROMIUM = "/usr/bin/chromium"
sync_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed (pip install -e '.[test]')")
pytestmark = [
    pytest.mark.skipif(shutil.which(CHROMIUM) is None, reason=f"no Chromium at {CHROMIUM} (apt-get install chromium)"),
    pytest.mark.slow,
    pytest.mark.realtime,  # a browser and a server in threads; the test waits for what the page shows, never for a time
]

VIEWPORT = {"width": 1280, "height": 900}
FORCED_RED = (0xD0, 0x00, 0x00)  # --forced in style.css
TREND_BLUE = (0x1F, 0x5F, 0xBF)  # the first trend colour in app.js
WAIT_MS = 15_000  # only stops a broken test from hanging: nothing here is timed


@pytest.fixture(scope="module")
def browser():
    with sync_api.sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=CHROMIUM, args=["--no-sandbox"])
        try:
            yield chromium
        finally:
            chromium.close()


def test_the_page_shows_the_motor_start_and_a_force_that_stops_it(web_plc, browser, tmp_path):
    # virtual time: a busy CI host cannot fault the plant's tasks with its watchdog
    web = web_plc(PLC.from_config(), web_config(writable=("Motor.*",), period_ms=250), pause_s=0.005)
    elsewhere: list = []
    expect = sync_api.expect
    page = browser.new_page(viewport=VIEWPORT)
    try:
        page.route("**/*", lambda route: _only_loopback(route, elsewhere))
        page.goto(web.url)
        expect(page.locator("#link")).to_have_text("live", timeout=WAIT_MS)

        def row(path: str):
            return page.locator(f'.row[data-path="{path}"]')

        def value(path: str):
            return row(path).locator(".value")

        # the tree: open the Motor program and its LTMR_CONTROL instance
        row("Motor").click()
        row("Motor.ltmr").click()
        # the motor starts: the sequence goes Forward and the LTMR (simulated, on CANopen) reports running
        expect(value("Motor.state")).to_have_text("Forward", timeout=WAIT_MS)
        expect(value("Motor.ltmr.Running")).to_have_text("TRUE", timeout=WAIT_MS)
        expect(page.locator('[data-driver="canopen"] .dot')).to_have_class("dot ok")
        expect(page.locator('#tasks tr[data-task="MotorTask"] td').last).to_have_text("running")
        # the trend of the LTMR's Running, drawn by the page on a canvas
        row("Motor.ltmr.Running").click()
        page.click("#do-trend")
        expect(page.locator("#trend-legend")).to_contain_text("Motor.ltmr.Running")

        # force Auto FALSE from the page: the program leaves the sequence and stops the motor
        row("Motor.Auto").click()
        page.select_option("#edit-value", "FALSE")
        page.click("#do-force")
        expect(row("Motor.Auto")).to_have_class("row selected forced", timeout=WAIT_MS)
        expect(value("Motor.Auto")).to_have_text("FALSE")
        expect(value("Motor.state")).to_have_text("Stopped", timeout=WAIT_MS)
        expect(value("Motor.ltmr.Running")).to_have_text("FALSE", timeout=WAIT_MS)
        expect(page.locator("#forced-count")).to_have_text("1 FORCED")
        assert web.engine.get("Motor.Auto") is False

        # a variable [web] writable does not cover: the page says why
        row("Conveyor").click()
        row("Conveyor.batchSize").click()
        page.fill("#edit-value", "3")
        page.click("#do-write")
        expect(page.locator("#message")).to_have_text(
            "Conveyor.batchSize: web may not write it (allow it in [web] writable)", timeout=WAIT_MS
        )
        shot = tmp_path / "web-monitor.png"
        png = page.screenshot(path=str(shot))
        assert _png_size(png) == (VIEWPORT["width"], VIEWPORT["height"])
        mark = _png(row("Motor.Auto").locator(".forced-mark").screenshot())
        assert _share(mark, FORCED_RED) > 0.5  # the F's box in the forced red (white letter inside)
        assert _share(_png(row("Motor.AutoReset").screenshot()), FORCED_RED) == 0  # not forced: no red
        box = page.locator("#trend").bounding_box()  # its right edge: the latest values
        edge = page.screenshot(
            clip={"x": box["x"] + box["width"] - 60, "y": box["y"], "width": 60, "height": box["height"]}
        )
        assert _share(_png(edge), TREND_BLUE, tolerance=40) > 0.0005  # the trend's line is drawn (a few pixels)
        # unforce from the forced list (Auto keeps its value, as in CODESYS), then write TRUE:
        # the sequence starts the motor again
        page.locator("#forced-list button").click()
        expect(row("Motor.Auto")).not_to_have_class("row forced", timeout=WAIT_MS)
        expect(page.locator("#forced-count")).to_be_hidden()
        row("Motor.Auto").click()
        page.select_option("#edit-value", "TRUE")
        page.click("#do-write")
        expect(value("Motor.state")).to_have_text("Forward", timeout=WAIT_MS)
        expect(value("Motor.ltmr.Running")).to_have_text("TRUE", timeout=WAIT_MS)
    finally:
        page.close()
    assert elsewhere == [], "the page asked for something beyond the PLC"
    print(f"screenshot: {shot}")


def test_a_faulted_task_is_shown_and_restarted_from_the_page(web_plc, browser):
    web = web_plc()  # tests/surfaces/web/conftest.py PLANT, in virtual time
    expect = sync_api.expect
    page = browser.new_page(viewport=VIEWPORT)
    try:
        page.goto(web.url)
        expect(page.locator("#link")).to_have_text("live", timeout=WAIT_MS)
        state = page.locator('#tasks tr[data-task="MainTask"] td').last
        expect(state).to_have_text("running", timeout=WAIT_MS)
        assert web.post("write", path="G_crash", value=True).status_code == 200
        expect(state).to_contain_text("FAULT: ", timeout=WAIT_MS)
        expect(state).to_contain_text("division by zero")
        expect(page.locator("#safe")).to_be_visible()  # OUTPUTS SAFE in the header
        assert web.post("write", path="G_crash", value=False).status_code == 200  # the cause removed
        state.locator("button.restart").click()
        expect(state).to_have_text("running", timeout=WAIT_MS)
        expect(page.locator("#safe")).to_be_hidden()
        assert web.engine.restarts == 1
    finally:
        page.close()


def _only_loopback(route, elsewhere: list) -> None:
    host = urlsplit(route.request.url).hostname
    if host in ("127.0.0.1", "localhost"):
        route.continue_()
    else:
        elsewhere.append(route.request.url)
        route.abort()


def _share(image: tuple, colour: tuple, tolerance: int = 24) -> float:
    """The share of an image's pixels within tolerance of colour."""
    _w, _h, pixels = image
    close = sum(1 for p in pixels if all(abs(a - b) <= tolerance for a, b in zip(p, colour)))
    return close / len(pixels)


def _png_size(data: bytes) -> tuple:
    """(width, height) from a PNG's header (IHDR, the first chunk)."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR", "not a PNG"
    return struct.unpack(">II", data[16:24])


def _png(data: bytes) -> tuple:
    """(width, height, [(r, g, b), ...]) of an 8-bit RGB or RGBA PNG, as Chromium writes them."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    pos, idat, header = 8, b"", None
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos : pos + 8])
        body = data[pos + 8 : pos + 8 + length]
        if kind == b"IHDR":
            header = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    assert header is not None
    width, height, depth, colour, _c, _f, interlace = header
    assert depth == 8 and colour in (2, 6) and interlace == 0, f"an unexpected PNG: {header}"
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows: list = []
    prev = bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1 : (y + 1) * (stride + 1)])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = prev[i]
            corner = prev[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 0xFF
            elif kind == 2:
                line[i] = (line[i] + up) & 0xFF
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 0xFF
            elif kind == 4:
                pa, pb, pc = abs(up - corner), abs(left - corner), abs(left + up - 2 * corner)
                line[i] = (line[i] + (left if pa <= pb and pa <= pc else up if pb <= pc else corner)) & 0xFF
        rows.append(line)
        prev = line
    pixels = [tuple(line[x * channels : x * channels + 3]) for line in rows for x in range(width)]
    return width, height, pixels
