"""Scan-engine figures, each beside a baseline measured in the same run.

1. Engine overhead per cycle: an empty PROGRAM in one task on the virtual
   clock (no sleeping), against a bare Python loop calling the same empty
   program instance. The overhead is the difference per cycle; target
   <= 10 us.
2. Wake-up jitter of a 10 ms task on the real clock (lateness of each
   cycle's start against its release), against a plain time.sleep loop with
   the same period; target p99 <= 100 us.

    python benchmarks/bench_engine.py                 # 60 s of jitter each (2 minutes)
    python benchmarks/bench_engine.py --seconds 10    # shorter
    python benchmarks/bench_engine.py --skip-jitter
"""

from __future__ import annotations

import argparse
import statistics
import time

from softplc.runtime.config import ProgramInstance, TaskConfig
from softplc.runtime.engine.clock import RealClock, VirtualClock
from softplc.runtime.engine.scan import Engine
from softplc.runtime.program import compile_files

EMPTY = "PROGRAM Empty\nEND_PROGRAM\n"
MS = 1_000_000


def _engine(program, clock, interval_ns=10 * MS) -> Engine:
    task = TaskConfig(
        name="Main",
        interval_ns=interval_ns,
        pause_ns=MS,
        priority=1,
        watchdog_ns=100 * MS,
        sensitivity=1,
        programs=[ProgramInstance("Empty", "Empty", "bench")],
        key="bench",
    )
    engine = Engine(program, [task], clock=clock)
    engine.start()
    return engine


def overhead(program, cycles: int, repeats: int = 5) -> dict:
    engine_per, bare_per = [], []
    for _ in range(repeats):
        engine = _engine(program, VirtualClock())
        t0 = time.perf_counter()
        engine.run(cycles=cycles)
        engine_per.append((time.perf_counter() - t0) / cycles)
        call = engine.tasks[0].calls[0]
        t0 = time.perf_counter()
        for _ in range(cycles):
            call()
        bare_per.append((time.perf_counter() - t0) / cycles)
        engine.stop()
    e, b = min(engine_per), min(bare_per)
    return {
        "engine_us": e * 1e6,
        "bare_us": b * 1e6,
        "overhead_us": (e - b) * 1e6,
        "median_overhead_us": (statistics.median(engine_per) - statistics.median(bare_per)) * 1e6,
    }


def _percentiles(samples_ns: list) -> dict:
    s = sorted(samples_ns)
    pick = lambda q: s[min(len(s) - 1, int(q * len(s)))] / 1e3  # noqa: E731
    return {"n": len(s), "p50_us": pick(0.50), "p99_us": pick(0.99), "max_us": s[-1] / 1e3}


def engine_jitter(program, seconds: float) -> dict:
    engine = _engine(program, RealClock())
    samples = []
    engine.after_tick.append(lambda e: samples.append(e.tasks[0].stats.jitter_last_ns))
    engine.run(duration_ns=int(seconds * 1e9))
    engine.stop()
    return _percentiles(samples[1:])  # the first release is "now": no lateness to measure


def sleep_jitter(seconds: float, period_ns: int = 10 * MS) -> dict:
    samples = []
    start = time.perf_counter_ns()
    release = start
    end = start + int(seconds * 1e9)
    while release + period_ns < end:
        release += period_ns
        delay = release - time.perf_counter_ns()
        if delay > 0:
            time.sleep(delay / 1e9)
        samples.append(time.perf_counter_ns() - release)
    return _percentiles(samples)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=60.0, help="jitter measurement time for each loop")
    parser.add_argument("--cycles", type=int, default=200_000, help="cycles for the overhead measurement")
    parser.add_argument("--skip-jitter", action="store_true")
    args = parser.parse_args()
    program = compile_files([], texts={"empty.st": EMPTY})

    o = overhead(program, args.cycles)
    print(f"engine overhead, empty program, virtual clock, {args.cycles} cycles (best of 5):")
    print(
        f"  engine {o['engine_us']:.2f} us/cycle, bare call {o['bare_us']:.2f} us/cycle, "
        f"overhead {o['overhead_us']:.2f} us/cycle (median {o['median_overhead_us']:.2f}), "
        f"ratio {o['engine_us'] / o['bare_us']:.1f}x  [target <= 10 us]"
    )
    if args.skip_jitter:
        return
    print(f"wake-up jitter of a 10 ms task, real clock, {args.seconds:g} s each:")
    base = sleep_jitter(args.seconds)
    print(
        f"  time.sleep loop : p50 {base['p50_us']:.0f} us, p99 {base['p99_us']:.0f} us, "
        f"max {base['max_us']:.0f} us ({base['n']} cycles)"
    )
    eng = engine_jitter(program, args.seconds)
    print(
        f"  softplc engine  : p50 {eng['p50_us']:.0f} us, p99 {eng['p99_us']:.0f} us, "
        f"max {eng['max_us']:.0f} us ({eng['n']} cycles)  [target p99 <= 100 us]"
    )
    print(f"  ratio p99 engine/sleep: {eng['p99_us'] / max(base['p99_us'], 1e-9):.3g}")


if __name__ == "__main__":
    main()
