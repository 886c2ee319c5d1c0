"""Eaton PowerXL DA1, DB1, DC1 drives and DE1 speed starter on Modbus RTU
(manual 002, digest 002).

    registers.py  families (ID 17), addressing, scaling, process data and
                  monitor values, control and status words
    faults.py     the fault numbers of Tabelle 11
    parameters.py the parameter tables (Tabellen 20-24) and their registers
    settings.py   serial line, comm loss, drive variants and ratings, DE1 terminals
    st_codes.py   fblocks/vendor/eaton_codes.st from registers.py and faults.py
    model.py      a drive as a Modbus slave sees it: ramps, faults, watchdog
    defaults.py   the simulator's defaults and the parameters the model acts on
    effective.py  what the registers mean to the model, worked out once per change
    checks.py     whether the drive takes a register write
    sim_faults.py the faults a simulated drive takes from [[sim]] faults = [...]
ST blocks: fblocks/vendor/eaton.st (DA1_DRIVE, EATON_PARAMETER). Simulated
drives are units of a simulated Modbus line ([[sim]] type da1 ... de11).

Public names: DEVICE, EatonDriveModel, Family.
"""

from __future__ import annotations

from ...io.modbus import ModbusSimContext
from ...plugin.driver import DriverError
from ...plugin.seams import Device, GeneratedFile, PackageFile, StLibrary
from ...sim.options import RegisterPresets
from . import st_codes
from .model import EatonDriveModel
from .registers import Family
from .sim_faults import FAULTS

SIM_TYPES = ("da1", "db1", "dc1", "de1", "de11")  # the PowerXL families; de11: a DE1 with DXE-EXT-SET


def _simulator(sim, ctx: ModbusSimContext) -> EatonDriveModel:
    family = Family.DE1 if sim.type == "de11" else Family[sim.type.upper()]
    try:
        return EatonDriveModel(family, de11=sim.type == "de11", registers=dict(sim.options.registers))
    except ValueError as exc:  # a register the drive does not have
        raise DriverError(f"{ctx.where}: {sim.key}.registers: {exc}") from None


DEVICE = Device(
    name="eaton",
    order=20,
    bus="modbus",
    sim_types=SIM_TYPES,
    sim_options=RegisterPresets,
    simulator=_simulator,
    sim_faults=FAULTS,
    libraries=(StLibrary("softplc.fblocks.vendor", "eaton.st"), StLibrary("softplc.fblocks.vendor", "eaton_codes.st")),
    generated=(GeneratedFile(PackageFile("softplc.fblocks.vendor", "eaton_codes.st"), st_codes.render),),
)

__all__ = ["DEVICE", "EatonDriveModel", "Family"]
