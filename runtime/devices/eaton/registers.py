"""The Eaton PowerXL register map: ID 17, wire addresses, scaling, process data, control and status words.

The DA1, DB1 and DC1 drives and the DE1 speed starter on Modbus RTU. Source:
manual 002 ("PowerXL Modbus RTU Kommunikationshandbuch für Frequenzumrichter
/ Drehzahlstarter DA1, DB1, DC1, DE1", 3rd edition 12/22,
shared/manuals/002_a23ab2a6587941cb.txt; "L<n>" below is a line of that file)
and its digest (shared/digests/002_eaton_modbus.md, "§" and the ambiguities
A1..A34 of its §8). Pure data and pure functions: the Modbus driver, the drive
simulator and the ST function blocks all read it. Frames and their CRC belong
to the Modbus layer, not here. The rest of the manual's tables: faults.py
(Tabelle 11), parameters.py (Tabellen 20-24), settings.py (serial line, comm
loss, drive variants and ratings, DE1 terminals).

    family_from_id17(5632)                    -> Family.DA1
    wire_address(REG_STATUS_WORD)             -> 5      (ID 6 travels as 0x0005)
    fault_number(0x3208), status_flags(0x3208) -> 50, StatusWord.FAULT
    SPEED.to_raw(50.0), PARAMETER_FREQUENCY.to_raw(50.0) -> 500, 3000

The names of the P0 display values are the manual's German designations, as
printed; the numbers and everything the runtime acts on have English names.
"""

from __future__ import annotations

import enum
import math
import re
from dataclasses import dataclass
from fractions import Fraction

# ---------------------------------------------------------------------------
# Families and their identification (ID 17)
# ---------------------------------------------------------------------------


class Family(enum.IntEnum):
    """The four device families of the manual. DE11 (a DE1 with CANopen and a
    relay output, Tabelle 24) is a DE1 variant, not a family of its own."""

    DA1 = 1  # variable frequency drive: STO, encoder, function-block editor
    DB1 = 2  # variable frequency drive, new in the 12/22 edition
    DC1 = 3  # compact variable frequency drive
    DE1 = 4  # variable speed starter ("Drehzahlstarter")


# ID 17 "Frequenzumrichtererkennung/Drehzahlstartererkennung" (L1086-1096):
# register value -> (family, model as printed)
DEVICE_IDENTIFICATION = {
    5632: (Family.DA1, "DA1"),  # L1088 (0x1600)
    8198: (Family.DB1, "DB1"),  # L1090 (0x2006)
    10: (Family.DC1, "DC1"),  # L1092
    8: (Family.DE1, "DE1"),  # L1094
    9: (Family.DE1, "DE11"),  # L1096
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
# this package is a register number, never a wire address.
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
BROADCAST_ADDRESS = 0  # L658: every slave executes it, none answers
UNIT_ADDRESSES = range(1, 64)  # L657 "Adresse (1 bis 63)", at most 63 nodes (L268); DE1 P-47: 1..255 (A1)
MAX_REGISTERS_PER_READ = 11  # L667: function code 03 reads at most 11 registers
# Function codes (L664-670). The column is headed "[hex]" but 16 and 23 are
# decimal, 0x10 and 0x17 (A10). The manual documents no exception responses (A12).
FUNCTION_CODES = {
    3: "Read Holding Registers",
    6: "Write Single Register",  # also as a broadcast (L1168); the slave echoes the request
    16: "Write Multiple Registers",  # printed "Set Multiple Register"
    23: "Read/Write Multiple Registers",
}


@dataclass(frozen=True)
class RegisterGroups:
    """The "Register-Mapping" table of one family (L714-735)."""

    parameters: tuple  # (first, last) parameter register as printed
    writes: tuple  # "Eingangsprozessdaten": registers the PLC writes
    reads: tuple  # "Ausgangsprozessdaten": (first, last) registers the PLC reads


# The parameter tables reach beyond the printed parameter ranges (DC1 P-70 is
# 198, DE1 P-48 is 176, DE11 up to 184: A15); parameter_register follows the tables.
REGISTER_GROUPS = {
    Family.DA1: RegisterGroups(parameters=(101, 941), writes=(1, 2, 3, 4), reads=(6, 43)),  # L718-721
    Family.DB1: RegisterGroups(parameters=(129, 197), writes=(1, 2, 4), reads=(6, 24)),  # L725-728
    Family.DC1: RegisterGroups(parameters=(129, 197), writes=(1, 2, 4), reads=(6, 24)),  # L725-728
    Family.DE1: RegisterGroups(parameters=(129, 169), writes=(1, 2), reads=(6, 24)),  # L732-735
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
    def of(cls, raw: int, value, unit: str = "") -> Scale:
        """Scale.of(3000, "50.0", "Hz") for "3000 ≙ 50.0 Hz"."""
        return cls(Fraction(str(value)) / raw, unit)

    _NOTATION = re.compile(r"^(-?\d+) ≙ (-?\d+(?:\.\d+)?) ?([^≙]*)$")

    @classmethod
    def parse(cls, text: str) -> Scale | None:
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
        exact = value if isinstance(value, (int, Fraction)) else Fraction(str(value))  # a float as written
        return _round_half_away(exact / self.step)


# Process data (IDs 1-17) count in the manual's "Skalierungsfaktor" (L755-829)
SPEED = Scale.of(1, "0.1", "Hz")  # ID 2 setpoint and ID 7 actual speed: factor 0,1 (L792, L927)
TORQUE = Scale.of(1000, "100.0", "%")  # ID 3 and ID 9: "1000 ≙ 100 %" (L801, L942)
RAMP_TIME = Scale.of(300, "3", "s")  # ID 4: "300 ≙ 3 s" (L807)
CURRENT = Scale.of(1, "0.1", "A")  # ID 8: "34 ≙ 3,4 A" (L936); 0,3 A is sent as 3 (L744)
# ID 10: the table prints factor 1 (L822), the text "kW mit einer Dezimalstelle,
# 53 ≙ 5,3 kW" (L946-948). The worked example wins (A17).
OUTPUT_POWER = Scale.of(1, "0.1", "kW")
POWER_RATING = Scale.of(1, 1, "kW")  # ID 13: factor 1, kW or HP as ID 12 says (L825)
VOLTAGE_LEVEL = Scale.of(1, 1, "V")  # ID 14 (L826)
SOFTWARE_VERSION = Scale.of(1, "0.01")  # IDs 15, 16 "mit zwei Dezimalstellen" (L1080, L1084)

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
        raise ValueError(
            f"speed setpoint {hz} Hz is outside 0 .. 6553.5 Hz; "
            "set the direction with ControlWord.REVERSE, not a negative speed"
        )
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

REG_CONTROL_WORD = 1  # "Steuerwort Feldbus"
REG_SPEED_SETPOINT = 2  # 0.1 Hz, f-min .. f-max (P1-02..P1-01, P-02..P-01)
REG_TORQUE_SETPOINT = 3  # DA1 only: 0.1 %, 0 .. 2000
REG_RAMP_TIME = 4  # DA1, DB1, DC1: 0.01 s, 0 .. 60000
REG_STATUS_WORD = 6  # status bits 0-7, fault number bits 8-15
REG_ACTUAL_SPEED = 7  # 0.1 Hz
REG_MOTOR_CURRENT = 8  # 0.1 A
REG_TORQUE = 9  # DA1, DB1, DC1: 0.1 %
REG_OUTPUT_POWER = 10  # DA1, DB1, DC1: 0.1 kW (A17)
REG_DI_STATUS = 11  # bit 0 = DI1
REG_DRIVE_TYPE = 12  # "Ausführung" (Tabellen 12-19; DA1: P0-29 Rating ID)
REG_POWER_RATING = 13  # kW or HP
REG_VOLTAGE_LEVEL = 14  # V
REG_SOFTWARE_VERSION_CONTROL = 15  # two decimals
REG_SOFTWARE_VERSION_POWER = 16  # two decimals
REG_DEVICE_ID = 17  # DEVICE_IDENTIFICATION

_ALL = frozenset(Family)
_WITH_TORQUE = frozenset({Family.DA1, Family.DB1, Family.DC1})


@dataclass(frozen=True)
class ProcessRegister:
    """One process data register (the tables of L754-758 and L817-829)."""

    register: int
    name: str
    writes: bool  # True: the PLC writes it ("Eingangsprozessdaten" of the drive)
    families: frozenset
    scale: Scale | None  # None: a bit pattern or a code
    limits: tuple | None = None  # (lowest, highest) raw value where the manual gives them


PROCESS_DATA = {
    p.register: p
    for p in (
        ProcessRegister(1, "Fieldbus control word", True, _ALL, None),  # L755
        ProcessRegister(2, "Fieldbus speed setpoint", True, _ALL, SPEED),  # L756
        ProcessRegister(3, "Torque setpoint", True, frozenset({Family.DA1}), TORQUE, (0, 2000)),  # L757, L799
        ProcessRegister(4, "Modbus ramp time", True, _WITH_TORQUE, RAMP_TIME, (0, 60000)),  # L758, L805
        ProcessRegister(6, "Status and fault word", False, _ALL, None),  # L818
        ProcessRegister(7, "Fieldbus actual speed", False, _ALL, SPEED),  # L819
        ProcessRegister(8, "Motor current", False, _ALL, CURRENT),  # L820
        # IDs 9 and 10 "nur DA1, DB1, DC1" although the DE1 read range is 6-24 too (A18)
        ProcessRegister(9, "Torque", False, _WITH_TORQUE, TORQUE),  # L821
        ProcessRegister(10, "Output power", False, _WITH_TORQUE, OUTPUT_POWER),  # L822
        ProcessRegister(11, "DI status", False, _ALL, None),  # L823, L954
        ProcessRegister(12, "Drive type", False, _ALL, None),  # L824
        ProcessRegister(13, "Power rating", False, _ALL, POWER_RATING),  # L825
        ProcessRegister(14, "Voltage level", False, _ALL, VOLTAGE_LEVEL),  # L826
        ProcessRegister(15, "Software version, control section", False, _ALL, SOFTWARE_VERSION),  # L827
        ProcessRegister(16, "Software version, power section", False, _ALL, SOFTWARE_VERSION),  # L828
        ProcessRegister(17, "Device identification", False, _ALL, None),  # L829
    )
}


def process_registers(family: Family, *, writes: bool) -> tuple:
    """The process data registers a family has, written (writes=True) or read."""
    return tuple(sorted(r.register for r in PROCESS_DATA.values() if r.writes == writes and family in r.families))


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
    number: str  # "P0-12"
    name: str  # as printed
    scaling: str = ""  # as printed
    format: str = ""

    @property
    def scale(self) -> Scale | None:
        return Scale.parse(self.scaling)


# The P0 rows of the parameter tables that print a register (digest §3.8).
# DA1 Tabelle 20 (L1182-1228). It also prints P0-35..P0-40 at 20, 21, 11,
# 22, 41, 42 (L1229-1234): the registers of P0-01..P0-06 again, a copy error
# (A26), left out here.
_DA1_MONITOR = (
    MonitorValue(20, "P0-01", "Analogeingang1", "4096 ≙ 100.0 %", "U16"),  # L1182
    MonitorValue(21, "P0-02", "Analogeingang2", "4096 ≙ 100.0 %", "U16"),  # L1183
    MonitorValue(
        11, "P0-03", "DI Status", "Bit 0 ≙ Digital-Eingang 1, Bit 1 ≙ Digital-Eingang 2, ...", "WORD"
    ),  # L1184
    MonitorValue(22, "P0-04", "f-PreRamp", "", "S16"),  # L1185
    MonitorValue(41, "P0-05", "Drehmomentsollwert", "1000 ≙ 100.0 %", "U16"),  # L1186
    MonitorValue(42, "P0-06", "MotorPoti Sollwert", "", "U16"),  # L1187
    MonitorValue(9, "P0-12", "Motordrehmoment", "1000 ≙ 100.0 %", "U16"),  # L1193
    MonitorValue(23, "P0-20", "Zwischenkreisspannung", "600 ≙ 600 V"),  # L1201
    MonitorValue(24, "P0-21", "Kühlkörpertemperatur", "40 ≙ 40 °C"),  # L1202
    MonitorValue(30, "P0-26", "kWh Zähler", "100 ≙ 10.0 kWh", "U16"),  # L1207
    MonitorValue(33, "P0-27", "MWh Zähler", "", "U16"),  # L1208
    MonitorValue(15, "P0-28", "Applikationsversion"),  # L1209
    MonitorValue(16, "P0-28", "Applikationsversion"),  # L1210
    MonitorValue(12, "P0-29", "Rating ID", "", "WORD"),  # L1216: decode_da1_rating_id
    MonitorValue(17, "P0-29", "Gerätetyp", "", "WORD"),  # L1220 (P0-29 printed twice, A26)
    MonitorValue(25, "P0-30", "Seriennummer"),  # L1221
    MonitorValue(26, "P0-30", "Seriennummer"),
    MonitorValue(27, "P0-30", "Seriennummer"),
    MonitorValue(28, "P0-30", "Seriennummer"),
    MonitorValue(34, "P0-31", "t-Run", "", "U16"),  # L1225
    MonitorValue(36, "P0-34", "t-Run Freigabe", "", "U16"),  # L1228
)

# DB1 Tabelle 21 (L1568-1628) and DC1 Tabelle 22 (L1717-1777) print the same rows
_DB1_DC1_MONITOR = (
    MonitorValue(20, "P0-01", "Analogeingang1", "4096 ≙ 100.0 %"),  # L1568
    MonitorValue(21, "P0-02", "Analogeingang2", "4096 ≙ 100.0 %"),  # L1569
    MonitorValue(2, "P0-03", "Frequenzsollwert"),  # L1570: register 2 read back
    MonitorValue(11, "P0-04", "DI Status"),  # L1571
    MonitorValue(43, "P0-07", "Motorspannung"),  # L1574
    MonitorValue(23, "P0-08", "Zwischenkreisspannung", "230 ≙ 230 V"),  # L1575
    MonitorValue(24, "P0-09", "Kühlkörpertemperatur", "40 ≙ 40 °C"),  # L1576
    MonitorValue(25, "P0-10", "t-Run (h)", "1 ≙ 1"),  # L1577
    MonitorValue(26, "P0-10", "t-Run (min/sec)", "300 ≙ 3.00 s"),  # L1578
    MonitorValue(27, "P0-14", "t-StundenRun Freigegeben (h)"),  # L1582
    MonitorValue(28, "P0-14", "t-StundenRun Freigegeben (min/sec)"),  # L1583
    MonitorValue(39, "P0-20", "T-Reglerkarte", "40 ≙ 40 °C"),  # L1589, printed "T-Reglerkarter"
    MonitorValue(15, "P0-28", "Application Version"),  # L1598, printed "15/16"
    MonitorValue(16, "P0-28", "Application Version"),
    MonitorValue(12, "P0-29", "DeviceType"),  # L1599
    MonitorValue(29, "P0-30", "Seriennummer 4", "1 ≙ 1"),  # L1600
    MonitorValue(30, "P0-30", "Seriennummer 3", "1 ≙ 1"),  # L1601
    MonitorValue(31, "P0-30", "Seriennummer 2", "1 ≙ 1"),  # L1609
    MonitorValue(32, "P0-30", "Seriennummer 1", "1 ≙ 1"),  # L1610
    MonitorValue(18, "P0-48", "Scope Channel 1& 2"),  # L1628, printed "18/19"
    MonitorValue(19, "P0-48", "Scope Channel 1& 2"),
)

# DE1 Tabelle 23 (L1882-1892): P0-02..P0-07 and P0-11..P0-22 have no register
_DE1_MONITOR = (
    MonitorValue(20, "P0-01", "Analogeingang1", "4096 ≙ 100.0 %"),  # L1882
    MonitorValue(23, "P0-08", "Zwischenkreisspannung", "230 ≙ 230 V"),  # L1889
    MonitorValue(24, "P0-09", "Kühlkörpertemperatur", "40 ≙ 40 °C"),  # L1890
    MonitorValue(25, "P0-10", "t-Run (h)", "1 ≙ 1"),  # L1891
    MonitorValue(26, "P0-10", "t-Run (min/sec)", "300 ≙ 3.00 s"),  # L1892
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
    **{51 + i: f"UserRegister {i + 1}" for i in range(15)},  # L1533-1547
    66: "User Analogausgang1",
    67: "User Analogausgang2",
    **{70 + i: f"User RO{i + 1} LogikStatus" for i in range(5)},  # L1550-1554
    75: "User Skalierwert",  # also "Drive Skalierung Wert 1" (ro), L1559
    76: "User dezimal Skalierung",  # also "Drive Skalierung Wert 2" (ro), L1560
    77: "User Geschwindigkeitsreferenz",  # printed "Geschwindikeitsreferenz"
    78: "User Drehmoment Referenz",  # printed "Deferenz"
}

# ---------------------------------------------------------------------------
# Control word (ID 1) and status word (ID 6)
# ---------------------------------------------------------------------------


class ControlWord(enum.IntFlag):
    """ID 1 "Steuerwort Feldbus" (L760-781). A cleared bit means stop,
    forward, or "keine Aktion". Bits 4 and 8-15 are not used."""

    RUN = 1 << 0  # 0 = Stopp, 1 = Betrieb
    REVERSE = 1 << 1  # 0 = Rechtsdrehfeld (FWD), 1 = Linksdrehfeld (REV)
    FAULT_RESET = 1 << 2  # "Fehler zurücksetzen"; edge or level is not said (A23)
    COAST = 1 << 3  # "Freier Auslauf"
    QUICK_STOP = 1 << 5  # "Schnellstopp (Rampe 2)": DA1 P2-25, DB1/DC1 P-24 (A23)
    FIXED_FREQUENCY_1 = 1 << 6  # "Festfrequenz FF1"
    ZERO_SETPOINT = 1 << 7  # "Sollwert mit 0 überschreiben"


#: ID 1 while the PLC holds its outputs safe (a task fault, the stop): stop
#: (bit 0 = 0), by the drive's stop mode (DA1 P1-05, DB1/DC1/DE1 P-05),
#: forward, no other function (L760-781; digest 002 §4.2); ID 2 gets 0 Hz
SAFE_CONTROL_WORD = ControlWord(0)

CONTROL_WORD_UNUSED_BITS = 0xFF10  # bit 4 and bits 8-15 "nicht verwendet" (L770, L774-781)


class StatusWord(enum.IntFlag):
    """ID 6 bits 0-7, the "Statuswort" (L831-850); bits 8-15 are the fault
    number (fault_number)."""

    READY = 1 << 0  # "Startbereit"
    RUNNING = 1 << 1  # "Betrieb Laufmeldung"
    REVERSE = 1 << 2  # 0 = FWD, 1 = REV
    FAULT = 1 << 3  # "Fehler erkannt"
    AT_SETPOINT = 1 << 4  # actual = set frequency; 0 is printed "Beschleunigungsrampe" (A21)
    ZERO_SPEED = 1 << 5  # printed "Nullzahl", read as zero speed (A21)
    SPEED_CONTROL_ACTIVE = 1 << 6  # "Drehzahlsteuerung aktiviert"
    # DA1: the STO status ("Bereit"); DB1, DC1, DE1: the hardware enable
    # (a high signal at DI1, L320, L327) is present (A21); DA1 STO: L316
    HARDWARE_ENABLE = 1 << 7


STATUS_BITS_MASK = 0x00FF
FAULT_NUMBER_SHIFT = 8  # "Fehlerwort (Bit 8 bis Bit 15)" (L833), a fault number of Tabelle 11 (A20)


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
