"""FC 280 drive parameters over CANopen: the index rule, the conversion index
and the parameters the blocks, the simulator and the examples use.

    parameter("8-03").index                    # 0x2323 (2000h + 803)
    to_raw(parameter("8-03"), 1.0)             # 10 (conversion index -1)
    from_raw(parameter("8-03"), 10)            # 1.0 s

Index rule (manual 003 §5.1, Tabelle 5.1): OD index = 2000h + the parameter
number g-nn read as the decimal g*100 + nn; sub-index 0 (an array parameter
uses its element's sub-index). Conversion index (§6.1.1, Tabelle 6.2): the
actual value is the raw value times the factor.

Decided where the manual contradicts itself (docs/contradictions.md "Danfoss FC 280 — digest 003"):
- Conversion index -6 is printed as 0.00001, the same as -5 (digest 003
  A34): taken as 0.000001, the only reading that keeps the table regular.
- Conversion index 67 is 1/60 (RPM parameters 8-90, 8-91): applied as
  printed, 100 RPM is raw 6000 (A34; other Danfoss manuals send plain RPM).
- 8-03 ranges 0.1-18000 s but is a UInt16 with index -1 (A27): what the bus
  carries is 0.1-6553.5 s; more is refused.

Rows marked "Tabelle 6.1" are the manual's; the others are parameters the
manual only names (ramps, reference range, motor data ...): their type,
conversion index and default are this simulator's choice, said per row.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from fractions import Fraction

from ...plugin.seams import ParameterValueError

FIRST_INDEX = 0x2000  # §5.1: parameter 0-00 is object 2000h

CONVERSION_FACTORS: dict[int, Fraction] = {
    100: Fraction(1),
    67: Fraction(1, 60),
    6: Fraction(10**6),
    5: Fraction(10**5),
    4: Fraction(10**4),
    3: Fraction(1000),
    2: Fraction(100),
    1: Fraction(10),
    0: Fraction(1),
    -1: Fraction(1, 10),
    -2: Fraction(1, 100),
    -3: Fraction(1, 1000),
    -4: Fraction(1, 10**4),
    -5: Fraction(1, 10**5),
    -6: Fraction(1, 10**6),  # printed 0.00001 (A34)
}

# (size in bytes, lowest, highest) of the manual's data types (Tabelle 6.1)
TYPES = {
    "UInt8": (1, 0, 0xFF),
    "UInt16": (2, 0, 0xFFFF),
    "UInt32": (4, 0, 0xFFFF_FFFF),
    "Int16": (2, -0x8000, 0x7FFF),
    "Int32": (4, -0x8000_0000, 0x7FFF_FFFF),
    "VisStr": (0, 0, 0),
}

MANUAL = "Tabelle 6.1"
CHOICE = "simulator choice"  # not in manual 003


@dataclass(frozen=True)
class Parameter:
    number: str  # "8-03", as the manual writes it
    name: str  # the manual's (German) name
    type: str  # a key of TYPES
    conversion: int | None  # Tabelle 6.2 index; None: an option [n] or a bare count
    default: int  # raw
    source: str  # MANUAL, or CHOICE for a parameter the manual only names
    unit: str = ""
    elements: int = 0  # an array parameter: its number of elements ([i] at sub-index i + 1)

    @property
    def group(self) -> int:
        return int(self.number.split("-")[0])

    @property
    def index(self) -> int:
        return index_of(self.number)

    @property
    def size(self) -> int:
        return TYPES[self.type][0]

    @property
    def signed(self) -> bool:
        return TYPES[self.type][1] < 0

    @property
    def factor(self) -> Fraction:
        return CONVERSION_FACTORS[self.conversion if self.conversion is not None else 0]


_NUMBER = re.compile(r"\s*(\d{1,2})-(\d{1,2})\s*\Z")


def split_number(text: str) -> tuple[int, int]:
    """'8-03' -> (8, 3); ValueError for anything that is no g-nn number."""
    m = _NUMBER.match(text) if isinstance(text, str) else None
    if m is None:
        raise ValueError(f"a parameter number is written g-nn, such as 8-03 (got {text!r})")
    return int(m.group(1)), int(m.group(2))


def index_of(number: str | tuple[int, int]) -> int:
    """The object index of a parameter: '8-03' or (8, 3) -> 2323h."""
    group, nn = split_number(number) if isinstance(number, str) else number
    if not (0 <= group <= 99 and 0 <= nn <= 99):
        raise ValueError(f"parameter group and number are 0..99 (got {group}-{nn:02d})")
    return FIRST_INDEX + group * 100 + nn


def number_of(index: int) -> str:
    """The parameter number of an object index in 2000h..470Fh: 2323h -> '8-03'."""
    if not FIRST_INDEX <= index <= FIRST_INDEX + 9999:
        raise ValueError(f"object {index:04X}h is no drive parameter (2000h..470Fh)")
    group, nn = divmod(index - FIRST_INDEX, 100)
    return f"{group}-{nn:02d}"


def _round_half_away(x: Fraction) -> int:
    """Rounded half away from zero, as FC280_PARAMETER rounds in ST (0.25 s
    at 0.1 s steps is 3, not Python's banker's 2)."""
    whole = int(abs(x) + Fraction(1, 2))
    return whole if x >= 0 else -whole


def to_raw(p: Parameter, value: float | int) -> int:
    """value in the parameter's unit -> the raw integer on the bus (rounded
    to the nearest step); ParameterValueError beyond what the type holds."""
    if not math.isfinite(value):
        raise ParameterValueError(f"{p.number} {p.name}: {value} is no value a parameter holds")
    raw = _round_half_away(Fraction(value) / p.factor) if p.conversion is not None else int(value)
    _size, lo, hi = TYPES[p.type]
    if not lo <= raw <= hi:
        unit = f" {p.unit}" if p.unit else ""
        raise ParameterValueError(
            f"{p.number} {p.name}: {value}{unit} is raw {raw}, outside {lo}..{hi} ({p.type}"
            + (f", conversion index {p.conversion}" if p.conversion is not None else "")
            + ")"
        )
    return raw


def from_raw(p: Parameter, raw: int) -> float:
    """The raw integer on the bus -> the value in the parameter's unit."""
    return float(raw * p.factor) if p.conversion is not None else raw


def encode(p: Parameter, raw: int) -> bytes:
    """The bytes of an expedited SDO download for a raw value (little endian)."""
    size, _lo, _hi = TYPES[p.type]
    return (raw & ((1 << (8 * size)) - 1)).to_bytes(size, "little")


def decode(p: Parameter, data: bytes) -> int:
    return int.from_bytes(data[: p.size], "little", signed=p.signed)


def _p(number, name, type_, conversion, default, source=MANUAL, unit="", elements=0) -> Parameter:
    return Parameter(number, name, type_, conversion, default, source, unit, elements)


PARAMETERS: dict[str, Parameter] = {
    p.number: p
    for p in (
        # Tabelle 5.1 (index examples) and what the blocks and examples set
        _p("0-01", "Sprache", "UInt8", None, 0, CHOICE),
        _p("0-10", "Aktiver Satz", "UInt8", None, 1, CHOICE),  # [9] Externe Anwahl: set-up from the CTW
        _p("0-11", "Programm-Satz", "UInt8", None, 1, CHOICE),
        _p("1-00", "Regelverfahren", "UInt8", None, 0, CHOICE),
        _p("1-01", "Steuerprinzip", "UInt8", None, 1, CHOICE),
        _p("1-23", "Motornennfrequenz", "UInt16", 0, 50, CHOICE, "Hz"),
        _p("1-25", "Motornenndrehzahl", "UInt16", 0, 1500, CHOICE, "RPM"),
        _p("2-01", "DC-Bremsstrom", "UInt16", 0, 50, CHOICE, "%"),
        _p("2-02", "DC-Bremszeit", "UInt16", -1, 100, CHOICE, "s"),
        _p("3-00", "Sollwertbereich", "UInt8", None, 1, CHOICE),  # [0] Min-Max, [1] -Max..+Max
        _p("3-02", "Minimaler Sollwert", "Int32", -3, 0, CHOICE, "Hz"),
        _p("3-03", "Maximaler Sollwert", "Int32", -3, 50_000, CHOICE, "Hz"),
        _p("3-10", "Festsollwert", "Int16", -2, 0, CHOICE, "%", elements=8),
        _p("3-19", "Festdrehzahl Jog [UPM]", "UInt16", 67, 300 * 60, CHOICE, "RPM"),
        _p("3-41", "Rampenzeit Auf 1", "UInt32", -2, 300, CHOICE, "s"),
        _p("3-42", "Rampenzeit Ab 1", "UInt32", -2, 300, CHOICE, "s"),
        _p("3-51", "Rampenzeit Auf 2", "UInt32", -2, 1000, CHOICE, "s"),
        _p("3-52", "Rampenzeit Ab 2", "UInt32", -2, 1000, CHOICE, "s"),
        _p("3-81", "Rampenzeit Schnellstopp", "UInt32", -2, 100, CHOICE, "s"),
        _p("4-14", "Max Frequenz [Hz]", "UInt16", -1, 650, CHOICE, "Hz"),
        _p("5-40", "Relaisfunktion", "UInt8", None, 0, CHOICE, elements=2),  # [36]/[37] CTW bit 11/12
        # Tabelle 6.1
        _p("8-01", "Führungshoheit", "UInt8", None, 0),
        _p("8-02", "Steuerquelle", "UInt8", None, 3),  # set to [3] Option A at first power-up (§3.3.1)
        _p("8-03", "Steuerwort Timeout-Zeit", "UInt16", -1, 10, MANUAL, "s"),
        _p("8-04", "Steuerwort Timeout-Funktion", "UInt8", None, 0),
        _p("8-07", "Diagnose Trigger", "UInt8", None, 0),
        _p("8-10", "Steuerwortprofil", "UInt8", None, 0),
        _p("8-14", "Konfigurierbares Steuerwort STW", "UInt8", None, 1),
        _p("8-50", "Anwahl Motorfreilauf", "UInt8", None, 3),
        _p("8-51", "Anwahl Schnellstopp", "UInt8", None, 3),
        _p("8-52", "Anwahl DC-Bremse", "UInt8", None, 3),
        _p("8-53", "Anwahl Start", "UInt8", None, 3),
        _p("8-54", "Anwahl Reversierung", "UInt8", None, 3),  # the list's [3]; notes say [0] (A25)
        _p("8-55", "Parametersatzanwahl", "UInt8", None, 3),
        _p("8-56", "Festsollwertanwahl", "UInt8", None, 3),
        _p("8-90", "Bus Festdrehzahl JOG 1", "UInt16", 67, 100 * 60, MANUAL, "RPM"),
        _p("8-91", "Bus Festdrehzahl JOG 2", "UInt16", 67, 200 * 60, MANUAL, "RPM"),
        _p("10-01", "Baudratenauswahl", "UInt8", None, 20),
        _p("10-02", "Node-ID", "UInt8", 0, 127),
        _p("10-05", "Zähler Übertragungsfehler", "UInt8", 0, 0),
        _p("10-06", "Zähler Empfangsfehler", "UInt8", 0, 0),
        _p("10-31", "Datenwerte speichern", "UInt8", None, 0),
        _p("10-33", "Immer speichern", "UInt8", None, 0),
        _p("15-40", "FC-Typ", "VisStr", None, 0, CHOICE),
        _p("15-49", "Steuerkarte SW-Version", "VisStr", None, 0, CHOICE),
        # the FC profile's objects (§4.4) and the status parameters
        _p("16-03", "Zustandswort", "UInt16", 0, 0, CHOICE),
        _p("16-05", "Hauptistwert [%]", "Int16", 0, 0, CHOICE),  # HIW, scaled as the reference (§4.4.4)
        _p("16-80", "Bus Steuerwort 1", "UInt16", 0, 0, CHOICE),
        _p("16-82", "Bus Sollwert 1", "Int16", 0, 0, CHOICE),
        _p("16-84", "Feldbus-Komm. Status", "UInt16", 0, 0),
        _p("16-90", "Alarmwort", "UInt32", 0, 0),
        _p("16-91", "Alarmwort 2", "UInt32", 0, 0),
        _p("16-92", "Warnwort", "UInt32", 0, 0),
        _p("16-93", "Warnwort 2", "UInt32", 0, 0),
        _p("16-97", "Alarmwort 3", "UInt32", 0, 0),
    )
}

# Options the blocks and the simulator name (Tabelle 6.1 and chapter 6)
PROFILE_FC = 0  # 8-10 [0] FC-Profil
PROFILE_DSP402 = 7  # 8-10: "[5] CANopen DSP 402" in §4.3.1, [7] in chapter 6 (A16): [7]
TIMEOUT_OFF, TIMEOUT_FREEZE, TIMEOUT_STOP, TIMEOUT_JOG, TIMEOUT_MAX_SPEED, TIMEOUT_STOP_AND_ALARM = range(6)  # 8-04
BAUD_CODES = {
    16: 10_000,
    17: 20_000,
    18: 50_000,
    20: 125_000,
    21: 250_000,
    22: 500_000,
    23: 800_000,
    24: 1_000_000,
}  # 10-01 (Tabelle 6.1; no [19])
FACTORY_NODE_ID = 127  # 10-02
FACTORY_BITRATE = 125_000  # 10-01 [20]


_ELEMENT = re.compile(r"\s*(\d{1,2}-\d{1,2})\s*(?:\[\s*(\d+)\s*\])?\s*\Z")


def sdo_object(name: str, value: float | int) -> tuple[int, int, int, int]:
    """A configured write ('8-03' = 1.0, '3-10[2]' = 25.0): (index, sub-index,
    size, raw). An array parameter's element [i] is sub-index i + 1, sub-index
    0 holding the count as in every CiA 301 array (digest 003 A35: the manual
    only says "the correct subindex"). ValueError for what cannot be written."""
    m = _ELEMENT.match(name) if isinstance(name, str) else None
    if m is None:
        raise ValueError(f"a parameter number is written g-nn, or g-nn[i] for an array element (got {name!r})")
    try:
        p = parameter(m.group(1))
    except KeyError as exc:
        raise ValueError(exc.args[0]) from None
    if p.type == "VisStr":
        raise ValueError(f"{p.number} {p.name} is text; only numbers can be written here")
    element = m.group(2)
    if element is not None and not p.elements:
        raise ValueError(f"{p.number} {p.name} is not an array parameter")
    if element is not None and int(element) >= p.elements:
        raise ValueError(f"{p.number} {p.name} has elements [0] to [{p.elements - 1}]")
    if element is None and p.elements:
        raise ValueError(f"{p.number} {p.name} is an array: write one element, such as {p.number}[0]")
    sub = int(element) + 1 if element is not None else 0
    return p.index, sub, p.size, to_raw(p, value)


_BY_TEXT: dict[str, Parameter] = {}  # every number text found once: the simulator asks each tick


def parameter(number: str) -> Parameter:
    """The parameter of a number ('8-03'); KeyError naming it otherwise."""
    found = _BY_TEXT.get(number)
    if found is not None:
        return found
    group, nn = split_number(number)
    key = f"{group}-{nn:02d}"
    found = PARAMETERS.get(key)
    if found is None:
        raise KeyError(f"parameter {key} is not one the softplc FC 280 support knows")
    _BY_TEXT[number] = found
    return found
