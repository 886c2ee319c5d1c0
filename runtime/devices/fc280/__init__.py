"""The Danfoss VLT Midi Drive FC 280 on CANopen (manual 003, digest 003).
So far only its EDS skeleton (eds.py -> io_config/eds/fc280.eds), so that a
[[canopen.node]] can name eds = "fc280".

Public names: DEVICE.
"""

from __future__ import annotations

from ...io.canopen.eds import render as render_eds
from ...plugin.seams import Device, GeneratedFile, PackageFile, StLibrary
from . import st_codes
from .eds import fc280_eds
from .parameters import sdo_object

EDS = PackageFile("softplc.io_config", "eds/fc280.eds")

DEVICE = Device(
    parameter_object=sdo_object,
    name="fc280",
    order=30,
    libraries=(
        StLibrary("softplc.fblocks.vendor", "fc280.st"),
        StLibrary("softplc.fblocks.vendor", "fc280_parameter.st"),
        StLibrary("softplc.fblocks.vendor", "fc280_codes.st"),
    ),
    files={"eds": {"fc280": EDS}},
    generated=(
        GeneratedFile(PackageFile("softplc.fblocks.vendor", "fc280_codes.st"), st_codes.render),
        GeneratedFile(EDS, lambda: render_eds(fc280_eds()), encoding="ascii"),
    ),
)

__all__ = ["DEVICE"]
