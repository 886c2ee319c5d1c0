"""What the safe-state tests of the devices share (README, "Safe outputs"):
a shipped configuration with a program that faults on demand in the task
of the device's block, run in virtual time through softplc.testing.

    plc = safe_plant(tmp_path, "canopen.toml", "Main")
    ... get the device running ...
    fault_the_task(plc)            # a division by zero in that task
    plc.stop()                     # or: the PLC stops

The simulated devices are the real ones of the configuration (CANopen
slaves on python-can's virtual bus, Modbus units behind pymodbus framing):
what a test asserts is what they received and what they do with it."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from softplc.testing import PLC

from ..config.support import EXAMPLES

CRASH = """\
PROGRAM Crash
VAR
    Go : BOOL;
    zero : INT;
    r : INT;
END_VAR
IF Go THEN
    r := 1 / zero;
END_IF
END_PROGRAM
"""


def safe_plant(
    tmp_path: Path,
    example: str | None,
    task: str,
    *,
    configured_safe: bool = True,
    edit: Callable[[dict], None] | None = None,
    virtual_time: bool = True,
) -> PLC:
    """The shipped configuration (an io_config/examples file, None: the
    default plant) with the program Crash in task; without its [outputs]
    table when not configured_safe (the devices' own safe values then)."""
    crash = tmp_path / "crash.st"
    crash.write_text(CRASH)

    def tables(t: dict) -> None:
        t["plc"]["programs"].append(str(crash))
        [entry] = [e for e in t["task"] if e["name"] == task]
        entry["programs"].append("Crash")
        t.get("sim", [{}])[0].pop("faults", None)  # no fault on the examples' schedule
        if not configured_safe:
            t.pop("outputs", None)
        if edit is not None:
            edit(t)

    return PLC.from_config(EXAMPLES / example if example else None, edit=tables, virtual_time=virtual_time)


def fault_the_task(plc: PLC) -> None:
    """A runtime fault in the task of Crash: the engine holds the outputs safe."""
    assert not plc["PLC_DIAG.OutputsSafe"]
    plc.write("Crash.Go", True)
    plc.step()
    assert plc["PLC_DIAG.Faulted"] and plc["PLC_DIAG.OutputsSafe"]
    assert plc["PLC_DIAG.FaultKind"] == "division", plc["PLC_DIAG.FaultKind"]
