"""The Danfoss VLT Midi Drive FC 280 on CANopen (manual 003, digest 003).
So far only its EDS skeleton (eds.py -> io_config/eds/fc280.eds), so that a
[[canopen.node]] can name eds = "fc280".

Public names: DEVICE.
"""

from __future__ import annotations

from ...io.can import CanSimContext
from ...io.canopen.eds import render as render_eds
from ...plugin.seams import Device, GeneratedFile, PackageFile
from .eds import fc280_eds
from .options import Fc280Options
from .sim import Fc280Simulator

EDS = PackageFile("softplc.io_config", "eds/fc280.eds")


def _simulator(sim, ctx: CanSimContext) -> Fc280Simulator:
    return Fc280Simulator(
        sim.at.node_id,
        settings=ctx.settings,
        clock=ctx.clock,
        pump=ctx.pump,
        name=sim.name,
        parameters=dict(sim.options.parameters),
    )


DEVICE = Device(
    name="fc280",
    order=30,
    bus="can",
    sim_types=("fc280",),
    sim_options=Fc280Options,
    simulator=_simulator,
    files={"eds": {"fc280": EDS}},
    generated=(GeneratedFile(EDS, lambda: render_eds(fc280_eds()), encoding="ascii"),),
)

__all__ = ["DEVICE"]
