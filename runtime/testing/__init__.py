"""Testing a PLC offline, from Python and pytest: the public API.

    from softplc.testing import PLC          # or softplc.runtime.testing

    with PLC.from_config() as plc:           # the default plant, virtual time
        plc.watch("Motor.state")
        plc.run_until(lambda: plc["Motor.state"] == "Forward", timeout="1s")

PLC (plc.py): build from a configuration or ST files, run (step, run_for,
run_until), read / write / force by ST path with ST types (values.py), the
simulated devices and their faults, scripted inputs, the trace of watched
values (trace.py). pytest_plugin.py: the fixtures plc and plc_factory and
the marker softplc, installed as a pytest plugin with the package.
docs/guide/testing.md "Testing a sequence offline (Python and pytest)".

Tests written in ST (docs/guide/testing.md "Tests in ST: softplc test"): test
FUNCTION_BLOCKs with ASSERT_* calls, run in virtual time against the
configured plant by ``softplc test`` and by pytest.

    natives.py          the assertion functions (native functions, st/native.py)
                        and the service that records them
    discover.py         which POUs of the test files are tests
    runner.py           one engine per test: the plant's tasks and the test's
    junit.py            the JUnit XML report
    command.py          ``softplc test``: output and exit codes
    st_pytest_plugin.py the pytest collector of test_*.st files (entry point softplc_st)

Nothing below this package knows it: the test runner compiles with its own
native functions (compile_files(natives=...)) and binds their service on
the engine's ExecContext, the way a bus driver binds its own.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..engine.places import PathError
    from ..engine.values import EnumValue
    from .plc import PLC, EngineTime, duration_ns
    from .trace import Row, Trace

# The names are imported on first use (PEP 562): the pytest plugins live in
# this package, and a pytest run that never builds a PLC must not pay for
# importing the engine, the buses and the compiler.
_WHERE = {
    "PLC": ".plc",
    "EngineTime": ".plc",
    "duration_ns": ".plc",
    "PathError": "..engine.places",
    "Row": ".trace",
    "Trace": ".trace",
    "EnumValue": "..engine.values",
}


def __getattr__(name: str) -> Any:
    module = _WHERE.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(importlib.import_module(module, __name__), name)


__all__ = ["PLC", "EngineTime", "EnumValue", "PathError", "Row", "Trace", "duration_ns"]
