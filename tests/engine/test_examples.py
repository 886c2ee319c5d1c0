"""Every configuration shipped in io_config/ builds and runs in virtual
time without a fault, and the embedded default does what its comments say."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from softplc.runtime.config import default_config_path, load_config
from softplc.runtime.engine.build import build_engine

from .conftest import MS

CONFIGS = sorted(p for p in Path(default_config_path()).parent.glob("**/*.toml") if p.parent.name != "sweeps")


@pytest.mark.parametrize("path", CONFIGS, ids=lambda p: p.name)
def test_shipped_configuration_runs(path, tmp_path):
    config = load_config(path)
    if config.retain is not None:  # keep the source tree clean
        config = dataclasses.replace(config, retain=dataclasses.replace(config.retain, file=tmp_path / "x.retain"))
    engine = build_engine(config, virtual_time=True)
    engine.start()
    engine.run(duration_ns=3000 * MS)
    engine.stop()
    assert engine.faults == []
    assert all(t.stats.cycles > 0 for t in engine.tasks)


def test_default_panel_sees_the_conveyor_through_the_loopback():
    engine = build_engine(load_config(default_config_path()), virtual_time=True)
    engine.start()
    previous_output = False
    lamp_lit = False
    while engine.clock.now_ns() < 3000 * MS:
        engine.run(cycles=1)
        # The input a scan reads is the output the scan before wrote.
        assert engine.get("%IX0.0") == previous_output
        previous_output = engine.get("Conveyor.contactor")
        lamp_lit |= engine.get("Panel.runLamp")
    engine.stop()
    assert lamp_lit
    loopback = next(d for d in engine.drivers if d.name == "loopback")
    assert loopback.exchanges == engine.cycle + 1  # every scan, and the safe outputs at stop
    # What the drivers were last given is the [outputs] safe table of default.toml.
    loopback.read_inputs(engine.image)
    assert [engine.get(a) for a in ("%IX0.0", "%IX0.1", "%IX0.3", "%IW1")] == [False, False, True, 0]
