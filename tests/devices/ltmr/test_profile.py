"""The LTMR communication profile (profile.py): PDO defaults and identity
with the manual's own numbers (manual 001 §4; digest 001 §2.3, §2.5)."""

from __future__ import annotations

import pytest

from softplc.runtime.devices.ltmr import profile as ltmr_profile
from softplc.runtime.devices.ltmr.registers import REGISTERS, object_to_register
from softplc.runtime.io.canopen.cia301 import split_mapping_entry

# ---------------------------------------------------------------------------
# PDO defaults and identity (manual §4)
# ---------------------------------------------------------------------------


def test_pdo_defaults_as_printed_in_the_object_dictionary():
    assert ltmr_profile.RPDO1_DEFAULT == (0x20080510, 0x20080410, 0x20080110)
    assert ltmr_profile.TPDO1_DEFAULT == (0x20040610, 0x20040710, 0x20040810, 0x20040A10)
    assert ltmr_profile.RPDO4_DEFAULT == (0x30000120, 0x30000220)
    assert ltmr_profile.TPDO4_DEFAULT == (0x30000320, 0x30000420)


def test_identity_and_product_codes():
    assert ltmr_profile.VENDOR_ID == 0x0300005A and ltmr_profile.PRODUCT_REVISION == 0x00010001
    assert set(ltmr_profile.PRODUCT_CODES) == {0x30, 0x31, 0x130, 0x131}
    # "For TeSys T MMC L and TeSys T MMC L EV40, PKW use is restricted to read access." (L343)
    assert [ltmr_profile.pkw_read_only(code) for code in (0x30, 0x31, 0x130, 0x131)] == [False, False, True, True]
    assert [ltmr_profile.has_expansion_module(code) for code in (0x30, 0x31, 0x130, 0x131)] == [
        False,
        True,
        False,
        True,
    ]
    with pytest.raises(ValueError):
        ltmr_profile.pkw_read_only(0x32)


def test_pdo1_defaults_name_registers_704_703_700_and_455_456_457_459():
    # A2: RPDO1 word 2 is 2008:04 = 703 (printed "Reg [706]"), reserved either way
    rx = [object_to_register(*split_mapping_entry(e)[:2]) for e in ltmr_profile.RPDO1_DEFAULT]
    assert rx == [704, 703, 700] and REGISTERS[703].kind == REGISTERS[706].kind == "reserved"
    # A1: TPDO1 word 4 is 2004:0A = 459 I/O status (the overview table says 458)
    tx = [object_to_register(*split_mapping_entry(e)[:2]) for e in ltmr_profile.TPDO1_DEFAULT]
    assert tx == [455, 456, 457, 459]
    assert all(split_mapping_entry(e)[2] == 16 for e in ltmr_profile.RPDO1_DEFAULT + ltmr_profile.TPDO1_DEFAULT)
