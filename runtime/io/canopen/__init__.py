"""CANopen: a master (master.py) that boots the configured nodes as a CANopen
manager does, maps their PDOs into the process image, produces heartbeat
and SYNC, watches heartbeats and emergencies and serves READ_VAR /
WRITE_VAR over SDO (sdo.py); its [canopen] configuration (config.py),
CANOPEN_NODE / CANOPEN_MASTER for the program (diag.py), the CiA 301 numbers
(cia301.py), an EDS writer (eds.py) and the simulated slave devices build
on (slave.py: a real canopen LocalNode).

Public names: BUS, CanopenDriver, CanopenConfig, SimulatedCanopenSlave.
"""

from __future__ import annotations

from ...plugin.seams import BuildContext, Bus, Contribution, StLibrary
from ..can import port_of, pump_of, settings_of
from .config import CanopenConfig, CanopenSection
from .decode import frame_text
from .master import CanopenDriver
from .sdo import READ_VAR, WRITE_VAR
from .slave import SimulatedCanopenSlave


def _build(config, ctx: BuildContext) -> Contribution:
    if config.canopen is None:
        return Contribution()
    bus = next(b for b in config.can if b.name == config.canopen.bus)
    return Contribution(
        drivers=[
            CanopenDriver(
                config.canopen,
                settings_of(bus),
                clock=ctx.clock,
                pump=pump_of(ctx),
                addressing=ctx.addressing,
                port=port_of(ctx, bus),
            )
        ]
    )


BUS = Bus(
    name="canopen",
    order=30,
    sections=(CanopenSection(),),
    natives=(READ_VAR, WRITE_VAR),
    libraries=(
        StLibrary("softplc.fblocks.comm", "sdo.st"),
        StLibrary("softplc.fblocks.comm", "canopen_diag.st"),
        StLibrary("softplc.fblocks.comm", "cia402.st"),
    ),
    build=_build,
    frame_text=frame_text,
)

__all__ = ["BUS", "CanopenConfig", "CanopenDriver", "SimulatedCanopenSlave"]
