"""Virtual-time speed of every shipped configuration: the embedded default
plant (io_config/default.toml) and every io_config/examples/*.toml, run for
N plant-seconds on the virtual clock (what `softplc run CFG --virtual-time
--duration Ns` runs), printed as plant-seconds per wall-clock second.

The baseline, measured in the same run: the bare engine, the same task set
with the same programs but no bus, no simulator and no [[sim]] faults (the
configuration's [[can]], [canopen], [[plaincan]], [[modbus]], [[loopback]]
and [[sim]] tables removed). Its ratio to the whole plant is what the buses
and the simulated devices cost.

Each configuration runs in a fresh process (CAN channel names and serial
ports stay private to it), prepared as `softplc run` prepares it (the heap
of the start-up frozen out of the garbage collector's sight: settle_heap).
The start-up is cancelled: neither compiling, the CANopen boot nor the
simulators' start is timed, nor the first WARM_S plant-seconds (the boot's
SDO traffic, first-time caches); the figure is the rate between the two
durations, (T - WARM_S) plant-seconds over the wall time between them.

Printed: the host's timeit factor (benchmarks/host.py), each figure here,
and the whole plant's figure scaled to the reference host (x here times the
factor), which is what the targets of issue 32 are checked against (the
default plant 200x, every example 150x). "cpu x" is the same rate over the
process's CPU time instead of the wall clock: on a busy host it moves less.

    python benchmarks/bench_examples.py                  # 60 s of plant each, about 1.5 minutes
    python benchmarks/bench_examples.py --quick          # 10 s each
    python benchmarks/bench_examples.py --only default   # one configuration
    python benchmarks/bench_examples.py --profile genset # cProfile of one, top 25 by own time
    python benchmarks/bench_examples.py --parts default  # what each part of one costs a tick

--parts times each driver's phases (advance_to, read_inputs, write_outputs)
and each task's programs with perf_counter_ns, in this process: µs per tick
of each, their sum and the whole tick. The timing itself costs a few tenths
of a µs per part and call (the whole tick is slower than without it), and
a part's share in the tick is not what leaving it out would save: a part's
code and data leave the processor's caches while the rest of the tick runs
(benchmarks/README.md, "the same code costs three to four times more inside
the tick than in a loop").
"""

from __future__ import annotations

import argparse
import cProfile
import json
import pstats
import subprocess
import sys
import time
import tomllib
from contextlib import contextmanager
from pathlib import Path

from softplc.runtime.config import config_from_dict, load_config
from softplc.runtime.config.load import default_config_path
from softplc.runtime.engine.build import build_engine
from softplc.runtime.launch import settle_heap

sys.path.insert(0, str(Path(__file__).resolve().parent))
from host import timeit_factor

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "io_config" / "examples"
BUS_TABLES = ("can", "canopen", "plaincan", "modbus", "loopback", "sim")
TARGET_DEFAULT, TARGET_EXAMPLE = 200.0, 150.0  # issue 32, on the reference host
WARM_S = 5.0  # plant-seconds run before the timed span: the start-up, cancelled


def configs() -> dict[str, Path]:
    found = {"default": default_config_path()}
    for path in sorted(EXAMPLES.glob("*.toml")):
        found[path.stem] = path
    return found


def _engine(path: Path, bare: bool, tmp: Path):
    data = tomllib.loads(path.read_text())
    if bare:
        for key in BUS_TABLES:
            data.pop(key, None)
    if "retain" in data:  # keep the example's retain file out of the repository
        data["retain"]["file"] = str(tmp / "retain.bin")
    config = config_from_dict(data, path) if (bare or "retain" in data) else load_config(path)
    return build_engine(config, virtual_time=True)


@contextmanager
def _warmed(path: Path, bare: bool):
    """The configuration's engine built and started as `softplc run` does,
    after WARM_S plant-seconds; stopped at the end."""
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        engine = _engine(path, bare, Path(tmp))
        settle_heap()
        engine.start()
        try:
            engine.run(duration_ns=int(WARM_S * 1e9))
            yield engine
        finally:
            engine.stop()


def run_one(path: Path, seconds: float, bare: bool, profile: bool = False) -> dict:
    """Build, start as `softplc run` does, run WARM_S plant-seconds, then
    time engine.run() for seconds more of plant time."""
    with _warmed(path, bare) as engine:
        prof = cProfile.Profile() if profile else None
        t0, c0 = time.perf_counter(), time.process_time()
        if prof is not None:
            prof.enable()
        engine.run(duration_ns=int(seconds * 1e9))
        if prof is not None:
            prof.disable()
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
    if prof is not None:
        pstats.Stats(prof).sort_stats("tottime").print_stats(25)
        pstats.Stats(prof).sort_stats("cumulative").print_stats(25)
    return {"plant_s": seconds, "wall_s": wall, "ratio": seconds / wall, "cpu_ratio": seconds / cpu}


def parts(path: Path, seconds: float) -> None:
    """Print what each driver's phases and each task cost per tick (--parts)."""
    from collections import Counter

    spent: Counter = Counter()
    counter = time.perf_counter_ns

    def timed(call, key):
        def run(*args):
            t0 = counter()
            call(*args)
            spent[key] += counter() - t0

        return run

    with _warmed(path, False) as engine:
        for driver in engine.drivers:
            for phase in ("advance_to", "read_inputs", "write_outputs"):
                setattr(driver, phase, timed(getattr(driver, phase), f"{type(driver).__name__}.{phase}"))
        for task in engine.tasks:
            task.calls = [timed(call, f"task {task.name}") for call in task.calls]
        engine.tick = timed(engine.tick, "whole tick")
        cycle = engine.cycle
        engine.run(duration_ns=int(seconds * 1e9))
        ticks = engine.cycle - cycle
    whole = spent.pop("whole tick")
    print(f"{path.name}: {ticks} ticks, µs per tick (each part timed: the whole tick is slower than untimed)")
    for key, ns in spent.most_common():
        if ns / ticks >= 50:
            print(f"  {key:<40} {ns / ticks / 1e3:7.1f}  {100 * ns / whole:5.1f} %")
    rest = whole - sum(spent.values())
    print(f"  {'the engine between the parts':<40} {rest / ticks / 1e3:7.1f}  {100 * rest / whole:5.1f} %")
    print(f"  {'whole tick':<40} {whole / ticks / 1e3:7.1f}")


def _child(name: str, path: Path, seconds: float, bare: bool) -> dict:
    cmd = [sys.executable, __file__, "--child", str(path), "--seconds", str(seconds)]
    if bare:
        cmd.append("--bare")
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=1800)
    if done.returncode != 0:
        raise RuntimeError(f"{name}: {done.stderr.strip().splitlines()[-1] if done.stderr else done.returncode}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="10 s of plant time each instead of 60 s")
    parser.add_argument("--seconds", type=float, default=None, help="plant seconds per configuration")
    parser.add_argument("--only", action="append", default=[], help="a configuration by name (repeatable)")
    parser.add_argument("--profile", metavar="NAME", help="cProfile one configuration in this process")
    parser.add_argument("--parts", metavar="NAME", help="what each driver and task of one costs a tick")
    parser.add_argument("--child", metavar="PATH", help=argparse.SUPPRESS)
    parser.add_argument("--bare", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    seconds = args.seconds or (10.0 if args.quick else 60.0)
    if args.child:
        print(json.dumps(run_one(Path(args.child), seconds, args.bare)))
        return
    table = configs()
    if args.profile:
        run_one(table[args.profile], seconds, False, profile=True)
        return
    if args.parts:
        parts(table[args.parts], seconds)
        return
    names = args.only or list(table)
    host = timeit_factor()
    print(host.line())
    print(
        f"{seconds:g} s of plant time per configuration after {WARM_S:g} s not timed, virtual clock; "
        "x = plant-seconds per wall-second"
    )
    print(
        f"{'configuration':<20} {'bare engine':>12} {'whole plant':>12} {'cpu x':>8} {'plant/bare':>10} "
        f"{'wall s':>8} {'reference':>10}  target"
    )
    for name in names:
        path = table[name]
        bare = _child(name, path, seconds, True)
        full = _child(name, path, seconds, False)
        target = TARGET_DEFAULT if name == "default" else TARGET_EXAMPLE
        reference = seconds / host.scaled(full["wall_s"])  # the wall time as on the reference host
        mark = "ok" if reference >= target else "MISSED"
        print(
            f"{name:<20} {bare['ratio']:>11.0f}x {full['ratio']:>11.0f}x {full['cpu_ratio']:>7.0f}x "
            f"{full['ratio'] / bare['ratio']:>10.2f} {full['wall_s']:>8.2f} {reference:>9.0f}x  "
            f">= {target:.0f}x {mark}",
            flush=True,
        )
    print(host.line())


if __name__ == "__main__":
    main()
