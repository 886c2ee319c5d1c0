"""The SFC example (st_programs/tank_sfc.st, io_config/examples/sfc.toml)
in virtual time, and the steps' flags where a user looks for them: the
testing API, ``softplc run --watch`` and its trace."""

from __future__ import annotations

import csv
import json
from datetime import timedelta
from pathlib import Path

import pytest

from softplc.testing import PLC

from ..test_cli import softplc

EXAMPLE = Path(__file__).resolve().parents[2] / "io_config" / "examples" / "sfc.toml"
STEPS = ("Idle", "Fill", "Heat", "Hold", "Drain", "Cool", "Cooled")


def active(plc) -> list:
    return [s for s in STEPS if plc[f"Tank.{s}.X"]]


def test_the_tank_runs_its_batches_in_order():
    # 10 ms a cycle; the times follow from the model's rates (tank_sfc.st)
    with PLC.from_config(EXAMPLE) as plc:
        plc.step()
        assert active(plc) == ["Idle"]
        plc.run_until(lambda: plc["Tank.Fill.X"], timeout="1s")
        assert plc.now_ns == 200_000_000  # Idle.T >= PauseTime (200 ms)
        assert plc["FillValve"] is True and plc["Tank.Idle.T"] == timedelta(milliseconds=200)
        plc.run_until(lambda: plc["Tank.Heat.X"], timeout="2s")
        assert plc["Level"] == 80 and plc["FillValve"] is False and plc["Heater"] is True
        assert plc["Mixer"] is True  # S: stored ...
        plc.run_until(lambda: plc["Tank.Hold.X"], timeout="2s")
        assert plc["Heater"] is False  # D: the heater comes back after 100 ms
        plc.step(10)  # 10 cycles: 100 ms
        assert plc["Heater"] is True and plc["Tank.Hold.T"] == timedelta(milliseconds=100)
        plc.run_until(lambda: plc["Tank.Drain.X"], timeout="2s")
        # the simultaneous divergence: both branches at once, after HoldTime
        assert active(plc) == ["Drain", "Cool"] and plc["Tank.Hold.T"] == timedelta(milliseconds=500)
        assert plc["Mixer"] is False and plc["Fan"] is True  # ... until R; L: the fan for 300 ms
        plc.run_until(lambda: plc["Tank.Cooled.X"], timeout="1s")
        assert active(plc) == ["Drain", "Cooled"] and plc["Fan"] is False
        # the convergence waits for the empty tank
        plc.run_until(lambda: plc["Tank.Idle.X"], timeout="1s")
        assert plc["Level"] == 0 and active(plc) == ["Idle"]
        assert plc["Batches"] == 1  # Done (P1) pulsed once
        plc.run_for("5s")
        assert plc["Batches"] == 3


@pytest.mark.slow
def test_steps_are_watched_and_traced(tmp_path):
    trace = tmp_path / "trace.csv"
    proc = softplc(
        "run",
        EXAMPLE,
        "--virtual-time",
        "--cycles",
        "30",
        "--watch",
        "Tank.Idle.X,Tank.Fill.X,Tank.Idle.T,Tank.Fill",
        "--trace",
        trace,
        "--final-json",
        "-",
    )
    assert proc.returncode == 0, proc.stderr
    rows = list(csv.DictReader(trace.open()))
    assert [(r["Tank.Idle.X"], r["Tank.Fill.X"]) for r in (rows[19], rows[20])] == [("1", "0"), ("0", "1")]
    assert rows[19]["Tank.Idle.T"] == "190"  # TIME in ms, as TON's
    assert json.loads(rows[29]["Tank.Fill"]) == {"X": True, "T": "T#90ms"}
    assert "Tank.Fill.X=true" in proc.stderr  # the status line
    final = json.loads(proc.stdout)
    assert final["Tank"]["Fill"] == {"X": True, "T": "T#90ms"}
