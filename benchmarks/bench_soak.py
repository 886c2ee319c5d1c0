"""Soak: the default plant (io_config/default.toml) for an hour of virtual
time under random bus cuts and device faults, then `softplc run` processes
killed with SIGKILL at random moments and started again over their retain
file. Seeded: the same seed gives the same faults at the same engine times.

Part 1, in this process (softplc.testing.PLC, virtual time): one fault at a
time, at random times, of random kinds and lengths:

    CAN trunk cut      both CANopen nodes unplugged (ltmr40, fc28020)
    node unplugged     the LTMR or the FC 280 alone
    Modbus line cut    the RTU cable to the DA1 cut (its MemoryCable)
    unit silent        the DA1 stops answering
    motor jam          the LTMR's load at 400 % of FLC
    drive trips        FC 280 over-current, alarm, trip lock (cleared by a
                       power cycle), DA1 trip with a fault number
    enable off         the DA1's hardware enable opens

Every 100 ms of engine time the program's own view is read (CANOPEN_NODE[n],
MODBUS_CHANNEL[0], the drive and motor blocks, the sequence states): a fault
is "seen" when the view shows it before it ends (plus 10 s), "recovered" when
the affected part is healthy again within the recovery window after it ends.
Reported: faults injected, seen, recovered (with the median and worst time
to recover), runtime faults, log lines with a traceback, memory (RSS, and
with --tracemalloc the Python heap) after the warm-up and at the end, wall
time.

Part 2, processes: the retain example (st_programs/counter_retain.st: kept
is VAR RETAIN, gTotal VAR_GLOBAL PERSISTENT, both counting cycles) in a
temporary directory, retain period 100 ms, run on the real clock and killed
with SIGKILL at a random moment after its first scan, N times; after each
kill the retain file must read back (retain.read_file, as a start does) with
kept = gTotal (one snapshot) and kept never below the previous kill's (a
warm start restored it); a last run stops cleanly and must report a warm
start with the retained values restored.

    python benchmarks/bench_soak.py                   # 1 h of plant, 5 kills: about 2 minutes
    python benchmarks/bench_soak.py --minutes 5 --kills 2
    python benchmarks/bench_soak.py --seed 7 --tracemalloc
"""

from __future__ import annotations

import argparse
import json
import logging
import random
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import tracemalloc
from dataclasses import dataclass, field
from pathlib import Path

from softplc.runtime.engine.retain_file import RetainFileError, read_file
from softplc.testing import PLC

ROOT = Path(__file__).resolve().parents[1]

STEP = "100ms"
STEP_S = 0.1
WARM_UP_S = 30.0
SEEN_GRACE_S = 10.0
RECOVERY_S = 180.0  # an LTMR trip waits for its thermal reset before the program may reset it
STABLE_S = 2.0  # recovered: healthy for this long


@dataclass
class Fault:
    kind: str
    on_s: float
    length_s: float  # 0: a trip, cleared by the program (or the power cycle after length_s)
    seen_s: float | None = None
    recovered_s: float | None = None
    cleared: bool = False  # a lasting fault undone
    healthy_since: float | None = None

    @property
    def off_s(self) -> float:
        return self.on_s + self.length_s


# kind -> (what it does, its length range in s, the part it hits)
KINDS = {
    "can trunk cut": ((3, 20), "canopen"),
    "ltmr unplugged": ((3, 20), "ltmr"),
    "fc280 unplugged": ((3, 20), "fc280"),
    "modbus line cut": ((2, 15), "modbus"),
    "da1 silent": ((2, 15), "modbus"),
    "motor jam": ((5, 20), "ltmr trip"),
    "fc280 over-current": ((0, 0), "fc280 trip"),
    "fc280 alarm": ((0, 0), "fc280 trip"),
    "fc280 trip lock": ((2, 10), "fc280 trip"),
    "da1 trip": ((0, 0), "da1 trip"),
    "da1 enable off": ((2, 15), "da1 enable"),
}


def schedule(rng: random.Random, total_s: float) -> list[Fault]:
    """One fault at a time: a random gap, a random kind and length."""
    faults = []
    t = WARM_UP_S
    while True:
        t += rng.uniform(20, 60)
        kind = rng.choice(sorted(KINDS))
        lo, hi = KINDS[kind][0]
        length = round(rng.uniform(lo, hi), 1)
        if t + length + 60 > total_s:
            return faults
        faults.append(Fault(kind, round(t, 1), length))
        t += length + 60  # the plant gets a minute to recover before the next one


class Plant:
    """The default plant and what its program shows of each part."""

    def __init__(self, seed: int) -> None:
        self.plc = PLC.from_config(edit=lambda d: d["can"][0].__setitem__("channel", f"soak-{seed}"))
        self.line = self.plc.sim("da1_1").line

    def inject(self, fault: Fault, on: bool) -> None:
        plc, k = self.plc, fault.kind
        if k == "can trunk cut":
            for sim in ("ltmr40", "fc28020"):
                plc.fault(sim, "unplug") if on else plc.clear_fault(sim, "unplug")
        elif k in ("ltmr unplugged", "fc280 unplugged"):
            sim = "ltmr40" if k.startswith("ltmr") else "fc28020"
            plc.fault(sim, "unplug") if on else plc.clear_fault(sim, "unplug")
        elif k == "modbus line cut":
            self.line.cable.cut() if on else self.line.cable.mend()
        elif k == "da1 silent":
            plc.fault("da1_1", "silent") if on else plc.clear_fault("da1_1", "silent")
        elif k == "motor jam":
            plc.fault("ltmr40", "load", 400) if on else plc.clear_fault("ltmr40", "load", 400)
        elif k == "fc280 over-current" and on:
            plc.fault("fc28020", "over_current")
        elif k == "fc280 alarm" and on:
            plc.fault("fc28020", "alarm", 0x00000008)
        elif k == "fc280 trip lock":
            plc.fault("fc28020", "trip_lock", 0x00000020) if on else plc.fault("fc28020", "power_cycle")
        elif k == "da1 trip" and on:
            plc.fault("da1_1", "trip", 2)
        elif k == "da1 enable off":
            plc.fault("da1_1", "enable_off") if on else plc.clear_fault("da1_1", "enable_off")

    def healthy(self, part: str) -> bool:
        r = self.plc.read
        if part == "canopen":
            return self.healthy("ltmr") and self.healthy("fc280")
        if part == "ltmr":
            return r("CANOPEN_NODE[40].Operational") and r("Motor.ltmr.NodeOk")
        if part == "fc280":
            return r("CANOPEN_NODE[20].Operational") and r("Pump.state") != "NoNode"
        if part == "modbus":
            return r("MODBUS_CHANNEL[0].Ok") and not r("Drive.drive.ERROR")
        if part == "ltmr trip":
            return not r("Motor.ltmr.Tripped") and r("Motor.state") != "Tripped"
        if part == "fc280 trip":
            return not r("Pump.drive.FAULT") and r("Pump.state") not in ("Faulted", "FaultReset", "NoNode")
        if part == "da1 trip":
            return not r("Drive.drive.FAULT") and r("Drive.state") not in ("Faulted", "FaultReset")
        if part == "da1 enable":
            return r("Drive.drive.HARDWARE_ENABLE")
        raise AssertionError(part)

    def seen(self, fault: Fault) -> bool:
        part = KINDS[fault.kind][1]
        if fault.kind == "motor jam":  # a jam of a stopped motor draws nothing: an alarm or a trip
            return self.plc.read("Motor.ltmr.Alarm") or not self.healthy(part)
        return not self.healthy(part)

    def stop(self) -> None:
        self.plc.stop()


def judge(plant: Plant, fault: Fault, now: float) -> bool:
    """One step of a fault's life, after a scan step ending at now: seen?
    time to undo it? recovered (healthy for STABLE_S)? True when done."""
    if fault.seen_s is None and now <= fault.off_s + SEEN_GRACE_S and plant.seen(fault):
        fault.seen_s = round(now - fault.on_s, 1)
    if now < fault.off_s:
        return False
    if fault.length_s and not fault.cleared:
        plant.inject(fault, False)
        fault.cleared = True
        return False  # judged from the next step on
    if fault.seen_s is not None and plant.healthy(KINDS[fault.kind][1]):
        if fault.healthy_since is None:
            fault.healthy_since = now
        if now - fault.healthy_since >= STABLE_S:
            fault.recovered_s = round(fault.healthy_since - fault.off_s, 1)
            return True
    else:
        fault.healthy_since = None
    return now > fault.off_s + RECOVERY_S


class LogCount(logging.Handler):
    def __init__(self) -> None:
        super().__init__(logging.WARNING)
        self.lines = 0
        self.by_logger: dict[str, int] = {}
        self.tracebacks: list[str] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.lines += 1
        self.by_logger[record.name] = self.by_logger.get(record.name, 0) + 1
        if record.exc_info:
            self.tracebacks.append(f"{record.name}: {record.getMessage()}")


def rss_mb() -> float:
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


@dataclass
class SoakResult:
    faults: list = field(default_factory=list)
    runtime_faults: int = 0
    log_lines: int = 0
    by_logger: dict = field(default_factory=dict)
    tracebacks: list = field(default_factory=list)
    rss_mb: tuple = (0.0, 0.0)
    rss_quarters: list = field(default_factory=list)  # MB after each quarter of the soak
    heap_mb: tuple | None = None
    heap_growth: list = field(default_factory=list)  # the 5 places whose heap grew most
    wall_s: float = 0.0
    plant_s: float = 0.0


def soak(minutes: float, seed: int, trace_heap: bool) -> SoakResult:
    total_s = minutes * 60
    faults = schedule(random.Random(seed), total_s)
    logs = LogCount()
    logging.getLogger().addHandler(logs)
    plant = Plant(seed)
    result = SoakResult(faults=faults)
    t0 = time.perf_counter()
    try:
        plant.plc.run_for(f"{WARM_UP_S}s")
        rss0 = rss_mb()
        if trace_heap:
            tracemalloc.start()
            snap0 = tracemalloc.take_snapshot()
        heap0 = tracemalloc.get_traced_memory()[0] if trace_heap else 0
        pending = list(faults)
        active: list[Fault] = []
        steps = round((total_s - WARM_UP_S) / STEP_S)
        for i in range(1, steps + 1):
            start = WARM_UP_S + (i - 1) * STEP_S
            while pending and pending[0].on_s <= start:
                fault = pending.pop(0)
                plant.inject(fault, True)
                active.append(fault)
            plant.plc.run_for(STEP)
            now = start + STEP_S
            if i % (steps // 4 or 1) == 0:
                result.rss_quarters.append(rss_mb())
            for fault in list(active):
                if judge(plant, fault, now):
                    active.remove(fault)
        result.plant_s = plant.plc.now_ns / 1e9
        result.rss_mb = (rss0, rss_mb())
        if trace_heap:
            result.heap_mb = (heap0 / 2**20, tracemalloc.get_traced_memory()[0] / 2**20)
            growth = tracemalloc.take_snapshot().compare_to(snap0, "lineno")
            result.heap_growth = [f"{g.size_diff / 1024:+9.1f} kB  {g.traceback}" for g in growth[:5]]
            tracemalloc.stop()
        result.runtime_faults = len(plant.plc.engine.faults)
    finally:
        plant.stop()
        logging.getLogger().removeHandler(logs)
    result.wall_s = time.perf_counter() - t0
    result.log_lines = logs.lines
    result.by_logger = logs.by_logger
    result.tracebacks = logs.tracebacks
    return result


def report_soak(r: SoakResult) -> None:
    print(f"plant time {r.plant_s / 60:.1f} min in {r.wall_s:.1f} s wall ({r.plant_s / r.wall_s:.0f}x)")
    print(f"{'fault':22} {'injected':>8} {'seen':>5} {'recovered':>9} {'median s':>9} {'worst s':>8}")
    for kind in sorted(KINDS):
        mine = [f for f in r.faults if f.kind == kind]
        if not mine:
            continue
        times = [f.recovered_s for f in mine if f.recovered_s is not None]
        seen = sum(f.seen_s is not None for f in mine)
        median = f"{statistics.median(times):.1f}" if times else "-"
        worst = f"{max(times):.1f}" if times else "-"
        print(f"{kind:22} {len(mine):8} {seen:5} {len(times):9} {median:>9} {worst:>8}")
    seen = sum(f.seen_s is not None for f in r.faults)
    recovered = sum(f.recovered_s is not None for f in r.faults)
    print(f"{'total':22} {len(r.faults):8} {seen:5} {recovered:9}")
    for f in r.faults:
        if f.seen_s is None or f.recovered_s is None:
            what = "not seen" if f.seen_s is None else f"not recovered within {RECOVERY_S:g} s"
            print(f"  {f.kind} at t={f.on_s:.1f} s for {f.length_s:g} s: {what}")
    n = len(r.tracebacks)
    print(f"runtime faults {r.runtime_faults}; log lines (warnings, errors) {r.log_lines}; tracebacks {n}")
    for name, count in sorted(r.by_logger.items(), key=lambda kv: -kv[1])[:5]:
        print(f"  {count:6} {name}")
    for line in r.tracebacks[:5]:
        print(f"  traceback: {line}")
    (rss0, rss1), heap = r.rss_mb, r.heap_mb
    quarters = ", ".join(f"{q:.1f}" for q in r.rss_quarters)
    print(
        f"RSS after the warm-up {rss0:.1f} MB, at the end {rss1:.1f} MB ({rss1 - rss0:+.1f} MB); by quarter {quarters}"
    )
    if heap is not None:
        print(
            f"Python heap (tracemalloc) {heap[0]:.2f} MB -> {heap[1]:.2f} MB ({heap[1] - heap[0]:+.2f} MB); grew most:"
        )
        for line in r.heap_growth:
            print(f"  {line}")


# ---------------------------------------------------------------- kill -9


RETAIN_CONFIG = """[plc]
programs = ["{program}"]
start = "warm"

[retain]
file = "counter.retain"
period = "100ms"
"""


class Run:
    """One `softplc run` process on the real clock; its stderr read by a thread."""

    def __init__(self, config: Path, *extra: str) -> None:
        softplc = Path(sys.executable).with_name("softplc")
        self.proc = subprocess.Popen(
            [str(softplc), "run", str(config), *extra],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
            text=True,
        )
        self.lines: list[str] = []
        self.running = threading.Event()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        assert self.proc.stderr is not None
        for line in self.proc.stderr:
            self.lines.append(line.rstrip("\n"))
            if "running;" in line:
                self.running.set()

    def finish(self, timeout: float = 60) -> int:
        code = self.proc.wait(timeout)
        self._reader.join(timeout)
        return code

    def said(self, text: str) -> bool:
        return any(text in line for line in self.lines)


def _counters(path: Path) -> tuple[int, int]:
    """(Counter.kept, gTotal) in a retain file, as a start reads it."""
    data = read_file(path)
    if data is None:
        raise RetainFileError(f"{path}: no retain file")
    found = {name.upper(): v["value"] for name, v in data.vars.items()}
    return found["COUNTER.KEPT"], found["GTOTAL"]


def kill_runs(kills: int, rng: random.Random) -> bool:
    """kills runs killed with SIGKILL at a random moment after their first
    scan, then a clean one; True when the retained data came through intact."""
    ok = True
    with tempfile.TemporaryDirectory(prefix="softplc-soak-") as tmp:
        config = Path(tmp) / "retain.toml"
        config.write_text(RETAIN_CONFIG.format(program=ROOT / "st_programs" / "counter_retain.st"))
        retain = Path(tmp) / "counter.retain"
        last = 0
        print(f"{'run':>4} {'killed after s':>14} {'kept':>8} {'gTotal':>8}  retained data")
        for k in range(1, kills + 1):
            run = Run(config, "--duration", "1h")
            if not run.running.wait(120):
                run.proc.kill()
                run.finish()
                print(f"{k:4} did not start: {run.lines[-3:]}")
                return False
            delay = rng.uniform(0.1, 2.5)
            time.sleep(delay)
            run.proc.kill()
            run.finish()
            restored = k == 1 or run.said("warm start: 2 retained variable(s) restored")
            try:
                kept, total = _counters(retain)
            except (RetainFileError, KeyError) as exc:
                print(f"{k:4} {delay:14.2f} the retain file does not read back: {exc}")
                ok = False
                continue
            intact = restored and kept == total and kept >= last
            verdict = (
                "intact"
                if intact
                else "NOT INTACT: "
                + ", ".join(
                    why
                    for why, bad in (
                        ("not restored at the start", not restored),
                        ("kept and gTotal differ", kept != total),
                        (f"below the last run's {last}", kept < last),
                    )
                    if bad
                )
            )
            print(f"{k:4} {delay:14.2f} {kept:8} {total:8}  {verdict}")
            ok = ok and intact
            last = kept
        final = Path(tmp) / "final.json"
        run = Run(config, "--duration", "1s", "--final-json", str(final))
        code = run.finish()
        values = json.loads(final.read_text()) if final.exists() else {}
        kept = values.get("Counter", {}).get("kept", -1)
        clean = code == 0 and run.said("warm start: 2 retained variable(s) restored") and kept >= last
        print(f"clean run: exit {code}, kept {kept} (last saved {last}): {'intact' if clean else 'NOT INTACT'}")
        tracebacks = [line for line in run.lines if "Traceback" in line]
        if tracebacks:
            print(f"  {len(tracebacks)} traceback(s) on stderr")
        return ok and clean and not tracebacks


def main(argv: list | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=float, default=60, help="virtual minutes of the soak (default 60)")
    parser.add_argument("--seed", type=int, default=1, help="the seed of the fault schedule and kill times")
    parser.add_argument("--kills", type=int, default=5, help="softplc run processes killed with SIGKILL (default 5)")
    parser.add_argument("--tracemalloc", action="store_true", help="also trace the Python heap (slower)")
    parser.add_argument("--skip-soak", action="store_true", help="only the kill -9 runs")
    args = parser.parse_args(argv)
    # warnings and errors are counted by logger (LogCount), not printed
    logging.getLogger().setLevel(logging.WARNING)
    ok = True
    if not args.skip_soak:
        print(f"== soak: default plant, {args.minutes:g} virtual minutes, seed {args.seed}")
        result = soak(args.minutes, args.seed, args.tracemalloc)
        report_soak(result)
        ok = not result.tracebacks and not result.runtime_faults
    if args.kills:
        print(f"== kill -9: {args.kills} softplc run processes killed, then a clean run")
        ok = kill_runs(args.kills, random.Random(args.seed)) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
