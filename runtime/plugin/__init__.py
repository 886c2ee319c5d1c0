"""The seams through which buses and devices plug into softplc, and the
registry that finds them.

    seams.py     what a bus (Bus) and a device (Device) declare
    driver.py    how a bus driver meets the scan (Driver, DriverStatus, DriverError)
    registry.py  the installed buses and devices (entry points softplc.buses
                 and softplc.devices); extended() adds some for a while

Public names: Bus, Device, Driver, DriverError, DriverStatus, registry.
"""

from .driver import Driver, DriverError, DriverStatus
from .registry import registry
from .seams import Bus, Device

__all__ = ["Bus", "Device", "Driver", "DriverError", "DriverStatus", "registry"]
