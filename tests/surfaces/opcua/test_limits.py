"""The OPC UA server against what issue 31 sent it: a connection sending
malformed chunks (asyncua wrote a traceback per chunk: ~10,000 lines from
120 kB), a refused write of a 1 MB string (logged in full), a NaN for a
REAL, a string variable holding a lone surrogate (every Read and Publish
failed with BadInternalError); a real asyncua client, raw sockets, and the
lines that reach the PLC's log counted."""

from __future__ import annotations

import logging
import socket
import struct
from urllib.parse import urlsplit

from asyncua import ua

from ...engine.conftest import task, wait_until
from .conftest import client, run, until, value

SRC = """
PROGRAM Main
VAR
    n : INT;
    name : STRING[10];
    speed : REAL;
    odd : WSTRING[10];
END_VAR
n := n + 1;
odd := WCHAR_TO_WSTRING(WORD_TO_WCHAR(16#D800));   (* a program can make one *)
END_PROGRAM
"""
TASKS = [task("Main", 10, "Main")]


def _asyncua(caplog) -> list:
    return [r for r in caplog.records if r.name.startswith(("asyncua", "asyncio"))]


def test_malformed_chunks_from_one_connection_leave_a_bounded_number_of_one_line_records(running, caplog):
    plc = running(SRC, TASKS)
    address = urlsplit(plc.url)
    garbage = b"XYZF" + struct.pack("<I", 12) + bytes(4)  # no message type asyncua knows
    with caplog.at_level(logging.INFO):
        with socket.create_connection((address.hostname, address.port), timeout=10) as sock:
            try:
                for _ in range(120_000 // (20 * len(garbage))):  # the 120 kB, in segments
                    sock.sendall(garbage * 20)
            except OSError:  # the server closed it: fine too
                pass
            wait_until(lambda: _asyncua(caplog), "the server's first complaint")
        plc.stop()  # the servers' process ends: every line it sent has been logged here
    lines = _asyncua(caplog)
    assert 1 <= len(lines) <= 21, [r.getMessage()[:100] for r in lines]  # the budget, and a summary
    assert all("Traceback" not in r.getMessage() and "\n" not in r.getMessage() for r in lines)


def test_a_refused_write_of_a_megabyte_string_is_logged_cut(running, caplog):
    caplog.set_level(logging.INFO)  # before the servers' process starts: it logs refusals at INFO
    plc = running(SRC, TASKS, writable=["Main.name", "Main.speed"])
    V = ua.VariantType

    async def check() -> None:
        async with client(plc.url) as c:
            for variant in (ua.Variant("x" * 1_000_000, V.String), ua.Variant(float("nan"), V.Float)):
                node = c.get_node("ns=2;s=" + ("Main.name" if variant.VariantType == V.String else "Main.speed"))
                try:
                    await node.write_value(ua.DataValue(variant))
                except ua.UaStatusCodeError as exc:
                    assert exc.code == ua.StatusCodes.BadOutOfRange
                else:
                    raise AssertionError(f"{variant.VariantType.name} taken")
            await c.get_node("ns=2;s=Main.speed").write_value(ua.DataValue(ua.Variant(2.5, V.Float)))
            assert plc.surfaces.access.place("Main.speed").read() == 2.5 and plc.engine.get("Main.name") == ""

    run(check())
    plc.stop()
    lines = [r.getMessage() for r in caplog.records if "refused" in r.getMessage()]
    assert lines and all(len(line) < 400 for line in lines), [line[:200] for line in lines]
    assert any("(1000000 characters)" in line for line in lines)


def test_a_string_holding_a_lone_surrogate_is_read_and_published(running, caplog):
    plc = running(SRC, TASKS)
    seen: list = []

    class Handler:
        def datachange_notification(self, node, val, data) -> None:
            seen.append(val)

    async def check() -> None:
        async with client(plc.url) as c:

            async def replaced():  # what a UTF-16 decoder makes of it
                return await value(c, "Main.odd") == "\ufffd"

            await until(replaced, "the string after the first scan")
            sub = await c.create_subscription(20, Handler())
            await sub.subscribe_data_change([c.get_node("ns=2;s=Main.odd"), c.get_node("ns=2;s=Main.n")])

            async def published():
                return len(seen) >= 3

            await until(published, "data changes after the odd string")
            await sub.delete()

    with caplog.at_level(logging.WARNING):
        run(check())
    assert "\ufffd" in seen
    assert not [r for r in caplog.records if "BadInternalError" in r.getMessage() or "Traceback" in r.getMessage()]
