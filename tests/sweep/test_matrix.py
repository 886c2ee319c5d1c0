"""The sweep file (sweep/matrix.py): the three ways to say the scenarios,
in a fixed order, and an error that names the file and the key."""

from __future__ import annotations

import pytest

from softplc.runtime.sweep.matrix import SweepError, load_sweep, sweep_from_dict


def test_a_matrix_is_every_combination_in_the_file_s_order():
    sweep = sweep_from_dict({"matrix": {"sim.gen.slip": [0.1, 0.2], "sim.gen.closing_time": ["40ms", "80ms", "150ms"]}})
    assert sweep.keys == ["sim.gen.slip", "sim.gen.closing_time"]
    assert [tuple(s.params.values()) for s in sweep.scenarios] == [
        (0.1, "40ms"),
        (0.1, "80ms"),
        (0.1, "150ms"),
        (0.2, "40ms"),
        (0.2, "80ms"),
        (0.2, "150ms"),
    ]
    assert [s.index for s in sweep.scenarios] == list(range(6))
    assert sweep.scenarios[4].id == "slip=0.2-closing_time=80ms"
    assert sweep.duration_ns == 10_000_000_000  # the default, 10 s


def test_a_list_of_scenarios_is_taken_as_given():
    sweep = sweep_from_dict({"duration": "2s", "scenario": [{"init.Main.x": 1}, {"init.Main.x": 5}]})
    assert [s.params for s in sweep.scenarios] == [{"init.Main.x": 1}, {"init.Main.x": 5}]
    assert sweep.duration_ns == 2_000_000_000


def test_random_draws_are_the_same_for_the_same_seed_and_differ_for_another():
    table = {
        "draws": 50,
        "a": {"uniform": [0.05, 0.35]},
        "b": {"choice": ["40ms", "80ms"]},
        "c": {"integers": [1, 6]},
        "d": {"normal": [250.0, 20.0]},
    }
    one = sweep_from_dict({"seed": 7, "random": table})
    assert one == sweep_from_dict({"seed": 7, "random": table})
    assert one.scenarios != sweep_from_dict({"seed": 8, "random": table}).scenarios
    assert len(one.scenarios) == 50
    assert all(0.05 <= s.params["a"] <= 0.35 for s in one.scenarios)
    assert {s.params["b"] for s in one.scenarios} == {"40ms", "80ms"}
    assert {s.params["c"] for s in one.scenarios} <= set(range(1, 7))


@pytest.mark.parametrize(
    ("data", "key", "message"),
    [
        ({}, "", "give exactly one of [matrix], [[scenario]] and [random]"),
        ({"matrix": {"a": [1]}, "random": {"draws": 1}}, "", "(found matrix, random)"),
        ({"matrix": {"a": 1}}, "matrix.a", "a list of the values to try"),
        ({"matrix": {"a": [1]}, "duration": "soon"}, "duration", ""),
        ({"matrix": {"a": [1]}, "duration": "0s"}, "duration", "not a positive duration"),
        ({"matrix": {"a": [1]}, "colour": 1}, "colour", "not a key of a sweep file"),
        ({"scenario": [{"a": 1}, {"b": 2}]}, "scenario[1]", "give every one the same"),
        ({"random": {"draws": 0, "a": {"uniform": [0, 1]}}}, "random.draws", "a whole number from 1"),
        ({"random": {"draws": 2, "a": {"gamma": [1, 2]}}}, "random.a", "uniform = [...]"),
        ({"random": {"draws": 2, "a": {"uniform": [1]}}}, "random.a.uniform", "two numbers, [low, high]"),
        ({"matrix": {"a": [1]}, "result": {"expect": ["__import__('os')"]}}, "result.expect[0]", "may be called"),
        ({"matrix": {"a": [1]}, "result": {"values": ["x +"]}}, "result.values[0]", "not an expression"),
        ({"matrix": {"a": [1]}, "result": {"plot": {"x": "a"}}}, "result.plot", "{ x = KEY, y = VALUE }"),
        ({"matrix": {"a": [1]}, "result": {"plot": {"x": "a", "y": "b"}}}, "result.plot.y", "neither a key"),
    ],
)
def test_a_bad_sweep_file_names_the_key(data, key, message):
    with pytest.raises(SweepError) as info:
        sweep_from_dict(data, "slip.toml")
    assert info.value.file == "slip.toml" and info.value.key == key
    assert message in info.value.message


def test_a_file_that_is_not_toml_names_the_file(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[matrix\n", encoding="utf-8")
    with pytest.raises(SweepError, match=r"bad\.toml: not TOML"):
        load_sweep(bad)
