"""Eaton PowerXL settings: serial line, communication loss, drive variants and ratings, DE1 terminals.

Which parameters hold them and what their codes mean; parameters.py gives
their registers. Source: manual 002 (shared/manuals/002_a23ab2a6587941cb.txt,
"L<n>" a line of that file) and its digest (shared/digests/002_eaton_modbus.md,
"§" and the ambiguities "A<n>").
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import NamedTuple

from .registers import Family, Scale

# ---------------------------------------------------------------------------
# Serial line settings (manual §2.3.2, §2.4)
# ---------------------------------------------------------------------------


class DataFormat(NamedTuple):
    """One character: 1 start bit, 8 data bits, parity and stop bits."""

    parity: str  # "N", "O" or "E"
    stop_bits: int


# DA1 P5-04 (L379), DB1/DC1 P-56 (L401, L424), DE1 P-48 (L447): the same codes
DATA_FORMATS = {0: DataFormat("N", 1), 1: DataFormat("N", 2), 2: DataFormat("O", 1), 3: DataFormat("E", 1)}

_BAUD_FROM_0 = {0: 9600, 1: 19200, 2: 38400, 3: 57600, 4: 115200}
_BAUD_FROM_2 = {code + 2: baud for code, baud in _BAUD_FROM_0.items()}


@dataclass(frozen=True)
class SerialSettings:
    """Where a family keeps its Modbus address, baud rate and data format,
    with the factory values of the communication tables (Tabellen 1-4)."""

    address: str  # parameter number
    baud_rate: str
    baud_codes: dict  # parameter value -> bit/s
    baud_factory: int  # parameter value
    data_format: str
    data_format_factory: int | None  # DATA_FORMATS code; None where none is printed


# Factory data formats (A5): §2.3.2 states no parity, 1 stop bit for every
# family (L336-356), the parameter tables print DC1 P-56 = 2 (odd) and DE1
# P-48 = 1 (2 stop bits), DB1 P-56 nothing. The parameter tables are kept
# here; a configuration names the format of its line explicitly.
SERIAL_SETTINGS = {
    # P5-01 range is "0 - 63" in Tabelle 1 (L377), "1, 2, ..., 63" in Tabelle 20 (A2)
    Family.DA1: SerialSettings(
        address="P5-01",
        baud_rate="P5-03",
        baud_codes=_BAUD_FROM_0,
        baud_factory=4,
        data_format="P5-04",
        data_format_factory=0,
    ),  # L377-379, "n-1"
    # P-36 holds address (bits 0-7), baud rate (8-11) and timeout (12-15) of
    # register 164; baud codes 0 and 1 are not described (A4)
    Family.DB1: SerialSettings(
        address="P-36",
        baud_rate="P-36",
        baud_codes=_BAUD_FROM_2,
        baud_factory=2,
        data_format="P-56",
        data_format_factory=None,
    ),  # L398-401
    Family.DC1: SerialSettings(
        address="P-36",
        baud_rate="P-36",
        baud_codes=_BAUD_FROM_2,
        baud_factory=2,
        data_format="P-56",
        data_format_factory=2,
    ),  # L421-424
    # DE1: §2.6.1.1 names P-34 "PDP-Address" (162, L657), the DE1
    # communication table P-47 "Modbus-Adresse", "used as dedicated Modbus
    # communication address", 1..255 (175, L446). P-47 is taken (A1).
    # P-35 code 0 is printed "960 Bit/s", read as 9.6 kBit/s (A6).
    Family.DE1: SerialSettings(
        address="P-47",
        baud_rate="P-35",
        baud_codes=_BAUD_FROM_0,
        baud_factory=4,
        data_format="P-48",
        data_format_factory=1,
    ),  # L437, L446-447
}
DE1_PDP_ADDRESS = "P-34"  # the address parameter §2.6.1.1 names for the DE1 (A1)

# ---------------------------------------------------------------------------
# Communication loss (digest §4.3)
# ---------------------------------------------------------------------------

# DA1: P5-05 "Modbus RTU0 COM Timeout": with an active connection and no
# valid telegram for this time, the drive reacts as P5-06 selects (L387).
DA1_COMM_TIMEOUT = "P5-05"  # register 505
DA1_COMM_TIMEOUT_SCALE = Scale.of(1, "0.1", "s")  # "1 ≙ 0.1 s" (L1395)
DA1_COMM_TIMEOUT_MAX = 50  # "0.0 - 5.0" s
# Factory value printed "2" (L387) with a 0.1 s scale: read as the keypad
# value 2.0 s, as P5-04's factory "n-1" is a display text too, not 0.2 s (A7).
DA1_COMM_TIMEOUT_FACTORY = 20
# Whether 0.0 s switches the DA1 monitoring off is not said (A7); a zero
# timeout cannot be met, so 0 is taken as "off", as code 0 of the others.
DA1_COMM_TIMEOUT_OFF = 0
DA1_COMM_LOSS_ACTION = "P5-06"  # register 506


class Da1CommLossAction(enum.IntEnum):
    """P5-06 "Aktion@Modbus RTU Fehler" (L388); factory 0."""

    TRIP = 0  # "Abschalten"
    RAMP_STOP_THEN_TRIP = 1  # ramps to standstill, then trips
    RAMP_STOP_NO_FAULT = 2  # ramps to standstill, no fault message
    FIXED_FREQUENCY_8 = 3  # runs at fixed frequency 8 (P2-08)


DA1_COMM_LOSS_ACTION_FACTORY = Da1CommLossAction.TRIP


class CommLossReaction(enum.Enum):
    NONE = "no reaction"
    TRIP = "trip"  # "t: Abschalten des Antriebs nach der eingestellten Zeit"
    RAMP_TO_ZERO = "ramp to zero"  # "r: ... fährt der Antrieb mit Rampe auf null"


class CommTimeout(NamedTuple):
    timeout_ms: int | None  # None: not monitored ("Die Einstellung 0 deaktiviert die Abschaltung")
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
    unit: str  # the country-specific factory unit of power, "kW" or "HP"
    mains_phases: int
    motor_phases: int


# Tabellen 12, 16, 18 (L967-977, L1025-1035, L1057-1067); DB1 Table 14 lists 0-5 only (L999-1007)
DRIVE_VARIANTS = {
    0: DriveVariant("kW", 3, 3),
    1: DriveVariant("HP", 3, 3),
    2: DriveVariant("kW", 3, 1),
    3: DriveVariant("HP", 3, 1),
    4: DriveVariant("kW", 1, 3),
    5: DriveVariant("HP", 1, 3),
    6: DriveVariant("kW", 1, 1),
    7: DriveVariant("HP", 1, 1),
}
DRIVE_VARIANT_VALUES = {Family.DA1: range(8), Family.DB1: range(6), Family.DC1: range(8), Family.DE1: range(8)}

# Rated power by frame size and power index: frame -> (kW by index, HP by
# index), None where the table prints "–". How these indices and the values
# above sit in register 12 is not said (A19).
RATED_POWER = {
    Family.DA1: {  # Tabelle 13 (L979-994); FS6 HP 12 and 15 as printed, probably truncated (A31)
        "FS2": ((0.75, 1.5, 2.2, 0.75, 1.5, 2.2, 4, None), (1, 2, 3, 1, 2, 3, 5, None)),
        "FS3": ((3, 4, 5.5, 5.5, 7.5, 11, None, None), (4, 5, 7.5, 7.5, 10, 15, None, None)),
        "FS4": ((7.5, 11, 15, 18.5, 22, None, None, None), (10, 15, 20, 25, 30, None, None, None)),
        "FS5": ((15, 18.5, 22, 30, 37, 45, None, None), (20, 25, 30, 40, 50, 60, None, None)),
        "FS6": ((22, 30, 37, 45, 45, 55, 75, 90), (30, 40, 50, 60, 60, 75, 12, 15)),
        "FS7": ((55, 75, 90, 110, 132, 160, None, None), (75, 100, 125, 175, 200, 250, None, None)),
    },
    Family.DB1: {  # Table 15 (L1009-1020)
        "FS1": ((0.37, 0.75, 0.37, 0.75, 0.75, 1.5), (0.5, 1, 0.5, 1, 1, 2)),
        "FS1B": ((0.75, 1.5, None, None, None, None), (1, 2, None, None, None, None)),
        "FS1C": ((0.75, 1.5, None, None, None, None), (1, 2, None, None, None, None)),
        "FS2": ((2.2, 4, None, None, None, None), (3, 5, None, None, None, None)),
    },
    Family.DC1: {  # Tabelle 17 (L1037-1048)
        "FS1": ((0.37, 0.75, 0.37, 0.75, 1.5, 0.75, 1.5, None, None), (0.5, 1, 0.5, 1, 2, 1, 2, None, None)),
        "FS2": ((1.1, 0.75, 1.5, 2.2, 0.75, 1.5, 2.2, 4, 3), (1.5, 1, 2, 3, 1, 2, 3, 5, 4)),
        "FS3": ((4, 5.5, 7.5, 11, 4, 3, 5.5, None, None), (5, 7.5, 10, 15, 5, 4, 7.5, None, None)),
        "FS4": ((5.5, 7.5, 11, 11, 15, 18.5, 22, None, None), (7.5, 10, 15, 15, 20, 25, 30, None, None)),
    },
    Family.DE1: {  # Tabelle 19 (L1069-1076)
        "FS1": ((0.25, 0.37, 0.55, 0.75, 1.5, 3.7, 7.5, 1.5), (0.3, 0.5, 0.7, 1, 2, 5, 10, 2)),
        "FS2": ((2.2, 2.2, 3.0, 4.0, 5.5, 7.5, None, None), (3, 3, 4, 5, 7.5, 10, None, None)),
    },
}


class Da1RatingId(NamedTuple):
    """DA1 register 12 as P0-29 "Rating ID" (L1216-1219)."""

    power_index: int  # bits 0-3, "Power Index (Internal Reference)"
    power_unit: int  # bits 4-7, "Leistungseinheit (kW/HP)"
    voltage_index: int  # bits 8-11, "Eingangsspannungsindex (Voltage Rating Index)"
    frame_size: int  # bits 12-15, "Baugröße"


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
        raise ValueError(
            "Tabelle 9 gives the direction for DI1 (ENA) or DI2 (ENADIR) high, not "
            + ("both" if di1_ena else "neither")
        )
    return di2_enadir != control_reverse


# Fixed frequencies selected with FF2⁰/FF2¹ (Tabelle 10, L622-630):
# name -> (FF2⁰, FF2¹, parameter, factory Hz)
DE1_FIXED_FREQUENCIES = {
    "FF1": (False, False, "P-20", 20.0),
    "FF2": (True, False, "P-21", 30.0),
    "FF3": (False, True, "P-22", 40.0),
    "FF4": (True, True, "P-23", 50.0),
}
