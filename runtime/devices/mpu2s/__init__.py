"""The Woodward MPU2-S multi-measurement transducer on plain CAN (manual 004
"MPU2-S Multimeßwertumsetzer Protokollbeschreibung", digest 004), and the
genset synchronisation built on it.

    frames.py       CAN identifiers, byte-0 kinds, the XOR checksum; requests,
                    replies and telegram frames (digest §1)
    scaling.py      the scaling families of the parameters: value <-> raw (§3.1)
    telegram.py     the 69-word send telegram, its bit maps, the assembler (§2)
    parameters.py   the 170 parameters of parameters.csv: lookup, encode and
                    decode with the documented ranges, read-modify-write (§3)
    codewords.py    fault texts, relay-manager words, DI digit words (§3.5-3.8)
    st_codes.py     fblocks/vendor/mpu2s_codes.st from those tables
    requests.py     parameter reads and writes: password, factors, RMW, retries
    exchange.py     MPU2S_EXCHANGE, the native function under MPU2S_PARAM
    node.py         the [[plaincan]] type "mpu2s": telegram and requests on the bus
    plant.py        the genset, its busbar and its breaker in virtual time
    sim_options.py  the [[sim]] keys of a simulated MPU2-S: scenario and wiring
    sim_store.py    the simulated device's parameter memory and its write rules
    sim_telegram.py the simulated device's 69 telegram words
    sim_sync.py     the simulated device closing the GCB itself (supervise mode)
    sim.py          the simulated MPU2-S on the CAN bus, over the plant

ST blocks: fblocks/vendor/mpu2s.st (MPU2S, MPU2S_PARAM, MPU2S_DEVICE),
fblocks/vendor/genset.st (STEP3, GENSET_SYNC).

Public names: DEVICE, Mpu2sSimulator.
"""

from __future__ import annotations

from ...io.can import CanSimContext
from ...io.plaincan import PlainCanKind
from ...plugin.seams import Device, GeneratedFile, PackageFile, StLibrary
from . import st_codes
from .exchange import MPU2S_EXCHANGE
from .node import Mpu2sNode, Mpu2sOptions
from .sim import FAULTS, Mpu2sSimulator
from .sim_options import Mpu2sSimOptions
from .words import frame_text


def _simulator(sim, ctx: CanSimContext) -> Mpu2sSimulator:
    return Mpu2sSimulator(
        sim.at.node_id, settings=ctx.settings, clock=ctx.clock, pump=ctx.pump, name=sim.name, scenario=sim.options
    )


DEVICE = Device(
    name="mpu2s",
    order=40,
    bus="can",
    sim_types=("mpu2s",),
    sim_options=Mpu2sSimOptions,
    simulator=_simulator,
    sim_faults=FAULTS,
    node_kind=PlainCanKind(options=Mpu2sOptions, build=Mpu2sNode, frame_text=frame_text),
    natives=(MPU2S_EXCHANGE,),
    libraries=(
        StLibrary("softplc.fblocks.vendor", "mpu2s_codes.st"),
        StLibrary("softplc.fblocks.vendor", "mpu2s.st"),
        StLibrary("softplc.fblocks.vendor", "genset.st"),
    ),
    generated=(GeneratedFile(PackageFile("softplc.fblocks.vendor", "mpu2s_codes.st"), st_codes.render),),
)

__all__ = ["DEVICE", "Mpu2sSimulator"]
