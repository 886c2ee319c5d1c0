"""The Schneider TeSys T LTMR motor management controller on CANopen
(manuals 000 German, 001 English; digests 000/001).

    registers.py  the register map and the registers' CANopen objects (manual 001 §5-6)
    bits.py       the bits of the status, control, trip, alarm and configuration words
    codes.py      enumerations (operating mode, fallback, reset mode ...), trip and alarm codes
    datatypes.py  DT_DateTime, DT_CommercialReference, two-word and signed values
    profile.py    the communication profile: PDO defaults, PKW object, identity (manual 001 §4)
    pkw.py        the PKW codec on PDO4
    st_codes.py   fblocks/vendor/ltmr_codes.st from those tables
    eds.py        io_config/eds/ltmr.eds from those tables
    emcy.py       the emergency messages: what the simulator sends, the master's log line
    defaults.py   the settings at power-up, the simulator's choices, the manual's constants
    thermal.py    the thermal image (class N) as plain functions
    model.py      the motor model: commands, outputs, trips and resets, fallback
    publish.py    what the model shows in its status, current and thermal registers
    sim.py        the simulated LTMR: a CANopen slave on a [[can]] bus
ST blocks: fblocks/vendor/ltmr.st (LTMR_CONTROL, LTMR_PKW).

Public names: DEVICE, LtmrSimulator.
"""

from __future__ import annotations

from ...io.can import CanSimContext
from ...io.canopen.eds import render as render_eds
from ...plugin.seams import Device, GeneratedFile, PackageFile, StLibrary
from . import st_codes
from .bits import SAFE_CONTROL_1
from .eds import ltmr_eds
from .emcy import emcy_text
from .registers import REG_CONTROL_1, register_to_object
from .sim import FAULTS, LtmrSimulator
from .sim_options import LtmrSimOptions
from .words import object_text

EDS = PackageFile("softplc.io_config", "eds/ltmr.eds")


def _simulator(sim, ctx: CanSimContext) -> LtmrSimulator:
    return LtmrSimulator(
        sim.at.node_id,
        settings=ctx.settings,
        clock=ctx.clock,
        pump=ctx.pump,
        name=sim.name,
        registers=dict(sim.options.registers),
        load_percent=sim.options.load_percent,
    )


DEVICE = Device(
    name="ltmr",
    order=10,
    bus="can",
    sim_types=("ltmr",),
    sim_options=LtmrSimOptions,
    simulator=_simulator,
    sim_faults=FAULTS,
    libraries=(StLibrary("softplc.fblocks.vendor", "ltmr.st"), StLibrary("softplc.fblocks.vendor", "ltmr_codes.st")),
    files={"eds": {"ltmr": EDS}},
    generated=(
        GeneratedFile(PackageFile("softplc.fblocks.vendor", "ltmr_codes.st"), st_codes.render),
        GeneratedFile(EDS, lambda: render_eds(ltmr_eds()), encoding="ascii"),
    ),
    safe_objects={register_to_object(REG_CONTROL_1): int(SAFE_CONTROL_1)},  # 2008:05 = 0: motor off
    emcy_text=emcy_text,
    object_text=object_text,
)

__all__ = ["DEVICE", "LtmrSimulator"]
