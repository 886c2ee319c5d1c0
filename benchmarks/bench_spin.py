#!/usr/bin/env python3
"""The real clock's spin window: wake-up lateness against CPU (see
benchmarks/README.md).

    python benchmarks/bench_spin.py                       # 6 settings x 30 s, about 3.5 minutes
    python benchmarks/bench_spin.py --seconds 10          # shorter
    python benchmarks/bench_spin.py --spins 0,0.2,1       # other settings (ms)
    python benchmarks/bench_spin.py --config io_config/default.toml   # a whole plant

Before each release the real clock sleeps until `spin` before it, then
busy-waits the rest ([plc] spin). For each setting the engine runs a 10 ms
task (an empty PROGRAM, or the plant of --config with its drivers and
simulated devices) on the real clock and records, for every cycle of its
fastest task, the lateness of the start against the release; the process's
CPU time over the wall time is the price. Beside them, measured in the same
run, a plain loop that time.sleep()s to the same releases (spin 0 with
nothing around it). The settings take turns in rounds, so that a change in
the machine's load hits them alike.

Nothing here is asserted: the script prints figures measured in this run.
"""

from __future__ import annotations

import argparse
import logging
import statistics
import sys
import time
from dataclasses import replace

from softplc.runtime.config import ProgramInstance, TaskConfig, load_config
from softplc.runtime.engine.build import build_engine
from softplc.runtime.engine.clock import RealClock
from softplc.runtime.engine.scan import Engine
from softplc.runtime.program import compile_files

MS = 1_000_000
EMPTY = "PROGRAM Empty\nEND_PROGRAM\n"


def _empty_engine(program, spin_ns: int) -> Engine:
    task = TaskConfig(
        name="Main",
        interval_ns=10 * MS,
        pause_ns=MS,
        priority=1,
        watchdog_ns=100 * MS,
        sensitivity=1,
        programs=[ProgramInstance("Empty", "Empty", "bench")],
        key="bench",
    )
    return Engine(program, [task], clock=RealClock(spin_ns=spin_ns))


def run_engine(make, seconds: float) -> tuple:
    """(lateness samples in ns of the fastest task, CPU seconds, wall seconds)."""
    engine = make()
    engine.start()
    fastest = min(engine.tasks, key=lambda t: t.interval_ns or 0)
    samples: list = []
    seen = [0]

    def record(e) -> None:
        if fastest.stats.cycles != seen[0]:  # the task ran in this tick
            seen[0] = fastest.stats.cycles
            samples.append(fastest.stats.jitter_last_ns)

    engine.after_tick.append(record)
    engine.run(cycles=2)  # the first releases are "now"
    samples.clear()
    c0, w0 = time.process_time(), time.perf_counter()
    engine.run(duration_ns=int(seconds * 1e9))
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    engine.stop()
    return samples, cpu, wall


def run_sleep(seconds: float, period_ns: int = 10 * MS) -> tuple:
    samples = []
    c0, w0 = time.process_time(), time.perf_counter()
    release = time.perf_counter_ns()
    end = release + int(seconds * 1e9)
    while release + period_ns < end:
        release += period_ns
        delay = release - time.perf_counter_ns()
        if delay > 0:
            time.sleep(delay / 1e9)
        samples.append(time.perf_counter_ns() - release)
    return samples, time.process_time() - c0, time.perf_counter() - w0


def summary(samples: list, cpu: float, wall: float) -> dict:
    s = sorted(samples)
    return {
        "n": len(s),
        "mean_us": statistics.fmean(s) / 1e3,
        "p50_us": s[len(s) // 2] / 1e3,
        "p99_us": s[min(len(s) - 1, int(0.99 * len(s)))] / 1e3,
        "max_us": s[-1] / 1e3,
        "cpu_pct": 100 * cpu / wall,
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seconds", type=float, default=30.0, help="real-clock seconds per setting (default 30)")
    ap.add_argument("--rounds", type=int, default=3, help="the seconds of each setting are cut in this many turns")
    ap.add_argument("--spins", default="0,0.05,0.1,0.2,0.5,1", help="spin windows in ms, comma-separated")
    ap.add_argument("--config", help="run this configuration's plant instead of an empty 10 ms task")
    args = ap.parse_args()
    spins = [round(float(x) * MS) for x in args.spins.split(",")]
    logging.disable(logging.WARNING)  # a plant's bus start-up talk is not the figure

    if args.config:
        config = load_config(args.config)
        program = compile_files(config.programs, profile=config.profile)
        what = f"the plant of {args.config}"

        def maker(spin_ns: int):
            return lambda: build_engine(replace(config, spin_ns=spin_ns), program=program, retain=False)
    else:
        program = compile_files([], texts={"empty.st": EMPTY})
        what = "an empty PROGRAM in a 10 ms task"

        def maker(spin_ns: int):
            return lambda: _empty_engine(program, spin_ns)

    keys = ["sleep"] + spins
    collected: dict = {k: ([], 0.0, 0.0) for k in keys}
    turn = args.seconds / args.rounds
    print(f"spin window against lateness and CPU: {what}, real clock, {args.seconds:g} s per setting")
    for r in range(args.rounds):
        order = keys[r % len(keys) :] + keys[: r % len(keys)]  # rotate who goes first
        for key in order:
            samples, cpu, wall = run_sleep(turn) if key == "sleep" else run_engine(maker(key), turn)
            old = collected[key]
            collected[key] = (old[0] + samples, old[1] + cpu, old[2] + wall)
    print(f"   {'spin':>10} {'cycles':>7} {'mean':>9} {'p50':>9} {'p99':>9} {'max':>9} {'CPU':>7}")
    for key in keys:
        s = summary(*collected[key])
        label = "sleep loop" if key == "sleep" else f"{key / 1e6:g} ms"
        print(
            f"   {label:>10} {s['n']:>7} {s['mean_us']:>6.0f} us {s['p50_us']:>6.0f} us "
            f"{s['p99_us']:>6.0f} us {s['max_us']:>6.0f} us {s['cpu_pct']:>6.1f}%"
        )
    print(
        "   lateness: a cycle's start after its release (mean, median, 99th percentile, worst);\n"
        "   CPU: process CPU time / wall time, in % of one core; sleep loop: time.sleep() to the\n"
        "   same releases, no engine (the kernel's own wake-up lateness)"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
