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
README: "Testing a sequence offline (Python and pytest)".
"""

from .places import PathError
from .plc import PLC, duration_ns
from .trace import Row, Trace
from .values import EnumValue

__all__ = ["PLC", "EnumValue", "PathError", "Row", "Trace", "duration_ns"]
