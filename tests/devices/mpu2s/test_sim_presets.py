"""[[sim]] parameters of a simulated MPU2-S (sim_options.py): its parameter
memory preset by chapter 4's keys, in their units, checked against the
manual's ranges (4.2.47 +df max: raw 5..125 in 1/256 Hz, parameters.csv)
as a write from the bus is; the PLC reads the preset value over
the wire (the genset example reads ID 26 at its start)."""

from __future__ import annotations

import pytest

from softplc.runtime.config import ConfigError, default_config_path
from softplc.testing import PLC

from ...test_cli import softplc

GENSET = default_config_path().parent / "examples" / "genset.toml"


def run_and_read_log(tmp_path, presets: dict | None) -> str:
    def edit(tables: dict) -> None:
        if presets is not None:
            tables["sim"][0]["parameters"] = presets

    log = tmp_path / "gs.log"
    plc = PLC.from_config(GENSET, edit=edit, bus_log=log)
    try:
        plc.run_for("0.5s")
    finally:
        plc.stop()
    done = softplc("log", log, GENSET)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_a_preset_parameter_is_what_the_device_answers(tmp_path):
    assert "read ID 26 Synchronising +df max = 51" in run_and_read_log(tmp_path, None)  # sim_store: 0.20 Hz
    (tmp_path / "preset").mkdir()
    assert "read ID 26 Synchronising +df max = 64" in run_and_read_log(tmp_path / "preset", {"sync_df_max": 0.25})


def test_the_preset_is_in_the_simulator_s_store():
    plc = PLC.from_config(GENSET, edit=lambda t: t["sim"][0].update(parameters={"gcb_closing_time": 100}))
    try:
        (sim,) = plc.engine.simulators.values()
        assert sim.store.value("gcb_closing_time") == 100
        assert sim.scenario.closing_time_ms == 80  # the breaker itself keeps the file's closing_time
    finally:
        plc.stop()


@pytest.mark.parametrize(
    ("presets", "said"),
    [
        (
            {"sync_df_mx": 0.25},
            "sim[0].parameters.sync_df_mx: no MPU2-S parameter of that key (did you mean 'sync_df_max'?)",
        ),
        ({"sync_df_max": 9.0}, "outside the documented raw range 5..125"),
        ({"sync_df_max": "fast"}, "sim[0].parameters.sync_df_max: "),
    ],
)
def test_a_bad_preset_names_the_file_and_the_key(presets, said):
    with pytest.raises(ConfigError) as caught:
        PLC.from_config(GENSET, edit=lambda t: t["sim"][0].update(parameters=presets))
    assert said in str(caught.value)
    assert "genset.toml" in str(caught.value)
