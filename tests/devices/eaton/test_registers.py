"""Eaton PowerXL DA1/DB1/DC1/DE1 device knowledge against the manual's own
numbers (manual 002, shared/manuals/002_a23ab2a6587941cb.txt; "L<n>" is a
line of that file; digest shared/digests/002_eaton_modbus.md).

Every expected value below is copied from the manual (or, where a test says
so, from the digest's derived examples); none is computed by the code under
test. The telegrams are the manual's worked examples M1-M4 (digest §5.1):
their register address and data are checked here, their CRC belongs to the
Modbus layer.
"""
from __future__ import annotations

import pytest

from softplc.runtime.devices.eaton import faults as eaton_faults
from softplc.runtime.devices.eaton import parameters as eaton_parameters
from softplc.runtime.devices.eaton import registers as eaton
from softplc.runtime.devices.eaton import settings as eaton_settings
from softplc.runtime.devices.eaton.registers import ControlWord, Family, StatusWord
from softplc.runtime.devices.eaton.settings import COMM_TIMEOUT_CODES, CommLossReaction, Da1CommLossAction

DA1, DB1, DC1, DE1 = Family.DA1, Family.DB1, Family.DC1, Family.DE1


def telegram(text: str) -> bytes:
    return bytes.fromhex(text.replace(" ", ""))


def word(frame: bytes, offset: int) -> int:
    return frame[offset] << 8 | frame[offset + 1]


# ---------------------------------------------------------------------------
# ID 17 device identification (§2.6.5.10, L1086-1096)
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("value, family, model", [
    (5632, DA1, "DA1"),     # L1088
    (8198, DB1, "DB1"),     # L1090
    (10, DC1, "DC1"),       # L1092
    (8, DE1, "DE1"),        # L1094
    (9, DE1, "DE11"),       # L1096: the DE1 variant with CANopen and relay
])
def test_id17_values_of_the_manual_name_the_family(value, family, model):
    assert eaton.family_from_id17(value) is family
    assert eaton.model_from_id17(value) == model


@pytest.mark.parametrize("value", [0, 1, 11, 5633, 8197, 0x1600 + 0x100, 0xFFFF])
def test_unknown_id17_value_is_an_error(value):
    with pytest.raises(ValueError, match=f"ID 17 value {value} is not an Eaton"):
        eaton.family_from_id17(value)
    with pytest.raises(ValueError):
        eaton.model_from_id17(value)


def test_id17_is_a_read_register_of_every_family():
    assert eaton.REG_DEVICE_ID == 17     # L829
    for family in Family:
        assert 17 in eaton.process_registers(family, writes=False)


# ---------------------------------------------------------------------------
# Register addressing (§2.6.6: "Offset von +1") and the worked telegrams
# ---------------------------------------------------------------------------

def test_register_numbers_travel_minus_one():
    assert eaton.wire_address(6) == 0x0005      # L1125: "0005 ... Die ID ist 6"
    assert eaton.wire_address(1) == 0x0000      # L1151: "0000 ... Die ID ... ist 1"
    assert eaton.register_number(0x0005) == 6
    assert eaton.register_number(0x0000) == 1
    assert eaton.wire_address(101) == 0x0064    # P1-01, register 101 (L1287)


@pytest.mark.parametrize("register", [0, -1, 0x10001])
def test_register_numbers_start_at_one(register):
    with pytest.raises(ValueError):
        eaton.wire_address(register)


@pytest.mark.parametrize("address", [-1, 0x10000])
def test_wire_addresses_are_16_bit(address):
    with pytest.raises(ValueError):
        eaton.register_number(address)


def test_m1_read_status_word_request():
    """M1: read the status and fault word (ID 6) of a DA1 at slave address 1 (L1120-1127)."""
    frame = telegram("01 03 0005 0001 940B")
    assert frame[0] == 1 and frame[0] in eaton.UNIT_ADDRESSES
    assert frame[1] == 3 and eaton.FUNCTION_CODES[3] == "Read Holding Registers"
    assert eaton.register_number(word(frame, 2)) == eaton.REG_STATUS_WORD == 6
    count = word(frame, 4)
    assert count == 1 and count <= eaton.MAX_REGISTERS_PER_READ
    assert eaton.REG_STATUS_WORD in eaton.process_registers(DA1, writes=False)


def test_m2_read_status_word_response():
    """M2: the slave answers two data bytes, register 6 = 0 (L1129-1136)."""
    frame = telegram("01 03 02 0000 B844")
    assert frame[2] == 2                      # "1 Register = 2 Byte"
    value = word(frame, 3)
    assert value == 0
    assert eaton.status_flags(value) == StatusWord(0)
    assert StatusWord.READY not in eaton.status_flags(value)
    assert eaton.fault_number(value) == eaton_faults.FAULT_NONE
    assert eaton_faults.fault_text(eaton.fault_number(value)) == "No fault"


@pytest.mark.parametrize("text", [
    "01 06 0000 0001 480A",     # M3, master request (L1146)
    "01 06 0000 0001 480A",     # M4, the response "ist eine Kopie der Master-Anfrage" (L1157; printed "480", A14)
])
def test_m3_m4_write_control_word_run(text):
    """Write the control word (ID 1) of a DA1 at slave address 1: RUN (L1146-1164)."""
    frame = telegram(text)
    assert frame[0] == 1
    assert frame[1] == 6 and eaton.FUNCTION_CODES[6] == "Write Single Register"
    assert eaton.register_number(word(frame, 2)) == eaton.REG_CONTROL_WORD == 1
    assert eaton.REG_CONTROL_WORD in eaton.process_registers(DA1, writes=True)
    value = word(frame, 4)
    assert value == 0b0000_0000_0000_0001     # "0000 0000 0000 001 bin -> RUN" (15 digits printed, A14)
    assert ControlWord(value) == ControlWord.RUN
    assert ControlWord.REVERSE not in ControlWord(value)    # bit 1 = 0: forward


def test_function_codes_and_limits():
    assert set(eaton.FUNCTION_CODES) == {3, 6, 16, 23}      # L667-670, decimal (A10)
    assert eaton.MAX_REGISTERS_PER_READ == 11               # L667
    assert eaton.BROADCAST_ADDRESS == 0                     # L658
    assert (eaton.UNIT_ADDRESSES.start, eaton.UNIT_ADDRESSES.stop - 1) == (1, 63)     # L657


# ---------------------------------------------------------------------------
# Process data (§2.6.3 - §2.6.5)
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("family, writes, parameters", [
    (DA1, (1, 2, 3, 4), (101, 941)),     # L718-720
    (DB1, (1, 2, 4), (129, 197)),        # L725-727
    (DC1, (1, 2, 4), (129, 197)),
    (DE1, (1, 2), (129, 169)),           # L732-734
])
def test_register_groups_per_family(family, writes, parameters):
    groups = eaton.REGISTER_GROUPS[family]
    assert groups.writes == writes
    assert groups.parameters == parameters
    assert eaton.process_registers(family, writes=True) == writes


def test_read_ranges_per_family():
    assert eaton.REGISTER_GROUPS[DA1].reads == (6, 43)      # L721
    assert eaton.REGISTER_GROUPS[DB1].reads == (6, 24)      # L728
    assert eaton.REGISTER_GROUPS[DE1].reads == (6, 24)      # L735


def test_process_register_numbers():
    assert (eaton.REG_CONTROL_WORD, eaton.REG_SPEED_SETPOINT, eaton.REG_TORQUE_SETPOINT,
            eaton.REG_RAMP_TIME) == (1, 2, 3, 4)                                       # L755-758
    assert (eaton.REG_STATUS_WORD, eaton.REG_ACTUAL_SPEED, eaton.REG_MOTOR_CURRENT, eaton.REG_TORQUE,
            eaton.REG_OUTPUT_POWER, eaton.REG_DI_STATUS) == (6, 7, 8, 9, 10, 11)       # L818-823


def test_torque_setpoint_is_da1_only_and_ramp_time_not_de1():
    assert eaton.PROCESS_DATA[3].families == {DA1}                  # L757 "nur DA1"
    assert eaton.PROCESS_DATA[4].families == {DA1, DB1, DC1}        # L758 "nur DA1, DB1, DC1"
    assert DE1 not in eaton.PROCESS_DATA[9].families                # L821
    assert DE1 not in eaton.PROCESS_DATA[10].families               # L822


def test_current_is_sent_without_the_decimal_point():
    assert eaton.CURRENT.to_value(3) == 0.3          # L744: 0,3 A on the display, 003 dez on Modbus
    assert eaton.CURRENT.to_raw(0.3) == 3
    assert eaton.CURRENT.to_value(34) == 3.4         # L936: 34 ≙ 3,4 A
    assert eaton.PROCESS_DATA[8].scale.unit == "A"


def test_torque_and_power_examples():
    assert eaton.PROCESS_DATA[9].scale.to_value(1000) == 100.0       # L942: 1000 ≙ 100,0 %
    assert eaton.PROCESS_DATA[10].scale.to_value(53) == 5.3          # L948: 53 ≙ 5,3 kW (A17)
    assert eaton.PROCESS_DATA[10].scale.unit == "kW"


def test_torque_setpoint_and_ramp_time_examples_and_limits():
    torque = eaton.PROCESS_DATA[eaton.REG_TORQUE_SETPOINT]
    assert torque.scale.to_raw(100) == 1000            # L801: 1000 ≙ 100 %
    assert torque.limits == (0, 2000)                  # L799
    ramp = eaton.PROCESS_DATA[eaton.REG_RAMP_TIME]
    assert ramp.scale.to_raw(3) == 300                 # L807: 300 ≙ 3 s
    assert ramp.scale.to_value(300) == 3.0
    assert ramp.limits == (0, 60000)                   # L805


def test_speed_counts_in_tenths_of_hertz():
    assert eaton.PROCESS_DATA[2].scale.to_value(500) == 50.0     # factor 0,1 (L792)
    assert eaton.PROCESS_DATA[7].scale.to_value(500) == 50.0     # factor 0,1 (L927)
    assert eaton.speed_setpoint_raw(50.0) == 500
    assert eaton.speed_setpoint_raw(0.05) == 1                   # halves round away from zero


def test_negative_speed_setpoint_is_refused():
    with pytest.raises(ValueError, match="REVERSE"):
        eaton.speed_setpoint_raw(-10.0)


def test_serial_number_registers():
    assert eaton.SERIAL_NUMBER_REGISTERS[DA1] == (25, 26, 27, 28)    # L1100
    assert eaton.SERIAL_NUMBER_REGISTERS[DB1] == (29, 30, 31, 32)    # L1102
    assert eaton.SERIAL_NUMBER_REGISTERS[DC1] == (29, 30, 31, 32)
    assert eaton.SERIAL_NUMBER_REGISTERS[DE1] == ()                  # L1104: none on the DE1


# ---------------------------------------------------------------------------
# Control word (ID 1) and status word (ID 6)
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("flag, value", [
    (ControlWord.RUN, 0x01),                # bit 0 Betrieb (L766)
    (ControlWord.REVERSE, 0x02),            # bit 1 Linksdrehfeld (L767)
    (ControlWord.FAULT_RESET, 0x04),        # bit 2 Fehler zurücksetzen (L768)
    (ControlWord.COAST, 0x08),              # bit 3 Freier Auslauf (L769)
    (ControlWord.QUICK_STOP, 0x20),         # bit 5 Schnellstopp (Rampe 2) (L771)
    (ControlWord.FIXED_FREQUENCY_1, 0x40),  # bit 6 Festfrequenz FF1 (L772)
    (ControlWord.ZERO_SETPOINT, 0x80),      # bit 7 Sollwert mit 0 überschreiben (L773)
])
def test_control_word_bits(flag, value):
    assert flag == value


def test_control_word_unused_bits():
    used = 0
    for flag in ControlWord:
        used |= flag
    assert used & 0x10 == 0                               # bit 4 "nicht verwendet" (L770)
    assert used & 0xFF00 == 0                             # bits 8-15 (L774-781)
    assert eaton.CONTROL_WORD_UNUSED_BITS == 0xFF10
    assert ControlWord.RUN | ControlWord.REVERSE == 0x0003     # run reverse


@pytest.mark.parametrize("flag, value", [
    (StatusWord.READY, 0x01),               # bit 0 Startbereit (L843)
    (StatusWord.RUNNING, 0x02),             # bit 1 Betrieb Laufmeldung (L844)
    (StatusWord.REVERSE, 0x04),             # bit 2 Linksdrehfeld (L845)
    (StatusWord.FAULT, 0x08),               # bit 3 Fehler erkannt (L846)
    (StatusWord.AT_SETPOINT, 0x10),         # bit 4 Frequenz-Istwert gleich Sollwertvorgabe (L847)
    (StatusWord.ZERO_SPEED, 0x20),          # bit 5 "Nullzahl" (L848, A21)
    (StatusWord.SPEED_CONTROL_ACTIVE, 0x40),    # bit 6 Drehzahlsteuerung aktiviert (L849)
    (StatusWord.HARDWARE_ENABLE, 0x80),     # bit 7 STO status / Hardware-Freigabe (L850)
])
def test_status_word_bits(flag, value):
    assert flag == value


def test_fault_number_is_the_high_byte_of_the_status_word():
    """Status bits 0-7, fault word bits 8-15 (L833); 50 = 0x32 is the Modbus timeout (L906)."""
    word_ = 0x3208
    assert eaton.fault_number(word_) == 50
    assert eaton.status_flags(word_) == StatusWord.FAULT
    assert eaton.status_word(StatusWord.FAULT, 50) == 0x3208
    assert eaton.status_word(StatusWord.READY | StatusWord.RUNNING) == 0x0003


def test_status_word_refuses_what_does_not_fit():
    with pytest.raises(ValueError):
        eaton.status_word(0, 256)
    with pytest.raises(ValueError):
        eaton.status_word(0x100)


# ---------------------------------------------------------------------------
# Faults (Tabelle 11, L854-916)
# ---------------------------------------------------------------------------

MANUAL_FAULT_NUMBERS = (0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20,
                        21, 22, 23, 24, 25, 26, 29, 30, 31, 32, 33, 34, 35, 40, 41, 42, 43, 44, 49,
                        50, 51, 52, 53, 60, 61, 70, 71, 72, 73, 74)


def test_fault_numbers_are_those_of_the_table():
    assert tuple(sorted(eaton_faults.FAULTS)) == MANUAL_FAULT_NUMBERS


@pytest.mark.parametrize("code, words, display", [
    (0, "No fault", "no-Flt"),                      # L859
    (3, "Overcurrent", "O-I"),                      # L862
    (6, "overvoltage", "O-Volt"),                   # L865
    (7, "undervoltage", "U-Volt"),                  # L866
    (14, "supply phase", "P-LOSS"),                 # L873
    (50, "Modbus telegram", "SC-F01"),              # L906
    (51, "CANopen telegram", "SC-F02"),             # L907
    (74, "table overflow", "PLC-05"),               # L916
])
def test_fault_texts(code, words, display):
    assert words.lower() in eaton_faults.fault_text(code).lower()
    assert eaton_faults.fault_display(code) == display


@pytest.mark.parametrize("code", [27, 28, 36, 45, 54, 62, 75, 255])
def test_numbers_missing_from_the_table_are_unknown(code):
    assert eaton_faults.fault_text(code) == f"unknown fault number {code}"
    assert eaton_faults.fault_display(code) == ""


def test_fault_families_as_printed():
    assert eaton_faults.FAULTS[1].families == {DA1, DB1, DC1, DE1}      # L860
    assert eaton_faults.FAULTS[19].families == {DA1, DB1, DC1}          # L878
    assert eaton_faults.FAULTS[24].families == {DA1}                    # L890
    assert eaton_faults.FAULTS[50].families == {DA1, DB1, DC1}          # L906 (no DE1, A20)
    assert DC1 in eaton_faults.FAULTS[15].families                      # L874 names DC1 in its text (A20)


def test_comm_loss_fault_is_the_modbus_timeout():
    assert eaton_faults.COMM_LOSS_FAULT == 50
    assert "Modbus" in eaton_faults.fault_text(eaton_faults.COMM_LOSS_FAULT)


# ---------------------------------------------------------------------------
# Parameter numbers -> registers (Tabellen 20-24)
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("number, register", [
    ("P1-01", 101),     # L1287
    ("P1-12", 112),     # L1298
    ("P1-14", 114),     # L1300
    ("P2-25", 225),     # L1332
    ("P2-40", 240),     # L1347
    ("P3-18", 318),     # L1370
    ("P4-13", 413),     # L1383
    ("P5-05", 505),     # L1395
    ("P5-17", 517),     # L1407
    ("P6-30", 630),     # L1442
    ("P7-17", 717),     # L1459
    ("P8-13", 813),     # L1479
    ("P9-41", 941),     # L1525
])
def test_da1_parameter_registers(number, register):
    assert eaton_parameters.parameter_register(DA1, number) == register
    group, index = int(number[1]), int(number[3:])
    assert eaton_parameters.da1_parameter_register(group, index) == register


@pytest.mark.parametrize("number", ["P1-15", "P2-41", "P3-19", "P4-14", "P5-18", "P6-31", "P7-18",
                                    "P8-14", "P9-42", "P1-00"])
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
    assert len(rows) == 203     # P1-01..P1-14, P2 40, P3 18, P4 13, P5 17, P6 30, P7 17, P8 13, P9 41
    for row in rows:
        group, index = int(row.number[1]), int(row.number[3:])
        assert row.register == group * 100 + index, row
    registers = [row.register for row in rows]
    assert (min(registers), max(registers)) == eaton.REGISTER_GROUPS[DA1].parameters     # "101 - 941", L719


@pytest.mark.parametrize("family, number, register", [
    (DB1, "P-01", 129),     # L1631
    (DB1, "P-12", 140),     # L1647
    (DB1, "P-36", 164),     # L1672
    (DB1, "P-56", 184),     # L1700
    (DB1, "P-68", 196),     # L1709
    (DC1, "P-01", 129),     # L1780
    (DC1, "P-53", 181),     # L1848
    (DC1, "P-56", 184),
    (DC1, "P-70", 198),     # L1870
    (DE1, "P-12", 140),     # L1921
    (DE1, "P-34", 162),     # L1943
    (DE1, "P-35", 163),     # L1944
    (DE1, "P-36", 164),     # L1945
    (DE1, "P-40", 168),     # L1949
    (DE1, "P-47", 175),     # L1956
    (DE1, "P-48", 176),     # L1957
])
def test_compact_parameter_registers(family, number, register):
    assert eaton_parameters.parameter_register(family, number) == register
    assert eaton_parameters.compact_parameter_register(family, int(number[2:])) == register


@pytest.mark.parametrize("family, number", [
    (DB1, "P-52"), (DB1, "P-53"), (DB1, "P-57"), (DB1, "P-58"), (DB1, "P-69"), (DB1, "P-70"),
    (DB1, "P-59"), (DC1, "P-59"), (DC1, "P-71"), (DE1, "P-49"), (DE1, "P-50"), (DE1, "P-57"),
    (DE1, "P-00"),
])
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


@pytest.mark.parametrize("number, register", [
    ("P-50", 178),      # L1968
    ("P-54", 182),      # L1972
    ("P-57", 183),      # L1973: not 185 (A16)
    ("P-58", 184),      # L1974: not 186 (A16)
])
def test_de11_parameters(number, register):
    assert eaton_parameters.parameter_register(DE1, number, de11=True) == register


def test_de11_keeps_the_de1_parameters():
    assert eaton_parameters.parameter_register(DE1, "P-48", de11=True) == 176


@pytest.mark.parametrize("family", [DB1, DC1, DE1])
def test_every_compact_table_row_is_128_plus_n(family):
    for row in eaton_parameters.PARAMETERS[family]:
        assert row.register == 128 + int(row.number[2:]), row


def test_de11_rows_are_128_plus_n_but_for_p57_p58():
    off_rule = {row.number: row.register for row in eaton_parameters.DE11_PARAMETERS
                if row.register != 128 + int(row.number[2:])}
    assert off_rule == {"P-57": 183, "P-58": 184}


def test_table_sizes():
    assert len(eaton_parameters.PARAMETERS[DB1]) == 67     # P-01..P-68 without 52, 53, 57-59; 3 shared registers
    assert len(eaton_parameters.PARAMETERS[DC1]) == 73     # + P-52, P-53, P-57, P-58, P-69, P-70
    assert len(eaton_parameters.PARAMETERS[DE1]) == 48     # P-01..P-48
    assert len(eaton_parameters.DE11_PARAMETERS) == 7


# ---------------------------------------------------------------------------
# Parameter access and scaling (digest §3.13, M14)
# ---------------------------------------------------------------------------

def rows(family, number, **kw):
    return eaton_parameters.parameter_rows(family, number, **kw)


@pytest.mark.parametrize("family, number, raw, value, unit", [
    (DA1, "P1-01", 3000, 50.0, "Hz"),       # L1287 "3000 ≙ 50.0 Hz"
    (DA1, "P1-03", 300, 30.0, "s"),         # L1289 "300 ≙ 30.0 s"
    (DA1, "P1-07", 230, 230, "V"),          # L1293
    (DA1, "P1-08", 1, 0.1, "A"),            # L1294 "1 ≙ 0.1 A"
    (DA1, "P1-09", 500, 50, "Hz"),          # L1295 "500 ≙ 50 Hz"
    (DA1, "P1-10", 1500, 1500, "rpm"),      # L1296
    (DA1, "P4-05", 99, 0.99, ""),           # L1375
    (DA1, "P4-07", 2000, 200.0, "%"),       # L1377
    (DA1, "P5-05", 50, 5.0, "s"),           # L1395 "1 ≙ 0.1 s", range 0.0 - 5.0
    (DA1, "P6-20", 1, 0.01, "kW"),          # L1432
    (DB1, "P-03", 300, 3.0, "s"),           # L1633 "300 ≙ 3.00 s"
    (DB1, "P-08", 100, 10.0, "A"),          # L1638 "100 ≙ 10.0 A"
    (DB1, "P-09", 50, 50, "Hz"),            # L1639 "50 ≙ 50 Hz"
    (DC1, "P-20", 3000, 50.0, "Hz"),        # L1804
    (DE1, "P-26", 100, 10.0, "s"),          # L1935 "100 ≙ 10.0 s"
])
def test_parameter_scales(family, number, raw, value, unit):
    scale = rows(family, number)[0].scale
    assert scale.to_value(raw) == value
    assert scale.to_raw(value) == raw
    assert scale.unit == unit


def test_packed_field_scales():
    t_dc_brake, dc_brake = rows(DC1, "P-32")
    assert t_dc_brake.scale.to_value(30) == 3.0                     # L1816 "30 ≙ 3.0 s"
    display_scaling, source = rows(DB1, "P-40")
    assert display_scaling.scale.to_value(10000) == 10.0            # L1685 "10000 ≙ 10.000"


@pytest.mark.parametrize("family, number", [
    (DA1, "P2-25"),     # frame-size dependent (L1332)
    (DA1, "P8-01"),     # L1467
    (DA1, "P1-11"),     # "-1 ≙ Auto 0 ≙ Disabled 1 ≙ 0.1 %" (L1297)
    (DA1, "P5-02"),     # codes "0 ≙ 125 kbps 1 ≙ 250 kbps" (L1392)
    (DA1, "P5-04"),     # codes "0 ≙ N-1 1 ≙ N-2" (L1394)
    (DA1, "P1-05"),     # no scaling printed (L1291)
])
def test_cells_that_are_not_one_linear_scale(family, number):
    assert rows(family, number)[0].scale is None


def test_da1_ramp_scale_depends_on_the_frame_size():
    assert eaton.da1_ramp_scale(2).to_value(300) == 3.0      # FS2, FS3: 1 ≙ 0.01 s (L1332)
    assert eaton.da1_ramp_scale(3).to_value(300) == 3.0
    assert eaton.da1_ramp_scale(4).to_value(300) == 30.0     # FS4 ... FS7: 1 ≙ 0.1 s
    assert eaton.da1_ramp_scale(7).to_value(300) == 30.0
    with pytest.raises(ValueError):
        eaton.da1_ramp_scale(1)


def test_process_data_and_parameters_count_hertz_differently():
    """50 Hz is 500 as a speed setpoint (ID 2, 0.1 Hz) and 3000 in a frequency parameter."""
    assert eaton.SPEED.to_raw(50.0) == 500                       # L792
    assert eaton.PARAMETER_FREQUENCY.to_raw(50.0) == 3000        # L1287
    assert eaton.frequency_parameter_to_speed_raw(3000) == 500
    assert eaton_settings.DE1_FIXED_FREQUENCIES["FF1"][3] == 20.0
    assert eaton.PARAMETER_FREQUENCY.to_raw(20.0) == 1200


@pytest.mark.parametrize("family, number, mode", [
    (DA1, "P1-01", eaton_parameters.RUN),      # L1287
    (DA1, "P1-12", eaton_parameters.STOP),     # L1298
    (DA1, "P4-01", eaton_parameters.STOP),     # L1371
    (DB1, "P-01", eaton_parameters.RUN),       # L1631
    (DB1, "P-12", eaton_parameters.STOP),      # L1647
    (DE1, "P-01", eaton_parameters.STOP),      # L1905 (A33)
    (DE1, "P-13", eaton_parameters.RO),        # L1922
    (DA1, "P3-14", eaton_parameters.RESERVED),     # L1366
    (DA1, "P9-32", eaton_parameters.RESERVED),     # L1516
])
def test_parameter_modes(family, number, mode):
    row = rows(family, number)[0]
    assert row.mode == mode
    assert row.writable == (mode in (eaton_parameters.RUN, eaton_parameters.STOP))
    assert row.writable_in_run == (mode == eaton_parameters.RUN)


def test_signed_parameters():
    assert rows(DA1, "P2-29")[0].format == eaton_parameters.S16             # L1336, -500.0 .. +500.0 %
    assert eaton.to_signed16(0xFFFF) == -1
    assert eaton.from_signed16(-5000) == 0xEC78                  # P2-35 lower limit -5000 (L1342)
    assert eaton.to_signed16(0xEC78) == -5000
    with pytest.raises(ValueError):
        eaton.from_signed16(40000)


# ---------------------------------------------------------------------------
# Shared registers: DB1/DC1 P-36 = register 164 (Tabellen 21/22)
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("family", [DB1, DC1])
def test_register_164_fields(family):
    address, baud, timeout = rows(family, "P-36")
    assert (address.register, address.bits) == (164, (0, 7))       # "164 (Low Byte)" L1672
    assert (baud.register, baud.bits) == (164, (8, 11))             # "164 (Bit 8 - Bit 11)" L1673
    assert (timeout.register, timeout.bits) == (164, (12, 15))      # "164 (Bit 12 - Bit 15)" L1681


def test_register_164_read_modify_write():
    """Derived example of digest §1.4: address 1, 115.2 kBit/s (code 6), r 3000 ms (code 8) -> 0x8601."""
    address, baud, timeout = rows(DC1, "P-36")
    word_ = address.insert(0, 1)
    word_ = baud.insert(word_, 6)
    word_ = timeout.insert(word_, 8)
    assert word_ == 0x8601
    assert (address.extract(word_), baud.extract(word_), timeout.extract(word_)) == (1, 6, 8)
    assert timeout.insert(word_, 4) == 0x4601       # the other fields stay
    with pytest.raises(ValueError):
        timeout.insert(word_, 16)


def test_register_160_and_168_fields():
    low, high = rows(DB1, "P-32")
    assert (low.bits, high.bits) == ((0, 7), (8, 15))               # L1667-1668
    scaling, source = rows(DB1, "P-40")
    assert (scaling.bits, source.bits) == ((0, 13), (14, 15))       # L1685-1686
    assert source.extract(0xC000) == 3 and scaling.extract(0xC000) == 0


def test_de1_p36_is_a_whole_register():
    (row,) = rows(DE1, "P-36")
    assert row.bits is None and row.extract(0x0008) == 8


# ---------------------------------------------------------------------------
# P0 display values with registers (digest §3.8)
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("family, number, registers", [
    (DA1, "P0-01", (20,)),                  # L1182
    (DA1, "P0-03", (11,)),                  # L1184
    (DA1, "P0-12", (9,)),                   # L1193
    (DA1, "P0-20", (23,)),                  # L1201
    (DA1, "P0-28", (15, 16)),               # L1209-1210
    (DA1, "P0-30", (25, 26, 27, 28)),       # L1221
    (DB1, "P0-03", (2,)),                   # L1570
    (DB1, "P0-10", (25, 26)),               # L1577-1578
    (DC1, "P0-30", (29, 30, 31, 32)),       # L1749-1759
    (DE1, "P0-09", (24,)),                  # L1890
])
def test_monitor_registers(family, number, registers):
    assert eaton.monitor_registers(family, number) == registers


@pytest.mark.parametrize("family, number", [
    (DA1, "P0-07"),     # no register printed (L1188)
    (DA1, "P0-35"),     # printed at 20, a copy of P0-01 (A26)
    (DE1, "P0-04"),     # L1885
])
def test_monitor_values_without_register(family, number):
    with pytest.raises(ValueError, match="has no Modbus register"):
        eaton.monitor_registers(family, number)


@pytest.mark.parametrize("family, register, raw, value", [
    (DA1, 20, 4096, 100.0),     # "4096 ≙ 100.0 %" (L1182)
    (DA1, 23, 600, 600),        # "600 ≙ 600 V" (L1201)
    (DA1, 24, 40, 40),          # "40 ≙ 40 °C" (L1202)
    (DA1, 30, 100, 10.0),       # "100 ≙ 10.0 kWh" (L1207)
    (DB1, 23, 230, 230),        # "230 ≙ 230 V" (L1575)
    (DE1, 26, 300, 3.0),        # "300 ≙ 3.00 s" (L1892)
])
def test_monitor_scales(family, register, raw, value):
    (monitor,) = [m for m in eaton.MONITOR_VALUES[family] if m.register == register]
    assert monitor.scale.to_value(raw) == value


def test_da1_user_registers():
    assert eaton.DA1_USER_REGISTERS[51] == "UserRegister 1"      # L1533
    assert eaton.DA1_USER_REGISTERS[65] == "UserRegister 15"     # L1547
    assert 68 not in eaton.DA1_USER_REGISTERS and 69 not in eaton.DA1_USER_REGISTERS
    assert max(eaton.DA1_USER_REGISTERS) == 78                   # L1558


# ---------------------------------------------------------------------------
# Serial settings and communication loss
# ---------------------------------------------------------------------------

def test_data_format_codes():
    assert eaton_settings.DATA_FORMATS[0] == ("N", 1)    # N-1 (L379)
    assert eaton_settings.DATA_FORMATS[1] == ("N", 2)    # N-2
    assert eaton_settings.DATA_FORMATS[2] == ("O", 1)    # O-1
    assert eaton_settings.DATA_FORMATS[3] == ("E", 1)    # E-1


@pytest.mark.parametrize("family, code, baud", [
    (DA1, 0, 9600), (DA1, 4, 115200),           # P5-03 (L378)
    (DB1, 2, 9600), (DB1, 6, 115200),           # P-36 (L399)
    (DC1, 2, 9600), (DC1, 4, 38400),            # L422
    (DE1, 0, 9600), (DE1, 3, 57600),            # P-35, 0 printed "960 Bit/s" (L437, A6)
])
def test_baud_rate_codes(family, code, baud):
    assert eaton_settings.SERIAL_SETTINGS[family].baud_codes[code] == baud


def test_db1_dc1_baud_codes_start_at_2():
    assert set(eaton_settings.SERIAL_SETTINGS[DB1].baud_codes) == {2, 3, 4, 5, 6}     # L399 (A4)


@pytest.mark.parametrize("family, address, baud, data_format, baud_factory, format_factory", [
    (DA1, "P5-01", "P5-03", "P5-04", 4, 0),     # L377-379: WE 4, "n-1"
    (DB1, "P-36", "P-36", "P-56", 2, None),     # L398-401: WE 2, format blank (A5)
    (DC1, "P-36", "P-36", "P-56", 2, 2),        # L421-424
    (DE1, "P-47", "P-35", "P-48", 4, 1),        # L437, L446-447 (A1, A5)
])
def test_serial_settings(family, address, baud, data_format, baud_factory, format_factory):
    settings = eaton_settings.SERIAL_SETTINGS[family]
    assert (settings.address, settings.baud_rate, settings.data_format) == (address, baud, data_format)
    assert (settings.baud_factory, settings.data_format_factory) == (baud_factory, format_factory)
    eaton_parameters.parameter_register(family, settings.address)      # every one is in its table


def test_address_registers():
    assert eaton_parameters.parameter_register(DA1, eaton_settings.SERIAL_SETTINGS[DA1].address) == 501     # L377
    assert eaton_parameters.parameter_register(DE1, eaton_settings.SERIAL_SETTINGS[DE1].address) == 175     # L446
    assert eaton_parameters.parameter_register(DE1, eaton_settings.DE1_PDP_ADDRESS) == 162                  # L1943


def test_da1_comm_loss_parameters():
    assert eaton_parameters.parameter_register(DA1, eaton_settings.DA1_COMM_TIMEOUT) == 505         # L387
    assert eaton_parameters.parameter_register(DA1, eaton_settings.DA1_COMM_LOSS_ACTION) == 506     # L388
    assert eaton_settings.DA1_COMM_TIMEOUT_SCALE.to_value(
        eaton_settings.DA1_COMM_TIMEOUT_MAX) == 5.0                                     # "0.0 - 5.0" (L1395)
    assert eaton_settings.DA1_COMM_TIMEOUT_SCALE.to_value(
        eaton_settings.DA1_COMM_TIMEOUT_FACTORY) == 2.0                                 # WE "2" (A7)
    assert eaton_settings.DA1_COMM_LOSS_ACTION_FACTORY == 0                              # WE 0 (L388)


@pytest.mark.parametrize("value, name", [
    (0, "TRIP"),                    # "Abschalten"
    (1, "RAMP_STOP_THEN_TRIP"),     # "Fährt mit Rampe zum Stillstand und schaltet dann ab"
    (2, "RAMP_STOP_NO_FAULT"),      # "... keine Fehlermeldung"
    (3, "FIXED_FREQUENCY_8"),       # "Fährt auf Festfrequenz 8 (P2-08)"
])
def test_da1_comm_loss_actions(value, name):
    assert Da1CommLossAction(value).name == name        # L388
    assert eaton_parameters.parameter_register(DA1, "P2-08") == 208


@pytest.mark.parametrize("code, timeout_ms, reaction", [
    (0, None, CommLossReaction.NONE),           # "keine Reaktion"
    (1, 30, CommLossReaction.TRIP),             # "t 30 ms"
    (2, 100, CommLossReaction.TRIP),
    (3, 1000, CommLossReaction.TRIP),
    (4, 3000, CommLossReaction.TRIP),           # "t 3000 ms"
    (5, 30, CommLossReaction.RAMP_TO_ZERO),     # "r 30 ms"
    (6, 100, CommLossReaction.RAMP_TO_ZERO),
    (7, 1000, CommLossReaction.RAMP_TO_ZERO),
    (8, 3000, CommLossReaction.RAMP_TO_ZERO),   # "r 3000 ms"
])
def test_comm_timeout_codes(code, timeout_ms, reaction):
    assert COMM_TIMEOUT_CODES[code] == (timeout_ms, reaction)      # L400, L423, L445


def test_comm_timeout_parameters_and_factory_codes():
    assert set(COMM_TIMEOUT_CODES) == set(range(9))
    for family in (DB1, DC1, DE1):
        assert eaton_parameters.parameter_register(family, eaton_settings.COMM_TIMEOUT_PARAMETER[family]) == 164
    assert COMM_TIMEOUT_CODES[eaton_settings.COMM_TIMEOUT_FACTORY_CODE[DC1]].timeout_ms == 3000    # "3000 ms" (A8)
    assert eaton_settings.COMM_TIMEOUT_FACTORY_CODE[DE1] == 0                                      # WE 0 (L445)


def test_second_loss_action_parameters():
    assert eaton_parameters.parameter_register(DA1, eaton_settings.COMM_LOSS_ACTION_PARAMETERS[DA1]) == 516     # L1406
    assert eaton_parameters.parameter_register(DC1, eaton_settings.COMM_LOSS_ACTION_PARAMETERS[DC1]) == 181     # L1848
    assert eaton_parameters.parameter_register(DE1, eaton_settings.COMM_LOSS_ACTION_PARAMETERS[DE1]) == 168     # L1949
    assert DB1 not in eaton_settings.COMM_LOSS_ACTION_PARAMETERS


def test_modbus_control_sources():
    assert eaton_parameters.MODBUS_CONTROL_SOURCES[DA1] == (4,)        # P1-12 = 4 (L376)
    assert eaton_parameters.MODBUS_CONTROL_SOURCES[DC1] == (3, 4)      # P-12 = 3, 4 (L413)
    assert eaton_parameters.MODBUS_CONTROL_SOURCES[DE1] == (3,)        # P-12 = 3 (L436)
    assert eaton_parameters.parameter_register(DA1, eaton_parameters.CONTROL_SOURCE_PARAMETER[DA1]) == 112
    assert eaton_parameters.parameter_register(DE1, eaton_parameters.CONTROL_SOURCE_PARAMETER[DE1]) == 140
    assert eaton_parameters.parameter_register(DA1, eaton_parameters.DA1_FIELDBUS_RAMP_CONTROL) == 507     # L389


# ---------------------------------------------------------------------------
# Drive type and rated power (§2.6.5.7)
# ---------------------------------------------------------------------------

def test_drive_variants():
    assert eaton_settings.DRIVE_VARIANTS[0] == ("kW", 3, 3)      # L970
    assert eaton_settings.DRIVE_VARIANTS[4] == ("kW", 1, 3)      # L974
    assert eaton_settings.DRIVE_VARIANTS[7] == ("HP", 1, 1)      # L977
    assert list(eaton_settings.DRIVE_VARIANT_VALUES[DB1]) == [0, 1, 2, 3, 4, 5]     # Table 14 (L1002-1007)


@pytest.mark.parametrize("family, frame, unit, index, power", [
    (DA1, "FS2", "kW", 6, 4),        # L983
    (DA1, "FS7", "kW", 5, 160),      # L993
    (DA1, "FS6", "HP", 7, 15),       # L992, printed 15 (A31)
    (DA1, "FS4", "kW", 5, None),     # L987 "–"
    (DB1, "FS1B", "HP", 1, 2),       # L1016
    (DC1, "FS2", "kW", 8, 3),        # L1043
    (DE1, "FS1", "kW", 0, 0.25),     # L1073
    (DE1, "FS2", "HP", 4, 7.5),      # L1076
])
def test_rated_power(family, frame, unit, index, power):
    kw, hp = eaton_settings.RATED_POWER[family][frame]
    assert (kw if unit == "kW" else hp)[index] == power


def test_da1_rating_id_fields():
    """P0-29 Rating ID: bits 0-3 power index, 4-7 unit, 8-11 voltage index, 12-15 frame size (L1216-1219)."""
    assert eaton_settings.decode_da1_rating_id(0x7215) == (5, 1, 2, 7)


# ---------------------------------------------------------------------------
# DE1 under Modbus control (§2.5.3, Tabellen 9 and 10)
# ---------------------------------------------------------------------------

@pytest.mark.parametrize("di1, di2, control_reverse, reverse", [
    (True, False, False, False),    # H = FWD, L, Bit1 = 0 -> FWD (rechts)
    (False, True, False, True),     # L, H = REV, Bit1 = 0 -> REV (links)
    (True, False, True, True),      # H = FWD, L, Bit1 = 1 -> REV
    (False, True, True, False),     # L, H = REV, Bit1 = 1 -> FWD
])
def test_de1_direction_table(di1, di2, control_reverse, reverse):
    assert eaton_settings.de1_reverse(di1, di2, control_reverse) is reverse      # L606-609


@pytest.mark.parametrize("di1, di2", [(False, False), (True, True)])
def test_de1_direction_outside_the_table(di1, di2):
    with pytest.raises(ValueError, match="Tabelle 9"):
        eaton_settings.de1_reverse(di1, di2, False)


@pytest.mark.parametrize("name, ff0, ff1, number, hz, register", [
    ("FF1", False, False, "P-20", 20.0, 148),     # L625
    ("FF2", True, False, "P-21", 30.0, 149),
    ("FF3", False, True, "P-22", 40.0, 150),
    ("FF4", True, True, "P-23", 50.0, 151),       # L628
])
def test_de1_fixed_frequencies(name, ff0, ff1, number, hz, register):
    assert eaton_settings.DE1_FIXED_FREQUENCIES[name] == (ff0, ff1, number, hz)
    assert eaton_parameters.parameter_register(DE1, number) == register       # L1929-1932
