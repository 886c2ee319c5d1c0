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
    plant.py        the genset, its busbar and its breaker in virtual time

ST blocks: fblocks/vendor/genset.st (STEP3, GENSET_SYNC).

Public names: DEVICE.
"""

from __future__ import annotations

from ...plugin.seams import Device, GeneratedFile, PackageFile, StLibrary
from . import st_codes

DEVICE = Device(
    name="mpu2s",
    order=40,
    libraries=(
        StLibrary("softplc.fblocks.vendor", "mpu2s_codes.st"),
        StLibrary("softplc.fblocks.vendor", "genset.st"),
    ),
    generated=(GeneratedFile(PackageFile("softplc.fblocks.vendor", "mpu2s_codes.st"), st_codes.render),),
)

__all__ = ["DEVICE"]
