"""The compile side asks the registry only for the plugins' ST libraries and
native function names (plugin_libraries, plugin_natives): with the index in
the cache, a program that uses no bus and no device compiles without
importing one, and a program that calls a bus's native function still gets
it."""

from __future__ import annotations

import json
import subprocess
import sys

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
