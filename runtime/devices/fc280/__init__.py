"""The Danfoss VLT Midi Drive FC 280 on CANopen (manual 003 "Programmier-
handbuch CANopen - VLT Midi Drive FC 280", digest 003).

    profile.py      the FC profile's control and status words, the reference scaling (§4.4)
    parameters.py   the parameter list (Tabelle 6.1), its object indices and conversions
    diagnostics.py  EMCY codes and flags, alarm and warning words (§3.1.4, §8)
    st_codes.py     fblocks/vendor/fc280_codes.st from those tables
    eds.py          io_config/eds/fc280.eds: every parameter, the CiA 402 vl objects
    store.py        the simulated drive's parameter memory: ranges, save and restore
    control.py      FC profile gating (8-5x) and the DSP 402 state machine (§4.3)
    motor.py        ramps
    model.py        the drive: references, 8-03/8-04, alarms and warnings, trip lock
    emcy.py         what the simulated drive sends as EMCY
    options.py      the [[sim]] key `parameters`
    sim.py          the simulated FC 280: a CANopen slave on a [[can]] bus
The generic CiA 402 states and commands are in io/canopen/cia402.py.
ST blocks: fblocks/vendor/fc280.st (FC280_DRIVE, FC280_DSP402) and
fc280_parameter.st (FC280_PARAMETER, FC280_STORE); fblocks/comm/cia402.st.

Public names: DEVICE, Fc280Simulator.
"""

from __future__ import annotations

from ...io.can import CanSimContext
from ...io.canopen import cia402
from ...io.canopen.eds import render as render_eds
from ...plugin.seams import Device, GeneratedFile, PackageFile, StLibrary
from . import st_codes
from .diagnostics import emcy_text
from .eds import fc280_eds
from .options import Fc280Options
from .parameters import sdo_object
from .profile import OBJ_CONTROL_WORD, OBJ_REFERENCE, SAFE_CONTROL_WORD
from .sim import FAULTS, Fc280Simulator
from .words import object_text

EDS = PackageFile("softplc.io_config", "eds/fc280.eds")

#: what the RPDOs carry while the PLC holds its outputs safe: in both profiles
#: the motor coasts, the power section off, with a reference of 0
SAFE_OBJECTS = {
    (OBJ_CONTROL_WORD, 0): SAFE_CONTROL_WORD,  # FC profile: 0434h, coast (§4.4.2)
    (OBJ_REFERENCE, 0): 0,
    (0x6040, 0): cia402.DISABLE_VOLTAGE,  # DSP 402: 0000h, transition 9: coast (§4.3.2)
    (0x6042, 0): 0,  # vl target velocity
}


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
    sim_faults=FAULTS,
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
    parameter_object=sdo_object,
    emcy_text=emcy_text,
    object_text=object_text,
    safe_objects=SAFE_OBJECTS,
)

__all__ = ["DEVICE", "Fc280Simulator"]
