"""The Eaton PowerXL parameter tables (parameters.py, Tabellen 20-24) against
the manual's own numbers (manual 002, shared/manuals/002_a23ab2a6587941cb.txt;
"L<n>" is a line of that file; digest shared/digests/002_eaton_modbus.md).

Every expected value below is copied from the manual (or, where a test says
so, from the digest's derived examples); none is computed by the code under
test.
"""

from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import parameters as eaton_parameters
from softplc.runtime.devices.eaton import registers as eaton
from softplc.runtime.devices.eaton.registers import Family

DA1, DB1, DC1, DE1 = Family.DA1, Family.DB1, Family.DC1, Family.DE1


# ---------------------------------------------------------------------------
# Parameter numbers -> registers (Tabellen 20-24)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "number, register",
    [
        ("P1-01", 101),  # L1287
        ("P1-12", 112),  # L1298
        ("P1-14", 114),  # L1300
        ("P2-25", 225),  # L1332
        ("P2-40", 240),  # L1347
        ("P3-18", 318),  # L1370
        ("P4-13", 413),  # L1383
        ("P5-05", 505),  # L1395
        ("P5-17", 517),  # L1407
        ("P6-30", 630),  # L1442
        ("P7-17", 717),  # L1459
        ("P8-13", 813),  # L1479
        ("P9-41", 941),  # L1525
    ],
)
def test_da1_parameter_registers(number, register):
    assert eaton_parameters.parameter_register(DA1, number) == register
    group, index = int(number[1]), int(number[3:])
    assert eaton_parameters.da1_parameter_register(group, index) == register


@pytest.mark.parametrize(
    "number", ["P1-15", "P2-41", "P3-19", "P4-14", "P5-18", "P6-31", "P7-18", "P8-14", "P9-42", "P1-00"]
)
def test_da1_numbers_the_table_does_not_have(number):
    with pytest.raises(ValueError, match="not in the DA1 parameter table"):
        eaton_parameters.parameter_register(DA1, number)


@pytest.mark.parametrize("number", ["P-01", "P10-01", "P1-001", "101", "P1.01"])
def test_da1_numbers_of_the_wrong_form(number):
    with pytest.raises(ValueError, match="DA1 parameters are named"):
        eaton_parameters.parameter_register(DA1, number)


def test_da1_p0_values_are_not_in_the_formula():
    with pytest.raises(ValueError, match="monitor_registers"):
        eaton_parameters.parameter_register(DA1, "P0-01")


def test_every_da1_table_row_follows_group_times_100_plus_index():
    rows = eaton_parameters.PARAMETERS[DA1]
    assert len(rows) == 203  # P1-01..P1-14, P2 40, P3 18, P4 13, P5 17, P6 30, P7 17, P8 13, P9 41
    for row in rows:
        group, index = int(row.number[1]), int(row.number[3:])
        assert row.register == group * 100 + index, row
    registers = [row.register for row in rows]
    assert (min(registers), max(registers)) == eaton.REGISTER_GROUPS[DA1].parameters  # "101 - 941", L719


@pytest.mark.parametrize(
    "family, number, register",
    [
        (DB1, "P-01", 129),  # L1631
        (DB1, "P-12", 140),  # L1647
        (DB1, "P-36", 164),  # L1672
        (DB1, "P-56", 184),  # L1700
        (DB1, "P-68", 196),  # L1709
        (DC1, "P-01", 129),  # L1780
        (DC1, "P-53", 181),  # L1848
        (DC1, "P-56", 184),
        (DC1, "P-70", 198),  # L1870
        (DE1, "P-12", 140),  # L1921
        (DE1, "P-34", 162),  # L1943
        (DE1, "P-35", 163),  # L1944
        (DE1, "P-36", 164),  # L1945
        (DE1, "P-40", 168),  # L1949
        (DE1, "P-47", 175),  # L1956
        (DE1, "P-48", 176),  # L1957
    ],
)
def test_compact_parameter_registers(family, number, register):
    assert eaton_parameters.parameter_register(family, number) == register
    assert eaton_parameters.compact_parameter_register(family, int(number[2:])) == register


@pytest.mark.parametrize(
    "family, number",
    [
        (DB1, "P-52"),
        (DB1, "P-53"),
        (DB1, "P-57"),
        (DB1, "P-58"),
        (DB1, "P-69"),
        (DB1, "P-70"),
        (DB1, "P-59"),
        (DC1, "P-59"),
        (DC1, "P-71"),
        (DE1, "P-49"),
        (DE1, "P-50"),
        (DE1, "P-57"),
        (DE1, "P-00"),
    ],
)
def test_compact_numbers_the_table_does_not_have(family, number):
    with pytest.raises(ValueError, match=f"not in the {family.name} parameter table"):
        eaton_parameters.parameter_register(family, number)


@pytest.mark.parametrize("family", [DB1, DC1, DE1])
def test_compact_families_have_no_grouped_numbers(family):
    with pytest.raises(ValueError, match="named P-<n>"):
        eaton_parameters.parameter_register(family, "P1-01")


def test_da1_has_no_compact_numbers():
    with pytest.raises(ValueError):
        eaton_parameters.compact_parameter_register(DA1, 1)


@pytest.mark.parametrize(
    "number, register",
    [
        ("P-50", 178),  # L1968
        ("P-54", 182),  # L1972
        ("P-57", 183),  # L1973: not 185 (A16)
        ("P-58", 184),  # L1974: not 186 (A16)
    ],
)
def test_de11_parameters(number, register):
    assert eaton_parameters.parameter_register(DE1, number, de11=True) == register


def test_de11_keeps_the_de1_parameters():
    assert eaton_parameters.parameter_register(DE1, "P-48", de11=True) == 176


@pytest.mark.parametrize("family", [DB1, DC1, DE1])
def test_every_compact_table_row_is_128_plus_n(family):
    for row in eaton_parameters.PARAMETERS[family]:
        assert row.register == 128 + int(row.number[2:]), row


def test_de11_rows_are_128_plus_n_but_for_p57_p58():
    off_rule = {
        row.number: row.register
        for row in eaton_parameters.DE11_PARAMETERS
        if row.register != 128 + int(row.number[2:])
    }
    assert off_rule == {"P-57": 183, "P-58": 184}


def test_table_sizes():
    assert len(eaton_parameters.PARAMETERS[DB1]) == 67  # P-01..P-68 without 52, 53, 57-59; 3 shared registers
    assert len(eaton_parameters.PARAMETERS[DC1]) == 73  # + P-52, P-53, P-57, P-58, P-69, P-70
    assert len(eaton_parameters.PARAMETERS[DE1]) == 48  # P-01..P-48
    assert len(eaton_parameters.DE11_PARAMETERS) == 7


# ---------------------------------------------------------------------------
# Parameter access and scaling (digest §3.13, M14)
# ---------------------------------------------------------------------------


def rows(family, number, **kw):
    return eaton_parameters.parameter_rows(family, number, **kw)


@pytest.mark.parametrize(
    "family, number, raw, value, unit",
    [
        (DA1, "P1-01", 3000, 50.0, "Hz"),  # L1287 "3000 ≙ 50.0 Hz"
        (DA1, "P1-03", 300, 30.0, "s"),  # L1289 "300 ≙ 30.0 s"
        (DA1, "P1-07", 230, 230, "V"),  # L1293
        (DA1, "P1-08", 1, 0.1, "A"),  # L1294 "1 ≙ 0.1 A"
        (DA1, "P1-09", 500, 50, "Hz"),  # L1295 "500 ≙ 50 Hz"
        (DA1, "P1-10", 1500, 1500, "rpm"),  # L1296
        (DA1, "P4-05", 99, 0.99, ""),  # L1375
        (DA1, "P4-07", 2000, 200.0, "%"),  # L1377
        (DA1, "P5-05", 50, 5.0, "s"),  # L1395 "1 ≙ 0.1 s", range 0.0 - 5.0
        (DA1, "P6-20", 1, 0.01, "kW"),  # L1432
        (DB1, "P-03", 300, 3.0, "s"),  # L1633 "300 ≙ 3.00 s"
        (DB1, "P-08", 100, 10.0, "A"),  # L1638 "100 ≙ 10.0 A"
        (DB1, "P-09", 50, 50, "Hz"),  # L1639 "50 ≙ 50 Hz"
        (DC1, "P-20", 3000, 50.0, "Hz"),  # L1804
        (DE1, "P-26", 100, 10.0, "s"),  # L1935 "100 ≙ 10.0 s"
    ],
)
def test_parameter_scales(family, number, raw, value, unit):
    scale = rows(family, number)[0].scale
    assert scale.to_value(raw) == value
    assert scale.to_raw(value) == raw
    assert scale.unit == unit


def test_packed_field_scales():
    t_dc_brake, dc_brake = rows(DC1, "P-32")
    assert t_dc_brake.scale.to_value(30) == 3.0  # L1816 "30 ≙ 3.0 s"
    display_scaling, source = rows(DB1, "P-40")
    assert display_scaling.scale.to_value(10000) == 10.0  # L1685 "10000 ≙ 10.000"


@pytest.mark.parametrize(
    "family, number",
    [
        (DA1, "P2-25"),  # frame-size dependent (L1332)
        (DA1, "P8-01"),  # L1467
        (DA1, "P1-11"),  # "-1 ≙ Auto 0 ≙ Disabled 1 ≙ 0.1 %" (L1297)
        (DA1, "P5-02"),  # codes "0 ≙ 125 kbps 1 ≙ 250 kbps" (L1392)
        (DA1, "P5-04"),  # codes "0 ≙ N-1 1 ≙ N-2" (L1394)
        (DA1, "P1-05"),  # no scaling printed (L1291)
    ],
)
def test_cells_that_are_not_one_linear_scale(family, number):
    assert rows(family, number)[0].scale is None


@pytest.mark.parametrize(
    "family, number, mode",
    [
        (DA1, "P1-01", eaton_parameters.RUN),  # L1287
        (DA1, "P1-12", eaton_parameters.STOP),  # L1298
        (DA1, "P4-01", eaton_parameters.STOP),  # L1371
        (DB1, "P-01", eaton_parameters.RUN),  # L1631
        (DB1, "P-12", eaton_parameters.STOP),  # L1647
        (DE1, "P-01", eaton_parameters.STOP),  # L1905 (A33)
        (DE1, "P-13", eaton_parameters.RO),  # L1922
        (DA1, "P3-14", eaton_parameters.RESERVED),  # L1366
        (DA1, "P9-32", eaton_parameters.RESERVED),  # L1516
    ],
)
def test_parameter_modes(family, number, mode):
    row = rows(family, number)[0]
    assert row.mode == mode
    assert row.writable == (mode in (eaton_parameters.RUN, eaton_parameters.STOP))
    assert row.writable_in_run == (mode == eaton_parameters.RUN)


def test_signed_parameters():
    assert rows(DA1, "P2-29")[0].format == eaton_parameters.S16  # L1336, -500.0 .. +500.0 %
    assert eaton.to_signed16(0xFFFF) == -1
    assert eaton.from_signed16(-5000) == 0xEC78  # P2-35 lower limit -5000 (L1342)
    assert eaton.to_signed16(0xEC78) == -5000
    with pytest.raises(ValueError):
        eaton.from_signed16(40000)


# ---------------------------------------------------------------------------
# Shared registers: DB1/DC1 P-36 = register 164 (Tabellen 21/22)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize("family", [DB1, DC1])
def test_register_164_fields(family):
    address, baud, timeout = rows(family, "P-36")
    assert (address.register, address.bits) == (164, (0, 7))  # "164 (Low Byte)" L1672
    assert (baud.register, baud.bits) == (164, (8, 11))  # "164 (Bit 8 - Bit 11)" L1673
    assert (timeout.register, timeout.bits) == (164, (12, 15))  # "164 (Bit 12 - Bit 15)" L1681


def test_register_164_read_modify_write():
    """Derived example of digest §1.4: address 1, 115.2 kBit/s (code 6), r 3000 ms (code 8) -> 0x8601."""
    address, baud, timeout = rows(DC1, "P-36")
    word_ = address.insert(0, 1)
    word_ = baud.insert(word_, 6)
    word_ = timeout.insert(word_, 8)
    assert word_ == 0x8601
    assert (address.extract(word_), baud.extract(word_), timeout.extract(word_)) == (1, 6, 8)
    assert timeout.insert(word_, 4) == 0x4601  # the other fields stay
    with pytest.raises(ValueError):
        timeout.insert(word_, 16)


def test_register_160_and_168_fields():
    low, high = rows(DB1, "P-32")
    assert (low.bits, high.bits) == ((0, 7), (8, 15))  # L1667-1668
    scaling, source = rows(DB1, "P-40")
    assert (scaling.bits, source.bits) == ((0, 13), (14, 15))  # L1685-1686
    assert source.extract(0xC000) == 3 and scaling.extract(0xC000) == 0


def test_de1_p36_is_a_whole_register():
    (row,) = rows(DE1, "P-36")
    assert row.bits is None and row.extract(0x0008) == 8


# ---------------------------------------------------------------------------
# Parameters the runtime names: the command source and the bus ramp switch
# ---------------------------------------------------------------------------


def test_modbus_control_sources():
    assert eaton_parameters.MODBUS_CONTROL_SOURCES[DA1] == (4,)  # P1-12 = 4 (L376)
    assert eaton_parameters.MODBUS_CONTROL_SOURCES[DC1] == (3, 4)  # P-12 = 3, 4 (L413)
    assert eaton_parameters.MODBUS_CONTROL_SOURCES[DE1] == (3,)  # P-12 = 3 (L436)
    assert eaton_parameters.parameter_register(DA1, eaton_parameters.CONTROL_SOURCE_PARAMETER[DA1]) == 112
    assert eaton_parameters.parameter_register(DE1, eaton_parameters.CONTROL_SOURCE_PARAMETER[DE1]) == 140
    assert eaton_parameters.parameter_register(DA1, eaton_parameters.DA1_FIELDBUS_RAMP_CONTROL) == 507  # L389
