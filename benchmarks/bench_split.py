"""Where a plant's tick goes, by kind of work: the default plant (or any
shipped configuration) in virtual time, sampled by py-spy from outside the
process, each sample put in one of five kinds:

    ST programs          the generated code and its runtime library (rtlib)
    device models        the simulated devices' physics and registers
                         (runtime/devices/*/, all but the bus side, sim.py)
    protocol libraries   pymodbus, canopen, python-can
    our bus plumbing     the masters, the simulated slaves and lines, the
                         bus pump (runtime/io/, runtime/sim/, devices' sim.py)
    engine               the scan (runtime/engine/) and everything else

A sample goes to the innermost frame of ours or of a library on its stack:
the standard library (fractions, struct ...), the process image's accessors
and the program's struct writers count for whatever called them.

Printed: the host's timeit factor, the plant's rate measured in this
process without sampling (bench_examples.run_one), each kind's share of the
sampled ticks and its µs per plant-second, here and scaled to the reference
host. Then what a target of issue 32 leaves: at T x on the reference host a
plant-second may take 1/T s there; what the first three kinds take now is
what the simulation itself computes, and the rest is what our plumbing and
the engine may take for the target to hold.

The sampling is py-spy's (a separate program: `pip install py-spy`); the
shares are of wall time in the scan thread, without the distortion of an
in-process profiler, which slows code that calls many small functions more
than the rest. py-spy pauses the process briefly at each sample; the rate
it is sampled at is printed, not used.

    python benchmarks/bench_split.py                        # the default plant, 600 plant-seconds sampled
    python benchmarks/bench_split.py --config genset --seconds 100
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
from collections import Counter
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import bench_examples
from bench_examples import TARGET_DEFAULT, TARGET_EXAMPLE, configs, run_one
from host import timeit_factor

KINDS = ("ST programs", "device models", "protocol libraries", "our bus plumbing", "engine")
_FILE = re.compile(r"\((.*?):\d+\)$")
_LIBRARIES = ("pymodbus/", "canopen/", "can/")
_TICK = "Engine.tick ("
#: ours, but counted for whatever called them: the image's accessors, the ST structs' writers
_PASS_THROUGH = ("runtime/image/", "runtime/program/variables.py")


def kind_of(stack: list[str]) -> str | None:
    """The kind of one py-spy stack (frames outermost first, each
    "function (file:line)"); None when it is not inside a tick."""
    ticks = [i for i, frame in enumerate(stack) if frame.startswith(_TICK)]
    if not ticks:
        return None
    for frame in reversed(stack[ticks[0] + 1 :]):
        if "<softplc-" in frame:
            return "ST programs"
        found = _FILE.search(frame)
        path = found.group(1) if found else ""
        path = path.removeprefix("softplc/")  # an installed package; an editable one has none
        if path.startswith(_LIBRARIES):
            return "protocol libraries"
        if not path.startswith("runtime/") or path.startswith(_PASS_THROUGH):
            continue  # the standard library, or ours passed through
        if path.startswith("runtime/st/"):
            return "ST programs"
        if path.startswith("runtime/devices/"):
            return "our bus plumbing" if path.endswith("/sim.py") else "device models"
        if path.startswith(("runtime/io/", "runtime/sim/")):
            return "our bus plumbing"
        return "engine"
    return "engine"


def split(raw: str) -> Counter:
    """Samples per kind, from py-spy's raw output ("frame;frame;... count" lines)."""
    kinds: Counter = Counter()
    for line in raw.splitlines():
        stack, _, count = line.rstrip().rpartition(" ")
        if not stack or not count.isdigit():
            continue
        kind = kind_of(stack.split(";"))
        if kind is not None:
            kinds[kind] += int(count)
    return kinds


def sample(path: Path, seconds: float, py_spy: str, rate: int) -> Counter:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "raw.txt"
        cmd = [py_spy, "record", "--rate", str(rate), "--format", "raw", "--output", str(out), "--"]
        # bench_examples' own child: the configuration warmed and run as its table runs it
        cmd += [sys.executable, bench_examples.__file__, "--child", str(path), "--seconds", str(seconds)]
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=3600)
        if done.returncode != 0 or not out.exists():
            raise SystemExit(f"py-spy failed ({done.returncode}): {done.stderr.strip()[-500:]}")
        return split(out.read_text())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--config", default="default", help="a shipped configuration by name (bench_examples)")
    parser.add_argument("--seconds", type=float, default=600.0, help="plant seconds sampled")
    parser.add_argument("--rate", type=int, default=1000, help="py-spy's samples per second")
    args = parser.parse_args()
    py_spy = shutil.which("py-spy") or shutil.which("py-spy", path=str(Path(sys.executable).parent))
    if py_spy is None:
        raise SystemExit("bench_split needs py-spy, a sampling profiler: pip install py-spy")
    path = configs()[args.config]
    host = timeit_factor()
    print(host.line())
    measured = run_one(path, 30.0, False)  # unsampled: the rate the shares are taken of
    wall_us = 1e6 / measured["ratio"]  # µs of wall time per plant-second, here
    kinds = sample(path, args.seconds, py_spy, args.rate)
    total = sum(kinds.values())
    if not total:
        raise SystemExit("py-spy took no sample inside a tick")
    print(
        f"{args.config}: {measured['ratio']:.0f}x here ({wall_us:,.0f} µs per plant-second, 30 plant-seconds "
        f"unsampled); {total:,} samples of its ticks over {args.seconds:g} plant-seconds"
    )
    print(f"  {'kind':<22} {'share':>6} {'µs/plant-s here':>16} {'scaled':>8}")
    for kind in KINDS:
        share = kinds[kind] / total
        print(f"  {kind:<22} {100 * share:5.1f}% {share * wall_us:16,.0f} {share * wall_us / host.factor:8,.0f}")
    computed = sum(kinds[k] for k in KINDS[:3]) / total
    target = TARGET_DEFAULT if args.config == "default" else TARGET_EXAMPLE
    budget = 1e6 / target  # µs per plant-second on the reference host
    floor = computed * wall_us / host.factor
    print(
        f"at {target:.0f}x a plant-second may take {budget:,.0f} µs on the reference host; the programs, models "
        f"and libraries take {floor:,.0f} ({100 * computed:.0f} % of the tick): our plumbing and the engine, "
        f"{(1 - computed) * wall_us / host.factor:,.0f} µs now, would have to fit in {budget - floor:,.0f}"
    )
    print(f"with our plumbing and the engine taking no time, the plant would run at {1e6 / floor:.0f}x scaled")


if __name__ == "__main__":
    main()
