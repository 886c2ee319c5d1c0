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
    python benchmarks/bench_surfaces.py --web-in-plc    # a third run per round: the web page in the PLC's process

It prints the host's timeit factor (host.py), each round's ratio of the
loaded run to the baseline run just before it, and their median (issue
32's target: at most 1.05x at normal priority). With --web-in-plc each
round also runs the clients against the web page served from the PLC's
process, as it was before issue 32 (the OPC UA and Modbus servers in the
servers' process either way): the ratio with and without it, paired.
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

from host import timeit_factor

from softplc.runtime.config import config_from_dict
from softplc.runtime.config.load import default_config_path
from softplc.runtime.config.servers import ServerConfig
from softplc.runtime.engine.build import build_engine
from softplc.runtime.surfaces.host import OWN_PROCESS, Surfaces

BULK = 1000
TARGET = 1.05
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


def timed_surfaces(surfaces, spent: dict) -> None:
    """Record the wall time of each capture and each snapshot sent to the servers' process (ns)."""
    counter = time.perf_counter_ns
    hub, process = surfaces.hub, surfaces.process

    def timed(what: str, function):
        def call(*args):
            t0 = counter()
            try:
                return function(*args)
            finally:
                spent[what].append(counter() - t0)

        return call

    hub._capture = timed("capture", hub._capture)
    if process is not None:
        process.forward = timed("forward", process.forward)


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
        try:
            line = response.fp.readline()
        except TimeoutError:  # no event in 10 s: the run has ended (the engine no longer scans)
            if stop.is_set():
                break
            raise
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


def run(
    seconds: float,
    loaded: bool,
    only: tuple = ("web", "opcua", "modbus"),
    realtime_priority: int = 0,
    web_in_plc: bool = False,
) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        engine = build(Path(tmp), realtime_priority)
        engine.start()
        durations, late = timed_ticks(engine)
        surfaces = None
        spent: dict = {"capture": [], "forward": []}  # ns per call, in the PLC's process
        ctx = multiprocessing.get_context("spawn")
        stop = ctx.Event()
        clients: list = []
        counts = {"web": ctx.Value("q", 0), "opcua": ctx.Value("q", 0), "modbus": ctx.Value("q", 0)}
        try:
            if loaded:
                keys = {"web": "web", "opcua": "opcua", "modbus": "modbus_server"}
                apart = OWN_PROCESS - {"web"} if web_in_plc else OWN_PROCESS
                surfaces = Surfaces(engine, {keys[k]: server(keys[k]) for k in only}, own_process=apart)
                surfaces.start()
                timed_surfaces(surfaces, spent)
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
            for calls in spent.values():
                calls.clear()
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
        # what the PLC's process spends for the servers, per snapshot: the capture (between two
        # scans), the pickling and sending to the servers' process (a thread of its own)
        "captures": len(spent["capture"]),
        "capture_us": statistics.fmean(spent["capture"]) / 1e3 if spent["capture"] else 0.0,
        "forward_us": statistics.fmean(spent["forward"]) / 1e3 if spent["forward"] else 0.0,
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
    parser.add_argument(
        "--web-in-plc", action="store_true", help="also the web page in the PLC's process (as before issue 32)"
    )
    args = parser.parse_args()
    host = timeit_factor()
    print(host.line(), flush=True)
    only = tuple(args.only or ("web", "opcua", "modbus"))
    rt = args.realtime_priority
    kinds = {"servers' process": False, **({"web in the PLC": True} if args.web_in_plc else {})}
    base: list = []
    load: dict = {kind: [] for kind in kinds}
    for r in range(args.rounds):
        b = run(args.seconds, loaded=False, realtime_priority=rt)
        base.append(b)
        print(f"round {r + 1}: no clients {json.dumps(b)}", flush=True)
        for kind, web_in_plc in kinds.items():
            m = run(args.seconds, loaded=True, only=only, realtime_priority=rt, web_in_plc=web_in_plc)
            load[kind].append(m)
            print(f"round {r + 1}: clients, {kind}: {json.dumps(m)}", flush=True)
            print(
                f"round {r + 1}: {kind}: per scan {m['mean_us'] / b['mean_us']:.2f}x the baseline "
                f"(median scan {m['median_us'] / b['median_us']:.2f}x); PLC's process per snapshot: "
                f"capture {m['capture_us']:.0f} us, sending {m['forward_us']:.0f} us ({m['captures']} snapshots)",
                flush=True,
            )
    for kind in kinds:
        print(f"-- clients, {kind}")
        for what in ("mean_us", "median_us", "p99_us", "late_mean_us", "late_p99_us", "overruns", "plc_cpu_us"):
            b = statistics.fmean(x[what] for x in base)
            m = statistics.fmean(x[what] for x in load[kind])
            ratio = f"{m / b:5.2f}" if b else "  -  "
            print(f"{what:<12} no clients {b:8.1f}   clients {m:8.1f}   ratio {ratio}")
    print(host.line())
    for kind in kinds:
        ratios = [m["mean_us"] / b["mean_us"] for b, m in zip(base, load[kind])]
        median = statistics.median(ratios)
        print(
            f"per scan, mean, {kind}: {median:.2f}x the plant without clients (median of the rounds' "
            f"{', '.join(f'{x:.2f}' for x in ratios)}; target <= {TARGET:.2f}x): "
            f"{'ok' if median <= TARGET else 'MISSED'}"
        )


if __name__ == "__main__":
    main()
