"""Genset synchronisation figures, in virtual time, through the whole stack
(st_programs/genset_sync.st, the plain-CAN driver, the MPU2-S node, the
simulated MPU2-S with its genset, busbar and breaker):

1. The phase error at closing over a sweep of initial slips and breaker
   closing times, with the PLC closing (GENSET_SYNC, a fast phase input)
   and with the MPU2-S closing (supervise mode); then, PLC closing, over
   the slip at closing (GENSET_SYNC.SLIP_TARGET, within the window of
   -df min 0.10 .. +df max 0.20 Hz) and the closing times: every value,
   then min, median and max of |phase| when the contacts touch.
2. Speed: virtual seconds per wall-clock second of the live-bus example
   (io_config/examples/genset.toml) for 60 s of plant time, against a
   baseline measured in the same run: the same program and task with no
   bus and no simulator.

    python benchmarks/bench_genset.py           # about 15 s
    python benchmarks/bench_genset.py --quick
"""

from __future__ import annotations

import argparse
import statistics
import time
import tomllib
from pathlib import Path

from softplc.runtime.config import config_from_dict
from softplc.runtime.engine.build import build_engine

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "io_config" / "examples" / "genset.toml"
PROGRAM = ROOT / "st_programs" / "genset_sync.st"
MS = 1_000_000
CLOSED = 5  # GENSET_STATE_CLOSED


def _data(channel: str, sim: dict | None = None, plant: bool = True) -> dict:
    data = tomllib.loads(EXAMPLE.read_text())
    data["plc"]["programs"] = [str(PROGRAM)]
    data["can"][0]["channel"] = channel
    data["sim"][0].update(sim or {})
    if not plant:
        for key in ("can", "plaincan", "sim"):
            del data[key]
    return data


def close_phase(n: int, slip: float, closing_ms: int, supervise: bool, target: float | None = None) -> float:
    data = _data(f"bench-genset-{n}", {"slip": slip, "closing_time": f"{closing_ms}ms"})
    engine = build_engine(config_from_dict(data, EXAMPLE), virtual_time=True)
    sim = engine.simulators["mpu2s1"]
    sim.store.set_word(32, closing_ms)  # ID 32, the GCB closing time the program reads
    engine.start()
    engine.set("Genset.Supervise", supervise)
    if target is not None:
        engine.set("Genset.sync.SLIP_TARGET", target)  # the slip GENSET_SYNC's f controller aims at
    try:
        while engine.get("Genset.sync.STATE") != CLOSED:
            if engine.now_ns() > 120_000 * MS:
                raise RuntimeError(f"slip {slip} Hz, {closing_ms} ms: no close in 120 s")
            engine.run(cycles=1)
        [close] = sim.closes
        return close.phase_deg
    finally:
        engine.stop()


def speed(seconds: float, plant: bool) -> float:
    data = _data("bench-genset-speed", plant=plant)
    engine = build_engine(config_from_dict(data, EXAMPLE), virtual_time=True)
    engine.start()
    t0 = time.perf_counter()
    engine.run(duration_ns=int(seconds * 1000) * MS)
    wall = time.perf_counter() - t0
    engine.stop()
    return seconds / wall


def sweep(rows, closing, supervise: bool, runs) -> None:
    """One line per row (label, initial slip, SLIP_TARGET), a column per
    closing time; then min, median and max of |phase|."""
    phases = []
    for label, slip, target in rows:
        cells = []
        for ms in closing:
            phase = close_phase(next(runs), slip, ms, supervise, target)
            phases.append(abs(phase))
            cells.append(f"{ms:>3} ms {phase:+7.3f}°")
        print(f"   {label}: " + "  ".join(cells))
    print(
        f"   |phase| over {len(phases)} closes: min {min(phases):.3f}°, "
        f"median {statistics.median(phases):.3f}°, max {max(phases):.3f}°"
    )


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    slips = (0.1, 0.3) if args.quick else (0.05, 0.1, 0.2, 0.3, 0.45, -0.1, -0.15)
    closing = (80,) if args.quick else (40, 80, 150, 300)
    runs = iter(range(1, 1000))
    for supervise in (False, True):
        who = "MPU2-S closes (supervise)" if supervise else "PLC closes (GENSET_SYNC, fast phase input)"
        print(f"1. phase at closing, {who}")
        rows = [(f"slip {slip:+.2f} Hz", slip, None) for slip in slips]
        sweep(rows, closing, supervise, runs)
    targets = (0.15,) if args.quick else (0.03, 0.1, 0.15, -0.03, -0.06)
    print("1. phase at closing, PLC closes, by the slip at closing (SLIP_TARGET)")
    sweep([(f"target {t:+.2f} Hz", 0.3, t) for t in targets], closing, False, runs)
    seconds = 20.0 if args.quick else 60.0
    base = speed(seconds, plant=False)
    full = speed(seconds, plant=True)
    print(f"2. {seconds:.0f} s of plant time, 10 ms task")
    print(f"   program alone (baseline): {base:8.1f} x real time")
    print(f"   whole plant:              {full:8.1f} x real time  ({full / base:.2f} of the baseline)")


if __name__ == "__main__":
    main()
