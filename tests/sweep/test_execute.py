"""Where a sweep runs changes nothing (sweep/execute.py): 100 genset
scenarios (random slips, breaker times and voltage offsets, one seed) give
the same rows in this process, in a pool of two worker processes and on a
real Dask cluster (a LocalCluster of two worker processes of two threads
each, with its scheduler on 127.0.0.1, started here)."""

from __future__ import annotations

import pytest

from softplc.runtime.config import default_config_path
from softplc.runtime.sweep import execute
from softplc.runtime.sweep.matrix import sweep_from_dict
from softplc.runtime.sweep.scenario import jobs

pytestmark = pytest.mark.slow  # 100 plants, three times

GENSET = default_config_path().parent / "examples" / "genset.toml"
SWEEP = {
    "duration": "8s",
    "seed": 31,
    "random": {
        "draws": 100,
        "sim.mpu2s1.slip": {"uniform": [0.1, 0.4]},
        "sim.mpu2s1.closing_time": {"choice": ["40ms", "80ms", "150ms"]},
        "sim.mpu2s1.voltage_offset": {"uniform": [-3.0, 3.0]},
    },
    "result": {
        "values": ["records.mpu2s1.closes[0].phase_deg", "records.mpu2s1.closes[0].t_s", "Genset.State"],
        "expect": ["len(records.mpu2s1.closes) == 1", "abs(records.mpu2s1.closes[0].phase_deg) < 10"],
    },
}


@pytest.fixture(scope="module")
def serial() -> tuple:
    sweep = sweep_from_dict(SWEEP, "random.toml")
    made = jobs(sweep, GENSET)
    return made, execute.run(made, workers=1)


def test_the_serial_sweep_runs_every_scenario_and_some_close(serial):
    made, rows = serial
    assert [r["scenario"] for r in rows] == list(range(100))
    closed = [r for r in rows if r["records.mpu2s1.closes[0].t_s"] is not None]
    assert len(closed) > 10  # in 8 s, the slower slips close
    assert all(r["passed"] == (r in closed and abs(r["records.mpu2s1.closes[0].phase_deg"]) < 10) for r in rows)
    assert {r["sim.mpu2s1.closing_time"] for r in rows} == {"40ms", "80ms", "150ms"}


def test_a_pool_of_worker_processes_gives_the_same_rows(serial):
    made, rows = serial
    assert execute.run(made, workers=2) == rows


def test_a_dask_cluster_gives_the_same_rows(serial):
    distributed = pytest.importorskip("distributed", reason="the test extra installs Dask distributed")
    made, rows = serial
    # two threads a worker: two scenarios reach one process at once, and run one after the other
    # (their plants would share the example's virtual CAN channel)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=2, processes=True, host="127.0.0.1", dashboard_address=None
    ) as cluster:
        assert cluster.scheduler_address.startswith("tcp://127.0.0.1:")
        assert execute.run(made, scheduler=cluster.scheduler_address) == rows
