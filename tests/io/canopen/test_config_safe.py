"""The safe values of a node's device (Device.safe_objects) for the %Q
addresses its RPDOs map (runtime/io/canopen/config_node.claim_safe_values,
config/plc.with_safe_defaults): what the engine holds there while outputs
are safe, unless [outputs] safe sets any bit of the address."""

from __future__ import annotations

import tomllib

from softplc.runtime.config import config_from_dict, default_config_path

from ...config.support import EXAMPLES


def _safe(path, edit=None) -> dict:
    tables = tomllib.loads(path.read_text(encoding="utf-8"))
    if edit is not None:
        edit(tables)
    return {o.address.text: (o.value, o.key) for o in config_from_dict(tables, path).safe_outputs}


def _without_outputs(tables: dict) -> None:
    del tables["outputs"]


def test_the_default_plant_without_outputs_safe_gets_its_devices_values():
    assert _safe(default_config_path(), _without_outputs) == {
        "%QW100": (0x0000, "canopen.node[0].rpdo[0].map[0].address"),  # LTMR 704: no run command
        "%QW110": (0x0434, "canopen.node[1].rpdo[0].map[0].address"),  # FC 280 2690h: coast
        "%QW111": (0x0000, "canopen.node[1].rpdo[0].map[1].address"),  # 2692h: reference 0
    }


def test_dsp402_gets_disable_voltage():
    assert _safe(EXAMPLES / "fc280_dsp402.toml", _without_outputs) == {
        "%QW110": (0x0000, "canopen.node[0].rpdo[0].map[0].address"),  # 6040h
        "%QW111": (0x0000, "canopen.node[0].rpdo[0].map[1].address"),  # 6042h
    }


def test_outputs_safe_wins_where_it_sets_any_bit_of_the_address():
    def edit(tables: dict) -> None:
        tables["outputs"] = {"safe": {"%QX220.2": True, "%QW100": 0}}

    assert _safe(default_config_path(), edit) == {
        "%QX220.2": (True, 'outputs.safe."%QX220.2"'),  # a bit of the FC 280's %QW110 (bytes 220-221)
        "%QW100": (0, 'outputs.safe."%QW100"'),
        "%QW111": (0, "canopen.node[1].rpdo[0].map[1].address"),
    }


def test_a_node_without_a_devices_eds_gets_none(tmp_path):
    eds = tmp_path / "other.eds"
    eds.write_text((default_config_path().parent / "eds" / "ltmr.eds").read_text(encoding="ascii"))

    def edit(tables: dict) -> None:
        del tables["outputs"]
        tables["canopen"]["node"][0]["eds"] = str(eds)  # the LTMR's objects, no device's file

    assert "%QW100" not in _safe(default_config_path(), edit)
