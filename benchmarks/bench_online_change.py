"""What an online change costs the scan (issue 31: 3 overruns in 20 changes
of an idle PLC, 36.9 ms of jitter; 9 in 10 with a web client): the
default plant on the real clock, changed again and again (a comment added
to one of its ST files, so every change compiles and swaps the whole
program), against the same plant left alone for as long, in the same run.

Measured per run: how late a tick began after its release (the kernel's
wake-up, the interpreter lock, the swap itself), the releases missed (the
tasks' overrun counters), and the swap: the time the scan thread spent in
the change (OnlineChange's ChangeRequest, between two scans). With --web a
page watches 50 variables over the event stream and posts a watch every
100 ms, in a process of its own, as issue 31's client did.

    python benchmarks/bench_online_change.py                  # 20 changes, then as long without
    python benchmarks/bench_online_change.py --changes 10 --web
    python benchmarks/bench_online_change.py --bulk 1000      # and a program of 1,000 globals
    python benchmarks/bench_online_change.py --in-process     # compiled in the PLC's process, as before

The compile runs in the compile process (engine/compile_process.py),
started and warmed before the changes as softplc run does; --in-process
compiles in the requester's thread of the PLC's process instead (the
compile= hook), as every change did before, for the comparison.
"""

from __future__ import annotations

import argparse
import http.client
import json
import multiprocessing
import shutil
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
from softplc.runtime.engine import online_change
from softplc.runtime.engine.build import build_engine
from softplc.runtime.launch import settle_heap
from softplc.runtime.program import compile_files
from softplc.runtime.surfaces.host import Surfaces

#: the page's variables: the default plant's
WATCHED = ["Conveyor.state", "Conveyor.speedOut", "Motor.state", "Pump.state", "Drive.state"]


def build(tmp: Path, bulk: int):
    """The default plant with its ST files copied into tmp (the change edits a copy)."""
    path = default_config_path()
    data = tomllib.loads(path.read_text())
    programs = []
    for p in data["plc"]["programs"]:
        copy = tmp / Path(p).name
        shutil.copy(path.parent / p, copy)
        programs.append(str(copy))
    if bulk:
        decls = "\n".join(f"    b{i} : DINT;" for i in range(bulk))
        body = "\n".join(f"b{i} := b{i} + 1;" for i in range(0, bulk, 10))
        (tmp / "bulk.st").write_text(f"VAR_GLOBAL\n{decls}\nEND_VAR\nPROGRAM Bulk\n{body}\nEND_PROGRAM\n")
        programs.append(str(tmp / "bulk.st"))
        data["task"].append({"name": "BulkTask", "interval": "10ms", "priority": 5, "programs": ["Bulk"]})
    data["plc"]["programs"] = programs
    config = config_from_dict(data, path)
    return config, build_engine(config, virtual_time=False, retain=False)


def timed(engine) -> tuple:
    """Record how late each tick began (ns) and the time of each swap (ns)."""
    late: list = []
    swaps: list = []
    tick = engine.tick

    def timed_tick() -> None:
        late.append(engine.clock.now_ns() - engine.next_release())
        tick()

    engine.tick = timed_tick
    call = online_change.ChangeRequest.__call__

    def timed_call(self, eng) -> None:
        t0 = time.perf_counter_ns()
        call(self, eng)
        swaps.append(time.perf_counter_ns() - t0)

    online_change.ChangeRequest.__call__ = timed_call  # type: ignore[method-assign]
    return late, swaps


def page(url: str, stop) -> None:
    """A web page that reads its event stream and posts a watch every 100 ms."""
    from urllib.parse import urlsplit

    u = urlsplit(url)

    def reader() -> None:
        conn = http.client.HTTPConnection(u.hostname, u.port, timeout=30)
        conn.request("GET", "/api/events?client=bench")
        response = conn.getresponse()
        while not stop.is_set() and response.fp.readline():
            pass

    threading.Thread(target=reader, daemon=True).start()
    conn = http.client.HTTPConnection(u.hostname, u.port, timeout=30)
    while not stop.is_set():
        conn.request(
            "POST",
            "/api/watch",
            json.dumps({"client": "bench", "paths": WATCHED}),
            {"Content-Type": "application/json"},
        )
        conn.getresponse().read()
        time.sleep(0.1)


def run(changes: int, web: bool, bulk: int, pause_s: float, freeze: bool, in_process: bool = False) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        config, engine = build(Path(tmp), bulk)
        if freeze:
            settle_heap()  # as softplc run does before the first scan
        engine.start()
        late, swaps = timed(engine)
        surfaces = None
        stop = multiprocessing.get_context("spawn").Event()
        client = None
        if web:
            surfaces = Surfaces(engine, {"web": ServerConfig("web", "127.0.0.1", 0, ("*",), 250_000_000)})
            surfaces.start()
            client = multiprocessing.get_context("spawn").Process(target=page, args=(surfaces.urls["web"], stop))
            client.start()
        scan = threading.Thread(target=engine.run, name="scan")
        scan.start()
        try:
            time.sleep(2.0)  # the plant's start-up is not measured
            out = {}
            for phase in ("changes", "alone"):
                before = sum(t.stats.overruns for t in engine.tasks)
                first = len(late)
                t0 = time.monotonic()
                if phase == "changes":
                    here = (
                        (lambda: compile_files(config.programs, profile=config.profile, libraries=config.libraries))
                        if in_process
                        else None
                    )
                    changer = online_change.OnlineChange(engine, config, compile=here)
                    changer.warm()  # as softplc run's start(): the child's start-up is not a change's
                    before = sum(t.stats.overruns for t in engine.tasks)
                    first = len(late)
                    t0 = time.monotonic()
                    target = Path(config.programs[0])
                    for n in range(changes):
                        target.write_text(target.read_text() + f"\n(* change {n} *)\n")
                        report = changer.request(f"bench {n}")
                        assert report.applied, report.lines()
                        time.sleep(pause_s)
                    spent = time.monotonic() - t0
                    changer.stop()
                else:
                    time.sleep(spent)
                window = late[first:]
                out[phase] = {
                    "ticks": len(window),
                    "late_max_ms": max(window) / 1e6,
                    "late_p99_ms": statistics.quantiles(window, n=100)[98] / 1e6,
                    "overruns": sum(t.stats.overruns for t in engine.tasks) - before,
                }
            out["changes"]["swap_ms"] = [s / 1e6 for s in swaps]
            return out
        finally:
            stop.set()
            engine.request_stop()
            scan.join(30)
            if client is not None:
                client.join(10)
            if surfaces is not None:
                surfaces.stop()
            engine.stop()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--changes", type=int, default=20)
    parser.add_argument("--web", action="store_true", help="a page on the event stream, posting watches")
    parser.add_argument("--bulk", type=int, default=0, help="a program of this many DINT globals too")
    parser.add_argument("--pause", type=float, default=0.2, help="seconds between two changes")
    parser.add_argument("--in-process", action="store_true", help="compile in the PLC's process, as before")
    parser.add_argument("--no-freeze", action="store_true", help="without softplc run's gc.freeze() at the start")
    args = parser.parse_args()
    host = timeit_factor()
    print(host.line())
    result = run(args.changes, args.web, args.bulk, args.pause, not args.no_freeze, args.in_process)
    swaps = result["changes"].pop("swap_ms")
    print(
        f"{args.changes} online changes{' with a web page' if args.web else ''}"
        f"{f', {args.bulk} globals more' if args.bulk else ''}"
        f", compiled {'in the PLC' + chr(39) + 's process' if args.in_process else 'in the compile process'}:"
    )
    print(f"  swap in the scan thread: median {statistics.median(swaps):.2f} ms, max {max(swaps):.2f} ms")
    for phase, r in result.items():
        print(
            f"  {phase:8} {r['ticks']:6} ticks: late max {r['late_max_ms']:.2f} ms, "
            f"p99 {r['late_p99_ms']:.2f} ms, overruns {r['overruns']}"
        )


if __name__ == "__main__":
    main()
