"""The Woodward MPU2-S multi-measurement transducer on plain CAN (manual 004
"MPU2-S Multimeßwertumsetzer Protokollbeschreibung", digest 004), and the
genset synchronisation built on it.

    plant.py        the genset, its busbar and its breaker in virtual time
ST blocks: fblocks/vendor/genset.st (STEP3, GENSET_SYNC).

Public names: DEVICE.
"""

from __future__ import annotations

from ...plugin.seams import Device, StLibrary

DEVICE = Device(
    name="mpu2s",
    order=40,
    libraries=(StLibrary("softplc.fblocks.vendor", "genset.st"),),
)

__all__ = ["DEVICE"]
