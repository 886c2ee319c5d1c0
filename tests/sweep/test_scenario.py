"""A scenario's values placed in the configuration's tables (sweep/
scenario.py), and the genset example's sweep (io_config/sweeps/
genset_slip.toml) as pytest parametrisation: each case a virtual-time run
of the example with the MPU2-S simulator's slip and breaker time set."""

from __future__ import annotations

import tomllib

import pytest

from softplc.runtime.config import default_config_path
from softplc.runtime.config.errors import ConfigError
from softplc.runtime.sweep.matrix import Scenario, SweepError, load_sweep, sweep_from_dict
from softplc.runtime.sweep.scenario import jobs, place
from softplc.testing import sweep_params

EXAMPLES = default_config_path().parent / "examples"
GENSET = EXAMPLES / "genset.toml"
SLIP_SWEEP = default_config_path().parent / "sweeps" / "genset_slip.toml"


def tables() -> dict:
    return tomllib.loads(GENSET.read_text(encoding="utf-8"))


def test_a_scenario_s_values_go_to_the_sim_the_init_table_and_a_task_by_name():
    params = {"sim.mpu2s1.slip": 0.2, "init.Genset.Target": 200.0, "task.Main.interval": "20ms", "can.0.bitrate": 1}
    data = place(tables(), Scenario(3, params), {"MPU2S1": 0}, "s.toml")
    assert data["sim"][0]["slip"] == 0.2
    assert data["init"] == {"Genset.Target": 200.0}
    assert data["task"][0]["interval"] == "20ms"
    assert data["can"][0]["bitrate"] == 1
    assert tables()["sim"][0]["slip"] == 0.3  # the file's tables are left as they were


@pytest.mark.parametrize(
    ("key", "message"),
    [
        ("sim.nobody.slip", "no simulated device 'nobody' with a key (the [[sim]] names: mpu2s1)"),
        ("task.Nightly.interval", "no table 'Nightly' in that array"),
        ("task.interval", "an array of tables: name one"),
    ],
)
def test_a_key_that_goes_nowhere_is_named(key, message):
    with pytest.raises(SweepError) as info:
        place(tables(), Scenario(0, {key: 1}), {"MPU2S1": 0}, "s.toml")
    assert info.value.key == key and message in info.value.message


def test_a_value_the_configuration_refuses_names_the_scenario_before_any_runs():
    sweep = sweep_from_dict({"matrix": {"sim.mpu2s1.slip": [0.1, "fast"]}}, "s.toml")
    with pytest.raises(SweepError) as info:
        jobs(sweep, GENSET)
    assert info.value.key == "scenario 1 (slip=fast)"
    assert "sim[0].slip" in info.value.message


def test_every_scenario_is_checked_as_the_configuration_it_makes():
    sweep = sweep_from_dict({"matrix": {"task.Main.interval": ["10ms", "1us"]}}, "s.toml")
    with pytest.raises((SweepError, ConfigError)) as info:
        jobs(sweep, GENSET)
    assert "scenario 1" in str(info.value)


def test_the_sweep_file_s_scenarios_are_the_parametrisation_s_ids():
    ids = [p.id for p in sweep_params(GENSET, SLIP_SWEEP)]
    assert ids[:2] == ["slip=0.1-closing_time=40ms", "slip=0.1-closing_time=80ms"]
    assert len(ids) == len(load_sweep(SLIP_SWEEP).scenarios) == 12


@pytest.mark.parametrize("case", sweep_params(GENSET, SLIP_SWEEP))
def test_the_genset_closes_in_phase_at_every_slip_and_breaker_time(case):
    result = case.run()
    assert result.passed, result.failed
    (close,) = result.records["mpu2s1"]["closes"]
    assert result.values["records.mpu2s1.closes[0].phase_deg"] == close["phase_deg"]
    assert abs(close["phase_deg"]) < 10.0 and not close["tripped"]
    assert result.row["sim.mpu2s1.slip"] == case.params["sim.mpu2s1.slip"]


ASSERTING = """PROGRAM Main
VAR limit : INT := 10; level : INT; END_VAR
level := level + 1;
ASSERT_TRUE(level < limit, 'the level stays below the limit');
END_PROGRAM
"""


def test_the_program_s_own_assertions_decide_too(tmp_path):
    from softplc.runtime.sweep import execute

    (tmp_path / "p.st").write_text(ASSERTING, encoding="utf-8")
    config = tmp_path / "plant.toml"
    config.write_text(
        '[plc]\nprograms = ["p.st"]\n[[task]]\nname = "Main"\ninterval = "10ms"\nprograms = ["Main"]\n',
        encoding="utf-8",
    )
    sweep = sweep_from_dict({"duration": "1s", "matrix": {"init.Main.limit": [1000, 50]}}, "s.toml")
    rows = execute.run(jobs(sweep, config), workers=1)
    assert [r["passed"] for r in rows] == [True, False]
    assert rows[0]["failed"] == ""
    first = rows[1]["failed"].split("; ")[0]
    assert "p.st:4:" in first and "ASSERT_TRUE failed: the level stays below the limit" in first
    assert "at 0.49 s" in first  # the 50th scan, at 490 ms: level 50
    assert len(rows[1]["failed"].split("; ")) == 5  # the first five of 52
