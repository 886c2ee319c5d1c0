"""Scenarios per second of `softplc sweep` (issue 33): the genset example's
random sweep (slip, breaker time, voltage offset drawn with one seed; each
scenario --duration of engine time in virtual time) run in this process
(one core) and in a pool of one worker process per core, optionally on a
local Dask cluster too (--dask: a LocalCluster of as many worker processes
on 127.0.0.1, what `softplc sweep --scheduler` reaches).

The baseline, measured in the same run, is the serial sweep: the pool's
ratio to it is what the cores give (the pool pays for starting its worker
processes, some 0.5 s each, inside its figure). The rows of every run are
compared: they must be the same.

Printed: the host's timeit factor (benchmarks/host.py), each figure here
and scaled to the reference host (scenarios per second times the factor).

    python benchmarks/bench_sweep.py                     # 60 scenarios of 10 s
    python benchmarks/bench_sweep.py --draws 200 --duration 20s --dask
"""

from __future__ import annotations

import argparse
import time

from host import timeit_factor

from softplc.runtime.config import default_config_path
from softplc.runtime.sweep import execute
from softplc.runtime.sweep.matrix import sweep_from_dict
from softplc.runtime.sweep.scenario import jobs

GENSET = default_config_path().parent / "examples" / "genset.toml"


def sweep_table(draws: int, duration: str) -> dict:
    return {
        "duration": duration,
        "seed": 1,
        "random": {
            "draws": draws,
            "sim.mpu2s1.slip": {"uniform": [0.1, 0.4]},
            "sim.mpu2s1.closing_time": {"choice": ["40ms", "80ms", "150ms"]},
            "sim.mpu2s1.voltage_offset": {"uniform": [-3.0, 3.0]},
        },
        "result": {"values": ["records.mpu2s1.closes[0].phase_deg"], "expect": ["len(records.mpu2s1.closes) == 1"]},
    }


def timed(label: str, made: list, host, **where) -> list:
    t0 = time.perf_counter()
    rows = execute.run(made, **where)
    wall = time.perf_counter() - t0
    rate = len(made) / wall
    print(
        f"{label:<28} {len(made)} scenarios in {wall:6.2f} s: {rate:6.2f} scenarios/s here, "
        f"{rate * host.factor:6.2f} on the reference host",
        flush=True,
    )
    return [rows, rate]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--draws", type=int, default=60)
    parser.add_argument("--duration", default="10s")
    parser.add_argument("--dask", action="store_true", help="a local Dask cluster too")
    args = parser.parse_args()
    host = timeit_factor()
    print(host.line())
    made = jobs(sweep_from_dict(sweep_table(args.draws, args.duration), "bench"), GENSET)
    cores = execute.default_workers()
    print(f"genset random sweep: {len(made)} scenarios of {args.duration}; {cores} core(s)")
    serial, serial_rate = timed("one core (this process)", made, host, workers=1)
    pool, pool_rate = timed(f"{cores} worker processes", made, host, workers=cores)
    print(f"  ratio to one core: {pool_rate / serial_rate:.2f}x; same rows: {pool == serial}")
    if args.dask:
        from distributed import LocalCluster

        with LocalCluster(
            n_workers=cores, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
        ) as cluster:
            on_dask, dask_rate = timed(f"Dask, {cores} workers", made, host, scheduler=cluster.scheduler_address)
        print(f"  ratio to one core: {dask_rate / serial_rate:.2f}x; same rows: {on_dask == serial}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
