"""Eaton PowerXL DA1, DB1 and DC1 drives and the DE1 speed starter on Modbus
RTU: everything their communication manual says about registers, in one place.

Source: manual 002 ("PowerXL Modbus RTU Kommunikationshandbuch für
Frequenzumrichter / Drehzahlstarter DA1, DB1, DC1, DE1", 3rd edition 12/22,
shared/manuals/002_a23ab2a6587941cb.txt; "L<n>" below is a line of that file)
and its digest (shared/digests/002_eaton_modbus.md, "§" and the ambiguities
A1..A34 of its §8). Pure data and pure functions: the Modbus driver, the drive
simulator and the ST function blocks all read it. Frames and their CRC belong
to the Modbus layer, not here.

    family_from_id17(5632)                    -> Family.DA1
    wire_address(REG_STATUS_WORD)             -> 5      (ID 6 travels as 0x0005)
    parameter_register(Family.DA1, "P1-01")   -> 101
    parameter_register(Family.DC1, "P-36")    -> 164
    fault_number(0x3208), status_flags(0x3208) -> 50, StatusWord.FAULT
    SPEED.to_raw(50.0), PARAMETER_FREQUENCY.to_raw(50.0) -> 500, 3000

Parameter names are the manual's German designations, as printed; the
numbers and everything the runtime acts on have English names.
"""
from __future__ import annotations

import enum
import math
import re
from dataclasses import dataclass
from fractions import Fraction
from typing import NamedTuple

# ---------------------------------------------------------------------------
# Families and their identification (ID 17)
# ---------------------------------------------------------------------------


class Family(enum.IntEnum):
    """The four device families of the manual. DE11 (a DE1 with CANopen and a
    relay output, Tabelle 24) is a DE1 variant, not a family of its own."""
    DA1 = 1     # variable frequency drive: STO, encoder, function-block editor
    DB1 = 2     # variable frequency drive, new in the 12/22 edition
    DC1 = 3     # compact variable frequency drive
    DE1 = 4     # variable speed starter ("Drehzahlstarter")


# ID 17 "Frequenzumrichtererkennung/Drehzahlstartererkennung" (L1086-1096):
# register value -> (family, model as printed)
DEVICE_IDENTIFICATION = {
    5632: (Family.DA1, "DA1"),      # L1088 (0x1600)
    8198: (Family.DB1, "DB1"),      # L1090 (0x2006)
    10: (Family.DC1, "DC1"),        # L1092
    8: (Family.DE1, "DE1"),         # L1094
    9: (Family.DE1, "DE11"),        # L1096
}


def family_from_id17(value: int) -> Family:
    """The family of a device from its ID 17 register; ValueError for a value
    the manual does not list (another device, or a wrong register read)."""
    try:
        return DEVICE_IDENTIFICATION[value][0]
    except KeyError:
        known = ", ".join(f"{v} ({model})" for v, (_, model) in DEVICE_IDENTIFICATION.items())
        raise ValueError(f"ID 17 value {value} is not an Eaton PowerXL device ({known})") from None


def model_from_id17(value: int) -> str:
    """'DA1', 'DB1', 'DC1', 'DE1' or 'DE11'; ValueError as family_from_id17."""
    family_from_id17(value)
    return DEVICE_IDENTIFICATION[value][1]


# ---------------------------------------------------------------------------
# Register numbers on the wire (digest §2.4)
# ---------------------------------------------------------------------------

# The manual numbers registers from 1 ("ID"); a telegram carries the number
# minus one. Both worked examples say so: ID 6 is read at address 0x0005
# (L1125) and ID 1 written at 0x0000 (L1151), "da die Motorsteuerung einen
# Offset von +1 beinhaltet". Some PLC drivers add the +1 themselves (L739), so
# a configuration must say which of the two numbers it means. Everything in
# this module is a register number, never a wire address.
REGISTER_OFFSET = 1


def wire_address(register: int) -> int:
    """The Modbus PDU address of a register number: register 6 -> 5."""
    if not 1 <= register <= 0x10000:
        raise ValueError(f"register numbers run from 1 to 65536, not {register}")
    return register - REGISTER_OFFSET


def register_number(address: int) -> int:
    """The register number of a Modbus PDU address: 0x0005 -> 6."""
    if not 0 <= address <= 0xFFFF:
        raise ValueError(f"a Modbus address is 0..0xFFFF, not {address}")
    return address + REGISTER_OFFSET


# Protocol facts the devices state about themselves (L656-670)
BROADCAST_ADDRESS = 0           # L658: every slave executes it, none answers
UNIT_ADDRESSES = range(1, 64)   # L657 "Adresse (1 bis 63)", at most 63 nodes (L268); DE1 P-47: 1..255 (A1)
MAX_REGISTERS_PER_READ = 11     # L667: function code 03 reads at most 11 registers
# Function codes (L664-670). The column is headed "[hex]" but 16 and 23 are
# decimal, 0x10 and 0x17 (A10). The manual documents no exception responses (A12).
FUNCTION_CODES = {
    3: "Read Holding Registers",
    6: "Write Single Register",         # also as a broadcast (L1168); the slave echoes the request
    16: "Write Multiple Registers",     # printed "Set Multiple Register"
    23: "Read/Write Multiple Registers",
}


@dataclass(frozen=True)
class RegisterGroups:
    """The "Register-Mapping" table of one family (L714-735)."""
    parameters: tuple       # (first, last) parameter register as printed
    writes: tuple           # "Eingangsprozessdaten": registers the PLC writes
    reads: tuple            # "Ausgangsprozessdaten": (first, last) registers the PLC reads


# The parameter tables reach beyond the printed parameter ranges (DC1 P-70 is
# 198, DE1 P-48 is 176, DE11 up to 184: A15); parameter_register follows the tables.
REGISTER_GROUPS = {
    Family.DA1: RegisterGroups(parameters=(101, 941), writes=(1, 2, 3, 4), reads=(6, 43)),   # L718-721
    Family.DB1: RegisterGroups(parameters=(129, 197), writes=(1, 2, 4), reads=(6, 24)),      # L725-728
    Family.DC1: RegisterGroups(parameters=(129, 197), writes=(1, 2, 4), reads=(6, 24)),      # L725-728
    Family.DE1: RegisterGroups(parameters=(129, 169), writes=(1, 2), reads=(6, 24)),         # L732-735
}

# ---------------------------------------------------------------------------
# Scaling: the manual writes "3000 ≙ 50.0 Hz" (digest §3.13)
# ---------------------------------------------------------------------------


def _round_half_away(value: Fraction) -> int:
    """Round to the nearest count, halves away from zero (50.05 Hz -> 501, not 500)."""
    return math.floor(value + Fraction(1, 2)) if value >= 0 else -math.floor(-value + Fraction(1, 2))


@dataclass(frozen=True)
class Scale:
    """A register counting in steps of `step` units, as the manual's
    "raw ≙ value unit". Exact decimal arithmetic: 3 counts of 0.1 A are 0.3 A."""
    step: Fraction
    unit: str = ""

    @classmethod
    def of(cls, raw: int, value, unit: str = "") -> "Scale":
        """Scale.of(3000, "50.0", "Hz") for "3000 ≙ 50.0 Hz"."""
        return cls(Fraction(str(value)) / raw, unit)

    _NOTATION = re.compile(r"^(-?\d+) ≙ (-?\d+(?:\.\d+)?) ?([^≙]*)$")

    @classmethod
    def parse(cls, text: str) -> "Scale | None":
        """The scale of a table's "Skalierung" cell when it is one linear
        "raw ≙ value unit"; None for anything else (codes, special values,
        frame-size dependent steps, an empty cell)."""
        match = cls._NOTATION.match(text.strip())
        if not match or int(match.group(1)) == 0:
            return None
        return cls.of(int(match.group(1)), match.group(2), match.group(3).strip())

    def to_value(self, raw: int) -> float:
        """The physical value of a raw count: SPEED.to_value(500) -> 50.0."""
        return float(raw * self.step)

    def to_raw(self, value) -> int:
        """The nearest raw count of a physical value: SPEED.to_raw(50.0) -> 500."""
        return _round_half_away(Fraction(str(value)) / self.step)


# Process data (IDs 1-17) count in the manual's "Skalierungsfaktor" (L755-829)
SPEED = Scale.of(1, "0.1", "Hz")            # ID 2 setpoint and ID 7 actual speed: factor 0,1 (L792, L927)
TORQUE = Scale.of(1000, "100.0", "%")       # ID 3 and ID 9: "1000 ≙ 100 %" (L801, L942)
RAMP_TIME = Scale.of(300, "3", "s")         # ID 4: "300 ≙ 3 s" (L807)
CURRENT = Scale.of(1, "0.1", "A")           # ID 8: "34 ≙ 3,4 A" (L936); 0,3 A is sent as 3 (L744)
# ID 10: the table prints factor 1 (L822), the text "kW mit einer Dezimalstelle,
# 53 ≙ 5,3 kW" (L946-948). The worked example wins (A17).
OUTPUT_POWER = Scale.of(1, "0.1", "kW")
POWER_RATING = Scale.of(1, 1, "kW")         # ID 13: factor 1, kW or HP as ID 12 says (L825)
VOLTAGE_LEVEL = Scale.of(1, 1, "V")         # ID 14 (L826)
SOFTWARE_VERSION = Scale.of(1, "0.01")      # IDs 15, 16 "mit zwei Dezimalstellen" (L1080, L1084)

# Parameters count differently: every frequency parameter (f-max, f-min,
# f-Fix, skip frequencies ...) is "3000 ≙ 50.0 Hz", 60 counts per Hz, while
# the speed process data count 10 per Hz. Motor rated frequency is the
# exception: DA1 P1-09 "500 ≙ 50 Hz", DB1/DC1/DE1 P-09 "50 ≙ 50 Hz".
PARAMETER_FREQUENCY = Scale.of(3000, "50.0", "Hz")


def speed_setpoint_raw(hz: float) -> int:
    """The ID 2 count of a speed setpoint in Hz. ID 2 and ID 7 are unsigned;
    the direction is control word bit 1 (A24, as the digest proposes)."""
    raw = SPEED.to_raw(hz)
    if not 0 <= raw <= 0xFFFF:
        raise ValueError(f"speed setpoint {hz} Hz is outside 0 .. 6553.5 Hz; "
                         "set the direction with ControlWord.REVERSE, not a negative speed")
    return raw


def frequency_parameter_to_speed_raw(parameter_raw: int) -> int:
    """A frequency parameter (3000 ≙ 50.0 Hz) in ID 2/ID 7 counts (0.1 Hz):
    f-max 3000 -> 500, e.g. to limit a setpoint to P1-01/P-01."""
    return _round_half_away(Fraction(parameter_raw) * PARAMETER_FREQUENCY.step / SPEED.step)


# DA1 P2-25 and P8-01..P8-12 count in 0.01 s on frame sizes FS2/FS3 and in
# 0.1 s on FS4..FS7 (L1332, L1467-1477); the frame size is register 12 bits 12-15.
_DA1_RAMP_STEPS = {2: "0.01", 3: "0.01", 4: "0.1", 5: "0.1", 6: "0.1", 7: "0.1"}


def da1_ramp_scale(frame_size: int) -> Scale:
    """The scale of DA1 P2-25 (quick stop) and the P8 ramps on a frame size 2..7."""
    if frame_size not in _DA1_RAMP_STEPS:
        raise ValueError(f"DA1 frame sizes are FS2..FS7 (Tabelle 13), not FS{frame_size}")
    return Scale.of(1, _DA1_RAMP_STEPS[frame_size], "s")


def to_signed16(word: int) -> int:
    """An S16 register (e.g. DA1 P2-29, P0-04): 0xFFFF -> -1."""
    word &= 0xFFFF
    return word - 0x10000 if word & 0x8000 else word


def from_signed16(value: int) -> int:
    """The register word of an S16 value: -1 -> 0xFFFF."""
    if not -0x8000 <= value <= 0x7FFF:
        raise ValueError(f"{value} does not fit a signed 16-bit register")
    return value & 0xFFFF


# ---------------------------------------------------------------------------
# Process data (manual §2.6.4, §2.6.5)
# ---------------------------------------------------------------------------

REG_CONTROL_WORD = 1                # "Steuerwort Feldbus"
REG_SPEED_SETPOINT = 2              # 0.1 Hz, f-min .. f-max (P1-02..P1-01, P-02..P-01)
REG_TORQUE_SETPOINT = 3             # DA1 only: 0.1 %, 0 .. 2000
REG_RAMP_TIME = 4                   # DA1, DB1, DC1: 0.01 s, 0 .. 60000
REG_STATUS_WORD = 6                 # status bits 0-7, fault number bits 8-15
REG_ACTUAL_SPEED = 7                # 0.1 Hz
REG_MOTOR_CURRENT = 8               # 0.1 A
REG_TORQUE = 9                      # DA1, DB1, DC1: 0.1 %
REG_OUTPUT_POWER = 10               # DA1, DB1, DC1: 0.1 kW (A17)
REG_DI_STATUS = 11                  # bit 0 = DI1
REG_DRIVE_TYPE = 12                 # "Ausführung" (Tabellen 12-19; DA1: P0-29 Rating ID)
REG_POWER_RATING = 13               # kW or HP
REG_VOLTAGE_LEVEL = 14              # V
REG_SOFTWARE_VERSION_CONTROL = 15   # two decimals
REG_SOFTWARE_VERSION_POWER = 16     # two decimals
REG_DEVICE_ID = 17                  # DEVICE_IDENTIFICATION

_ALL = frozenset(Family)
_WITH_TORQUE = frozenset({Family.DA1, Family.DB1, Family.DC1})


@dataclass(frozen=True)
class ProcessRegister:
    """One process data register (the tables of L754-758 and L817-829)."""
    register: int
    name: str
    writes: bool            # True: the PLC writes it ("Eingangsprozessdaten" of the drive)
    families: frozenset
    scale: Scale | None     # None: a bit pattern or a code
    limits: tuple | None = None     # (lowest, highest) raw value where the manual gives them


PROCESS_DATA = {p.register: p for p in (
    ProcessRegister(1, "Fieldbus control word", True, _ALL, None),                          # L755
    ProcessRegister(2, "Fieldbus speed setpoint", True, _ALL, SPEED),                       # L756
    ProcessRegister(3, "Torque setpoint", True, frozenset({Family.DA1}), TORQUE, (0, 2000)),     # L757, L799
    ProcessRegister(4, "Modbus ramp time", True, _WITH_TORQUE, RAMP_TIME, (0, 60000)),      # L758, L805
    ProcessRegister(6, "Status and fault word", False, _ALL, None),                         # L818
    ProcessRegister(7, "Fieldbus actual speed", False, _ALL, SPEED),                        # L819
    ProcessRegister(8, "Motor current", False, _ALL, CURRENT),                              # L820
    # IDs 9 and 10 "nur DA1, DB1, DC1" although the DE1 read range is 6-24 too (A18)
    ProcessRegister(9, "Torque", False, _WITH_TORQUE, TORQUE),                              # L821
    ProcessRegister(10, "Output power", False, _WITH_TORQUE, OUTPUT_POWER),                 # L822
    ProcessRegister(11, "DI status", False, _ALL, None),                                    # L823, L954
    ProcessRegister(12, "Drive type", False, _ALL, None),                                   # L824
    ProcessRegister(13, "Power rating", False, _ALL, POWER_RATING),                         # L825
    ProcessRegister(14, "Voltage level", False, _ALL, VOLTAGE_LEVEL),                       # L826
    ProcessRegister(15, "Software version, control section", False, _ALL, SOFTWARE_VERSION),   # L827
    ProcessRegister(16, "Software version, power section", False, _ALL, SOFTWARE_VERSION),     # L828
    ProcessRegister(17, "Device identification", False, _ALL, None),                        # L829
)}


def process_registers(family: Family, *, writes: bool) -> tuple:
    """The process data registers a family has, written (writes=True) or read."""
    return tuple(sorted(r.register for r in PROCESS_DATA.values()
                        if r.writes == writes and family in r.families))


# Serial number words (L1098-1104); DB1/DC1 print 29 as "Seriennummer 4" ...
# 32 as "Seriennummer 1" (L1600-1610). The DE1 has no unique serial number.
SERIAL_NUMBER_REGISTERS = {
    Family.DA1: (25, 26, 27, 28),
    Family.DB1: (29, 30, 31, 32),
    Family.DC1: (29, 30, 31, 32),
    Family.DE1: (),
}


@dataclass(frozen=True)
class MonitorValue:
    """A read-only "P0" display value that has a Modbus register. Values of
    more than one word have one row per register, with the same number."""
    register: int
    number: str             # "P0-12"
    name: str               # as printed
    scaling: str = ""       # as printed
    format: str = ""

    @property
    def scale(self) -> Scale | None:
        return Scale.parse(self.scaling)


# The P0 rows of the parameter tables that print a register (digest §3.8).
# DA1 Tabelle 20 (L1182-1228). It also prints P0-35..P0-40 at 20, 21, 11,
# 22, 41, 42 (L1229-1234): the registers of P0-01..P0-06 again, a copy error
# (A26), left out here.
_DA1_MONITOR = (
    MonitorValue(20, "P0-01", "Analogeingang1", "4096 ≙ 100.0 %", "U16"),     # L1182
    MonitorValue(21, "P0-02", "Analogeingang2", "4096 ≙ 100.0 %", "U16"),     # L1183
    MonitorValue(11, "P0-03", "DI Status", "Bit 0 ≙ Digital-Eingang 1, Bit 1 ≙ Digital-Eingang 2, ...",
                 "WORD"),                                                     # L1184
    MonitorValue(22, "P0-04", "f-PreRamp", "", "S16"),                        # L1185
    MonitorValue(41, "P0-05", "Drehmomentsollwert", "1000 ≙ 100.0 %", "U16"),     # L1186
    MonitorValue(42, "P0-06", "MotorPoti Sollwert", "", "U16"),               # L1187
    MonitorValue(9, "P0-12", "Motordrehmoment", "1000 ≙ 100.0 %", "U16"),     # L1193
    MonitorValue(23, "P0-20", "Zwischenkreisspannung", "600 ≙ 600 V"),        # L1201
    MonitorValue(24, "P0-21", "Kühlkörpertemperatur", "40 ≙ 40 °C"),          # L1202
    MonitorValue(30, "P0-26", "kWh Zähler", "100 ≙ 10.0 kWh", "U16"),         # L1207
    MonitorValue(33, "P0-27", "MWh Zähler", "", "U16"),                       # L1208
    MonitorValue(15, "P0-28", "Applikationsversion"),                         # L1209
    MonitorValue(16, "P0-28", "Applikationsversion"),                         # L1210
    MonitorValue(12, "P0-29", "Rating ID", "", "WORD"),                       # L1216: decode_da1_rating_id
    MonitorValue(17, "P0-29", "Gerätetyp", "", "WORD"),                       # L1220 (P0-29 printed twice, A26)
    MonitorValue(25, "P0-30", "Seriennummer"),                                # L1221
    MonitorValue(26, "P0-30", "Seriennummer"),
    MonitorValue(27, "P0-30", "Seriennummer"),
    MonitorValue(28, "P0-30", "Seriennummer"),
    MonitorValue(34, "P0-31", "t-Run", "", "U16"),                            # L1225
    MonitorValue(36, "P0-34", "t-Run Freigabe", "", "U16"),                   # L1228
)

# DB1 Tabelle 21 (L1568-1628) and DC1 Tabelle 22 (L1717-1777) print the same rows
_DB1_DC1_MONITOR = (
    MonitorValue(20, "P0-01", "Analogeingang1", "4096 ≙ 100.0 %"),            # L1568
    MonitorValue(21, "P0-02", "Analogeingang2", "4096 ≙ 100.0 %"),            # L1569
    MonitorValue(2, "P0-03", "Frequenzsollwert"),                             # L1570: register 2 read back
    MonitorValue(11, "P0-04", "DI Status"),                                   # L1571
    MonitorValue(43, "P0-07", "Motorspannung"),                               # L1574
    MonitorValue(23, "P0-08", "Zwischenkreisspannung", "230 ≙ 230 V"),        # L1575
    MonitorValue(24, "P0-09", "Kühlkörpertemperatur", "40 ≙ 40 °C"),          # L1576
    MonitorValue(25, "P0-10", "t-Run (h)", "1 ≙ 1"),                          # L1577
    MonitorValue(26, "P0-10", "t-Run (min/sec)", "300 ≙ 3.00 s"),             # L1578
    MonitorValue(27, "P0-14", "t-StundenRun Freigegeben (h)"),                # L1582
    MonitorValue(28, "P0-14", "t-StundenRun Freigegeben (min/sec)"),          # L1583
    MonitorValue(39, "P0-20", "T-Reglerkarte", "40 ≙ 40 °C"),                 # L1589, printed "T-Reglerkarter"
    MonitorValue(15, "P0-28", "Application Version"),                         # L1598, printed "15/16"
    MonitorValue(16, "P0-28", "Application Version"),
    MonitorValue(12, "P0-29", "DeviceType"),                                  # L1599
    MonitorValue(29, "P0-30", "Seriennummer 4", "1 ≙ 1"),                     # L1600
    MonitorValue(30, "P0-30", "Seriennummer 3", "1 ≙ 1"),                     # L1601
    MonitorValue(31, "P0-30", "Seriennummer 2", "1 ≙ 1"),                     # L1609
    MonitorValue(32, "P0-30", "Seriennummer 1", "1 ≙ 1"),                     # L1610
    MonitorValue(18, "P0-48", "Scope Channel 1& 2"),                          # L1628, printed "18/19"
    MonitorValue(19, "P0-48", "Scope Channel 1& 2"),
)

# DE1 Tabelle 23 (L1882-1892): P0-02..P0-07 and P0-11..P0-22 have no register
_DE1_MONITOR = (
    MonitorValue(20, "P0-01", "Analogeingang1", "4096 ≙ 100.0 %"),            # L1882
    MonitorValue(23, "P0-08", "Zwischenkreisspannung", "230 ≙ 230 V"),        # L1889
    MonitorValue(24, "P0-09", "Kühlkörpertemperatur", "40 ≙ 40 °C"),          # L1890
    MonitorValue(25, "P0-10", "t-Run (h)", "1 ≙ 1"),                          # L1891
    MonitorValue(26, "P0-10", "t-Run (min/sec)", "300 ≙ 3.00 s"),             # L1892
)

MONITOR_VALUES = {
    Family.DA1: _DA1_MONITOR,
    Family.DB1: _DB1_DC1_MONITOR,
    Family.DC1: _DB1_DC1_MONITOR,
    Family.DE1: _DE1_MONITOR,
}


def monitor_registers(family: Family, number: str) -> tuple:
    """The registers of a P0 display value, in the order the table prints
    them: DA1 "P0-12" -> (9,). ValueError for a P0 value without a register."""
    registers = tuple(m.register for m in MONITOR_VALUES[family] if m.number == number.strip().upper())
    if not registers:
        raise ValueError(f"{family.name} {number} has no Modbus register in the manual's parameter table")
    return registers


# DA1 user registers for the function-block editor (Tabelle 20, L1533-1560).
# 75 and 76 are printed twice: rw user values and ro "Drive Skalierung Wert 1/2" (A26).
DA1_USER_REGISTERS = {
    **{51 + i: f"UserRegister {i + 1}" for i in range(15)},     # L1533-1547
    66: "User Analogausgang1",
    67: "User Analogausgang2",
    **{70 + i: f"User RO{i + 1} LogikStatus" for i in range(5)},     # L1550-1554
    75: "User Skalierwert",                 # also "Drive Skalierung Wert 1" (ro), L1559
    76: "User dezimal Skalierung",          # also "Drive Skalierung Wert 2" (ro), L1560
    77: "User Geschwindigkeitsreferenz",    # printed "Geschwindikeitsreferenz"
    78: "User Drehmoment Referenz",         # printed "Deferenz"
}

# ---------------------------------------------------------------------------
# Control word (ID 1) and status word (ID 6)
# ---------------------------------------------------------------------------


class ControlWord(enum.IntFlag):
    """ID 1 "Steuerwort Feldbus" (L760-781). A cleared bit means stop,
    forward, or "keine Aktion". Bits 4 and 8-15 are not used."""
    RUN = 1 << 0                # 0 = Stopp, 1 = Betrieb
    REVERSE = 1 << 1            # 0 = Rechtsdrehfeld (FWD), 1 = Linksdrehfeld (REV)
    FAULT_RESET = 1 << 2        # "Fehler zurücksetzen"; edge or level is not said (A23)
    COAST = 1 << 3              # "Freier Auslauf"
    QUICK_STOP = 1 << 5         # "Schnellstopp (Rampe 2)": DA1 P2-25, DB1/DC1 P-24 (A23)
    FIXED_FREQUENCY_1 = 1 << 6  # "Festfrequenz FF1"
    ZERO_SETPOINT = 1 << 7      # "Sollwert mit 0 überschreiben"


CONTROL_WORD_UNUSED_BITS = 0xFF10     # bit 4 and bits 8-15 "nicht verwendet" (L770, L774-781)


class StatusWord(enum.IntFlag):
    """ID 6 bits 0-7, the "Statuswort" (L831-850); bits 8-15 are the fault
    number (fault_number)."""
    READY = 1 << 0              # "Startbereit"
    RUNNING = 1 << 1            # "Betrieb Laufmeldung"
    REVERSE = 1 << 2            # 0 = FWD, 1 = REV
    FAULT = 1 << 3              # "Fehler erkannt"
    AT_SETPOINT = 1 << 4        # actual = set frequency; 0 is printed "Beschleunigungsrampe" (A21)
    ZERO_SPEED = 1 << 5         # printed "Nullzahl", read as zero speed (A21)
    SPEED_CONTROL_ACTIVE = 1 << 6   # "Drehzahlsteuerung aktiviert"
    # DA1: the STO status ("Bereit"); DB1, DC1, DE1: the hardware enable
    # (a high signal at DI1, L320, L327) is present (A21); DA1 STO: L316
    HARDWARE_ENABLE = 1 << 7


STATUS_BITS_MASK = 0x00FF
FAULT_NUMBER_SHIFT = 8     # "Fehlerwort (Bit 8 bis Bit 15)" (L833), a fault number of Tabelle 11 (A20)


def status_flags(word: int) -> StatusWord:
    """The status bits of an ID 6 word (its low byte)."""
    return StatusWord(word & STATUS_BITS_MASK)


def fault_number(word: int) -> int:
    """The fault number in an ID 6 word (its high byte): 0x3208 -> 50."""
    return (word >> FAULT_NUMBER_SHIFT) & 0xFF


def status_word(flags: int, fault: int = 0) -> int:
    """The ID 6 word of status bits and a fault number."""
    if not 0 <= fault <= 0xFF:
        raise ValueError(f"a fault number fits bits 8-15 (0..255), not {fault}")
    if flags & ~STATUS_BITS_MASK:
        raise ValueError(f"status flags 0x{flags:X} reach beyond bits 0-7")
    return fault << FAULT_NUMBER_SHIFT | int(flags)


# ---------------------------------------------------------------------------
# Faults (Tabelle 11, L854-916)
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Fault:
    number: int
    display: str            # the code on the drive's display
    text: str               # "Mögliche Ursache", translated
    families: frozenset


_DA1 = frozenset({Family.DA1})
_DA1_DB1_DC1 = _WITH_TORQUE

# The manual file garbles the seven-segment display texts ("DI-b" for OI-b,
# "I.L-ErrP" for I.t-trP, "Sc-FQ1" for SC-F01, "REf-Q1" for Atf-01); the
# display column holds the reading of digest §3.4. The printed hex column has
# two typos (16 printed "0A", 19 printed "12", A20); the numbers are decimal.
# The first row, "StoP" without a number, is not a fault: the drive is not enabled.
FAULTS = {f.number: f for f in (
    Fault(0, "no-Flt", "No fault", _ALL),                                     # L859: P0-13 shows no entry
    Fault(1, "OI-b", "Brake current too high", _ALL),                         # L860
    Fault(2, "OL-br", "Brake resistor thermal overload", _ALL),
    Fault(3, "O-I", "Overcurrent at the output", _ALL),
    Fault(4, "I.t-trP", "Motor overload", _ALL),
    Fault(5, "PS-trP", "Overcurrent (hardware)", _ALL),
    Fault(6, "O-Volt", "DC link overvoltage", _ALL),                          # L865, printed "UUolt"
    Fault(7, "U-Volt", "DC link undervoltage", _ALL),                         # L866, printed "UUolt"
    Fault(8, "O-t", "Heatsink overtemperature", _ALL),
    Fault(9, "U-t", "Undertemperature", _ALL),
    Fault(10, "P-dEF", "Factory default parameters loaded", _ALL),
    Fault(11, "E-trip", "External fault", _ALL),
    Fault(12, "SC-Obs", "Communication fault with the external keypad or PC", _ALL),
    Fault(13, "FLt-dc", "DC link voltage ripple too high", _ALL),
    Fault(14, "P-LOSS", "Loss of a supply phase (three-phase supplied devices only)", _ALL),
    # L874: families printed "DA1, DE1", yet the text names a DC1 meaning too (A20)
    Fault(15, "h O-I", "Overcurrent at the output; DC1: flying start fault",
          frozenset({Family.DA1, Family.DC1, Family.DE1})),
    Fault(16, "th-Flt", "Heatsink thermistor defective", _ALL),
    Fault(17, "dAtA-F", "Internal memory fault", _ALL),
    Fault(18, "4-20 F", "Analog input current outside the specified range", _ALL),
    Fault(19, "dAtA-E", "Internal memory fault", _DA1_DB1_DC1),
    Fault(20, "U-dEF", "Customer parameter set loaded", _DA1),                # L879
    Fault(21, "F-Ptc", "Motor PTC overtemperature", _DA1_DB1_DC1),            # L887
    Fault(22, "FAn-F", "Internal fan fault", _DA1_DB1_DC1),
    Fault(23, "O-hEAt", "Ambient temperature above the specified value", _DA1_DB1_DC1),
    Fault(24, "O-torq", "Maximum permitted torque exceeded", _DA1),
    Fault(25, "U-torq", "Hoist brake control (P2-18 = 8): torque below the threshold before the brake "
          "was released", _DA1),
    Fault(26, "OUt-F", "Fault at the device output", _DA1_DB1_DC1),
    Fault(29, "Sto-F", "STO circuit internal fault", _DA1),                   # L893
    Fault(30, "Enc-01", "No communication between the encoder module and the drive", _DA1),
    Fault(31, "Enc-02", "Calculated motor speed differs from the measured speed", _DA1),   # also "SP-Err"
    Fault(32, "Enc-03", "Motor speed and the encoder PPR in P6-06 do not match", _DA1),
    Fault(33, "Enc-04", "Encoder channel A fault", _DA1),
    Fault(34, "Enc-05", "Encoder channel B fault", _DA1),
    Fault(35, "Enc-06", "Encoder channels A and B fault", _DA1),
    Fault(40, "Atf-01", "Motor identification failed", _DA1_DB1_DC1),         # L900
    Fault(41, "Atf-02", "Motor identification failed: measured stator resistance too large", _DA1_DB1_DC1),
    Fault(42, "Atf-03", "Motor identification failed: measured motor inductance too low", _DA1_DB1_DC1),
    Fault(43, "Atf-04", "Motor identification failed: measured motor inductance too large", _DA1_DB1_DC1),
    Fault(44, "Atf-05", "Motor identification failed: measured motor parameters do not match",
          _DA1_DB1_DC1),
    Fault(49, "OUt-Ph", "A motor phase is not connected or interrupted", _DA1_DB1_DC1),
    # L906: listed for DA1, DB1, DC1 only, although the DE1 trips on a Modbus
    # timeout as well (P-36); the manual names no other fault for it (A20)
    Fault(50, "SC-F01", "No valid Modbus telegram received within the set time", _DA1_DB1_DC1),
    Fault(51, "SC-F02", "No valid CANopen telegram received within the set time", _DA1_DB1_DC1),
    Fault(52, "SC-F03", "Communication with the plugged-in fieldbus option interrupted", _DA1),
    Fault(53, "SC-F04", "Communication with the plugged-in I/O extension interrupted", _DA1),
    Fault(60, "OF-01", "No internal connection to an option card", _DA1),     # L910
    Fault(61, "OF-02", "Option module in an exceptional state", _DA1),
    Fault(70, "PLC-01", "Function block editor: unsupported function block", _DA1),   # L912
    Fault(71, "PLC-02", "Function block editor: program too large", _DA1),
    Fault(72, "PLC-03", "Function block editor: division by zero", _DA1),
    Fault(73, "PLC-04", "Function block editor: lower limit above upper limit", _DA1),
    Fault(74, "PLC-05", "Function block editor: table overflow", _DA1),       # L916
)}

FAULT_NONE = 0
# The fault a Modbus timeout trips with (L906), on every family: the DE1 has
# no other (A20)
COMM_LOSS_FAULT = 50


def fault_text(code: int) -> str:
    """The cause of a fault number, as Tabelle 11 gives it."""
    fault = FAULTS.get(code)
    return fault.text if fault else f"unknown fault number {code}"


def fault_display(code: int) -> str:
    """The display code of a fault number ('SC-F01' for 50); '' if unknown."""
    fault = FAULTS.get(code)
    return fault.display if fault else ""


# ---------------------------------------------------------------------------
# Parameters (Tabellen 20-24, L1178-1974)
# ---------------------------------------------------------------------------

# When a parameter may be written ("Zugriff", columns rw/ro and RUN/STOP)
RUN = "RUN"             # rw, also while the drive runs
STOP = "STOP"           # rw, only while the drive is stopped
RO = "ro"               # read-only
RESERVED = "reserved"   # "Reservierter Parameter"
U16, S16, WORD = "U16", "S16", "WORD"


@dataclass(frozen=True)
class Parameter:
    """One row of a parameter table. A register holding several parameters
    (DB1/DC1 160, 164, 168) has one row per field, with its bits."""
    register: int
    number: str             # "P1-01", "P-36"
    name: str               # the manual's designation, as printed
    mode: str               # RUN, STOP, RO or RESERVED
    scaling: str            # "Skalierung" as printed, "" where none
    range: str              # "Wertebereich" as printed
    format: str             # U16, S16, WORD, "" where none is printed
    bits: tuple | None = None   # (first bit, last bit) of a field in a shared register

    @property
    def writable(self) -> bool:
        return self.mode in (RUN, STOP)

    @property
    def writable_in_run(self) -> bool:
        return self.mode == RUN

    @property
    def scale(self) -> Scale | None:
        """The linear scale of the "Skalierung" cell, None where it is not one."""
        return Scale.parse(self.scaling)

    def _mask(self) -> tuple:
        first, last = self.bits if self.bits else (0, 15)
        return first, (1 << (last - first + 1)) - 1

    def extract(self, word: int) -> int:
        """This parameter's value in its register's word."""
        shift, mask = self._mask()
        return (word >> shift) & mask

    def insert(self, word: int, value: int) -> int:
        """The register word with this parameter set to value, the other
        fields kept (a read-modify-write of a shared register)."""
        shift, mask = self._mask()
        if not 0 <= value <= mask:
            raise ValueError(f"{self.number} {self.name}: {value} does not fit bits "
                             f"{shift}..{shift + mask.bit_length() - 1} (0..{mask})")
        return (word & ~(mask << shift) & 0xFFFF) | value << shift


HZ_60 = "3000 ≙ 50.0 Hz"    # every frequency parameter: PARAMETER_FREQUENCY
ONE = "1 ≙ 1"
_F_RANGE = "P1-02 (min: 0 Hz/0 rpm) - P1-01 (max: 500.0 Hz/30000 rpm)"
_FS_RAMP = "FS2, FS3: 1 ≙ 0.01 s FS4, ..., FS7: 1 ≙ 0.1 s"     # da1_ramp_scale

# Rows: (register or (register, first bit, last bit), number, name, mode,
# scaling, range, format), as printed; the comment is the manual line.

# DA1, Tabelle 20 (L1287-1525): register = group x 100 + index
_DA1_ROWS = (
    (101, "P1-01", "f-max", RUN, HZ_60, "P1-02 - (5 x P1-09) (max.: 500.0 Hz / 30000 rpm)", U16),  # L1287
    (102, "P1-02", "f-min", RUN, HZ_60, "0.0 Hz - P1-01", U16),  # L1288
    (103, "P1-03", "t-acc", RUN, "300 ≙ 30.0 s", "0.00 s - 6000 s", U16),  # L1289
    (104, "P1-04", "t-dec", RUN, "300 ≙ 30.0 s", "0.00 s - 6000 s", U16),  # L1290
    (105, "P1-05", "Stopp Modus", RUN, "", "0, 1, 2, 3, 4", U16),  # L1291
    (106, "P1-06", "Energieoptimierung", RUN, "", "0, 1", WORD),  # L1292
    (107, "P1-07", "Motor Nennspannung", STOP, "230 ≙ 230 V", "0 - U_e", U16),  # L1293
    (108, "P1-08", "Motor Nennstrom", STOP, "1 ≙ 0.1 A", "(0.1 - 1) x I_e", U16),  # L1294
    (109, "P1-09", "Motor Nennfrequenz", STOP, "500 ≙ 50 Hz", "10 Hz - 500 Hz", U16),  # L1295
    (110, "P1-10", "Motor Nenndrehzahl", RUN, "1500 ≙ 1500 rpm", "0 200 - 30000 rpm", U16),  # L1296
    (111, "P1-11", "U-Boost", STOP,  # L1297
     "-1 ≙ Auto 0 ≙ Disabled 1 ≙ 0.1 %", "0: Auto 0 - 30.0 % von P1-07", S16),
    (112, "P1-12", "Lokale Prozessdaten Quelle", STOP, "", "0 - 13", U16),  # L1298
    (113, "P1-13", "DI Konfiguration Auswahl", STOP, "", "0 - 21", U16),  # L1299
    (114, "P1-14", "Kennwort", RUN, "", "0 - 30000", U16),  # L1300
    (201, "P2-01", "f-Fix1", RUN, HZ_60, _F_RANGE, U16),  # L1301
    (202, "P2-02", "f-Fix2", RUN, HZ_60, _F_RANGE, U16),  # L1302
    (203, "P2-03", "f-Fix3", RUN, HZ_60, _F_RANGE, U16),  # L1303
    (204, "P2-04", "f-Fix4", RUN, HZ_60, _F_RANGE, U16),  # L1304
    (205, "P2-05", "f-Fix5", RUN, HZ_60, _F_RANGE, U16),  # L1305
    (206, "P2-06", "f-Fix6", RUN, HZ_60, _F_RANGE, U16),  # L1306
    (207, "P2-07", "f-Fix7", RUN, HZ_60, _F_RANGE, U16),  # L1307
    (208, "P2-08", "f-Fix8", RUN, HZ_60, _F_RANGE, U16),  # L1308
    (209, "P2-09", "f-Skip1", RUN, HZ_60, _F_RANGE, U16),  # L1316
    (210, "P2-10", "f-SkipBand1", RUN, HZ_60, _F_RANGE, U16),  # L1317
    (211, "P2-11", "ADO1 Funktion & Modus", RUN, "", "0, 1, ..., 11", U16),  # L1318
    (212, "P2-12", "A01 SignalFormat", RUN, "", "0, 1, ..., 5", U16),  # L1319
    (213, "P2-13", "ADO2 Funktion & Modus", RUN, "", "0, 1, ..., 11", U16),  # L1320
    (214, "P2-14", "A02 SignalFormat", RUN, "", "0, 1, ..., 5", U16),  # L1321
    (215, "P2-15", "RO1 Funktion", RUN, ONE, "0, ..., 7, 10, 11, 13", U16),  # L1322
    (216, "P2-16", "RO1 Obere Grenze", RUN, "1 ≙ 0.1 %", "P2-17 - 2000", U16),  # L1323
    (217, "P2-17", "RO1 Untere Grenze", RUN, "1 ≙ 0.1 %", "0.0 % - P2-16", U16),  # L1324
    (218, "P2-18", "RO2 Funktion", RUN, ONE, "0, ..., 7, 10, 11, 13", U16),  # L1325
    (219, "P2-19", "RO2 Obere Grenze", RUN, "1 ≙ 0.1 %", "P2-20 - 200 %", U16),  # L1326
    (220, "P2-20", "RO2 Untere Grenze", RUN, "1 ≙ 0.1 %", "0.0 % - P2-19", U16),  # L1327
    (221, "P2-21", "Anzeige Skalierung", RUN, "1 ≙ 0.001", "-30000 - +30000", U16),  # L1328
    (222, "P2-22", "Anzeige Quelle", RUN, "", "0, 1, 2, 3", U16),  # L1329
    (223, "P2-23", "t-n=0 Warten", RUN, "1 ≙ 0.1", "0.0 - 60.0 s", U16),  # L1330
    (224, "P2-24", "Schaltfrequenz", RUN, "", "0, 1, ..., 5", U16),  # L1331
    (225, "P2-25", "t-Schnellstopp", RUN, _FS_RAMP, "0.00 - 240 s", U16),  # L1332
    (226, "P2-26", "Motorfangschaltung Freigegeben", RUN, ONE, "0, 1, 2", WORD),  # L1333
    (227, "P2-27", "Standby Modus", RUN, "1 ≙ 0.01", "0.0 - 250 s", U16),  # L1334
    (228, "P2-28", "Slave Drehzahl-Skalierung", RUN, "", "0, 1, 2, 3", U16),  # L1335
    (229, "P2-29", "Slave Drehzahl-Skalierungsfaktor", RUN, "1 ≙ 0.1", "-500.0 - +500.0 %", S16),  # L1336
    (230, "P2-30", "A11 Signalbereich", RUN, "", "0, 1, ..., 7", U16),  # L1337
    (231, "P2-31", "A11 Gain", RUN, "1 ≙ 0.1", "0.0 - 2000.0 %", U16),  # L1338
    (232, "P2-32", "A11 Offset", RUN, "1 ≙ 0.1", "-500.0 - +500.0 %", S16),  # L1339
    (233, "P2-33", "A12 Signal Bereich", RUN, "", "0, 1, ..., 7", U16),  # L1340
    (234, "P2-34", "A12 Gain", RUN, "1 ≙ 0.1", "0.0 - 2000.0 %", U16),  # L1341
    (235, "P2-35", "A12 Offset", RUN, "1 ≙ 0.1", "-5000 - +5000", S16),  # L1342
    (236, "P2-36", "Start Modus", RUN, "", "0, 1, ..., 6", U16),  # L1343
    (237, "P2-37", "Digital Sollwert Reset Modus", RUN, "", "0, 1, ..., 7", U16),  # L1344
    (238, "P2-38", "Aktion@Netzausfall", RUN, "", "0, 1, 2, 3", U16),  # L1345
    (239, "P2-39", "Parametersperre", RUN, "", "0, 1", WORD),  # L1346
    (240, "P2-40", "Kennwort Level2", RUN, "", "0 - 9999", U16),  # L1347
    (301, "P3-01", "PID1 Kp", RUN, "1 ≙ 0.1", "1 - 300", U16),  # L1353
    (302, "P3-02", "PID1 Ti", RUN, "1 ≙ 0.1", "0 - 300 s", U16),  # L1354
    (303, "P3-03", "PID1 Kd", RUN, "1 ≙ 0.01", "0.00 - 100 s", U16),  # L1355
    (304, "P3-04", "PID1 Modus", RUN, "", "0, 1", WORD),  # L1356
    (305, "P3-05", "PID1 Sollwert 1 Quelle", RUN, ONE, "0, 1, 2", U16),  # L1357
    (306, "P3-06", "PID Sollwert Digital", RUN, "1 ≙ 0.1 %", "0 - 1000", U16),  # L1358
    (307, "P3-07", "PID1 Ausgang Obergrenze", RUN, "1 ≙ 0.1 %", "P3-08 - 1000", U16),  # L1359
    (308, "P3-08", "PID1 Ausgang Untergrenze", RUN, "1 ≙ 0.1 %", "0- P3-07", U16),  # L1360
    (309, "P3-09", "PID1 Ausgang GrenzeVorwahl", RUN, "", "0, 1, 2, 3", U16),  # L1361
    (310, "P3-10", "PID1 Istwert 1 Quelle", RUN, "", "0, 1", WORD),  # L1362
    (311, "P3-11", "PID1 Fehler Rampe", RUN, "1 ≙ 0.1 %", "0 - 250", U16),  # L1363
    (312, "P3-12", "PID1 Feedback 1 DispScale", RUN, "0: disabled 1 ≙ 0.001", "0.000 - 50.000", U16),  # L1364
    (313, "P3-13", "PID1 Aufweckschwelle", RUN, "1 ≙ 0.1 %", "0 - 1000", U16),  # L1365
    (314, "P3-14", "Reservierter Parameter", RESERVED, "", "", ""),  # L1366
    (315, "P3-15", "Reservierter Parameter", RESERVED, "", "", ""),  # L1367
    (316, "P3-16", "Reservierter Parameter", RESERVED, "", "", ""),  # L1368
    (317, "P3-17", "Reservierter Parameter", RESERVED, "", "", ""),  # L1369
    (318, "P3-18", "PID1 ResetControl", RUN, ONE, "0, 1", U16),  # L1370
    (401, "P4-01", "Steuerungsmodus", STOP, "", "0 - 6", U16),  # L1371
    (402, "P4-02", "Motor-Identifikation", STOP, "", "0, 1", WORD),  # L1372
    (403, "P4-03", "MSC Kp", RUN, "1 ≙ 0.1 %", "1 - 4000", U16),  # L1373
    (404, "P4-04", "MSC Ti", RUN, "1 ≙ 0.001 s", "1 - 1000", U16),  # L1374
    (405, "P4-05", "Motor CosPhi", RUN, "99 ≙ 0.99", "0,00 (= deaktiviert) 0,50 - 0,99", U16),  # L1375
    (406, "P4-06", "M-Soll Quelle", RUN, ONE, "0, 1, ..., 5", U16),  # L1376
    (407, "P4-07", "M-Max Motorbetrieb", RUN, "2000 ≙ 200.0 %", "0 - 2000", U16),  # L1377
    (408, "P4-08", "M-Min Motorbetrieb", RUN, "1 ≙ 0.1 %", "0 - 150 %", U16),  # L1378
    (409, "P4-09", "M-Max Generatorisch", RUN, "1 ≙ 1 %", "0 - 200 %", U16),  # L1379
    (410, "P4-10", "f-MidV/f", STOP, "1 ≙ 0.1 %", "0.0 - 100.0 %", U16),  # L1380
    (411, "P4-11", "V-MidV/f", RUN, "1 ≙ 0.1 %", "0.0 - 100.0 %", U16),  # L1381
    (412, "P4-12", "Thermischer Speicher Motor", RUN, ONE, "0, 1", U16),  # L1382
    (413, "P4-13", "Phasenfolge Motor drehen", RUN, ONE, "0, 1", U16),  # L1383
    (501, "P5-01", "PDP-Adresse", RUN, ONE, "1, 2, ..., 63", U16),  # L1391
    (502, "P5-02", "CAN0 Baudrate", RUN, "0 ≙ 125 kbps 1 ≙ 250 kbps", "0, 1, 2, 3", U16),  # L1392
    (503, "P5-03", "RS485-0 Baudrate", RUN, "0 ≙ 9.6 kbps 1 ≙ 19.2 kbps", "0, 1, 2, 3, 4", U16),  # L1393
    (504, "P5-04", "RS485-0 ParityType", RUN, "0 ≙ N-1 1 ≙ N-2", "0, 1, 2, 3", U16),  # L1394
    (505, "P5-05", "Modbus RTU0 COM Timeout", RUN, "1 ≙ 0.1 s", "0.0 - 5.0", U16),  # L1395
    (506, "P5-06", "Aktion@Modbus RTU Fehler", RUN, ONE, "0, 1, 2, 3", U16),  # L1396
    (507, "P5-07", "FieldbusRampControl", RUN, ONE, "0, 1", U16),  # L1397
    (508, "P5-08", "NETSendePZD4", RUN, ONE, "0, 1, ..., 7", U16),  # L1398
    (509, "P5-09", "Reservierter Parameter", RESERVED, "", "", U16),  # L1399
    (510, "P5-10", "Reservierter Parameter", RESERVED, "", "", U16),  # L1400
    (511, "P5-11", "Reservierter Parameter", RESERVED, "", "", U16),  # L1401
    (512, "P5-12", "NETSendePZD3", RUN, "", "0, 1, ..., 7", U16),  # L1402
    (513, "P5-13", "NETEmpfangsPZD4", RUN, "", "0, 1", U16),  # L1403
    (514, "P5-14", "NETEmpfangsPZD3", RUN, "", "0, 1, 2", U16),  # L1404
    (515, "P5-15", "ParameterAccess", RUN, ONE, "0, 1", U16),  # L1405
    (516, "P5-16", "Aktion@Kommunikationsverlust", RUN, ONE, "0, 1, 2, 3, 4", U16),  # L1406
    (517, "P5-17", "Modbus RTU0 Antwort Verzögerung", STOP, ONE, "0, 1, ..., 16", U16),  # L1407
    (601, "P6-01", "FirmwareUpgrade Freigegeben", STOP, ONE, "0, 1, 2, 3", U16),  # L1408
    (602, "P6-02", "Auto TemperaturManagement", RUN, ONE, "0, 1, ..., 5", WORD),  # L1409
    (603, "P6-03", "Auto Reset Verzögerung", RUN, ONE, "1 - 60", U16),  # L1410
    (604, "P6-04", "RO1 n-Hysterese", RUN, "1 ≙ 0.1 %", "0 - 250", U16),  # L1411
    (605, "P6-05", "Encoder Istwert Freigegeben", STOP, ONE, "0, 1", WORD),  # L1412
    (606, "P6-06", "Encoder PPR", STOP, "", "0 - 65535", U16),  # L1413
    (607, "P6-07", "Drehzahl Fehler Grenze", RUN, "1 ≙ 0.1 %", "0 - 500", U16),  # L1414
    (608, "P6-08", "Freq SollMax", RUN, "", "0, 5 - 20", U16),  # L1415
    (609, "P6-09", "DroopMax", RUN, "1 ≙ 0.1 %", "0 - 250", U16),  # L1416
    (610, "P6-10", "PLC Operation Freigegeben", RUN, ONE, "0, 1", WORD),  # L1417
    (611, "P6-11", "t-f-Fix vor Start", RUN, "1 ≙ 0.1 s", "0 - 2500", U16),  # L1418
    (612, "P6-12", "t-f-Fix nach Stopp", RUN, "1 ≙ 0.1 s", "0 - 2500", U16),  # L1419
    (613, "P6-13", "Bremse Lüften Verzögerung", RUN, "1 ≙ 0.1 s", "0 - 50", U16),  # L1420
    (614, "P6-14", "Bremse Schließen Verzögerung", RUN, "1 ≙ 0.1 s", "0 - 50", U16),  # L1421
    (615, "P6-15", "M vor Bremse Lüften", RUN, "1 ≙ 0.1 %", "0 - 2000", U16),  # L1422
    (616, "P6-16", "t vor Bremse Lüften", RUN, "1 ≙ 0.1 s", "0 - 250", U16),  # L1423
    (617, "P6-17", "Max Drehmoment Timeout", RUN, "1 ≙ 0.1 s", "0 - 250", U16),  # L1424
    (618, "P6-18", "DCBremseStrom", STOP, "0 ≙ Auto 1 ≙ 0.1 %", "0 : Auto 0 - 300", U16),  # L1430
    (619, "P6-19", "Bremswiderstand", RUN, ONE, "0 R_min - 200", U16),  # L1431
    (620, "P6-20", "P-Bremswiderstand", RUN, "1 ≙ 0.01 kW", "0 - 20000", U16),  # L1432
    (621, "P6-21", "Brake Chopper ED Heat-Up", RUN, "1 ≙ 0.1 %", "0 - 200", U16),  # L1433
    (622, "P6-22", "Reset Lüfterlaufzeit", RUN, ONE, "0, 1", WORD),  # L1434
    (623, "P6-23", "Reset kWh Zähler", RUN, ONE, "0, 1", WORD),  # L1435
    (624, "P6-24", "Service Intervall Zeit", RUN, ONE, "0 - 60 000 h (0 = disabled)", U16),  # L1436
    (625, "P6-25", "Reset ServiceAnzeige", RUN, ONE, "0 -1", WORD),  # L1437
    (626, "P6-26", "A01 Skalierung", RUN, "1 ≙ 0.1", "0 - 5000", U16),  # L1438
    (627, "P6-27", "A01 Offset", RUN, "1 ≙ 0.1 %", "-5000 - 5000", S16),  # L1439
    (628, "P6-28", "Zeiger auf Parameter", RUN, "", "0 - 127", U16),  # L1440
    (629, "P6-29", "Parameter Sichern", STOP, ONE, "0, 1", WORD),  # L1441
    (630, "P6-30", "Kennwort Level3", RUN, "", "0 - 9999", U16),  # L1442
    (701, "P7-01", "Motor Stator-Widerstand R1", RUN, "1 ≙ 0.001 Ω", "0.000 Ω - f (I_e)", U16),  # L1443
    (702, "P7-02", "Motor Rotor-Widerstand R2", RUN, "1 ≙ 0.001 Ω", "0.000 Ω - f (I_e)", U16),  # L1444
    (703, "P7-03", "Motor Stator Induktivität d-Achse", RUN, "1 ≙ 0.0001 H", "0.000 - 6.5535 H", U16),  # L1445
    (704, "P7-04", "Magnetisierungsstrom @M=0", RUN, "1 ≙ 0.1 A", "0.0 A - f (I_e)", U16),  # L1446
    (705, "P7-05", "Streuinduktivität Rel", RUN, "1 ≙ 0.001", "0.000 - 0.250", U16),  # L1447
    (706, "P7-06", "Motor Stator Induktivität q-Achse", RUN, "1 ≙ 0.0001 H", "0.000 - 6.5535 H", U16),  # L1448
    (707, "P7-07", "AnpassungGeneratorBetrieb", RUN, ONE, "0, 1", WORD),  # L1449
    (708, "P7-08", "ParameterAdaption", RUN, ONE, "0, 1", WORD),  # L1450
    (709, "P7-09", "Überspannung Stromgrenze", RUN, "1 ≙ 0.1 %", "0.0 - 100 % Motornennstrom", U16),  # L1451
    (710, "P7-10", "Trägheitsfaktor Last", RUN, ONE, "0 - 600", U16),  # L1452
    (711, "P7-11", "PWM untere Grenze", RUN, ONE, "0 - 500", U16),  # L1453
    (712, "P7-12", "t-Erregung-U/f", RUN, "", "0 - 2000", U16),  # L1454
    (713, "P7-13", "MSC Kd", RUN, "1 ≙ 0.1 %", "0 - 4000", U16),  # L1455
    (714, "P7-14", "Drehmomentanhebung", RUN, "1 ≙ 0.1 %", "0 - 1000", U16),  # L1456
    (715, "P7-15", "f-Drehmomentanhebung Grenze", RUN, "1 ≙ 0.1 %", "0 - 500", U16),  # L1457
    (716, "P7-16", "PM-MotorSignalIn", RUN, "", "0, 1, 2, 3", U16),  # L1458
    (717, "P7-17", "PM-MotorSignalInLevel", RUN, "", "0 - 100", U16),  # L1459
    (801, "P8-01", "t-acc2", RUN, _FS_RAMP, "0 - 60000", U16),  # L1467
    (802, "P8-02", "n-accMulti1", RUN, HZ_60, "0 - 30000", U16),  # L1468
    (803, "P8-03", "t-acc3", RUN, _FS_RAMP, "0 - 60000", U16),  # L1469
    (804, "P8-04", "n-accMulti2", RUN, HZ_60, "0 - 30000", U16),  # L1470
    (805, "P8-05", "t-acc4", RUN, _FS_RAMP, "0 - 60000", U16),  # L1471
    (806, "P8-06", "n-accMulti3", RUN, HZ_60, "0 - 30000", U16),  # L1472
    (807, "P8-07", "t-dec4", RUN, _FS_RAMP, "0 - 60000", U16),  # L1473
    (808, "P8-08", "n-decMulti3", RUN, HZ_60, "0 - 30000", U16),  # L1474
    (809, "P8-09", "t-dec3", RUN, _FS_RAMP, "0 - 60000", U16),  # L1475
    (810, "P8-10", "n-decMulti2", RUN, HZ_60, "0 - 30000", U16),  # L1476
    (811, "P8-11", "t-dec2", RUN, _FS_RAMP, "0 - 60000", U16),  # L1477
    (812, "P8-12", "n-decMulti1", RUN, HZ_60, "0 - 30000", U16),  # L1478
    (813, "P8-13", "Rampen Modus", RUN, ONE, "0, 1", WORD),  # L1479
    (901, "P9-01", "Betrieb Freigeben Quelle", STOP, ONE, "0 - 8", U16),  # L1480
    (902, "P9-02", "Stellstopp Quelle", STOP, ONE, "0 - 25", U16),  # L1481
    (903, "P9-03", "FWD Quelle", STOP, ONE, "0 - 25", U16),  # L1482
    (904, "P9-04", "REV Quelle", STOP, ONE, "0 - 25", U16),  # L1483
    (905, "P9-05", "Signalform", STOP, ONE, "0, 1", U16),  # L1484
    (906, "P9-06", "Erzwingen REV Quelle", STOP, ONE, "0 - 25", U16),  # L1485
    (907, "P9-07", "FehlerReset Quelle", STOP, ONE, "0 - 25", U16),  # L1486
    (908, "P9-08", "Externer Fehler1 Quelle", STOP, ONE, "0 - 25", U16),  # L1487
    (909, "P9-09", "LokalRemote @Einschalten", STOP, ONE, "0 - 25", U16),  # L1488
    (910, "P9-10", "Drehzahlquelle1", STOP, ONE, "0 - 16", U16),  # L1489
    (911, "P9-11", "Drehzahlquelle2", STOP, ONE, "0 - 16", U16),  # L1490
    (912, "P9-12", "Drehzahlquelle3", STOP, ONE, "0 - 16", U16),  # L1491
    (913, "P9-13", "Drehzahlquelle4", STOP, ONE, "0 - 16", U16),  # L1492
    (914, "P9-14", "Drehzahlquelle5", STOP, ONE, "0 - 16", U16),  # L1493
    (915, "P9-15", "Drehzahlquelle6", STOP, ONE, "0 - 16", U16),  # L1494
    (916, "P9-16", "Drehzahlquelle7", STOP, ONE, "0 - 16", U16),  # L1495
    (917, "P9-17", "Drehzahlquelle8", STOP, ONE, "0 - 16", U16),  # L1496
    (918, "P9-18", "Drehzahlauswahl B0", STOP, ONE, "0 - 25", U16),  # L1497
    (919, "P9-19", "Drehzahlauswahl B1", STOP, ONE, "0 - 25", U16),  # L1498
    (920, "P9-20", "Drehzahlauswahl B2", STOP, ONE, "0 - 25", U16),  # L1499
    (921, "P9-21", "f-Fix Auswahl B0", STOP, ONE, "0 - 25", U16),  # L1505
    (922, "P9-22", "f-Fix Auswahl B1", STOP, ONE, "0 - 25", U16),  # L1506
    (923, "P9-23", "f-Fix Auswahl B2", STOP, ONE, "0 - 25", U16),  # L1507
    (924, "P9-24", "t-acc Auswahl B0", STOP, ONE, "0 - 25", U16),  # L1508
    (925, "P9-25", "t-acc Auswahl B1", STOP, ONE, "0 - 25", U16),  # L1509
    (926, "P9-26", "t-dec Auswahl B0", STOP, ONE, "0 - 25", U16),  # L1510
    (927, "P9-27", "t-dec Auswahl B1", STOP, ONE, "0 - 25", U16),  # L1511
    (928, "P9-28", "digSollwert UP Quelle", STOP, ONE, "0 - 25", U16),  # L1512
    (929, "P9-29", "digSollwert DOWN Quelle", STOP, ONE, "0 - 25", U16),  # L1513
    (930, "P9-30", "Richtungsfreigabe FWD Quelle", STOP, ONE, "0 - 25", U16),  # L1514
    (931, "P9-31", "Richtungsfreigabe REV Quelle", STOP, ONE, "0 - 25", U16),  # L1515
    (932, "P9-32", "Reservierter Parameter", RESERVED, ONE, "", U16),  # L1516
    (933, "P9-33", "AD01 Funktions & Modus Erweiterung", STOP, ONE, "0, 1, 2", U16),  # L1517
    (934, "P9-34", "AD02 Funktions & Modus Erweiterung", STOP, ONE, "0, 1, 2", U16),  # L1518
    (935, "P9-35", "R01 Funktions Erweiterung", STOP, ONE, "0, 1", U16),  # L1519
    (936, "P9-36", "R02 Funktions Erweiterung", STOP, ONE, "0, 1", U16),  # L1520
    (937, "P9-37", "Anzeige Skalierung Quelle", STOP, ONE, "0, 1", U16),  # L1521
    (938, "P9-38", "PID1 Sollwert1 Quelle Ext", STOP, ONE, "0, 1", U16),  # L1522
    (939, "P9-39", "PID1 Istwert1 Quelle Ext", STOP, ONE, "0, 1", U16),  # L1523
    (940, "P9-40", "M-Ref Quelle Erweiterung", STOP, ONE, "0, 1", U16),  # L1524
    (941, "P9-41", "R05 Funktions Erweiterung", STOP, ONE, "0, 1", U16),  # L1525
)

# DB1, Tabelle 21 (L1631-1709). DC1's Tabelle 22 (L1780-1870) prints the
# same rows, a few in other words: P-02 "0.0 Hz - P-01", P-04 "0.00 s -
# 601 s" (a typo for 600 s), P-26/P-27 "3000 ≙ 50.0 Hz", P-32 low byte
# "t-DCBremse@Stopp", P-35 "100 ≙ 10.0 %"; none changes a register or a scale.
# The DB1 table has no P-52, P-53, P-57, P-58, P-69, P-70; neither has P-59.
_DB1_DC1_ROWS = (
    (129, "P-01", "f-max", RUN, HZ_60, "P-02 - (5 x P-09)", U16),  # L1631
    (130, "P-02", "f-min", RUN, HZ_60, "0 - P-01", U16),  # L1632
    (131, "P-03", "t-acc", RUN, "300 ≙ 3.00 s", "0.00 s - 600 s", U16),  # L1633
    (132, "P-04", "t-dec", RUN, "300 ≙ 3.00 s", "0.00 s - 600 s", U16),  # L1634
    (133, "P-05", "Stopp Modus", RUN, ONE, "0 - 3", U16),  # L1635
    (134, "P-06", "Energieoptimierung", RUN, ONE, "0 - 1", U16),  # L1636
    (135, "P-07", "Motor Nennspannung", STOP, "230 ≙ 230 V", "0 / 20 V - U_e", U16),  # L1637
    (136, "P-08", "Motor Nennstrom", RUN, "100 ≙ 10.0 A", "0.25 I_e - I_e", U16),  # L1638
    (137, "P-09", "Motor Nennfrequenz", STOP, "50 ≙ 50 Hz", "25 Hz - 500 Hz", U16),  # L1639
    (138, "P-10", "Motor Nenndrehzahl", RUN, ONE, "0 / 200 rpm - 30000 rpm", U16),  # L1640
    (139, "P-11", "U-Boost", RUN,  # L1646
     "100 ≙ 10.0 %", "0.0 % U_e - f (FS) FS1: 25 % U_e FS2: 20 % U_e FS3: 15 % U_e FS4: 10 % U_e", U16),
    (140, "P-12", "Lokale Prozessdaten Quelle", STOP, ONE, "0 - 13", U16),  # L1647
    (141, "P-13", "Letzter Fehler", RUN, ONE, "", U16),  # L1648
    (142, "P-14", "Kennwort", RUN, ONE, "0 - 65535", U16),  # L1649
    (143, "P-15", "DI Konfiguration Auswahl", STOP, ONE, "0-17", U16),  # L1650
    (144, "P-16", "AI1 Signal Bereich", RUN, ONE, "0 - 6", U16),  # L1651
    (145, "P-17", "Schaltfrequenz", RUN, ONE, "0 - f (I_e)", U16),  # L1652
    (146, "P-18", "RO1 Funktion", RUN, ONE, "0 - 7", U16),  # L1653
    (147, "P-19", "RO1 obere Grenze", RUN, "100 ≙ 10.0 %", "0 - 2", U16),  # L1654
    (148, "P-20", "f-Fix1", RUN, HZ_60, "f-min - f-max", U16),  # L1655
    (149, "P-21", "f-Fix2", RUN, HZ_60, "f-min - f-max", U16),  # L1656
    (150, "P-22", "f-Fix3", RUN, HZ_60, "f-min - f-max", U16),  # L1657
    (151, "P-23", "f-Fix4", RUN, HZ_60, "f-min - f-max", U16),  # L1658
    (152, "P-24", "t-Schnellstopp", RUN, "300 ≙ 3.00 s", "0.00 s - 600.0 s", U16),  # L1659
    (153, "P-25", "AO1 Funktion", RUN, ONE, "0 - 9", U16),  # L1660
    (154, "P-26", "f-SkipBand1", RUN, "3000 ≙ 50 Hz", "0.0 Hz - f-max", U16),  # L1661
    (155, "P-27", "f-Skip1", RUN, "3000 ≙ 50 Hz", "0.0 Hz - f-max", U16),  # L1662
    (156, "P-28", "U-MidU/f", STOP, "230 ≙ 230 V", "0 V - P-07", U16),  # L1663
    (157, "P-29", "f-MidU/f", STOP, HZ_60, "0 Hz - P-09", U16),  # L1664
    (158, "P-30", "Start Modus", RUN, ONE, "0 - 6", U16),  # L1665
    (159, "P-31", "Digital Sollwert Reset Modus", RUN, ONE, "0 - 3", U16),  # L1666
    ((160, 0, 7), "P-32", "t-DCBremse", RUN, "30 ≙ 3.0 s", "0.0 s - 25.0 s", U16),  # L1667
    ((160, 8, 15), "P-32", "DCBrake", RUN, ONE, "0-2", U16),  # L1668
    (161, "P-33", "Motorfangschaltung Freigeben", RUN, ONE, "0 - 1", U16),  # L1669
    (162, "P-34", "Bremschopper", RUN, ONE, "0 - 2", U16),  # L1670
    (163, "P-35", "AI1 Gain", RUN, "100 ≙ 10 %", "0 - 20", U16),  # L1671
    ((164, 0, 7), "P-36", "RS485-0 Adresse", RUN, ONE, "1 - 63", U16),  # L1672
    ((164, 8, 11), "P-36", "RS485-0 Baudrate", RUN, ONE, "0 - 6", U16),  # L1673
    ((164, 12, 15), "P-36", "Modbus RTU0 COM Timeout", RUN, ONE, "0 - 8", U16),  # L1681
    (165, "P-37", "Kennwort Level2", RUN, ONE, "0 - 9999", U16),  # L1682
    (166, "P-38", "Parametersperre", RUN, ONE, "0, 1", U16),  # L1683
    (167, "P-39", "AI1 Offset", RUN, "10 ≙ 1.0 %", "-5 - +5", U16),  # L1684
    ((168, 0, 13), "P-40", "Anzeige Skalierung", RUN, "10000 ≙ 10.000", "0 - 16.000", U16),  # L1685
    ((168, 14, 15), "P-40", "Anzeige Skalierung Quelle", RUN, ONE, "0 - 2", U16),  # L1686
    (169, "P-41", "PID1 Kp", RUN, "10 ≙ 1.0", "0,1 - 30", U16),  # L1687
    (170, "P-42", "PID1 Ti", RUN, "300 ≙ 3.00 s", "0.0 s - 30.0 s", U16),  # L1688
    (171, "P-43", "PID1 Modus", RUN, ONE, "0 - 1", U16),  # L1689
    (172, "P-44", "PID1 Sollwert 1 Quelle", RUN, ONE, "0 - 1", U16),  # L1690
    (173, "P-45", "PID1 Sollwert Digital", RUN, ONE, "0 - 1", U16),  # L1691
    (174, "P-46", "PID1 Istwert 1 Quelle", RUN, ONE, "0 - 3", U16),  # L1692
    (175, "P-47", "AI2 Signal Bereich", RUN, ONE, "0 - 6", U16),  # L1693
    (176, "P-48", "t-Standby", RUN, "300 ≙ 3.00 s", "0.0 s - 25.0 s", U16),  # L1694
    (177, "P-49", "PID1 Aufweckschwelle", RUN, ONE, "0 - 1", U16),  # L1695
    (178, "P-50", "CAN0 Baudrate", RUN, ONE, "0 - 3", U16),  # L1696
    (179, "P-51", "Thermischer Speicher Motor", RUN, ONE, "0 - 1", U16),  # L1697
    (182, "P-54", "RO1 Hysterese", RUN, ONE, "0 - 1", U16),  # L1698
    (183, "P-55", "RO1 Einschaltverzögerung", RUN, "300 ≙ 3.00 s", "0.0 s - 250.0 s", U16),  # L1699
    (184, "P-56", "Modbus Parity Type", RUN, "", "", U16),  # L1700
    (188, "P-60", "Steuerungsmodus", RUN, ONE, "0 - 4", U16),  # L1701
    (189, "P-61", "Motor-Identifikation", STOP, "300 ≙ 3.00 s", "0.0 s - 250.0 s", U16),  # L1702
    (190, "P-62", "MSC Verstärkung", RUN, "10 ≙ 1.0 %", "0.0 % - 200.0 %", U16),  # L1703
    (191, "P-63", "I-Stromgrenze", RUN, "10 ≙ 1.0 %", "0.1 % - 175 %", U16),  # L1704
    (192, "P-64", "Motor Stator Widerstand R1", RUN, "", "0.00 Ω - 655.35 Ω", U16),  # L1705
    (193, "P-65", "Motor Stator Induktivität d-Achse", RUN, "", "0.0 mH - 6553.5 mH", U16),  # L1706
    (194, "P-66", "Motor Stator Induktivität q-Achse", RUN, "", "0.0 mH - 6553.5 mH", U16),  # L1707
    (195, "P-67", "f-DCBremse@Stopp", RUN, HZ_60, "0.0 Hz - P-01", U16),  # L1708
    (196, "P-68", "DC-Bremse Strom", RUN, "10 ≙ 1.0 %", "0,0 % - 100.0 %", U16),  # L1709
)
_DC1_ONLY_ROWS = (
    (180, "P-52", "ParameterAccess", RUN, ONE, "0 - 1", U16),  # L1847
    (181, "P-53", "Aktion@Kommunikationsverlust", RUN, ONE, "0 - 4", U16),  # L1848
    (185, "P-57", "TCP Enable Service", RUN, "", "", U16),  # L1852
    (186, "P-58", "TCP0 Security Timeout", RUN, "", "", U16),  # L1853
    (197, "P-69", "LocalControl Logic1", RUN, "", "", U16),  # L1869
    (198, "P-70", "LocalControl Logic2", RUN, "", "", U16),  # L1870
)

# DE1, Tabelle 23 (L1905-1957). P-01/P-02 are STOP-only here but RUN on
# DB1/DC1; the DE1 communication table heads a "RUN, STOP" column and prints
# RUN everywhere (A33). The printed parameter range "129 - 169" ends before
# P-42 .. P-48 (A15).
_DE1_ROWS = (
    (129, "P-01", "f-max", STOP, HZ_60, "P-02 - 300 Hz", U16),  # L1905
    (130, "P-02", "f-min", STOP, HZ_60, "0 - P-01", U16),  # L1906
    (131, "P-03", "t-acc", RUN, "300 ≙ 3.00 s", "0.1 - 300 s", U16),  # L1907
    (132, "P-04", "t-dec", RUN, "300 ≙ 3.00 s", "0.1 - 300 s", U16),  # L1908
    (133, "P-05", "Stopp Modus", RUN, ONE, "0, 1", U16),  # L1909
    (134, "P-06", "Energieoptimierung", STOP, ONE, "0, 1", U16),  # L1910
    (135, "P-07", "Motor Nennspannung", STOP, "230 ≙ 230 V", "50 - 500 V", U16),  # L1911
    (136, "P-08", "Motor Nennstrom", STOP, "100 ≙ 10.0 A", "(10 - 100 %) x I_e", U16),  # L1912
    (137, "P-09", "Motor Nennfrequenz", STOP, "50 ≙ 50 Hz", "20 - 300 Hz", U16),  # L1913
    (138, "P-10", "Motor Nenndrehzahl", STOP, ONE, "0 200 - 15000 rpm", U16),  # L1914
    (139, "P-11", "U-Boost", RUN, "100 ≙ 10.0 %", "0.0 - 40.0 %", U16),  # L1915
    (140, "P-12", "Lokale Prozessdaten Quelle", RUN, ONE, "0 - 13", U16),  # L1921
    (141, "P-13", "Letzter Fehler", RO, "", "", U16),  # L1922
    (142, "P-14", "Kennwort", RUN, ONE, "0 - 65535", U16),  # L1923
    (143, "P-15", "DI Konfiguration Auswahl", STOP, ONE, "0 - 9", U16),  # L1924
    (144, "P-16", "AI1 Signal Bereich", STOP, ONE, "0- 3", U16),  # L1925
    (145, "P-17", "AI1 Gain", RUN, "10 ≙ 1", "0.10 - 2.500", U16),  # L1926
    (146, "P-18", "AI1 Invertieren", STOP, ONE, "0, 1", U16),  # L1927
    (147, "P-19", "DI3 Logik", STOP, ONE, "0, 1", U16),  # L1928
    (148, "P-20", "f-Fix1", STOP, HZ_60, "P-02 – P-01", U16),  # L1929
    (149, "P-21", "f-Fix2", STOP, HZ_60, "P-02 – P-01", U16),  # L1930
    (150, "P-22", "f-Fix3", STOP, HZ_60, "P-02 – P-01", U16),  # L1931
    (151, "P-23", "f-Fix4", STOP, HZ_60, "P-02 – P-01", U16),  # L1932
    (152, "P-24", "Digital Sollwert Reset Modus", RUN, ONE, "0, 1, 2, 3", U16),  # L1933
    (153, "P-25", "DCBremse", STOP, ONE, "0, 1, 2, 3", U16),  # L1934
    (154, "P-26", "t-DCBremse@Stop", RUN, "100 ≙ 10.0 s", "0 - 10 s", U16),  # L1935
    (155, "P-27", "DCBremseSpannung", RUN, "100 ≙ 10 %", "0 - P-07", U16),  # L1936
    (156, "P-28", "f-DCBremse@Stop", RUN, "3000 ≙ 50 Hz", "0 - P-01", U16),  # L1937
    (157, "P-29", "Schaltfrequenz", STOP, ONE, "0, 1, ..., 5", U16),  # L1938
    (158, "P-30", "Start Modus", STOP, ONE, "0, 1, ..., 10", U16),  # L1939
    (159, "P-31", "Überspannungs-Kontrolle", RUN, ONE, "0, 1", U16),  # L1940
    (160, "P-32", "Auto Temperatur-Management", STOP, ONE, "0, 1", U16),  # L1941
    (161, "P-33", "Thermischer Speicher Motor", STOP, ONE, "0, 1", U16),  # L1942
    (162, "P-34", "PDP-Address", RUN, ONE, "1 - 63", U16),  # L1943
    (163, "P-35", "RS485-0 Baudrate", RUN, ONE, "0, 1, 2, 3, 4", U16),  # L1944
    (164, "P-36", "Modbus RTU0 COM Timeout", RUN, ONE, "0, 1, ..., 8", U16),  # L1945
    (165, "P-37", "Parametertz", STOP, ONE, "0, 1", U16),  # L1946
    (166, "P-38", "Kennwort Level2", RUN, ONE, "0 - 9999", U16),  # L1947
    (167, "P-39", "Parameter sperre", RUN, ONE, "0, 1", U16),  # L1948
    (168, "P-40", "Aktion@Kommunikationsverlust", RUN, ONE, "0, 1, 2, 3, 4", U16),  # L1949
    (169, "P-41", "ParameterAccess", RUN, ONE, "0, 1", U16),  # L1950
    (170, "P-42", "f-SkipBand1", RUN, "", "", U16),  # L1951
    (171, "P-43", "f-Skip1", RUN, "", "", U16),  # L1952
    (172, "P-44", "AI1 Offset", RUN, "", "", U16),  # L1953
    (173, "P-45", "FireMode Functionality", RUN, "", "", U16),  # L1954
    (174, "P-46", "Motor-Identifikation", RUN, "", "", U16),  # L1955
    (175, "P-47", "Modbus Adresse", RUN, "", "", U16),  # L1956
    (176, "P-48", "Modbus Communication Data Format", RUN, "1", "", U16),  # L1957
)

# DE11 in addition, Tabelle 24 (L1968-1974). P-57 and P-58 sit at 183 and
# 184, not at 128 + n = 185/186 as on the DC1 (A16); the table is followed.
_DE11_ROWS = (
    (178, "P-50", "CANO Baudrate", RUN, "", "0, 1, 2, 3", U16),  # L1968
    (179, "P-51", "R01 Funktion", RUN, "", "0, 1, ..., 9", U16),  # L1969
    (180, "P-52", "R01 Obere Grenze", RUN, "", "0.0 - 200.0 %", U16),  # L1970
    (181, "P-53", "R01 Hysterese", RUN, "", "0.0 - 100.0 %", U16),  # L1971
    (182, "P-54", "R01 Einschaltverzögerung", RUN, "", "0.0 - 250.0 s", U16),  # L1972
    (183, "P-57", "TCP Enable Service", RUN, "", "0...7", U16),  # L1973
    (184, "P-58", "TCP0 Security Timeout", RUN, "", "0...60", U16),  # L1974
)


def _build(rows) -> tuple:
    params = []
    for register, number, name, mode, scaling, value_range, fmt in rows:
        bits = None
        if isinstance(register, tuple):
            register, first, last = register
            bits = (first, last)
        params.append(Parameter(register, number, name, mode, scaling, value_range, fmt, bits))
    return tuple(params)


PARAMETERS = {
    Family.DA1: _build(_DA1_ROWS),
    Family.DB1: _build(_DB1_DC1_ROWS),
    Family.DC1: _build(sorted(_DB1_DC1_ROWS + _DC1_ONLY_ROWS, key=lambda row: row[1])),
    Family.DE1: _build(_DE1_ROWS),
}
DE11_PARAMETERS = _build(_DE11_ROWS)

# Where a table contradicts the 128 + n rule (A16)
DE11_REGISTER_EXCEPTIONS = {"P-57": 183, "P-58": 184}

_DA1_NUMBER = re.compile(r"^P(\d)-(\d{1,2})$")
_COMPACT_NUMBER = re.compile(r"^P-(\d{1,2})$")


def parameter_rows(family: Family, number: str, *, de11: bool = False) -> tuple:
    """The table rows of a parameter number (more than one for the fields of
    a shared register, e.g. DB1/DC1 P-36). ValueError if the manual has none."""
    number = number.strip().upper()
    tables = PARAMETERS[family] + (DE11_PARAMETERS if family is Family.DE1 and de11 else ())
    rows = tuple(p for p in tables if p.number == number)
    if not rows:
        model = "DE11" if family is Family.DE1 and de11 else family.name
        raise ValueError(f"{number} is not in the {model} parameter table")
    return rows


def da1_parameter_register(group: int, index: int) -> int:
    """The register of DA1 parameter P<group>-<index>: group x 100 + index
    (every row of Tabelle 20 follows it, digest §3.5). ValueError for a number
    the table does not have; the P0 display values have their own registers
    (monitor_registers)."""
    if group == 0:
        raise ValueError(f"P0-{index:02d} is a display value, not in the group x 100 + index scheme: "
                         "see monitor_registers")
    parameter_rows(Family.DA1, f"P{group}-{index:02d}")
    return group * 100 + index


def compact_parameter_register(family: Family, n: int, *, de11: bool = False) -> int:
    """The register of P-<n> on a DB1, DC1 or DE1: 128 + n (digest §3.5),
    except DE11 P-57/P-58 (A16). ValueError for a number the family's table
    does not have."""
    if family is Family.DA1:
        raise ValueError(f"the DA1 numbers its parameters P<group>-<index>, it has no P-{n:02d}")
    number = f"P-{n:02d}"
    parameter_rows(family, number, de11=de11)
    if family is Family.DE1 and de11 and number in DE11_REGISTER_EXCEPTIONS:
        return DE11_REGISTER_EXCEPTIONS[number]
    return 128 + n


def parameter_register(family: Family, number: str, *, de11: bool = False) -> int:
    """The Modbus register of a parameter named as on the drive: DA1 "P1-01"
    -> 101, DC1 "P-36" -> 164. ValueError for a number of the wrong form for
    the family, or one the manual's table does not have."""
    text = number.strip().upper()
    if family is Family.DA1:
        match = _DA1_NUMBER.match(text)
        if not match:
            raise ValueError(f"DA1 parameters are named P<group>-<index> (P1-01), not {number!r}")
        return da1_parameter_register(int(match.group(1)), int(match.group(2)))
    match = _COMPACT_NUMBER.match(text)
    if not match:
        raise ValueError(f"{family.name} parameters are named P-<n> (P-01), not {number!r}")
    return compact_parameter_register(family, int(match.group(1)), de11=de11)


# Parameters the runtime names: the command source and the bus ramp switch
CONTROL_SOURCE_PARAMETER = {Family.DA1: "P1-12", Family.DB1: "P-12", Family.DC1: "P-12", Family.DE1: "P-12"}
# Values of that parameter that take commands and setpoint from Modbus:
# DA1 4 "Steuerung über Feldbus" (Modbus RTU unless a fieldbus option is
# fitted, L376); DB1/DC1 3 Modbus, 4 Modbus with ramp times from Modbus
# (L397, L413); DE1 3 (L436). The parameter is STOP-only on DA1, DB1, DC1.
MODBUS_CONTROL_SOURCES = {Family.DA1: (4,), Family.DB1: (3, 4), Family.DC1: (3, 4), Family.DE1: (3,)}
# ID 4 ramp time counts only when ramps come from the bus: DA1 P5-07
# FieldbusRampControl = 1 (L389), DB1/DC1 P-12 = 4. The DE1 has no ID 4.
DA1_FIELDBUS_RAMP_CONTROL = "P5-07"
DB1_DC1_MODBUS_RAMPS_SOURCE = 4

# ---------------------------------------------------------------------------
# Serial line settings (manual §2.3.2, §2.4)
# ---------------------------------------------------------------------------


class DataFormat(NamedTuple):
    """One character: 1 start bit, 8 data bits, parity and stop bits."""
    parity: str         # "N", "O" or "E"
    stop_bits: int


# DA1 P5-04 (L379), DB1/DC1 P-56 (L401, L424), DE1 P-48 (L447): the same codes
DATA_FORMATS = {0: DataFormat("N", 1), 1: DataFormat("N", 2), 2: DataFormat("O", 1), 3: DataFormat("E", 1)}

_BAUD_FROM_0 = {0: 9600, 1: 19200, 2: 38400, 3: 57600, 4: 115200}
_BAUD_FROM_2 = {code + 2: baud for code, baud in _BAUD_FROM_0.items()}


@dataclass(frozen=True)
class SerialSettings:
    """Where a family keeps its Modbus address, baud rate and data format,
    with the factory values of the communication tables (Tabellen 1-4)."""
    address: str                # parameter number
    baud_rate: str
    baud_codes: dict            # parameter value -> bit/s
    baud_factory: int           # parameter value
    data_format: str
    data_format_factory: int | None     # DATA_FORMATS code; None where none is printed


# Factory data formats (A5): §2.3.2 states no parity, 1 stop bit for every
# family (L336-356), the parameter tables print DC1 P-56 = 2 (odd) and DE1
# P-48 = 1 (2 stop bits), DB1 P-56 nothing. The parameter tables are kept
# here; a configuration names the format of its line explicitly.
SERIAL_SETTINGS = {
    # P5-01 range is "0 - 63" in Tabelle 1 (L377), "1, 2, ..., 63" in Tabelle 20 (A2)
    Family.DA1: SerialSettings(address="P5-01", baud_rate="P5-03", baud_codes=_BAUD_FROM_0, baud_factory=4,
                               data_format="P5-04", data_format_factory=0),        # L377-379, "n-1"
    # P-36 holds address (bits 0-7), baud rate (8-11) and timeout (12-15) of
    # register 164; baud codes 0 and 1 are not described (A4)
    Family.DB1: SerialSettings(address="P-36", baud_rate="P-36", baud_codes=_BAUD_FROM_2, baud_factory=2,
                               data_format="P-56", data_format_factory=None),     # L398-401
    Family.DC1: SerialSettings(address="P-36", baud_rate="P-36", baud_codes=_BAUD_FROM_2, baud_factory=2,
                               data_format="P-56", data_format_factory=2),        # L421-424
    # DE1: §2.6.1.1 names P-34 "PDP-Address" (162, L657), the DE1
    # communication table P-47 "Modbus-Adresse", "used as dedicated Modbus
    # communication address", 1..255 (175, L446). P-47 is taken (A1).
    # P-35 code 0 is printed "960 Bit/s", read as 9.6 kBit/s (A6).
    Family.DE1: SerialSettings(address="P-47", baud_rate="P-35", baud_codes=_BAUD_FROM_0, baud_factory=4,
                               data_format="P-48", data_format_factory=1),        # L437, L446-447
}
DE1_PDP_ADDRESS = "P-34"    # the address parameter §2.6.1.1 names for the DE1 (A1)

# ---------------------------------------------------------------------------
# Communication loss (digest §4.3)
# ---------------------------------------------------------------------------

# DA1: P5-05 "Modbus RTU0 COM Timeout": with an active connection and no
# valid telegram for this time, the drive reacts as P5-06 selects (L387).
DA1_COMM_TIMEOUT = "P5-05"                      # register 505
DA1_COMM_TIMEOUT_SCALE = Scale.of(1, "0.1", "s")    # "1 ≙ 0.1 s" (L1395)
DA1_COMM_TIMEOUT_MAX = 50                       # "0.0 - 5.0" s
# Factory value printed "2" (L387) with a 0.1 s scale: read as the keypad
# value 2.0 s, as P5-04's factory "n-1" is a display text too, not 0.2 s (A7).
DA1_COMM_TIMEOUT_FACTORY = 20
# Whether 0.0 s switches the DA1 monitoring off is not said (A7); a zero
# timeout cannot be met, so 0 is taken as "off", as code 0 of the others.
DA1_COMM_TIMEOUT_OFF = 0
DA1_COMM_LOSS_ACTION = "P5-06"                  # register 506


class Da1CommLossAction(enum.IntEnum):
    """P5-06 "Aktion@Modbus RTU Fehler" (L388); factory 0."""
    TRIP = 0                    # "Abschalten"
    RAMP_STOP_THEN_TRIP = 1     # ramps to standstill, then trips
    RAMP_STOP_NO_FAULT = 2      # ramps to standstill, no fault message
    FIXED_FREQUENCY_8 = 3       # runs at fixed frequency 8 (P2-08)


DA1_COMM_LOSS_ACTION_FACTORY = Da1CommLossAction.TRIP


class CommLossReaction(enum.Enum):
    NONE = "no reaction"
    TRIP = "trip"               # "t: Abschalten des Antriebs nach der eingestellten Zeit"
    RAMP_TO_ZERO = "ramp to zero"   # "r: ... fährt der Antrieb mit Rampe auf null"


class CommTimeout(NamedTuple):
    timeout_ms: int | None      # None: not monitored ("Die Einstellung 0 deaktiviert die Abschaltung")
    reaction: CommLossReaction


# DB1/DC1 P-36 bits 12-15 and DE1 P-36 (register 164 on all three):
# "Modbus RTU0 COM Timeout" codes (L400, L423, L445)
COMM_TIMEOUT_CODES = {
    0: CommTimeout(None, CommLossReaction.NONE),
    1: CommTimeout(30, CommLossReaction.TRIP),
    2: CommTimeout(100, CommLossReaction.TRIP),
    3: CommTimeout(1000, CommLossReaction.TRIP),
    4: CommTimeout(3000, CommLossReaction.TRIP),
    5: CommTimeout(30, CommLossReaction.RAMP_TO_ZERO),
    6: CommTimeout(100, CommLossReaction.RAMP_TO_ZERO),
    7: CommTimeout(1000, CommLossReaction.RAMP_TO_ZERO),
    8: CommTimeout(3000, CommLossReaction.RAMP_TO_ZERO),
}
COMM_TIMEOUT_PARAMETER = {Family.DB1: "P-36", Family.DC1: "P-36", Family.DE1: "P-36"}
# Factory: DB1/DC1 print "3000 ms" without t or r (L400, L423). The parameter
# describes the time until the resulting trip ("Abschaltung"), so code 4,
# t 3000 ms (A8). DE1: 0 (L445).
COMM_TIMEOUT_FACTORY_CODE = {Family.DB1: 4, Family.DC1: 4, Family.DE1: 0}

# A second loss-action parameter per family, values 0..4, whose meanings the
# manual does not give, nor how it combines with the above (A9). The DB1
# table has none.
COMM_LOSS_ACTION_PARAMETERS = {Family.DA1: "P5-16", Family.DC1: "P-53", Family.DE1: "P-40"}

# ---------------------------------------------------------------------------
# Drive type (ID 12) and power rating (ID 13), §2.6.5.7
# ---------------------------------------------------------------------------


class DriveVariant(NamedTuple):
    unit: str               # the country-specific factory unit of power, "kW" or "HP"
    mains_phases: int
    motor_phases: int


# Tabellen 12, 16, 18 (L967-977, L1025-1035, L1057-1067); DB1 Table 14 lists 0-5 only (L999-1007)
DRIVE_VARIANTS = {
    0: DriveVariant("kW", 3, 3), 1: DriveVariant("HP", 3, 3),
    2: DriveVariant("kW", 3, 1), 3: DriveVariant("HP", 3, 1),
    4: DriveVariant("kW", 1, 3), 5: DriveVariant("HP", 1, 3),
    6: DriveVariant("kW", 1, 1), 7: DriveVariant("HP", 1, 1),
}
DRIVE_VARIANT_VALUES = {Family.DA1: range(8), Family.DB1: range(6), Family.DC1: range(8), Family.DE1: range(8)}

# Rated power by frame size and power index: frame -> (kW by index, HP by
# index), None where the table prints "–". How these indices and the values
# above sit in register 12 is not said (A19).
RATED_POWER = {
    Family.DA1: {   # Tabelle 13 (L979-994); FS6 HP 12 and 15 as printed, probably truncated (A31)
        "FS2": ((0.75, 1.5, 2.2, 0.75, 1.5, 2.2, 4, None), (1, 2, 3, 1, 2, 3, 5, None)),
        "FS3": ((3, 4, 5.5, 5.5, 7.5, 11, None, None), (4, 5, 7.5, 7.5, 10, 15, None, None)),
        "FS4": ((7.5, 11, 15, 18.5, 22, None, None, None), (10, 15, 20, 25, 30, None, None, None)),
        "FS5": ((15, 18.5, 22, 30, 37, 45, None, None), (20, 25, 30, 40, 50, 60, None, None)),
        "FS6": ((22, 30, 37, 45, 45, 55, 75, 90), (30, 40, 50, 60, 60, 75, 12, 15)),
        "FS7": ((55, 75, 90, 110, 132, 160, None, None), (75, 100, 125, 175, 200, 250, None, None)),
    },
    Family.DB1: {   # Table 15 (L1009-1020)
        "FS1": ((0.37, 0.75, 0.37, 0.75, 0.75, 1.5), (0.5, 1, 0.5, 1, 1, 2)),
        "FS1B": ((0.75, 1.5, None, None, None, None), (1, 2, None, None, None, None)),
        "FS1C": ((0.75, 1.5, None, None, None, None), (1, 2, None, None, None, None)),
        "FS2": ((2.2, 4, None, None, None, None), (3, 5, None, None, None, None)),
    },
    Family.DC1: {   # Tabelle 17 (L1037-1048)
        "FS1": ((0.37, 0.75, 0.37, 0.75, 1.5, 0.75, 1.5, None, None), (0.5, 1, 0.5, 1, 2, 1, 2, None, None)),
        "FS2": ((1.1, 0.75, 1.5, 2.2, 0.75, 1.5, 2.2, 4, 3), (1.5, 1, 2, 3, 1, 2, 3, 5, 4)),
        "FS3": ((4, 5.5, 7.5, 11, 4, 3, 5.5, None, None), (5, 7.5, 10, 15, 5, 4, 7.5, None, None)),
        "FS4": ((5.5, 7.5, 11, 11, 15, 18.5, 22, None, None), (7.5, 10, 15, 15, 20, 25, 30, None, None)),
    },
    Family.DE1: {   # Tabelle 19 (L1069-1076)
        "FS1": ((0.25, 0.37, 0.55, 0.75, 1.5, 3.7, 7.5, 1.5), (0.3, 0.5, 0.7, 1, 2, 5, 10, 2)),
        "FS2": ((2.2, 2.2, 3.0, 4.0, 5.5, 7.5, None, None), (3, 3, 4, 5, 7.5, 10, None, None)),
    },
}


class Da1RatingId(NamedTuple):
    """DA1 register 12 as P0-29 "Rating ID" (L1216-1219)."""
    power_index: int        # bits 0-3, "Power Index (Internal Reference)"
    power_unit: int         # bits 4-7, "Leistungseinheit (kW/HP)"
    voltage_index: int      # bits 8-11, "Eingangsspannungsindex (Voltage Rating Index)"
    frame_size: int         # bits 12-15, "Baugröße"


def decode_da1_rating_id(word: int) -> Da1RatingId:
    return Da1RatingId(word & 0xF, (word >> 4) & 0xF, (word >> 8) & 0xF, (word >> 12) & 0xF)


# ---------------------------------------------------------------------------
# DE1 terminals with Modbus control (manual §2.5.3)
# ---------------------------------------------------------------------------


def de1_reverse(di1_ena: bool, di2_enadir: bool, control_reverse: bool) -> bool:
    """Whether a DE1 under Modbus control turns the motor in reverse
    (Tabelle 9, L603-612): the terminal direction (DI1 ENA = forward, DI2
    ENADIR = reverse) inverted by control word bit 1. The table lists one
    enabled terminal at a time; ValueError for the other combinations (with
    none the drive has no enable, L599)."""
    if di1_ena == di2_enadir:
        raise ValueError("Tabelle 9 gives the direction for DI1 (ENA) or DI2 (ENADIR) high, not "
                         + ("both" if di1_ena else "neither"))
    return di2_enadir != control_reverse


# Fixed frequencies selected with FF2⁰/FF2¹ (Tabelle 10, L622-630):
# name -> (FF2⁰, FF2¹, parameter, factory Hz)
DE1_FIXED_FREQUENCIES = {
    "FF1": (False, False, "P-20", 20.0),
    "FF2": (True, False, "P-21", 30.0),
    "FF3": (False, True, "P-22", 40.0),
    "FF4": (True, True, "P-23", 50.0),
}
