"""The PLC process of bench_soak_live.py: `softplc run CONFIG` (launch.run_plc,
the same code path: logging, status line, signals, online change, retain,
the web page and the servers' process), plus what the soak needs inside the
PLC's process, where a separate client cannot reach:

* bus faults at random times, one at a time: the CAN trunk cut (both
  CANopen nodes unplugged), the LTMR or the FC 280 unplugged, the DA1's RTU
  cable (its pseudo-terminal null modem) cut, the DA1 silent; each undone
  after 3-15 s, then judged recovered when the program's own view of that
  part (CANOPEN_NODE[n].Operational, MODBUS_CHANNEL[0].Ok) is healthy again
  within RECOVERY_S;
* how late each tick began after its release (Engine.tick wrapped, as
  bench_surfaces.py does), in a histogram of fixed size (10 us buckets up to
  100 ms: nothing grows with the run, so the RSS figure is the PLC's), and
  the ticks that took 5 ms or more (the tasks of such a tick start late: an
  online change's swap, the lock held by another thread), the newest kept;
* the garbage collections of 1 ms or more, with their monotonic time and
  thread (a collection holds the interpreter lock throughout);
* every second, the engine's own counters (scans, per task cycles,
  overruns, worst jitter), the histogram and the faults, written atomically
  to STATS (a JSON file): a kill -9 loses at most the last second.

With SOFTPLC_SOAK_TRACE_MEMORY=FILE in its environment (--trace-memory),
the process traces its allocations (tracemalloc, 8 frames) from
TRACE_FROM_S on (from the start, the compile and the servers' start under
tracemalloc take minutes) and writes to FILE, every TRACE_EVERY_S, the
allocations made since then that grew most, by where they were made: where
a growing RSS comes from.

With SOFTPLC_SOAK_NAME_THREADS=1, each thread's name is given to the
kernel (name_threads), for `perf sched record -k CLOCK_MONOTONIC` beside
the soak: the late ticks' monotonic times find the scan thread's wait.

The engine is reached by wrapping build_engine, which run_plc looks up when
it is called: nothing of softplc is changed.

    python benchmarks/soak_live_plc.py CONFIG STATS LOG SEED faults|no-faults
"""

from __future__ import annotations

import gc
import json
import os
import random
import sys
import threading
import time
from pathlib import Path

BUCKET_NS = 10_000  # 10 us
BUCKETS = 10_000  # up to 100 ms; later ticks in the last bucket (the max is kept exactly)
LATE_MS, LATE_KEPT = 5, 5000  # the ticks this late are kept with their wall time (the newest)
COLLECTION_MS = 1.0  # the garbage collections this long are kept (their monotonic time)
TRACE_FROM_S, TRACE_EVERY_S, TRACE_TOP = 90.0, 120.0, 25
RECOVERY_S = 60.0
FAULT_GAP_S = (20.0, 60.0)
FAULT_LENGTH_S = (3.0, 15.0)
FAULT_KINDS = ("can trunk cut", "ltmr unplugged", "fc280 unplugged", "modbus line cut", "da1 silent")
#: what the program shows of each part: healthy when all are TRUE
HEALTH = {
    "can trunk cut": ("CANOPEN_NODE[40].Operational", "CANOPEN_NODE[20].Operational"),
    "ltmr unplugged": ("CANOPEN_NODE[40].Operational",),
    "fc280 unplugged": ("CANOPEN_NODE[20].Operational",),
    "modbus line cut": ("MODBUS_CHANNEL[0].Ok",),
    "da1 silent": ("MODBUS_CHANNEL[0].Ok",),
}


class Lateness:
    """How late each tick began after its release: a histogram of fixed size."""

    def __init__(self) -> None:
        self.counts = [0] * BUCKETS
        self.n = 0
        self.max_ns = 0
        #: (wall, ms, monotonic) of the newest LATE_KEPT ticks late by LATE_MS or more
        #: (the monotonic time is perf's with -k CLOCK_MONOTONIC: see name_threads)
        self.late_ticks: list = []

    def add(self, late_ns: int) -> None:
        late_ns = max(late_ns, 0)
        self.counts[min(late_ns // BUCKET_NS, BUCKETS - 1)] += 1
        self.n += 1
        if late_ns > self.max_ns:
            self.max_ns = late_ns
        if late_ns >= LATE_MS * 1_000_000:
            self.late_ticks.append((round(time.time(), 3), round(late_ns / 1e6, 2), round(time.monotonic(), 4)))
            del self.late_ticks[:-LATE_KEPT]

    def sparse(self) -> dict:
        return {str(i): c for i, c in enumerate(self.counts) if c}


class Collections:
    """The garbage collections of COLLECTION_MS or more, the newest LATE_KEPT:
    (monotonic start, ms, generation, collected, thread name). A collection
    holds the interpreter lock throughout, in whichever thread allocated."""

    def __init__(self) -> None:
        self.kept: list = []
        self._start = 0.0
        gc.callbacks.append(self._phase)

    def _phase(self, phase: str, info: dict) -> None:
        if phase == "start":
            self._start = time.monotonic()
            return
        ms = (time.monotonic() - self._start) * 1e3
        if ms >= COLLECTION_MS:
            name = threading.current_thread().name
            self.kept.append((round(self._start, 4), round(ms, 2), info["generation"], info["collected"], name))
            del self.kept[:-LATE_KEPT]


class Faults:
    """One bus fault at a time, at random moments; each one's life is a dict."""

    def __init__(self, engine, rng: random.Random) -> None:
        self.engine = engine
        self.rng = rng
        self.done: list = []
        self.stop = threading.Event()
        self.access = None

    def _set(self, kind: str, on: bool) -> None:
        sims = self.engine.simulators
        if kind == "can trunk cut":
            for name in ("ltmr40", "fc28020"):
                sims[name].inject("unplug", None, on)
        elif kind in ("ltmr unplugged", "fc280 unplugged"):
            sims["ltmr40" if kind.startswith("ltmr") else "fc28020"].inject("unplug", None, on)
        elif kind == "modbus line cut":
            cable = sims["da1_1"].line.cable
            cable.cut() if on else cable.mend()
        elif kind == "da1 silent":
            sims["da1_1"].inject("silent", None, on)

    def healthy(self, kind: str) -> bool:
        try:
            return all(bool(self.access.place(path).read()) for path in HEALTH[kind])
        except Exception:  # an online change swapping the program under the read: ask again
            return False

    def run(self) -> None:
        from softplc.runtime.engine.access import Access

        self.access = Access(self.engine)  # reads only: the program's own view of the buses
        rng = self.rng
        while not self.stop.wait(rng.uniform(*FAULT_GAP_S)):
            kind = rng.choice(FAULT_KINDS)
            length = rng.uniform(*FAULT_LENGTH_S)
            fault = {"kind": kind, "on": time.time(), "length_s": round(length, 1), "seen": False}
            self.done.append(fault)
            self._set(kind, True)
            end = time.monotonic() + length
            while time.monotonic() < end and not self.stop.wait(0.1):
                fault["seen"] = fault["seen"] or not self.healthy(kind)
            self._set(kind, False)
            off = time.monotonic()
            fault["off"] = time.time()
            healthy_since = None
            while not self.stop.wait(0.1):
                now = time.monotonic()
                if self.healthy(kind):
                    healthy_since = healthy_since or now
                    if now - healthy_since >= 2.0:
                        fault["recovered_s"] = round(healthy_since - off, 2)
                        break
                else:
                    healthy_since = None
                if now - off > RECOVERY_S:
                    fault["recovered_s"] = None
                    break


def _write_json(path: Path, data: dict) -> None:
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text(json.dumps(data))
    os.replace(tmp, path)


def instrument(engine, stats_path: Path, seed: int, faults_on: bool) -> None:
    """Wrap the tick, start the fault and the stats threads (daemons)."""
    late = Lateness()
    long_ticks: list = []  # (wall, ms, monotonic at its end) of the ticks that took LATE_MS or more
    collections = Collections()
    tick, release, now = engine.tick, engine.next_release, engine.clock.now_ns

    def timed() -> None:
        begin = now()
        late.add(begin - release())
        tick()
        took = now() - begin
        if took >= LATE_MS * 1_000_000:  # a swap, a lock held elsewhere: the tasks of this tick started late
            long_ticks.append((round(time.time(), 3), round(took / 1e6, 2), round(time.monotonic(), 4)))
            del long_ticks[:-LATE_KEPT]

    engine.tick = timed
    faults = Faults(engine, random.Random(seed))

    def stats() -> None:
        while True:
            time.sleep(1.0)
            tasks = [
                {
                    "name": t.name,
                    "cycles": t.stats.cycles,
                    "overruns": t.stats.overruns,
                    "jitter_max_ns": t.stats.jitter_max_ns,
                    "max_ns": t.stats.max_ns,
                }
                for t in engine.tasks
            ]
            data = {
                "wall": time.time(),
                "cycle": engine.cycle,
                "tasks": tasks,
                "late": late.sparse(),
                "late_n": late.n,
                "late_max_ns": late.max_ns,
                "late_ticks": list(late.late_ticks),
                "long_ticks": list(long_ticks),
                "collections": list(collections.kept),
                "faults": list(faults.done),
                "runtime_faults": len(engine.faults),
            }
            try:
                _write_json(stats_path, data)
            except OSError:
                pass
            if faults_on and engine.cycle and not getattr(faults, "started", False):
                faults.started = True  # type: ignore[attr-defined]
                threading.Thread(target=faults.run, name="soak-faults", daemon=True).start()

    threading.Thread(target=stats, name="soak-stats", daemon=True).start()


def trace_memory(path: Path) -> None:
    """The allocations made from TRACE_FROM_S on that are still alive, the
    TRACE_TOP greatest growths by traceback, rewritten to path every
    TRACE_EVERY_S (a thread)."""
    import tracemalloc

    def watch() -> None:
        time.sleep(TRACE_FROM_S)
        tracemalloc.start(8)
        first = tracemalloc.take_snapshot()
        since = time.monotonic()
        while True:
            time.sleep(TRACE_EVERY_S)
            now = tracemalloc.take_snapshot()
            growth = now.compare_to(first, "traceback")[:TRACE_TOP]
            total = sum(s.size_diff for s in now.compare_to(first, "filename"))
            lines = [
                f"{(time.monotonic() - since) / 60:.1f} min after the first snapshot: {total / 1e6:+.2f} MB traced"
            ]
            for stat in growth:
                lines.append(f"{stat.size_diff / 1e3:+9.1f} kB {stat.count_diff:+7d} blocks")
                lines += [f"        {frame}" for frame in stat.traceback.format()[-16:]]
            tmp = path.with_suffix(".tmp")
            tmp.write_text("\n".join(lines) + "\n")
            os.replace(tmp, path)

    threading.Thread(target=watch, name="soak-memory", daemon=True).start()


def name_threads() -> None:
    """Each thread's Python name given to the kernel too (prctl PR_SET_NAME,
    15 bytes), so that `perf sched timehist` and `top -H` tell the scan from
    the servers' threads and python-can's: Python 3.11 names none. A profile
    function that every new thread calls once, then removes."""
    import ctypes
    import ctypes.util

    libc = ctypes.CDLL(ctypes.util.find_library("c"), use_errno=True)

    def name(label: str) -> None:
        libc.prctl(15, label.removeprefix("softplc-").encode("utf-8", "replace")[:15], 0, 0, 0)  # 15: PR_SET_NAME

    def once(frame, event, arg) -> None:
        sys.setprofile(None)
        name(threading.current_thread().name)

    threading.setprofile(once)
    name("plc-main")


def main(argv: list) -> int:
    config, stats_path, log_file, seed, faults_on = argv
    if os.environ.get("SOFTPLC_SOAK_NAME_THREADS"):
        name_threads()
    if os.environ.get("SOFTPLC_SOAK_TRACE_MEMORY"):
        trace_memory(Path(os.environ["SOFTPLC_SOAK_TRACE_MEMORY"]))
    from softplc.runtime.engine import build
    from softplc.runtime.launch import run_plc

    original = build.build_engine

    def build_engine(*args, **kwargs):
        engine = original(*args, **kwargs)
        instrument(engine, Path(stats_path), int(seed), faults_on == "faults")
        return engine

    build.build_engine = build_engine  # run_plc imports it when called

    def compile_errors(error) -> None:
        sys.stderr.write(f"{error}\n")

    return run_plc(
        config,
        virtual_time=False,
        duration_ns=None,
        cycles=None,
        watch=[],
        traces=[],
        units=[],
        final_json=None,
        start_mode=None,
        report_compile_errors=compile_errors,
        log_file=log_file,
    )


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
