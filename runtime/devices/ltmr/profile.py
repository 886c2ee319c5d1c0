"""The LTMR's CANopen communication profile: PDO defaults, the PKW object, identity and product codes.

The manual's object dictionary chapter, beside the register objects of
registers.py. Source: manual 001 (DOCA0132EN,
shared/manuals/001_5287ad2b8a6c20a4.txt; "L<n>" below is a line of that file)
and its digest (shared/digests/001_ltmr_canopen_en.md, "§" and the
ambiguities "A<n>" of its §10).
"""

from __future__ import annotations

# ---------------------------------------------------------------------------
# PDO defaults and identity (manual §4 object dictionary, digest §2.3, §2.5)
# ---------------------------------------------------------------------------

# 0x1600: 704, then 0x2008:04 (printed "Reg [706]", a reserved word either way: A2), then 700 (L1199-1221)
RPDO1_DEFAULT = (0x20080510, 0x20080410, 0x20080110)
# 0x1A00: 455, 456, 457, 0x2004:0A = 459 I/O status (overview table says 458: A1), L1526-1548
TPDO1_DEFAULT = (0x20040610, 0x20040710, 0x20040810, 0x20040A10)
# 0x1603 / 0x1A03: PKW request 0x3000:01/02, response 0x3000:03/04 (L1304, L1631)
RPDO4_DEFAULT = (0x30000120, 0x30000220)
TPDO4_DEFAULT = (0x30000320, 0x30000420)

PKW_INDEX = 0x3000  # sub 1/2 request (RPDO4), sub 3/4 response (TPDO4)
# The register objects PDOs may map (L253-280): 0x2004 into TPDOs, 0x2007/0x2008 into RPDOs
TPDO_MAPPABLE_INDICES = (0x2004,)
RPDO_MAPPABLE_INDICES = (0x2007, 0x2008)

VENDOR_ID = 0x0300005A  # 0x1018:01, L977
PRODUCT_REVISION = 0x00010001  # 0x1018:03, L991
DEVICE_NAME = "LTM"  # 0x1008, L907
HARDWARE_VERSION = "M1.0-ES1.0"  # 0x1009, L914
SOFTWARE_VERSION = "V01.01"  # 0x100A, L921 ("only an example")

# 0x1018:02 product code (L1034-1050); bit 0 = LTMEV40 present, 0x100 = local configuration (A24)
PRODUCT_CODES = {
    0x030: "TeSys T MMC R (remote configuration)",
    0x031: "TeSys T MMC R EV40 (remote configuration, LTMEV40)",
    0x130: "TeSys T MMC L (local configuration)",
    0x131: "TeSys T MMC L EV40 (local configuration, LTMEV40)",
}
PRODUCT_CODE_REMOTE = 0x030


def pkw_read_only(product_code: int) -> bool:
    """ "For TeSys T MMC L and TeSys T MMC L EV40, PKW use is restricted to read
    access" (L343): the local-configuration variants."""
    if product_code not in PRODUCT_CODES:
        raise ValueError(f"0x{product_code:X} is not an LTMR product code ({', '.join(map(hex, PRODUCT_CODES))})")
    return bool(product_code & 0x100)


def has_expansion_module(product_code: int) -> bool:
    return bool(product_code & 0x001)
