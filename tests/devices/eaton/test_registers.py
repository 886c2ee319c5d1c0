"""The Eaton PowerXL register map (registers.py) against the manual's own
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
from softplc.runtime.devices.eaton import registers as eaton
from softplc.runtime.devices.eaton import settings as eaton_settings
from softplc.runtime.devices.eaton.registers import ControlWord, Family, StatusWord

DA1, DB1, DC1, DE1 = Family.DA1, Family.DB1, Family.DC1, Family.DE1


def telegram(text: str) -> bytes:
    return bytes.fromhex(text.replace(" ", ""))


def word(frame: bytes, offset: int) -> int:
    return frame[offset] << 8 | frame[offset + 1]


# ---------------------------------------------------------------------------
# ID 17 device identification (§2.6.5.10, L1086-1096)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "value, family, model",
    [
        (5632, DA1, "DA1"),  # L1088
        (8198, DB1, "DB1"),  # L1090
        (10, DC1, "DC1"),  # L1092
        (8, DE1, "DE1"),  # L1094
        (9, DE1, "DE11"),  # L1096: the DE1 variant with CANopen and relay
    ],
)
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
    assert eaton.REG_DEVICE_ID == 17  # L829
    for family in Family:
        assert 17 in eaton.process_registers(family, writes=False)


# ---------------------------------------------------------------------------
# Register addressing (§2.6.6: "Offset von +1") and the worked telegrams
# ---------------------------------------------------------------------------


def test_register_numbers_travel_minus_one():
    assert eaton.wire_address(6) == 0x0005  # L1125: "0005 ... Die ID ist 6"
    assert eaton.wire_address(1) == 0x0000  # L1151: "0000 ... Die ID ... ist 1"
    assert eaton.register_number(0x0005) == 6
    assert eaton.register_number(0x0000) == 1
    assert eaton.wire_address(101) == 0x0064  # P1-01, register 101 (L1287)


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
    assert frame[2] == 2  # "1 Register = 2 Byte"
    value = word(frame, 3)
    assert value == 0
    assert eaton.status_flags(value) == StatusWord(0)
    assert StatusWord.READY not in eaton.status_flags(value)
    assert eaton.fault_number(value) == eaton_faults.FAULT_NONE
    assert eaton_faults.fault_text(eaton.fault_number(value)) == "No fault"


@pytest.mark.parametrize(
    "text",
    [
        "01 06 0000 0001 480A",  # M3, master request (L1146)
        "01 06 0000 0001 480A",  # M4, the response "ist eine Kopie der Master-Anfrage" (L1157; printed "480", A14)
    ],
)
def test_m3_m4_write_control_word_run(text):
    """Write the control word (ID 1) of a DA1 at slave address 1: RUN (L1146-1164)."""
    frame = telegram(text)
    assert frame[0] == 1
    assert frame[1] == 6 and eaton.FUNCTION_CODES[6] == "Write Single Register"
    assert eaton.register_number(word(frame, 2)) == eaton.REG_CONTROL_WORD == 1
    assert eaton.REG_CONTROL_WORD in eaton.process_registers(DA1, writes=True)
    value = word(frame, 4)
    assert value == 0b0000_0000_0000_0001  # "0000 0000 0000 001 bin -> RUN" (15 digits printed, A14)
    assert ControlWord(value) == ControlWord.RUN
    assert ControlWord.REVERSE not in ControlWord(value)  # bit 1 = 0: forward


def test_function_codes_and_limits():
    assert set(eaton.FUNCTION_CODES) == {3, 6, 16, 23}  # L667-670, decimal (A10)
    assert eaton.MAX_REGISTERS_PER_READ == 11  # L667
    assert eaton.BROADCAST_ADDRESS == 0  # L658
    assert (eaton.UNIT_ADDRESSES.start, eaton.UNIT_ADDRESSES.stop - 1) == (1, 63)  # L657


# ---------------------------------------------------------------------------
# Process data (§2.6.3 - §2.6.5)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "family, writes, parameters",
    [
        (DA1, (1, 2, 3, 4), (101, 941)),  # L718-720
        (DB1, (1, 2, 4), (129, 197)),  # L725-727
        (DC1, (1, 2, 4), (129, 197)),
        (DE1, (1, 2), (129, 169)),  # L732-734
    ],
)
def test_register_groups_per_family(family, writes, parameters):
    groups = eaton.REGISTER_GROUPS[family]
    assert groups.writes == writes
    assert groups.parameters == parameters
    assert eaton.process_registers(family, writes=True) == writes


def test_read_ranges_per_family():
    assert eaton.REGISTER_GROUPS[DA1].reads == (6, 43)  # L721
    assert eaton.REGISTER_GROUPS[DB1].reads == (6, 24)  # L728
    assert eaton.REGISTER_GROUPS[DE1].reads == (6, 24)  # L735


def test_process_register_numbers():
    assert (eaton.REG_CONTROL_WORD, eaton.REG_SPEED_SETPOINT, eaton.REG_TORQUE_SETPOINT, eaton.REG_RAMP_TIME) == (
        1,
        2,
        3,
        4,
    )  # L755-758
    assert (
        eaton.REG_STATUS_WORD,
        eaton.REG_ACTUAL_SPEED,
        eaton.REG_MOTOR_CURRENT,
        eaton.REG_TORQUE,
        eaton.REG_OUTPUT_POWER,
        eaton.REG_DI_STATUS,
    ) == (6, 7, 8, 9, 10, 11)  # L818-823


def test_torque_setpoint_is_da1_only_and_ramp_time_not_de1():
    assert eaton.PROCESS_DATA[3].families == {DA1}  # L757 "nur DA1"
    assert eaton.PROCESS_DATA[4].families == {DA1, DB1, DC1}  # L758 "nur DA1, DB1, DC1"
    assert DE1 not in eaton.PROCESS_DATA[9].families  # L821
    assert DE1 not in eaton.PROCESS_DATA[10].families  # L822


def test_current_is_sent_without_the_decimal_point():
    assert eaton.CURRENT.to_value(3) == 0.3  # L744: 0,3 A on the display, 003 dez on Modbus
    assert eaton.CURRENT.to_raw(0.3) == 3
    assert eaton.CURRENT.to_value(34) == 3.4  # L936: 34 ≙ 3,4 A
    assert eaton.PROCESS_DATA[8].scale.unit == "A"


def test_torque_and_power_examples():
    assert eaton.PROCESS_DATA[9].scale.to_value(1000) == 100.0  # L942: 1000 ≙ 100,0 %
    assert eaton.PROCESS_DATA[10].scale.to_value(53) == 5.3  # L948: 53 ≙ 5,3 kW (A17)
    assert eaton.PROCESS_DATA[10].scale.unit == "kW"


def test_torque_setpoint_and_ramp_time_examples_and_limits():
    torque = eaton.PROCESS_DATA[eaton.REG_TORQUE_SETPOINT]
    assert torque.scale.to_raw(100) == 1000  # L801: 1000 ≙ 100 %
    assert torque.limits == (0, 2000)  # L799
    ramp = eaton.PROCESS_DATA[eaton.REG_RAMP_TIME]
    assert ramp.scale.to_raw(3) == 300  # L807: 300 ≙ 3 s
    assert ramp.scale.to_value(300) == 3.0
    assert ramp.limits == (0, 60000)  # L805


def test_speed_counts_in_tenths_of_hertz():
    assert eaton.PROCESS_DATA[2].scale.to_value(500) == 50.0  # factor 0,1 (L792)
    assert eaton.PROCESS_DATA[7].scale.to_value(500) == 50.0  # factor 0,1 (L927)
    assert eaton.speed_setpoint_raw(50.0) == 500
    assert eaton.speed_setpoint_raw(0.05) == 1  # halves round away from zero


def test_negative_speed_setpoint_is_refused():
    with pytest.raises(ValueError, match="REVERSE"):
        eaton.speed_setpoint_raw(-10.0)


def test_serial_number_registers():
    assert eaton.SERIAL_NUMBER_REGISTERS[DA1] == (25, 26, 27, 28)  # L1100
    assert eaton.SERIAL_NUMBER_REGISTERS[DB1] == (29, 30, 31, 32)  # L1102
    assert eaton.SERIAL_NUMBER_REGISTERS[DC1] == (29, 30, 31, 32)
    assert eaton.SERIAL_NUMBER_REGISTERS[DE1] == ()  # L1104: none on the DE1


# ---------------------------------------------------------------------------
# Control word (ID 1) and status word (ID 6)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "flag, value",
    [
        (ControlWord.RUN, 0x01),  # bit 0 Betrieb (L766)
        (ControlWord.REVERSE, 0x02),  # bit 1 Linksdrehfeld (L767)
        (ControlWord.FAULT_RESET, 0x04),  # bit 2 Fehler zurücksetzen (L768)
        (ControlWord.COAST, 0x08),  # bit 3 Freier Auslauf (L769)
        (ControlWord.QUICK_STOP, 0x20),  # bit 5 Schnellstopp (Rampe 2) (L771)
        (ControlWord.FIXED_FREQUENCY_1, 0x40),  # bit 6 Festfrequenz FF1 (L772)
        (ControlWord.ZERO_SETPOINT, 0x80),  # bit 7 Sollwert mit 0 überschreiben (L773)
    ],
)
def test_control_word_bits(flag, value):
    assert flag == value


def test_control_word_unused_bits():
    used = 0
    for flag in ControlWord:
        used |= flag
    assert used & 0x10 == 0  # bit 4 "nicht verwendet" (L770)
    assert used & 0xFF00 == 0  # bits 8-15 (L774-781)
    assert eaton.CONTROL_WORD_UNUSED_BITS == 0xFF10
    assert ControlWord.RUN | ControlWord.REVERSE == 0x0003  # run reverse


@pytest.mark.parametrize(
    "flag, value",
    [
        (StatusWord.READY, 0x01),  # bit 0 Startbereit (L843)
        (StatusWord.RUNNING, 0x02),  # bit 1 Betrieb Laufmeldung (L844)
        (StatusWord.REVERSE, 0x04),  # bit 2 Linksdrehfeld (L845)
        (StatusWord.FAULT, 0x08),  # bit 3 Fehler erkannt (L846)
        (StatusWord.AT_SETPOINT, 0x10),  # bit 4 Frequenz-Istwert gleich Sollwertvorgabe (L847)
        (StatusWord.ZERO_SPEED, 0x20),  # bit 5 "Nullzahl" (L848, A21)
        (StatusWord.SPEED_CONTROL_ACTIVE, 0x40),  # bit 6 Drehzahlsteuerung aktiviert (L849)
        (StatusWord.HARDWARE_ENABLE, 0x80),  # bit 7 STO status / Hardware-Freigabe (L850)
    ],
)
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
# Scaling: process data and parameters count differently (digest §3.13)
# ---------------------------------------------------------------------------


def test_da1_ramp_scale_depends_on_the_frame_size():
    assert eaton.da1_ramp_scale(2).to_value(300) == 3.0  # FS2, FS3: 1 ≙ 0.01 s (L1332)
    assert eaton.da1_ramp_scale(3).to_value(300) == 3.0
    assert eaton.da1_ramp_scale(4).to_value(300) == 30.0  # FS4 ... FS7: 1 ≙ 0.1 s
    assert eaton.da1_ramp_scale(7).to_value(300) == 30.0
    with pytest.raises(ValueError):
        eaton.da1_ramp_scale(1)


def test_process_data_and_parameters_count_hertz_differently():
    """50 Hz is 500 as a speed setpoint (ID 2, 0.1 Hz) and 3000 in a frequency parameter."""
    assert eaton.SPEED.to_raw(50.0) == 500  # L792
    assert eaton.PARAMETER_FREQUENCY.to_raw(50.0) == 3000  # L1287
    assert eaton.frequency_parameter_to_speed_raw(3000) == 500
    assert eaton_settings.DE1_FIXED_FREQUENCIES["FF1"][3] == 20.0
    assert eaton.PARAMETER_FREQUENCY.to_raw(20.0) == 1200


# ---------------------------------------------------------------------------
# P0 display values with registers (digest §3.8)
# ---------------------------------------------------------------------------


@pytest.mark.parametrize(
    "family, number, registers",
    [
        (DA1, "P0-01", (20,)),  # L1182
        (DA1, "P0-03", (11,)),  # L1184
        (DA1, "P0-12", (9,)),  # L1193
        (DA1, "P0-20", (23,)),  # L1201
        (DA1, "P0-28", (15, 16)),  # L1209-1210
        (DA1, "P0-30", (25, 26, 27, 28)),  # L1221
        (DB1, "P0-03", (2,)),  # L1570
        (DB1, "P0-10", (25, 26)),  # L1577-1578
        (DC1, "P0-30", (29, 30, 31, 32)),  # L1749-1759
        (DE1, "P0-09", (24,)),  # L1890
    ],
)
def test_monitor_registers(family, number, registers):
    assert eaton.monitor_registers(family, number) == registers


@pytest.mark.parametrize(
    "family, number",
    [
        (DA1, "P0-07"),  # no register printed (L1188)
        (DA1, "P0-35"),  # printed at 20, a copy of P0-01 (A26)
        (DE1, "P0-04"),  # L1885
    ],
)
def test_monitor_values_without_register(family, number):
    with pytest.raises(ValueError, match="has no Modbus register"):
        eaton.monitor_registers(family, number)


@pytest.mark.parametrize(
    "family, register, raw, value",
    [
        (DA1, 20, 4096, 100.0),  # "4096 ≙ 100.0 %" (L1182)
        (DA1, 23, 600, 600),  # "600 ≙ 600 V" (L1201)
        (DA1, 24, 40, 40),  # "40 ≙ 40 °C" (L1202)
        (DA1, 30, 100, 10.0),  # "100 ≙ 10.0 kWh" (L1207)
        (DB1, 23, 230, 230),  # "230 ≙ 230 V" (L1575)
        (DE1, 26, 300, 3.0),  # "300 ≙ 3.00 s" (L1892)
    ],
)
def test_monitor_scales(family, register, raw, value):
    (monitor,) = [m for m in eaton.MONITOR_VALUES[family] if m.register == register]
    assert monitor.scale.to_value(raw) == value


def test_da1_user_registers():
    assert eaton.DA1_USER_REGISTERS[51] == "UserRegister 1"  # L1533
    assert eaton.DA1_USER_REGISTERS[65] == "UserRegister 15"  # L1547
    assert 68 not in eaton.DA1_USER_REGISTERS and 69 not in eaton.DA1_USER_REGISTERS
    assert max(eaton.DA1_USER_REGISTERS) == 78  # L1558
