"""A sweep as pytest parametrisation (softplc.testing.sweep_params):

    from softplc.testing import sweep_params

    @pytest.mark.parametrize("case", sweep_params("genset.toml", "slip.toml"))
    def test_synchronisation(case):
        result = case.run()
        assert result.passed, result.failed
        assert abs(result.values["records.mpu2s1.closes[0].phase_deg"]) < 5

Each case is one scenario of the sweep file, its id its values
(`slip=0.1-closing_time=40ms`), the same in every pytest-xdist worker (the
random draws are seeded), and run() the same deterministic virtual-time
run as `softplc sweep`'s, in the test's own process.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

from .matrix import load_sweep
from .scenario import FAILED, PASSED, RECORDS, Job, jobs, run_job


@dataclass(frozen=True)
class SweepResult:
    """A scenario's row: passed, what failed (text), the [result] values by
    their expression, the simulated devices' records, the whole row."""

    passed: bool
    failed: str
    values: dict
    records: dict
    row: dict


@dataclass(frozen=True)
class SweepCase:
    job: Job

    @property
    def params(self) -> dict:
        return dict(self.job.params)

    @property
    def index(self) -> int:
        return self.job.index

    def run(self) -> SweepResult:
        row = run_job(self.job)
        values = {text: row[text] for text in self.job.values}
        return SweepResult(row[PASSED], row[FAILED], values, json.loads(row[RECORDS]), row)


def sweep_cases(config: str | Path, matrix: str | Path) -> list:
    """A SweepCase per scenario of the sweep file matrix against config;
    SweepError or ConfigError when they do not fit."""
    return [SweepCase(job) for job in jobs(load_sweep(matrix), config)]


def sweep_params(config: str | Path, matrix: str | Path) -> list:
    """sweep_cases as pytest.param, each with its scenario's id."""
    import pytest

    sweep = load_sweep(matrix)
    ids = {s.index: s.id for s in sweep.scenarios}
    return [pytest.param(SweepCase(job), id=ids[job.index]) for job in jobs(sweep, config)]
