"""What the surfaces cost the scan: the default plant on the real clock, with
5 web pages on the live stream, an OPC UA subscription of 1,000 variables
and a Modbus TCP poll of 1,000 holding registers (each client in a process
of its own, as an HMI would be), against the same plant
with no server and no client, measured in the same run (issue 19's target:
under 10 % more per scan).

The plant is the embedded default (io_config/default.toml) plus a program
of 1,000 DINT globals, 100 of them changed per scan (so the OPC UA
subscription has data changes to send), in a task of its own; the baseline
runs the same plant. Per scan is the wall time of one tick (inputs, tasks,
outputs and the after-tick work), taken around Engine.tick. Late is how
long after its release a tick began (the kernel's wake-up, the interpreter
lock); overruns are the releases missed (the tasks' counters); PLC CPU is
the CPU time of the PLC's process (every thread of it) per scan. The
measurement begins after WARM_UP_S seconds of scans in both runs, in the
loaded one once every client has received data. The two runs
alternate (baseline, loaded, baseline, loaded ...) so that a drift of the
host hits both.

    python benchmarks/bench_surfaces.py                 # 2 rounds of 10 s each way
    python benchmarks/bench_surfaces.py --seconds 5 --rounds 1
    python benchmarks/bench_surfaces.py --realtime-priority 40   # both runs under SCHED_FIFO (root)
"""

from __future__ import annotations

import argparse
import asyncio
import http.client
import json
import multiprocessing
import os
import statistics
import tempfile
import threading
import time
import tomllib
from pathlib import Path

from softplc.runtime.config import config_from_dict
from softplc.runtime.config.load import default_config_path
from softplc.runtime.config.servers import ServerConfig
from softplc.runtime.engine.build import build_engine
from softplc.runtime.surfaces.host import Surfaces

BULK = 1000
TARGET = 1.10
#: seconds run before measuring, in both runs (the loaded one after its clients have data):
#: the plant's start-up (CANopen boot-ups, first SDOs) is not part of what is compared
WARM_UP_S = 3.0


def bulk_st() -> str:
    decls = "\n".join(f"    b{i} : DINT;" for i in range(BULK))
    branches = []
    for k in range(10):
        body = " ".join(f"b{i} := b{i} + 1;" for i in range(k, BULK, 10))
        branches.append(f"    {k}: {body}")
    return (
        "VAR_GLOBAL\n" + decls + "\nEND_VAR\n"
        "PROGRAM Bulk\nVAR k : INT; END_VAR\n"
        "k := (k + 1) MOD 10;\nCASE k OF\n" + "\n".join(branches) + "\nEND_CASE\nEND_PROGRAM\n"
    )


def build(tmp: Path, realtime_priority: int = 0):
    path = default_config_path()
    data = tomllib.loads(path.read_text())
    base = path.parent
    data["plc"]["programs"] = [str((base / p).resolve()) for p in data["plc"]["programs"]]
    bulk = tmp / "bulk.st"
    bulk.write_text(bulk_st())
    data["plc"]["programs"].append(str(bulk))
    data["task"].append({"name": "BulkTask", "interval": "10ms", "priority": 5, "programs": ["Bulk"]})
    data["plc"]["realtime_priority"] = realtime_priority
    return build_engine(config_from_dict(data, path), virtual_time=False)


def timed_ticks(engine) -> tuple:
    """Wrap engine.tick to record each tick's wall time and how late it began (ns)."""
    durations: list = []
    late: list = []
    tick = engine.tick
    counter = time.perf_counter_ns
    clock = engine.clock

    def timed() -> None:
        late.append(clock.now_ns() - engine.next_release())
        t0 = counter()
        tick()
        durations.append(counter() - t0)

    engine.tick = timed
    return durations, late


def server(key: str, **options) -> ServerConfig:
    return ServerConfig(key=key, host="127.0.0.1", port=0, writable=(), period_ns=100_000_000, options=options)


# ------------------------------------------------------------ clients


def normal_priority() -> None:
    """A client is an HMI at the normal priority, whatever the PLC's (SCHED_FIFO is inherited)."""
    try:
        os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))
    except (OSError, AttributeError):
        pass


def web_client(url: str, name: str, paths: list, stop: threading.Event, seen: list) -> None:
    """One open page: it says what it shows (POST /api/watch), then reads its
    server-sent events as the browser does."""
    from urllib.parse import urlsplit

    u = urlsplit(url)
    conn = http.client.HTTPConnection(u.hostname, u.port, timeout=10)
    body = json.dumps({"client": name, "paths": paths})
    conn.request("POST", "/api/watch", body, {"Content-Type": "application/json"})
    conn.getresponse().read()
    conn.request("GET", f"/api/events?client={name}")
    response = conn.getresponse()
    while not stop.is_set():
        line = response.fp.readline()
        if not line:
            break
        if line.startswith(b"data:"):
            seen.value += 1
    conn.close()


def web_clients(url: str, paths: list, stop, seen) -> None:
    """Five open pages, each its own connection, in one client process."""
    normal_priority()
    pages = [threading.Thread(target=web_client, args=(url, f"bench{n}", paths, stop, seen)) for n in range(5)]
    for page in pages:
        page.start()
    for page in pages:
        page.join()


def opcua_client(url: str, paths: list, stop: threading.Event, seen: list) -> None:
    from asyncua import Client

    normal_priority()

    class Handler:
        def datachange_notification(self, node, val, data) -> None:
            seen.value += 1

    async def main() -> None:
        async with Client(url) as client:
            idx = await client.get_namespace_index("urn:softplc")
            nodes = [client.get_node(f"ns={idx};s={p}") for p in paths]
            sub = await client.create_subscription(100, Handler())
            await sub.subscribe_data_change(nodes)
            while not stop.is_set():
                await asyncio.sleep(0.1)
            await sub.delete()

    asyncio.run(main())


def modbus_client(url: str, stop: threading.Event, seen: list) -> None:
    from pymodbus.client import ModbusTcpClient

    normal_priority()
    host, port = url.split("//", 1)[1].rsplit(":", 1)
    client = ModbusTcpClient(host, port=int(port))
    client.connect()
    while not stop.is_set():
        for start in range(0, BULK, 125):
            reply = client.read_holding_registers(start, count=min(125, BULK - start))
            if not reply.isError():
                seen.value += len(reply.registers)
        time.sleep(0.1)
    client.close()


# ------------------------------------------------------------ runs


def run(seconds: float, loaded: bool, only: tuple = ("web", "opcua", "modbus"), realtime_priority: int = 0) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        engine = build(Path(tmp), realtime_priority)
        engine.start()
        durations, late = timed_ticks(engine)
        surfaces = None
        ctx = multiprocessing.get_context("spawn")
        stop = ctx.Event()
        clients: list = []
        counts = {"web": ctx.Value("q", 0), "opcua": ctx.Value("q", 0), "modbus": ctx.Value("q", 0)}
        try:
            if loaded:
                keys = {"web": "web", "opcua": "opcua", "modbus": "modbus_server"}
                surfaces = Surfaces(engine, {keys[k]: server(keys[k]) for k in only})
                surfaces.start()
                urls = surfaces.urls
                web_paths = ["Motor.state", "Drive.state", "Pump.state", "Conveyor.state"]
                web_paths += [f"b{i}" for i in range(46)]
                targets = {
                    "web": (web_clients, (urls.get("web"), web_paths)),
                    "opcua": (opcua_client, (urls.get("opcua"), [f"b{i}" for i in range(BULK)])),
                    "modbus": (modbus_client, (urls.get("modbus_server"),)),
                }
                for key in only:
                    target, args = targets[key]
                    clients.append(ctx.Process(target=target, args=(*args, stop, counts[key])))
                for p in clients:
                    p.start()
                waited = 0
                while waited < 60 and not all(counts[key].value for key in only):
                    engine.run(duration_ns=int(1e9))  # the clients connect and subscribe
                    waited += 1
            engine.run(duration_ns=int(WARM_UP_S * 1e9))  # both runs: past the plant's start-up
            durations.clear()
            late.clear()
            overruns = sum(t.stats.overruns for t in engine.tasks)
            cpu = os.times()
            engine.run(duration_ns=int(seconds * 1e9))
            cpu_s = sum(os.times()[:2]) - sum(cpu[:2])
            overruns = sum(t.stats.overruns for t in engine.tasks) - overruns
        finally:
            stop.set()
            for p in clients:
                p.join(timeout=20)
                if p.is_alive():
                    p.kill()
            if surfaces is not None:
                surfaces.stop()
            engine.stop()
    ticks = sorted(durations)
    lateness = sorted(late)
    return {
        "ticks": len(ticks),
        "mean_us": statistics.fmean(ticks) / 1e3,
        "median_us": ticks[len(ticks) // 2] / 1e3,
        "p99_us": ticks[int(len(ticks) * 0.99)] / 1e3,
        "late_mean_us": statistics.fmean(lateness) / 1e3,
        "late_p99_us": lateness[int(len(lateness) * 0.99)] / 1e3,
        "overruns": overruns,
        "plc_cpu_us": cpu_s * 1e6 / len(ticks),
        "received": {k: v.value for k, v in counts.items()},
    }


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=10.0, help="seconds of real time per run")
    parser.add_argument("--rounds", type=int, default=2, help="baseline/loaded pairs")
    parser.add_argument(
        "--only", action="append", choices=("web", "opcua", "modbus"), help="these clients only (repeatable)"
    )
    parser.add_argument(
        "--realtime-priority", type=int, default=0, help="[plc] realtime_priority of both runs (SCHED_FIFO; root)"
    )
    args = parser.parse_args()
    base, load = [], []
    rt = args.realtime_priority
    for r in range(args.rounds):
        b = run(args.seconds, loaded=False, realtime_priority=rt)
        m = run(args.seconds, loaded=True, only=tuple(args.only or ("web", "opcua", "modbus")), realtime_priority=rt)
        base.append(b)
        load.append(m)
        print(f"round {r + 1}: no clients {json.dumps(b)}")
        print(f"round {r + 1}: clients    {json.dumps(m)}", flush=True)
    for what in ("mean_us", "median_us", "p99_us", "late_mean_us", "late_p99_us", "overruns", "plc_cpu_us"):
        b = statistics.fmean(x[what] for x in base)
        m = statistics.fmean(x[what] for x in load)
        ratio = f"{m / b:5.2f}" if b else "  -  "
        print(f"{what:<12} no clients {b:8.1f}   clients {m:8.1f}   ratio {ratio}")
    b = statistics.fmean(x["mean_us"] for x in base)
    m = statistics.fmean(x["mean_us"] for x in load)
    print(
        f"per scan, mean: {m / b:.2f}x the plant without clients (target <= {TARGET:.2f}x): "
        f"{'ok' if m / b <= TARGET else 'MISSED'}"
    )


if __name__ == "__main__":
    main()
