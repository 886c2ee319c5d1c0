"""The LTMR register map against the manual's own tables (manual 001,
"Register | CANopen Address | Variable Type | ... | Note" rows, L2279-5098).

MANUAL_ROWS (manual_rows.py) is copied from those tables, one tuple per
printed row (register range, first and last CANopen address, the Variable
Type cell, the name cell and the note cell, as printed, typos included; the
comment is the manual line). Nothing in it is computed by the code under
test.
"""

from __future__ import annotations

import pytest

from softplc.runtime.devices.ltmr import registers as ltmr
from softplc.runtime.devices.ltmr.registers import (
    REGISTERS,
    ForbiddenRegisterError,
    UnmappedRegisterError,
    object_to_register,
    register_to_object,
)

from .manual_rows import MANUAL_ROWS

# The six printed rows whose addresses disagree with the block rule (digest 001
# §5.2, A9): register range -> what the rule gives (first and last address).
TYPO_ROWS = {
    (0, 34): ((0x2000, 0x01), (0x2000, 0x23)),  # printed 2000:03-2000:28
    (35, 40): ((0x2000, 0x24), (0x2000, 0x29)),  # printed 2000:23-2000:29
    (82, 94): ((0x2000, 0x53), (0x2000, 0x5F)),  # printed 2000:53-2000:58
    (422, 423): ((0x2003, 0x7B), (0x2003, 0x7C)),  # printed "2003 : 7B9"
}
KIND_MARKERS = {
    "(Not significant)": "not significant",
    "(Reserved)": "reserved",
    "(Reserved": "reserved",
    "(Forbidden)": "forbidden",
}
PRINTED_TYPES = {"Ulnt": "UInt", "UDlnt": "UDInt", "lnt": "Int"}  # the extraction's "l" for "I"


def _address(text: str) -> tuple:
    index, sub = text.split(":")
    return int(index, 16), int(sub, 16)


def _kind(type_cell: str, name_cell: str) -> str:
    return KIND_MARKERS.get(type_cell) or KIND_MARKERS.get(name_cell) or "value"


def test_the_tables_have_the_390_rows_the_digest_counted():
    assert len(MANUAL_ROWS) == 390


@pytest.mark.parametrize(
    "row",
    [
        r
        for r in MANUAL_ROWS
        if (r[0], r[1]) not in TYPO_ROWS
        and (r[0], r[1]) not in ((684, 692), (707, 799))
        and _kind(r[4], r[5]) != "forbidden"
    ],
    ids=lambda r: f"{r[0]}-{r[1]}",
)
def test_printed_register_address_pairs_follow_the_rule(row):
    first, last, first_address, last_address = row[:4]
    assert register_to_object(first) == _address(first_address)
    assert register_to_object(last) == _address(last_address)
    index, sub = _address(first_address)
    for reg in range(first, last + 1):  # the registers between are consecutive sub-indices
        assert register_to_object(reg) == (index, sub + reg - first)
        assert object_to_register(index, sub + reg - first) == reg


@pytest.mark.parametrize(
    "row", [r for r in MANUAL_ROWS if _kind(r[4], r[5]) == "forbidden"], ids=lambda r: f"{r[0]}-{r[1]}"
)
def test_forbidden_rows_are_rejected_both_ways(row):
    first, last, first_address, last_address = row[:4]
    if (first, last) == (707, 799):
        first = 710  # printed "707-799": the addresses fit 710-799 (A9)
    for reg in range(first, last + 1):
        with pytest.raises(ForbiddenRegisterError, match=f"register {reg} is Forbidden"):
            register_to_object(reg)
    for address in (first_address, last_address):
        with pytest.raises(ForbiddenRegisterError):
            object_to_register(*_address(address))


@pytest.mark.parametrize("span, resolved", TYPO_ROWS.items(), ids=lambda v: str(v))
def test_printed_address_typos_are_resolved_by_the_rule(span, resolved):
    row = next(r for r in MANUAL_ROWS if (r[0], r[1]) == span)
    printed = (_address(row[2].replace("7B9", "7B")), _address(row[3]))
    rule = (register_to_object(span[0]), register_to_object(span[1]))
    assert rule == resolved
    if span != (422, 423):
        assert rule != printed  # the manual's cells really are wrong


def test_reserved_row_684_692_is_684_694():
    # printed 684-692 for 2007:23-2007:2D: eleven sub-indices, so 693 and 694 are in it
    row = next(r for r in MANUAL_ROWS if r[0] == 684)
    assert register_to_object(684) == _address(row[2])
    assert register_to_object(694) == _address(row[3]) == (0x2007, 0x2D)
    assert REGISTERS[693].kind == REGISTERS[694].kind == "reserved"
    assert register_to_object(695) == (0x2007, 0x2E)  # the next printed row


def test_forbidden_row_707_799_starts_at_710():
    # printed 707-799 for 2008:0B-2008:64, overlapping "706-709 (Reserved)" at 2008:07-0A
    assert [REGISTERS[r].kind for r in range(706, 710)] == ["reserved"] * 4
    assert register_to_object(709) == (0x2008, 0x0A)
    with pytest.raises(ForbiddenRegisterError):
        object_to_register(0x2008, 0x0B)
    with pytest.raises(ForbiddenRegisterError):
        register_to_object(710)


@pytest.mark.parametrize(
    "reg, index, sub",
    [
        # the test vectors of digest 001 §5.2
        (455, 0x2004, 0x06),
        (456, 0x2004, 0x07),
        (457, 0x2004, 0x08),
        (458, 0x2004, 0x09),
        (459, 0x2004, 0x0A),
        (474, 0x2004, 0x19),
        (500, 0x2004, 0x33),
        (540, 0x2005, 0x01),
        (601, 0x2006, 0x02),
        (652, 0x2007, 0x03),
        (655, 0x2007, 0x06),
        (682, 0x2007, 0x21),
        (683, 0x2007, 0x22),
        (695, 0x2007, 0x2E),
        (696, 0x2007, 0x2F),
        (700, 0x2008, 0x01),
        (704, 0x2008, 0x05),
        (705, 0x2008, 0x06),
        (64, 0x2000, 0x41),
        (76, 0x2000, 0x4D),
        (96, 0x2000, 0x61),
        (117, 0x2001, 0x12),
        (150, 0x2002, 0x01),
        (270, 0x2002, 0x79),
        (300, 0x2003, 0x01),
        (430, 0x2003, 0x83),
        (1200, 0x200D, 0x01),
        (1250, 0x200D, 0x33),
        (1270, 0x200D, 0x47),
        (1280, 0x200D, 0x51),
        (1301, 0x200D, 0x66),
        (1399, 0x200D, 0xC8),
        # the XREF-000 ST examples: FLC1 at 2007:03, trip register 1 at 2004:03
        (652, 0x2007, 3),
        (452, 0x2004, 3),
    ],
)
def test_digest_vectors(reg, index, sub):
    assert register_to_object(reg) == (index, sub)
    assert object_to_register(index, sub) == reg


def test_not_simply_hundreds():
    # "The address is not 0x2000 + reg//100 (700 -> 0x2008, not 0x2007)"
    assert register_to_object(700)[0] == 0x2008
    assert register_to_object(599)[0] == 0x2005 and register_to_object(600)[0] == 0x2006


@pytest.mark.parametrize("reg", [-1, 800, 1000, 1199, 1400, 65535])
def test_unmapped_register_numbers(reg):
    with pytest.raises(UnmappedRegisterError, match=f"register {reg} has no CANopen address"):
        register_to_object(reg)


@pytest.mark.parametrize(
    "index, sub",
    [
        (0x2009, 1),
        (0x200C, 1),
        (0x1000, 0),
        (0x3000, 1),
        (0x2004, 0x00),
        (0x2001, 0x33),
        (0x2008, 0x65),
        (0x200D, 0xC9),
    ],
)
def test_unmapped_objects(index, sub):
    with pytest.raises(UnmappedRegisterError):
        object_to_register(index, sub)


def test_both_errors_are_value_errors():
    for bad in (800, 97):
        with pytest.raises(ValueError):
            register_to_object(bad)


def test_group_table_alternative_for_custom_logic():
    # A8: the group table prints "200C : 01 to 200D : 64"; selectable, not the default
    assert register_to_object(1200, split_custom_logic=True) == (0x200C, 0x01)
    assert register_to_object(1299, split_custom_logic=True) == (0x200C, 0x64)
    assert register_to_object(1300, split_custom_logic=True) == (0x200D, 0x01)
    assert register_to_object(1399, split_custom_logic=True) == (0x200D, 0x64)
    assert object_to_register(0x200C, 0x33, split_custom_logic=True) == 1250
    assert register_to_object(1399) == (0x200D, 0xC8)


def test_every_register_round_trips():
    for reg, register in REGISTERS.items():
        if register.kind == "forbidden":
            continue
        assert object_to_register(*register_to_object(reg)) == reg


# ---------------------------------------------------------------------------
# REGISTERS against the printed rows
# ---------------------------------------------------------------------------


def test_registers_cover_exactly_0_799_and_1200_1399():
    assert sorted(REGISTERS) == list(range(800)) + list(range(1200, 1400))
    assert all(REGISTERS[n].number == n for n in REGISTERS)


@pytest.mark.parametrize("row", MANUAL_ROWS, ids=lambda r: f"{r[0]}-{r[1]}")
def test_type_kind_and_note_as_printed(row):
    first, last, _a1, _a2, type_cell, name_cell, note = row
    if (first, last) == (707, 799):
        first, last = 710, 799
    kind = _kind(type_cell, name_cell)
    expected_type = "" if kind != "value" else PRINTED_TYPES.get(type_cell, type_cell) or "UInt"  # A17
    for reg in range(first, last + 1):
        register = REGISTERS[reg]
        assert register.kind == kind
        assert register.type == expected_type
        assert register.notes == note
    if kind == "value":
        register = REGISTERS[first]
        if first in ltmr.MANUAL_NAMES:  # renamed (A18) or shortened
            assert ltmr.MANUAL_NAMES[first] == name_cell
        else:
            assert name_cell.lower().startswith(register.name.lower())
        assert register.first == first and register.words == last - first + 1


def test_unlisted_registers_are_not_significant():
    # 108 is not listed at all; the extension tables list only E+0..E+10 of 30 (A17)
    assert REGISTERS[108].kind == "not significant"
    for k in range(5):
        _main, extension = ltmr.trip_history_base(k)
        assert [REGISTERS[r].kind for r in range(extension + 11, extension + 30)] == ["not significant"] * 19


def test_access_by_table():
    # §5.3: 0-539 read-only tables, 540-799 read/write; the custom logic tables are headed read-only
    assert {REGISTERS[r].access for r in range(540)} == {"ro"}
    assert {REGISTERS[r].access for r in range(540, 800)} == {"rw"}
    assert {REGISTERS[r].access for r in range(1200, 1400)} == {"ro"}
    assert REGISTERS[704].writable and not REGISTERS[455].writable and not REGISTERS[799].writable


def test_multi_register_values():
    assert (REGISTERS[500].type, REGISTERS[500].words, REGISTERS[500].name) == ("UDInt", 2, "Average current")
    assert (REGISTERS[501].type, REGISTERS[501].first) == ("UDInt", 500)
    assert "Average current" in REGISTERS[501].name and REGISTERS[501].name != REGISTERS[500].name
    assert [REGISTERS[r].first for r in range(655, 659)] == [655] * 4
    assert REGISTERS[655].type == "Word[4]" and REGISTERS[655].format == "DT_DateTime"
    assert REGISTERS[64].words == 6 and REGISTERS[64].format == "DT_CommercialReference"


@pytest.mark.parametrize(
    "reg, scale, unit",
    [
        (474, 0.01, "Hz"),
        (160, 0.1, "Hz"),
        (481, 0.01, ""),
        (482, 0.1, "kW"),
        (483, 0.1, "kVAR"),
        (500, 0.01, "A"),
        (501, 0.01, "A"),
        (508, 1, "mA"),
        (470, 0.1, "% FLC min"),
        (96, 0.1, "A"),
        (81, 0.1, "A"),
        (652, 1, "% FLCmax"),
        (465, 1, "% trip level"),
        (472, 1, "°C"),
        (511, 1, "s"),
        (171, 0.1, "kWh"),  # "Active power n-0 (x 0.1 kWh)": kept as printed (A19)
    ],
)
def test_scale_and_unit_as_printed(reg, scale, unit):
    assert (REGISTERS[reg].scale, REGISTERS[reg].unit) == (scale, unit)


def test_scaled_values_of_digest_7_2():
    assert ltmr.scaled_value(474, 5000) == pytest.approx(50.00)  # Hz
    assert ltmr.scaled_value(160, 500) == pytest.approx(50.0)  # trip statistics x 0.1 Hz
    assert ltmr.scaled_value(472, 0xFFF6) == -10  # Int, °C
    assert ltmr.scaled_value(481, 85) == pytest.approx(0.85)
    assert ltmr.scaled_value(482, 75) == pytest.approx(7.5)
    assert ltmr.scaled_value(470, 125) == pytest.approx(12.5)
    assert ltmr.scaled_value(96, 80) == pytest.approx(8.0)


def test_trip_history_bases():
    assert [ltmr.trip_history_base(k) for k in range(5)] == [(150, 300), (180, 330), (210, 360), (240, 390), (270, 420)]
    with pytest.raises(ValueError):
        ltmr.trip_history_base(5)
    for k in range(5):
        main, extension = ltmr.trip_history_base(k)
        assert REGISTERS[main].name == f"Trip code n-{k}" and REGISTERS[main].format == "DT_FaultCode"
        assert REGISTERS[extension].name == f"Average current n-{k}" and REGISTERS[extension].type == "UDInt"
        assert REGISTERS[main + 12].format == "DT_DateTime"


def test_register_constants_name_the_right_registers():
    expected = {
        ltmr.REG_FLC_MAX: "Full load current max",
        ltmr.REG_TRIP_CODE: "Trip code",
        ltmr.REG_TRIP_REGISTER_1: "Trip register 1",
        ltmr.REG_STATUS_1: "System status register 1",
        ltmr.REG_STATUS_2: "System status register 2",
        ltmr.REG_IO_STATUS: "I/O status",
        ltmr.REG_ALARM_CODE: "Alarm code",
        ltmr.REG_THERMAL_CAPACITY: "Thermal capacity level",
        ltmr.REG_FREQUENCY: "Frequency",
        ltmr.REG_AVERAGE_CURRENT: "Average current",
        ltmr.REG_L3_CURRENT: "L3 current",
        ltmr.REG_TIME_TO_TRIP: "Time to trip",
        ltmr.REG_OPERATING_MODE: "Motor operating mode",
        ltmr.REG_TRIP_CLASS: "Motor trip class",
        ltmr.REG_TRIP_ENABLE_1: "Trip enable register 1",
        ltmr.REG_ALARM_ENABLE_1: "Alarm enable register 1",
        ltmr.REG_HMI_FALLBACK: "HMI port fallback setting",
        ltmr.REG_FLC1: "Motor full load current ratio, FLC1",
        ltmr.REG_DATE_TIME: "Date and time setting",
        ltmr.REG_NETWORK_FALLBACK: "Network port fallback setting",
        ltmr.REG_CONTROL_SETTING: "Control setting register",
        ltmr.REG_BAUD_RATE: "Network port baud rate setting",
        ltmr.REG_NODE_ADDRESS: "Network port address setting",
        ltmr.REG_CONTROL_1: "Control register 1",
        ltmr.REG_CONTROL_2: "Control register 2",
        ltmr.REG_NETWORK_PORT_STATUS: "Network port status",
    }
    for reg, name in expected.items():
        assert REGISTERS[reg].name == name


def test_register_labels_are_unique_ascii():
    labels = [ltmr.register_label(r) for r in REGISTERS]
    assert len(set(labels)) == len(labels)
    assert all(label.isascii() for label in labels)
    assert ltmr.register_label(455) == "System status register 1 [455]"
