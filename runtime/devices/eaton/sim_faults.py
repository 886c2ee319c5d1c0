"""The faults a simulated Eaton drive takes from [[sim]] faults = [...] or
a test (config/sim_faults.py), beside the line's SILENT:

    faults = [
        { at = "10s", fault = "trip", value = 50 },            # fault 50 of Tabelle 11
        { at = "30s", fault = "enable_off", for = "2s" },      # STO / DI1 open for 2 s
    ]
"""

from __future__ import annotations

from ...io.modbus.unit import SILENT
from ...plugin.seams import SimFault
from . import faults as eaton_faults

TRIP = SimFault("trip", "the drive trips with a fault of Tabelle 11", value="a fault number of Tabelle 11")
ENABLE_OFF = SimFault(
    "enable_off", "the hardware enable opens (STO on the DA1, DI1 on the others): the motor coasts", lasting=True
)
FAULTS = (SILENT, TRIP, ENABLE_OFF)


def inject(model, fault: str, value, on: bool) -> None:
    """For EatonDriveModel.inject: the model at its last advanced time."""
    if fault == TRIP.name:
        code = int(value)
        if code not in eaton_faults.FAULTS or code == eaton_faults.FAULT_NONE:
            raise ValueError(f"{code} is not a fault number of Tabelle 11")
        model.trip(code)
    elif fault == ENABLE_OFF.name:
        model.di1 = not on
    else:
        raise ValueError(f"an Eaton drive has no fault {fault!r}")
