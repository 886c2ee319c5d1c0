"""The random server clients of bench_soak_live.py, in a process of their own
(they do not share the PLC's interpreter), each a thread at a modest rate:

* web: pages, /api/info, /api/tree (good and bad paths and offsets), writes
  to writable variables (good values, NaN, text for a REAL, a string past
  its length, a path outside `writable`, not JSON, a body past 256 KiB),
  a force and its unforce, watch streams opened, read for a few events and
  dropped, watches never followed by a stream;
* OPC UA (asyncua): browse Objects two levels deep, read, subscribe to a
  few variables, write (a good value, a string past its length, a
  variable outside `writable`), reconnect now and then;
* Modbus TCP (pymodbus): holding registers and coils read and written in
  range, past the tables, past `writable`, with counts the protocol
  refuses.

Every request has the answers a correct server may give; another answer is
"unexpected" (with a sample), a failure to connect or a dropped connection
is an error of its kind. While the PLC is down (between a kill and the
restart; the `up` event) errors are counted apart: they are the kill's.
Counts go to STATS (JSON) every 5 s and at the end.
"""

from __future__ import annotations

import asyncio
import http.client
import json
import os
import random
import threading
import time
from collections import Counter
from pathlib import Path

WEB_RATE_S = (0.1, 0.4)
OPCUA_RATE_S = (0.2, 0.6)
MODBUS_RATE_S = (0.1, 0.4)


class Tally:
    def __init__(self, up) -> None:
        self.up = up
        self.lock = threading.Lock()
        self.counts: Counter = Counter()
        self.samples: dict = {}
        self.times: dict = {}  # key -> wall times of its first 50 (errors only)

    def ok(self, surface: str) -> None:
        with self.lock:
            self.counts[f"{surface} ok"] += 1

    def bad(self, surface: str, kind: str, sample: str = "") -> None:
        down = "" if self.up.is_set() else " (PLC down)"
        key = f"{surface} {kind}{down}"
        with self.lock:
            self.counts[key] += 1
            if sample and key not in self.samples:
                self.samples[key] = sample[:200]
            when = self.times.setdefault(key, [])
            if len(when) < 50:
                when.append(round(time.time(), 2))

    def dump(self, path: Path) -> None:
        with self.lock:
            data = {"counts": dict(self.counts), "samples": dict(self.samples), "times": dict(self.times)}
        tmp = path.with_name(path.name + ".tmp")
        tmp.write_text(json.dumps(data))
        os.replace(tmp, path)


# ---------------------------------------------------------------- web


def _web_requests(rng: random.Random) -> tuple:
    """(method, path, body or None, content type, answers a correct server gives)."""
    j = "application/json"
    r = rng.random()
    if r < 0.10:
        return "GET", rng.choice(["/", "/static/app.js", "/static/style.css", "/api/info"]), None, j, {200}
    if r < 0.25:
        path = rng.choice(["", "Soak", "Motor", "Pump.drive", "CANOPEN_NODE", "NoSuch.thing"])
        offset = rng.choice(["0", "0", "100", "-1", "abc"])
        return "GET", f"/api/tree?path={path}&offset={offset}", None, j, {200, 400, 404}
    if r < 0.45:
        return "POST", "/api/write", {"path": "Soak.setpoint", "value": round(rng.uniform(-1e3, 1e3), 3)}, j, {200}
    if r < 0.50:
        value = rng.choice(["nan", "lots", 1e999, "1e999"])
        return "POST", "/api/write", {"path": "Soak.setpoint", "value": value}, j, {400}
    if r < 0.55:
        text = "x" * rng.choice([5, 20, 21, 500])
        return "POST", "/api/write", {"path": "Soak.note", "value": text}, j, {200} if len(text) <= 20 else {400}
    if r < 0.60:
        return "POST", "/api/write", {"path": "Motor.Auto", "value": True}, j, {403}
    if r < 0.63:
        return "POST", "/api/write", {"path": "Soak.count", "value": "T#2s"}, j, {400}
    if r < 0.68:
        op = rng.choice(["force", "unforce"])
        body = {"path": "Soak.flag", "value": rng.random() < 0.5} if op == "force" else {"path": "Soak.flag"}
        return "POST", f"/api/{op}", body, j, {200, 409}
    if r < 0.72:
        return "POST", "/api/write", "not json", "text/plain", {415}
    if r < 0.74:
        return "POST", "/api/write", "[" * 300_000, j, {413}
    if r < 0.78:
        return "GET", rng.choice(["/nothing", "/api/nothing", "/static/../../etc/passwd"]), None, j, {400, 404, 405}
    if r < 0.82:
        return "POST", "/api/watch", {"client": f"pending{rng.randrange(100)}", "paths": ["Soak.kept"]}, j, {200, 429}
    return "STREAM", "", None, j, {200, 429, 503}


def web_client(port: int, seed: int, tally: Tally, stop: threading.Event) -> None:
    rng = random.Random(seed)
    while not stop.wait(rng.uniform(*WEB_RATE_S)):
        method, path, body, ctype, expected = _web_requests(rng)
        conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
        answer = b""
        try:
            if method == "STREAM":
                status = _stream(conn, rng)
            else:
                data = None if body is None else body if isinstance(body, str) else json.dumps(body)
                conn.request(method, path, data, {"Content-Type": ctype} if data is not None else {})
                response = conn.getresponse()
                answer = response.read()
                status = response.status
            if status in expected:
                tally.ok("web")
            else:  # the answer's body says why (a 500's names the exception)
                said = answer[:120].decode(errors="replace")
                tally.bad("web", f"unexpected {status}", f"{method} {path[:80]} {body!s:.80} -> {status} {said}")
        except (OSError, http.client.HTTPException) as exc:
            tally.bad("web", type(exc).__name__, f"{method} {path[:80]}: {exc}")
        finally:
            conn.close()


def _stream(conn: http.client.HTTPConnection, rng: random.Random) -> int:
    """A page: watch, open the stream, read a few events, drop it."""
    client = f"soak{rng.randrange(30)}"
    paths = rng.sample(["Soak.kept", "Soak.setpoint", "Motor.state", "Pump.state", "Drive.state", "Conveyor.state"], 3)
    conn.request(
        "POST", "/api/watch", json.dumps({"client": client, "paths": paths}), {"Content-Type": "application/json"}
    )
    response = conn.getresponse()
    response.read()
    if response.status != 200:
        return response.status
    conn.request("GET", f"/api/events?client={client}")
    response = conn.getresponse()
    if response.status != 200:
        response.read()
        return response.status
    for _ in range(rng.randrange(0, 6)):
        while True:
            line = response.fp.readline()
            if not line or line.startswith(b"data:"):
                break
        if not line:
            break
    return 200  # dropped here: the connection closes


# ---------------------------------------------------------------- OPC UA


async def _opcua(port: int, rng: random.Random, tally: Tally, stop: threading.Event) -> None:
    from asyncua import Client, ua

    class Handler:
        def datachange_notification(self, node, val, data) -> None:
            tally.ok("opcua notification")

    url = f"opc.tcp://127.0.0.1:{port}/softplc/"
    while not stop.is_set():
        client = Client(url, timeout=5)
        try:
            await client.connect()
        except Exception as exc:
            tally.bad("opcua", f"connect {type(exc).__name__}", str(exc))
            await asyncio.sleep(1.0)
            continue
        try:
            subscription = await client.create_subscription(200, Handler())
            nodes = [client.get_node(f"ns=2;s={p}") for p in ("Soak.kept", "Soak.setpoint", "Motor.state")]
            await subscription.subscribe_data_change(nodes)
            tally.ok("opcua")
            for _ in range(rng.randrange(20, 200)):
                if stop.is_set():
                    break
                await asyncio.sleep(rng.uniform(*OPCUA_RATE_S))
                await _opcua_request(client, ua, rng, tally)
            await subscription.delete()
        except Exception as exc:
            tally.bad("opcua", type(exc).__name__, str(exc))
        finally:
            try:
                await client.disconnect()
            except Exception:
                pass


async def _opcua_request(client, ua, rng: random.Random, tally: Tally) -> None:
    r = rng.random()
    try:
        if r < 0.15:
            objects = client.nodes.objects
            for child in (await objects.get_children())[:8]:
                await child.get_children()
        elif r < 0.55:
            path = rng.choice(
                ["Soak.kept", "Soak.note", "Motor.state", "Pump.state", "Conveyor.speedOut", "gSoakTotal"]
            )
            await client.get_node(f"ns=2;s={path}").read_value()
        elif r < 0.75:
            value = ua.DataValue(ua.Variant(rng.uniform(-100, 100), ua.VariantType.Float))
            await client.get_node("ns=2;s=Soak.setpoint").write_value(value)
        elif r < 0.85:
            text = "y" * rng.choice([3, 20, 21, 1000])
            try:
                await client.get_node("ns=2;s=Soak.note").write_value(
                    ua.DataValue(ua.Variant(text, ua.VariantType.String))
                )
            except ua.UaStatusCodeError as exc:
                if len(text) <= 20:
                    raise
                tally.ok(f"opcua refused {type(exc).__name__}")
                return
        elif r < 0.95:
            try:
                await client.get_node("ns=2;s=Motor.Auto").write_value(
                    ua.DataValue(ua.Variant(True, ua.VariantType.Boolean))
                )
                tally.bad("opcua", "unexpected write accepted", "Motor.Auto")
                return
            except ua.UaStatusCodeError as exc:
                tally.ok(f"opcua refused {type(exc).__name__}")
                return
        else:
            try:
                await client.get_node("ns=2;s=No.such").read_value()
                tally.bad("opcua", "unexpected read of No.such")
                return
            except ua.UaStatusCodeError:
                tally.ok("opcua refused BadNodeIdUnknown")
                return
        tally.ok("opcua")
    except ua.UaStatusCodeError as exc:
        tally.bad("opcua", f"status {type(exc).__name__}", str(exc))


def opcua_client(port: int, seed: int, tally: Tally, stop: threading.Event) -> None:
    asyncio.run(_opcua(port, random.Random(seed), tally, stop))


# ---------------------------------------------------------------- Modbus TCP


def _modbus_request(client, rng: random.Random) -> tuple:
    """(what, the reply, the exception codes a correct server answers: () for none)."""
    r = rng.random()
    if r < 0.30:
        address, count = rng.choice(
            [(rng.randrange(0, 1000), rng.randint(1, 24)), (rng.randrange(1024, 1100), rng.randint(1, 125))]
        )
        return "read HR", client.read_holding_registers(address, count=count), ()
    if r < 0.40:
        return "read HR past the table", client.read_holding_registers(40000, count=10), (2,)
    if r < 0.50:
        return "write HR %MW", client.write_register(1024 + rng.randrange(0, 50), rng.randrange(65536)), ()
    if r < 0.55:
        return "write HR %QW100 (not writable)", client.write_register(100, 0), (2,)
    if r < 0.65:
        return "write coil %QX100.x", client.write_coil(800 + rng.randrange(8), rng.random() < 0.5), ()
    if r < 0.70:
        return "write coil %QX0.0 (not writable)", client.write_coil(0, True), (2,)
    if r < 0.80:
        return "read coils", client.read_coils(rng.randrange(0, 900), count=rng.randint(1, 100)), ()
    if r < 0.85:
        return "read input registers", client.read_input_registers(rng.randrange(100, 210), count=8), ()
    if r < 0.90:
        return "read discrete inputs", client.read_discrete_inputs(0, count=32), ()
    return (
        "write registers %MW",
        client.write_registers(1100, [rng.randrange(65536) for _ in range(rng.randint(1, 20))]),
        (),
    )


def modbus_client(port: int, seed: int, tally: Tally, stop: threading.Event) -> None:
    from pymodbus.client import ModbusTcpClient
    from pymodbus.exceptions import ModbusException

    rng = random.Random(seed)
    client = ModbusTcpClient("127.0.0.1", port=port, timeout=3, retries=0)
    while not stop.wait(rng.uniform(*MODBUS_RATE_S)):
        try:
            if not client.connected and not client.connect():
                tally.bad("modbus", "connect failed")
                stop.wait(1.0)
                continue
            what, reply, codes = _modbus_request(client, rng)
            code = getattr(reply, "exception_code", 0) if reply.isError() else 0
            if (code in codes) if codes else not reply.isError():
                tally.ok("modbus")
            else:
                tally.bad("modbus", f"unexpected {what}", f"{what}: {reply}")
        except ModbusException as exc:
            tally.bad("modbus", type(exc).__name__, str(exc))
            client.close()
        except OSError as exc:
            tally.bad("modbus", type(exc).__name__, str(exc))
            client.close()
    client.close()


# ---------------------------------------------------------------- the process


def run(ports: dict, seed: int, stats: str, up, stop) -> None:
    """The clients' process: the three kinds of client until stop is set."""
    import logging

    logging.getLogger().setLevel(logging.CRITICAL)  # asyncua's and pymodbus's chatter is theirs
    tally = Tally(up)
    halt = threading.Event()
    threads = [
        threading.Thread(target=web_client, args=(ports["web"], seed * 10 + 1, tally, halt), daemon=True),
        threading.Thread(target=opcua_client, args=(ports["opcua"], seed * 10 + 2, tally, halt), daemon=True),
        threading.Thread(target=modbus_client, args=(ports["modbus"], seed * 10 + 3, tally, halt), daemon=True),
    ]
    for t in threads:
        t.start()
    path = Path(stats)
    while not stop.wait(5.0):
        tally.dump(path)
    halt.set()
    deadline = time.monotonic() + 10
    for t in threads:
        t.join(max(deadline - time.monotonic(), 0.1))
    tally.dump(path)
