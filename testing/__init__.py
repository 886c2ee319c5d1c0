"""softplc.testing: the API for testing a PLC offline, under its short name.

The code is softplc.runtime.testing (runtime/testing/); this package only
re-exports its public names. docs/guide/testing.md: "Testing a sequence offline
(Python and pytest)".
"""

from softplc.runtime.sweep.cases import SweepCase, SweepResult, sweep_cases, sweep_params
from softplc.runtime.testing import PLC, EngineTime, EnumValue, PathError, Row, Trace, duration_ns

__all__ = [
    "PLC",
    "EngineTime",
    "EnumValue",
    "PathError",
    "Row",
    "SweepCase",
    "SweepResult",
    "Trace",
    "duration_ns",
    "sweep_cases",
    "sweep_params",
]
