"""The compile side asks the registry only for the plugins' ST libraries and
native function names (plugin_libraries, plugin_natives): with the index in
the cache, a program that uses no bus and no device compiles without
importing one, and a program that calls a bus's native function still gets
it."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

PROBE = """
import json, sys
from softplc.runtime.program import compile_files
src = sys.argv[1]
r = compile_files([], texts={"main.st": src}).runner("Main")
r.run(1)
plugins = ("softplc.runtime.io.", "softplc.runtime.devices.", "can", "pymodbus", "canopen")
heavy = sorted(m for m in sys.modules if m.startswith(plugins))
print(json.dumps({"heavy": heavy, "x": r.get("x")}))
"""

PLAIN = "PROGRAM Main\nVAR x : INT; t : TON; END_VAR\nt(IN := TRUE, PT := T#1s);\nx := x + 1;\nEND_PROGRAM\n"
# READ_VAR: the CANopen bus's native function (without a bus it ends with an error report)
NATIVE = (
    "PROGRAM Main\nVAR x : INT; data : ARRAY[0..1] OF INT; mgmt : ARRAY[0..5] OF INT; END_VAR\n"
    "READ_VAR(ADR#0.1.SYS, 'SDO', 16#00062004, 40, data, mgmt);\nx := 1;\nEND_PROGRAM\n"
)


def _probe(src: str, cache_dir) -> dict:
    env = {"SOFTPLC_CACHE": str(cache_dir)}
    out = subprocess.run(
        [sys.executable, "-c", PROBE, src], capture_output=True, text=True, check=True, env={**_env(), **env}
    )
    return json.loads(out.stdout)


def _env() -> dict:
    import os

    return {k: v for k, v in os.environ.items() if k != "SOFTPLC_NO_CACHE"}


def test_a_program_without_a_bus_imports_none_once_the_index_is_kept(tmp_path):
    first = _probe(PLAIN, tmp_path)  # builds the index: every plugin is loaded once
    assert first["x"] == 1 and first["heavy"]
    again = _probe(PLAIN, tmp_path)
    assert again == {"heavy": [], "x": 1}


def test_a_native_function_loads_its_plugin(tmp_path):
    _probe(PLAIN, tmp_path)
    found = _probe(NATIVE, tmp_path)
    assert found["x"] == 1 and "softplc.runtime.io.canopen" in found["heavy"]


# a configuration without a bus section or a [[sim]] table: checked, built and run
# without importing a bus or a device, and the same as with the registry loaded
CONFIG_PROBE = """
import json, sys
from pathlib import Path
from softplc.runtime.config import ConfigError, config_from_dict
from softplc.runtime.engine.build import build_engine
from softplc.runtime.plugin.registry import registry

main = Path(sys.argv[1])
good = {
    "plc": {"programs": [str(main)], "on_fault": "plc"},
    "task": [{"name": "Fast", "interval": "5ms", "programs": ["Main"]}],
    "outputs": {"safe": {"%QX0.0": True}},
}
bare = {"plc": {"programs": [str(main)]}}
bad = {"plc": {"programs": [str(main)], "spin": "10 parsecs"}, "task": [{"name": "1x", "interval": 3}]}


def loaded(data):
    try:
        return repr(config_from_dict(data, main))
    except ConfigError as exc:
        return str(exc)


cases = [good, bad, bare, {}]
lazy = [loaded(data) for data in cases]
engine = build_engine(config_from_dict(good, main), virtual_time=True)
engine.start()
engine.run(cycles=3)
engine.stop()
plugins = ("softplc.runtime.io.", "softplc.runtime.devices.", "can", "pymodbus", "canopen")
heavy = sorted(m for m in sys.modules if m.startswith(plugins))
registry()
full = [loaded(data) for data in cases]
print(json.dumps({"heavy": heavy, "lazy": lazy, "full": full, "cycles": engine.cycle}))
"""


def test_a_configuration_without_a_bus_imports_none_and_is_the_same(tmp_path):
    main = tmp_path / "main.st"
    main.write_text(PLAIN)
    run = [sys.executable, "-c", CONFIG_PROBE, str(main)]
    env = {**_env(), "SOFTPLC_CACHE": str(tmp_path / "cache")}
    subprocess.run(run, capture_output=True, text=True, check=True, env=env)  # the index kept
    found = json.loads(subprocess.run(run, capture_output=True, text=True, check=True, env=env).stdout)
    assert found["heavy"] == []
    assert found["cycles"] == 3
    assert found["lazy"] == found["full"]
    good, bad, bare, empty = found["lazy"]
    assert "sections={'web': None, 'opcua': None, 'modbus_server': None, 'loopback': []" in good
    assert "plc.spin: expected a duration" in bad and "task[0].name" in bad
    assert "tasks=[]" in bare and "retain=None" in bare and "safe_outputs=[]" in bare
    assert "plc" in empty and "missing" in empty


# `softplc test` without a configuration and a PLC of ST text (the plc fixture)
TESTING_PROBE = """
import json, sys
from softplc.runtime.testing.runner import TestSuite
from softplc.testing import PLC

suite = TestSuite.load(None, [sys.argv[1]])
outcomes = [suite.run(case).outcome for case in suite.tests]
plc = PLC.from_st(sys.argv[2])
plc.step(2)
x = plc["Main.x"]
plc.stop()
plugins = ("softplc.runtime.io.", "softplc.runtime.devices.", "can", "pymodbus", "canopen")
heavy = sorted(m for m in sys.modules if m.startswith(plugins))
print(json.dumps({"heavy": heavy, "outcomes": outcomes, "x": x}))
"""

TEST_ST = (
    "FUNCTION_BLOCK TEST_Add\nVAR n : INT; END_VAR\nn := n + 1;\n"
    "ASSERT_EQUAL(n, 1, 'one');\nTEST_FINISHED();\nEND_FUNCTION_BLOCK\n"
)


def test_st_tests_and_a_plc_of_st_text_import_no_bus(tmp_path):
    test_file = tmp_path / "test_add.st"
    test_file.write_text(TEST_ST)
    run = [sys.executable, "-c", TESTING_PROBE, str(test_file), PLAIN]
    env = {**_env(), "SOFTPLC_CACHE": str(tmp_path / "cache")}
    subprocess.run(run, capture_output=True, text=True, check=True, env=env)  # the index kept
    found = json.loads(subprocess.run(run, capture_output=True, text=True, check=True, env=env).stdout)
    assert found == {"heavy": [], "outcomes": ["passed"], "x": 2}


# The entry points themselves are kept in the cache under the folders of
# sys.path and their times (registry._points): found again without
# importlib.metadata while nothing is installed or removed, and read again
# when something is.
POINTS_PROBE = """
import json, sys
from softplc.runtime.plugin.registry import plugin_libraries
packages = sorted({lib.package for lib in plugin_libraries()})
print(json.dumps({"packages": packages, "metadata": "importlib.metadata" in sys.modules}))
"""
RELAY_POINTS = "[softplc.devices]\nrelay = tests.plugin.relay:DEVICE\n"


def _points_probe(site, cache_dir) -> dict:
    root = str(Path(__file__).resolve().parents[2])  # where `tests.plugin.relay` imports from
    env = {**_env(), "SOFTPLC_CACHE": str(cache_dir), "PYTHONPATH": os.pathsep.join((str(site), root))}
    out = subprocess.run([sys.executable, "-c", POINTS_PROBE], capture_output=True, text=True, check=True, env=env)
    return json.loads(out.stdout)


def test_the_entry_points_are_kept_until_a_distribution_comes(tmp_path):
    site = tmp_path / "site"
    site.mkdir()
    first = _points_probe(site, tmp_path / "cache")
    assert first["metadata"] and "tests.plugin.relay" not in first["packages"]
    again = _points_probe(site, tmp_path / "cache")
    assert again == {"packages": first["packages"], "metadata": False}
    (site / "notes.txt").write_text("a project's file")  # a new file is no distribution: still kept
    (site / "pkg").mkdir()
    assert _points_probe(site, tmp_path / "cache") == again
    dist = site / "relay_plugin-1.0.dist-info"  # installed now: its folder changes site's time
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: relay-plugin\nVersion: 1.0\n")
    (dist / "entry_points.txt").write_text(RELAY_POINTS)
    found = _points_probe(site, tmp_path / "cache")
    assert found["metadata"] and "tests.plugin.relay" in found["packages"]
