"""The simulated LTMR's [[sim]] load (devices/ltmr/sim_options.py): the
motor current a run starts with, in % of FLC. The default plant's motor
(80 % by default) trips thermally near 57 s (an EMCY 1000h in the
records); sooner at 200 %, later at 40 %; a load out of range names the key."""

from __future__ import annotations

import pytest

from softplc.runtime.config.errors import ConfigError
from softplc.testing import PLC

pytestmark = pytest.mark.slow  # 70 s of the default plant, four times


def ltmr_table(data: dict) -> dict:
    (table,) = [t for t in data["sim"] if t["type"] == "ltmr"]
    return table


def plant(load: float | None) -> PLC:
    def edit(data: dict) -> None:
        if load is not None:
            ltmr_table(data)["load"] = load
        for can in data.get("can", ()):
            can["channel"] = f"{can['channel']}-ltmr-load-{load}"

    return PLC.from_config(edit=edit)


def thermal_trips(plc: PLC) -> list:
    emcys = [e for r in plc.records.values() for e in r.get("emcys", ())]
    return [e for e in emcys if e["code"] == "1000h"]


def trip_time(load: float | None) -> float:
    plc = plant(load)
    try:
        assert plc.sim("ltmr40").model.load_percent == (80.0 if load is None else load)
        plc.run_for("70s")
        (trip,) = thermal_trips(plc)
        return trip["t_s"]
    finally:
        plc.stop()


def test_the_load_a_run_starts_with_heats_the_motor_sooner_or_later():
    # the starts (600 % FLC of inrush) and the current while running heat the thermal image:
    # the higher the running current, the sooner the trip
    default, light, heavy = trip_time(None), trip_time(40.0), trip_time(200.0)
    assert default == trip_time(80.0)  # the default load is 80 % FLC
    assert heavy < default < light
    assert 50.0 < default < 65.0


@pytest.mark.parametrize("load", [-1.0, 1000.5, "high", True])
def test_a_load_out_of_range_names_the_key(load):
    with pytest.raises(ConfigError) as info:
        plant(load)
    assert any(
        key.endswith("load") and "a load in % of FLC from 0.0 to 1000.0" in msg for key, msg in info.value.errors
    )
