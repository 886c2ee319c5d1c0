"""Where a sweep's scenarios run: in this process one after the other
(workers=1), in a pool of worker processes on this machine (workers=N, by
default one per core), or on a Dask distributed cluster (scheduler=ADDRESS:
`dask scheduler` and `dask worker ADDRESS` on the machines, each with
softplc installed and the configuration's files at the same paths).

Dask rather than Ray: pure Python, installed by pip alone, a scheduler and
workers that are two commands, no object store or cluster manager to run,
and a LocalCluster that a test starts in its own process tree on
127.0.0.1. Its futures carry exceptions back as they were raised.

Every scenario is a deterministic virtual-time run of picklable data
(scenario.Job), so where it runs changes nothing: run() returns the rows
in scenario order, the same on one core, on many and on the cluster.
"""

from __future__ import annotations

import multiprocessing
import os
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor

from .scenario import Job, run_job


class SweepUnavailable(RuntimeError):
    """A cluster was asked for and Dask is not installed."""


def default_workers() -> int:
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)


def run(
    jobs: list, *, workers: int | None = None, scheduler: str | None = None, progress: Callable | None = None
) -> list:
    """The rows of every job, in scenario order. progress(done, total) after each."""
    if scheduler:
        rows = _on_cluster(jobs, scheduler, progress)
    elif (workers or default_workers()) <= 1 or len(jobs) <= 1:
        rows = []
        for job in jobs:
            rows.append(run_job(job))
            if progress:
                progress(len(rows), len(jobs))
    else:
        rows = _in_pool(jobs, workers or default_workers(), progress)
    return sorted(rows, key=lambda r: r["scenario"])


def _in_pool(jobs: list[Job], workers: int, progress: Callable | None) -> list:
    # spawn: a fresh interpreter per worker, nothing of this process's threads or buses
    context = multiprocessing.get_context("spawn")
    rows = []
    with ProcessPoolExecutor(max_workers=min(workers, len(jobs)), mp_context=context) as pool:
        for row in pool.map(run_job, jobs, chunksize=max(1, len(jobs) // (workers * 8))):
            rows.append(row)
            if progress:
                progress(len(rows), len(jobs))
    return rows


def _on_cluster(jobs: list[Job], scheduler: str, progress: Callable | None) -> list:
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise SweepUnavailable(
            "a sweep on a cluster needs Dask distributed, which comes with the `sweep` extra: "
            "pip install 'softplc[sweep]'"
        ) from None
    rows = []
    with Client(scheduler, timeout="30s") as client:
        futures = client.map(run_job, jobs, pure=False)
        for future in as_completed(futures):
            rows.append(future.result())
            if progress:
                progress(len(rows), len(jobs))
    return rows
