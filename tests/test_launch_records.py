"""--final-json's records of the simulated devices (launch.final_data,
under "[[sim]]"): the default plant's LTMR trips thermally near 57 s of
its run and says so in an EMCY (1000h, manual 001's trip code 4 "Thermal
overload" in its data), the genset example's breaker closes once, in
phase (its trip_limit 20 deg, the MPU2-S's window of the file)."""

from __future__ import annotations

import json

from softplc.runtime.config import default_config_path
from softplc.runtime.launch import RECORDS_KEY

from .test_cli import softplc


def final_json(tmp_path, *args) -> dict:
    out = tmp_path / "final.json"
    done = softplc("run", *args, "--virtual-time", "--final-json", out, cwd=tmp_path, timeout=300)
    assert done.returncode in (0, 3), done.stderr
    return json.loads(out.read_text(encoding="utf-8"))


def test_the_ltmr_s_thermal_trip_is_an_emcy_in_the_records(tmp_path):
    data = final_json(tmp_path, "--duration", "70s")
    records = data[RECORDS_KEY]
    (ltmr,) = [r for name, r in records.items() if "emcys" in r and any(e["code"] == "1000h" for e in r["emcys"])]
    trip = next(e for e in ltmr["emcys"] if e["code"] == "1000h")
    assert 50.0 < trip["t_s"] < 65.0
    assert "Thermal overload" in trip["text"]
    assert "Main" in data or any(k != RECORDS_KEY for k in data)  # the programs' variables are still there


def test_the_genset_s_breaker_closes_in_the_records(tmp_path):
    config = default_config_path().parent / "examples" / "genset.toml"
    data = final_json(tmp_path, config, "--duration", "60s")
    (sim,) = data[RECORDS_KEY].values()
    closes = sim["closes"]
    assert len(closes) == 1
    (close,) = closes
    assert not close["dead_bus"] and not close["tripped"]
    assert abs(close["phase_deg"]) < 20.0
    assert 0.0 < close["t_s"] < 60.0


def test_no_records_no_key(tmp_path):
    config = default_config_path().parent / "examples" / "loopback.toml"
    assert RECORDS_KEY not in final_json(tmp_path, config, "--duration", "1s")
