"""The benchmarks (benchmarks/) measure speed and are not run by the suite;
this only keeps them from rotting: each imports everything it uses and
understands its command line."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

BENCHMARKS = sorted((Path(__file__).resolve().parents[1] / "benchmarks").glob("bench_*.py"))


def test_there_are_benchmarks():
    assert [b.name for b in BENCHMARKS] == [
        "bench_canopen.py",
        "bench_engine.py",
        "bench_examples.py",
        "bench_genset.py",
        "bench_language.py",
        "bench_loops.py",
        "bench_modbus.py",
        "bench_modbus_server.py",
        "bench_soak.py",
        "bench_spin.py",
        "bench_surfaces.py",
    ]


@pytest.mark.parametrize("script", BENCHMARKS, ids=lambda p: p.name)
def test_benchmark_starts(script):
    done = subprocess.run([sys.executable, str(script), "--help"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("usage:")
