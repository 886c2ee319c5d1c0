"""--final-json's records of the simulated devices (launch.final_data,
under "[[sim]]"): the default plant's LTMR trips thermally near 57 s of
its run and says so in an EMCY (1000h, manual 001's trip code 4 "Thermal
overload" in its data), the genset example's breaker closes once, in
phase (its trip_limit 20 deg, the MPU2-S's window of the file). The same
events in every --trace file (trace/events.py), at the same times."""

from __future__ import annotations

import json

import pytest

from softplc.runtime.config import default_config_path
from softplc.runtime.launch import RECORDS_KEY
from softplc.runtime.trace.reading import read_trace

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


@pytest.mark.parametrize("suffix", [".csv", ".vcd"])
def test_the_genset_s_breaker_close_is_a_mark_of_the_trace_at_its_records_time(tmp_path, suffix):
    config = default_config_path().parent / "examples" / "genset.toml"
    trace = tmp_path / f"run{suffix}"
    plot = tmp_path / "run.svg"
    args = (config, "--duration", "60s", "--watch", "Genset.raiseF", "--trace", trace, "--trace", plot)
    (sim_name,) = (records := final_json(tmp_path, *args)[RECORDS_KEY])
    (close,) = records[sim_name]["closes"]
    ((at, text),) = read_trace(trace).marks
    assert at == pytest.approx(close["t_s"], abs=1e-6)
    assert text.startswith(f"{sim_name}: breaker closed: phase {close['phase_deg']:.1f} deg, dU ")
    svg = plot.read_text(encoding="utf-8")
    assert 'id="mark-0"' in svg and 'id="mark-1"' not in svg
    assert "breaker closed" in svg


def test_the_ltmr_s_trip_emcy_is_in_the_csv_trace_s_sim_column(tmp_path):
    trace = tmp_path / "run.csv"
    data = final_json(tmp_path, "--duration", "70s", "--watch", "Drive.cycles", "--trace", trace)
    emcys = [(name, e) for name, r in data[RECORDS_KEY].items() for e in r.get("emcys", ()) if e["code"] == "1000h"]
    marks = [m for m in read_trace(trace).marks if "EMCY 1000h" in m[1]]
    assert [(round(e["t_s"], 6), f"{name}: EMCY 1000h {e['text']}") for name, e in emcys] == [
        (t, text.rpartition(" (register")[0]) for t, text in marks
    ]
    header = trace.read_text(encoding="utf-8").splitlines()[0]
    assert header.endswith(f",{RECORDS_KEY}")
