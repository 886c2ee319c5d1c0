"""The registry (runtime/plugin/registry.py): softplc's own buses and devices
come from its entry points, and a device from outside (tests/plugin/relay: a
relay with one FB, one register and a simulator) plugs in through the same
public seam and runs end to end in virtual time, configuration to ST block
to simulated device, with no change to softplc."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from softplc.runtime.config import ConfigError, config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.io.modbus import SimulatedModbusLine
from softplc.runtime.plugin.registry import PluginError, extended, registry
from softplc.runtime.plugin.seams import Device

from . import relay

REPO = Path(__file__).resolve().parents[2]
MS = 1_000_000

PROGRAM = """
PROGRAM Switch
VAR
    relay : RELAY;
    close : BOOL := {close};
    closed : BOOL;
    error : BOOL;
END_VAR
relay(CONNECTION := 'line', UNIT := 3, CLOSE := close);
closed := relay.CLOSED;
error := relay.ERROR;
END_PROGRAM
"""


def plant(tmp_path: Path, close: bool = False, **sim) -> dict:
    st = tmp_path / "switch.st"
    st.write_text(PROGRAM.replace("{close}", "TRUE" if close else "FALSE"))
    return {
        "plc": {"programs": [str(st)]},
        "task": [{"name": "Main", "interval": "10ms", "programs": ["Switch"]}],
        "modbus": [{"name": "line", "transport": "tcp", "port": 0, "timeout": "2s"}],
        "sim": [{"type": "relay", "unit": 3, **sim}],
    }


def test_softplc_own_plugins_come_from_the_entry_points():
    reg = registry()
    assert [bus.name for bus in reg.buses] == ["loopback", "can", "canopen", "plaincan", "modbus"]
    assert [device.name for device in reg.devices] == ["ltmr", "eaton", "fc280", "mpu2s"]
    assert list(reg.natives()) == ["READ_VAR", "WRITE_VAR", "MODBUS_EXCHANGE", "MODBUS_SAFE_WRITE", "MPU2S_EXCHANGE"]
    assert list(reg.sim_types()) == ["ltmr", "da1", "db1", "dc1", "de1", "de11", "fc280", "mpu2s"]


def test_a_registered_device_runs_end_to_end_in_virtual_time(tmp_path):
    with extended(relay.DEVICE):
        config = config_from_dict(plant(tmp_path, closed=False), tmp_path / "plant.toml")
        engine = build_engine(config, virtual_time=True)
    line = next(d for d in engine.drivers if isinstance(d, SimulatedModbusLine))
    unit = line.unit(3)
    engine.start()
    try:
        engine.run(duration_ns=100 * MS)
        assert not unit.closed and engine.get("Switch.closed") is False and unit.telegrams > 0
        engine.set("Switch.close", True)
        engine.run(duration_ns=100 * MS)
        assert unit.closed and unit.switchings == 1
        assert engine.get("Switch.closed") is True and engine.get("Switch.error") is False
        engine.set("Switch.close", False)
        engine.run(duration_ns=100 * MS)
        assert not unit.closed and unit.switchings == 2 and engine.get("Switch.closed") is False
        assert engine.faults == []
    finally:
        engine.stop()


def test_the_device_s_own_sim_key(tmp_path):
    with extended(relay.DEVICE):
        config = config_from_dict(plant(tmp_path, closed=True), tmp_path / "plant.toml")
    assert config.sims[0].options == relay.RelayOptions(closed=True)
    assert (config.sims[0].name, config.sims[0].at.unit) == ("relay_3", 3)


def test_configuration_errors_through_the_seam(tmp_path):
    data = plant(tmp_path, closed="yes", node_id=4)
    with extended(relay.DEVICE), pytest.raises(ConfigError) as info:
        config_from_dict(data, tmp_path / "plant.toml")
    assert info.value.errors == [
        ("sim[0].closed", "expected true or false (got 'yes')"),
        ("sim[0].node_id", "only for a CAN device (ltmr, fc280, mpu2s); a Modbus device has modbus and unit"),
    ]
    # the LTMR does not take the relay's key
    data["sim"].append({"type": "ltmr", "node_id": 5, "bus": "can0", "closed": True})
    data["can"] = [{"interface": "virtual", "channel": "x"}]
    with extended(relay.DEVICE), pytest.raises(ConfigError) as info:
        config_from_dict(data, tmp_path / "plant.toml")
    assert ("sim[1].closed", "only for relay; type 'ltmr' does not take it") in info.value.errors


def test_unregistered_the_device_is_unknown_again(tmp_path):
    with extended(relay.DEVICE):
        pass
    with pytest.raises(ConfigError) as info:
        config_from_dict(plant(tmp_path), tmp_path / "plant.toml")
    assert info.value.errors[0] == (
        "sim[0].type",
        "expected one of 'ltmr', 'da1', 'db1', 'dc1', 'de1', 'de11', 'fc280', 'mpu2s' (got 'relay')",
    )


def test_names_are_unique():
    with pytest.raises(PluginError, match="two plugins are called 'ltmr'"):
        with extended(Device(name="ltmr")):
            pass
    with pytest.raises(PluginError, match="sim type 'da1' is device eaton's"):
        with extended(Device(name="other", bus="modbus", sim_types=("da1",))):
            pass
    assert [device.name for device in registry().devices] == ["ltmr", "eaton", "fc280", "mpu2s"]


def test_a_device_that_simulates_has_a_simulator():
    with pytest.raises(PluginError, match="device other: sim types lamp but no simulator"):
        with extended(Device(name="other", bus="modbus", sim_types=("lamp",))):
            pass
    assert [device.name for device in registry().devices] == ["ltmr", "eaton", "fc280", "mpu2s"]


def test_a_device_on_a_bus_that_is_not_there(tmp_path):
    with (
        extended(Device(name="lost", bus="profibus", sim_types=("lost",), simulator=relay.RelayUnit)),
        pytest.raises(
            PluginError,
            match="device lost: its simulators sit on bus 'profibus', which is not "
            "registered or takes no simulated devices",
        ),
    ):
        config_from_dict(plant(tmp_path), tmp_path / "plant.toml")


def test_an_installed_package_is_found_through_its_entry_point(tmp_path):
    """What `pip install` of a package declaring the entry point leaves on
    the path: a .dist-info with entry_points.txt. softplc run finds the relay
    with no registration in code."""
    dist = tmp_path / "site" / "softplc_relay-1.0.dist-info"
    dist.mkdir(parents=True)
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: softplc-relay\nVersion: 1.0\n")
    (dist / "entry_points.txt").write_text("[softplc.devices]\nrelay = tests.plugin.relay:DEVICE\n")
    data = plant(tmp_path, close=True)
    lines = [
        f"[plc]\nprograms = [{json.dumps(data['plc']['programs'][0])}]\n",
        '[[task]]\nname = "Main"\ninterval = "10ms"\nprograms = ["Switch"]\n',
        '[[modbus]]\nname = "line"\ntransport = "tcp"\nport = 0\ntimeout = "2s"\n',
        '[[sim]]\ntype = "relay"\nunit = 3\nclosed = false\n',
    ]
    (tmp_path / "plant.toml").write_text("".join(lines))
    env = {"PYTHONPATH": f"{tmp_path / 'site'}:{REPO}", "PATH": "/usr/bin:/bin"}
    done = subprocess.run(
        [
            sys.executable,
            "-m",
            "softplc.runtime.cli",
            "run",
            str(tmp_path / "plant.toml"),
            "--virtual-time",
            "--duration",
            "200ms",
            "--final-json",
            "-",
        ],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert done.returncode == 0, done.stderr
    final = json.loads(done.stdout)
    assert final["Switch"]["closed"] is True and final["Switch"]["error"] is False


def test_a_broken_installed_package_is_named_not_a_traceback(tmp_path):
    dist = tmp_path / "site" / "softplc_broken-1.0.dist-info"
    dist.mkdir(parents=True)
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: softplc-broken\nVersion: 1.0\n")
    (dist / "entry_points.txt").write_text("[softplc.devices]\nbroken = no_such_module:DEVICE\n")
    (tmp_path / "p.st").write_text("PROGRAM P\nEND_PROGRAM\n")
    env = {"PYTHONPATH": f"{tmp_path / 'site'}:{REPO}", "PATH": "/usr/bin:/bin"}
    done = subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", "check", str(tmp_path / "p.st")],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert done.returncode == 2
    assert done.stderr.startswith(
        "softplc: entry point broken = 'no_such_module:DEVICE' (softplc.devices) does not load: ModuleNotFoundError"
    )
    assert "Traceback" not in done.stderr
