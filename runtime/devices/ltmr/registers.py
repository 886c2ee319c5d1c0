"""The LTMR register map: register numbers, their CANopen objects and the register table of manual 001.

The Schneider TeSys T LTMR motor controller on CANopen. Source: manual 001
(DOCA0132EN, "Using the CANopen Communication Network",
shared/manuals/001_5287ad2b8a6c20a4.txt; "L<n>" below is a line of that file)
and its digest (shared/digests/001_ltmr_canopen_en.md, "§" and the
ambiguities A1..A26 of its §10). Pure data and pure functions: the
simulator, the CANopen master, the EDS generator and the ST constants all
read it. The rest of the manual's register chapter: bits.py (the bits of the
Word registers), codes.py (enumerations, trip and alarm codes), datatypes.py
(DT_DateTime, DT_CommercialReference, two-word values); its object
dictionary chapter: profile.py.

    register_to_object(455)          -> (0x2004, 0x06)
    REGISTERS[455].name              -> 'System status register 1'
    scaled_value(REG_FREQUENCY, 5000) -> 50.0
"""

from __future__ import annotations

import re
from dataclasses import dataclass

from .datatypes import int16

# ---------------------------------------------------------------------------
# Register number <-> CANopen object (digest §5.2; the manual prints no formula)
# ---------------------------------------------------------------------------

# (first register, last register, CANopen index): sub-index = register - first + 1.
# The blocks are irregular (700 -> 0x2008, not 0x2007). 1200-1399 use 0x200D
# with sub-indices 0x01..0xC8 as the detailed tables print them (A8).
REGISTER_BLOCKS = (
    (0, 99, 0x2000),  # identification, L2288-2394
    (100, 149, 0x2001),  # global and LTM monitoring statistics, L2434-2643
    (150, 299, 0x2002),  # trip history n-0..n-4, main tables, L2655-3199
    (300, 449, 0x2003),  # trip history extensions, L3210-3383
    (450, 539, 0x2004),  # monitoring, L3412-4006
    (540, 599, 0x2005),  # configuration, L4030-4322
    (600, 649, 0x2006),  # configuration, L4326-4720
    (650, 699, 0x2007),  # setting, L4724-4895
    (700, 799, 0x2008),  # command, L4908-4960
    (1200, 1399, 0x200D),  # custom logic, L4972-5096 (A8)
)

# The group table (L4015-4023) says "200C : 01 to 200D : 64" instead: 1200-1299 in
# 0x200C, 1300-1399 in 0x200D. Kept as an alternative for a device that proves it (A8).
_CUSTOM_LOGIC_SPLIT = ((1200, 1299, 0x200C), (1300, 1399, 0x200D))

# "Forbidden, means that read or write requests are rejected" (L1717-1723):
# 97-99 (L2394), 524-539 (L4006), 710-799 (printed "707-799", L4960, typo A9).
FORBIDDEN_RANGES = ((97, 99), (524, 539), (710, 799))


class UnmappedRegisterError(ValueError):
    """A register number or CANopen object the LTMR register map does not have."""


class ForbiddenRegisterError(ValueError):
    """A register the manual marks Forbidden: not accessible at all."""


def is_forbidden(reg: int) -> bool:
    return any(first <= reg <= last for first, last in FORBIDDEN_RANGES)


def _blocks(split_custom_logic: bool):
    return REGISTER_BLOCKS[:-1] + _CUSTOM_LOGIC_SPLIT if split_custom_logic else REGISTER_BLOCKS


def register_to_object(reg: int, *, split_custom_logic: bool = False) -> tuple:
    """The CANopen (index, sub-index) of a register number.
    UnmappedRegisterError for numbers outside the map (<0, 800-1199, >1399),
    ForbiddenRegisterError for the Forbidden ranges (both are ValueErrors)."""
    for first, last, index in _blocks(split_custom_logic):
        if first <= reg <= last:
            if is_forbidden(reg):
                raise ForbiddenRegisterError(f"LTMR register {reg} is Forbidden (not accessible)")
            return index, reg - first + 1
    raise UnmappedRegisterError(f"LTMR register {reg} has no CANopen address (the map covers 0-799 and 1200-1399)")


def object_to_register(index: int, subindex: int, *, split_custom_logic: bool = False) -> int:
    """The register number of a CANopen manufacturer object; the inverse of
    register_to_object, with the same errors."""
    for first, last, block_index in _blocks(split_custom_logic):
        if index == block_index:
            reg = first + subindex - 1
            if not first <= reg <= last:
                raise UnmappedRegisterError(
                    f"LTMR object 0x{index:04X}:{subindex:02X} has no register "
                    f"(sub-index 0x01..0x{last - first + 1:02X})"
                )
            if is_forbidden(reg):
                raise ForbiddenRegisterError(
                    f"LTMR object 0x{index:04X}:{subindex:02X} (register {reg}) is Forbidden (not accessible)"
                )
            return reg
    raise UnmappedRegisterError(f"0x{index:04X} is not an LTMR register object (0x2000-0x2008, 0x200D)")


# ---------------------------------------------------------------------------
# The register table (digest §6, manual L2279-5098)
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Register:
    """One 16-bit register. A value spread over several registers (UDInt,
    Word[n]) has one Register per word; `first` and `words` tie them together."""

    number: int
    name: str
    type: str  # 'UInt', 'Int', 'Word', 'UDInt', 'DInt', 'Word[n]' as printed; '' if unused
    access: str  # 'ro' (0-539, 1200-1399) or 'rw' (540-799), §5.3
    scale: float = 1  # 0.01 for "x 0.01 A"
    unit: str = ""
    notes: str = ""  # 1/2: needs the LTMEV40 expansion; A: motor off; B: config mode; C: no trip
    kind: str = "value"  # 'value', 'reserved', 'not significant', 'forbidden'
    format: str = ""  # the manual's DT_* data type, when it names one
    first: int = -1  # the register where the value starts (= number for one-word values)
    words: int = 1  # how many registers the value spans

    @property
    def signed(self) -> bool:
        return self.type in ("Int", "DInt")

    @property
    def writable(self) -> bool:
        return self.access == "rw" and self.kind != "forbidden"


# Rows of the detailed tables: (first, last, type, name, unit, notes, DT format).
# Unused rows name their kind in parentheses as the manual does. Units are
# copied as printed (A19); typed "Ulnt" in the manual, spelled UInt here.
_TABLE = (
    # identification, index 0x2000, read-only
    (0, 34, "", "(Not significant)", "", "", ""),  # L2288, printed 2000:03-2000:28 (A9)
    (35, 40, "Word[6]", "Expansion commercial reference", "", "1", "DT_CommercialReference"),  # L2292 (A9)
    (41, 45, "Word[5]", "Expansion serial number", "", "1", ""),
    (46, 46, "UInt", "Expansion ID code", "", "1", ""),
    (47, 47, "UInt", "Expansion firmware version", "", "1", "DT_FirmwareVersion"),
    (48, 48, "UInt", "Expansion compatibility code", "", "1", ""),
    (49, 60, "", "(Not significant)", "", "", ""),
    (61, 61, "UInt", "Network port ID code", "", "", ""),
    (62, 62, "UInt", "Network port firmware version", "", "", "DT_FirmwareVersion"),
    (63, 63, "UInt", "Network port compatibility code", "", "", ""),
    (64, 69, "Word[6]", "Controller commercial reference", "", "", "DT_CommercialReference"),
    (70, 74, "Word[5]", "Controller serial number", "", "", ""),
    (75, 75, "UInt", "Controller ID code", "", "", ""),
    (76, 76, "UInt", "Controller firmware version", "", "", "DT_FirmwareVersion"),
    (77, 77, "UInt", "Controller compatibility code", "", "", ""),
    (78, 78, "UInt", "Current scale ratio", "0.1 %", "", ""),
    (79, 79, "UInt", "Current sensor max", "", "", ""),
    (80, 80, "", "(Not significant)", "", "", ""),
    (81, 81, "UInt", "Current range max", "x 0.1 A", "", ""),
    (82, 94, "", "(Not significant)", "", "", ""),  # L2380, printed 2000:53-2000:58 (A9)
    (95, 95, "UInt", "Load CT ratio", "x 0.1 A", "", ""),
    (96, 96, "UInt", "Full load current max", "x 0.1 A", "", ""),  # L2389: maximum FLC range
    (97, 99, "", "(Forbidden)", "", "", ""),  # L2394
    # global statistics, 0x2001, read-only
    (100, 101, "", "(Not significant)", "", "", ""),
    (102, 102, "UInt", "Ground current trips count", "", "", ""),
    (103, 103, "UInt", "Thermal overload trips count", "", "", ""),
    (104, 104, "UInt", "Long start trips count", "", "", ""),
    (105, 105, "UInt", "Jam trips count", "", "", ""),
    (106, 106, "UInt", "Current phase imbalance trips count", "", "", ""),
    (107, 107, "UInt", "Undercurrent trips count", "", "", ""),
    (108, 108, "", "(Not significant)", "", "", ""),  # not listed at all (A17)
    (109, 109, "UInt", "HMI port trips count", "", "", ""),
    (110, 110, "UInt", "Controller internal trips count", "", "", ""),
    (111, 111, "UInt", "Internal port trips count", "", "", ""),
    (112, 112, "", "(Not significant)", "", "", ""),
    (113, 113, "UInt", "Network port config trips count", "", "", ""),
    (114, 114, "UInt", "Network port trips count", "", "", ""),
    (115, 115, "UInt", "Auto-resets count", "", "", ""),
    (116, 116, "UInt", "Thermal overload alarms count", "", "", ""),
    (117, 118, "UDInt", "Motor starts count", "", "", ""),
    (119, 120, "UDInt", "Operating time", "s", "", ""),
    (121, 121, "Int", "Controller internal temperature max", "°C", "", ""),
    # LTM monitoring statistics, 0x2001
    (122, 122, "UInt", "Trips count", "", "", ""),
    (123, 123, "UInt", "Alarms count", "", "", ""),
    (124, 125, "UDInt", "Motor LO1 closings count", "", "", ""),
    (126, 127, "UDInt", "Motor LO2 closings count", "", "", ""),
    (128, 128, "UInt", "Diagnostic trips count", "", "", ""),
    (129, 129, "", "(Reserved)", "", "", ""),
    (130, 130, "UInt", "Overcurrent trips count", "", "", ""),
    (131, 131, "UInt", "Current phase loss trips count", "", "", ""),
    (132, 132, "UInt", "Motor temperature sensor trips count", "", "", ""),
    (133, 133, "UInt", "Voltage phase imbalance trips count", "", "1", ""),
    (134, 134, "UInt", "Voltage phase loss trips count", "", "1", ""),
    (135, 135, "UInt", "Wiring trips count", "", "1", ""),
    (136, 136, "UInt", "Undervoltage trips count", "", "1", ""),
    (137, 137, "UInt", "Overvoltage trips count", "", "1", ""),
    (138, 138, "UInt", "Underpower trips count", "", "1", ""),
    (139, 139, "UInt", "Overpower trips count", "", "1", ""),
    (140, 140, "UInt", "Under power factor trips count", "", "1", ""),
    (141, 141, "UInt", "Over power factor trips count", "", "1", ""),
    (142, 142, "UInt", "Load sheddings count", "", "1", ""),
    (143, 144, "UDInt", "Active power consumption", "kWh", "1", ""),
    (145, 146, "UDInt", "Reactive power consumption", "kVARh", "1", ""),
    (147, 147, "UInt", "Auto restart immediate count", "", "", ""),
    (148, 148, "UInt", "Auto restart delayed count", "", "", ""),
    (149, 149, "UInt", "Auto restart manual count", "", "", ""),
    # 150-449: the five trip history tables, built by _trip_history_rows below
    # monitoring, 0x2004, read-only (L3412-4006)
    (450, 450, "UInt", "Minimum wait time", "s", "", ""),
    (451, 451, "UInt", "Trip code", "", "", "DT_FaultCode"),  # of the last trip, or of the one that takes priority
    (452, 452, "Word", "Trip register 1", "", "", ""),
    (453, 453, "Word", "Trip register 2", "", "", ""),
    (454, 454, "Word", "Trip register 3", "", "", ""),
    (455, 455, "Word", "System status register 1", "", "", ""),
    (456, 456, "Word", "System status register 2", "", "", ""),
    (457, 457, "Word", "Logic inputs status", "", "", ""),
    (458, 458, "Word", "Logic outputs status", "", "", ""),
    (459, 459, "Word", "I/O status", "", "", ""),
    (460, 460, "UInt", "Alarm code", "", "", "DT_WarningCode"),
    (461, 461, "Word", "Alarm register 1", "", "", ""),
    (462, 462, "Word", "Alarm register 2", "", "", ""),
    (463, 463, "Word", "Alarm register 3", "", "", ""),
    (464, 464, "UInt", "Motor temperature sensor degree", "°C", "", ""),  # type not printed: UInt (A17)
    (465, 465, "UInt", "Thermal capacity level", "% trip level", "", ""),
    (466, 466, "UInt", "Average current ratio", "% FLC", "", ""),
    (467, 467, "UInt", "L1 current ratio", "% FLC", "", ""),
    (468, 468, "UInt", "L2 current ratio", "% FLC", "", ""),
    (469, 469, "UInt", "L3 current ratio", "% FLC", "", ""),
    (470, 470, "UInt", "Ground current ratio", "x 0.1 % FLC min", "", ""),
    (471, 471, "UInt", "Current phase imbalance", "%", "", ""),
    (472, 472, "Int", "Controller internal temperature", "°C", "", ""),
    (473, 473, "UInt", "Controller config checksum", "", "", ""),
    (474, 474, "UInt", "Frequency", "x 0.01 Hz", "2", ""),
    (475, 475, "UInt", "Motor temperature sensor", "x 0.1 Ω", "", ""),
    (476, 476, "UInt", "Average voltage", "V", "1", ""),
    (477, 477, "UInt", "L3-L1 voltage", "V", "1", ""),
    (478, 478, "UInt", "L1-L2 voltage", "V", "1", ""),
    (479, 479, "UInt", "L2-L3 voltage", "V", "1", ""),
    (480, 480, "UInt", "Voltage phase imbalance", "%", "1", ""),
    (481, 481, "UInt", "Power factor", "x 0.01", "1", ""),
    (482, 482, "UInt", "Active power", "x 0.1 kW", "1", ""),
    (483, 483, "UInt", "Reactive power", "x 0.1 kVAR", "1", ""),
    (484, 484, "Word", "Auto restart status register", "", "", ""),
    (485, 489, "", "(Not significant)", "", "", ""),
    (490, 490, "Word", "Network port status", "", "", ""),
    (491, 491, "UInt", "Network port baud rate", "", "", "DT_ExtBaudRate"),
    (492, 492, "", "(Not significant)", "", "", ""),
    (493, 493, "UInt", "Network port parity", "", "", "DT_ExtParity"),
    (494, 499, "", "(Not significant)", "", "", ""),
    (500, 501, "UDInt", "Average current", "x 0.01 A", "", ""),
    (502, 503, "UDInt", "L1 current", "x 0.01 A", "", ""),
    (504, 505, "UDInt", "L2 current", "x 0.01 A", "", ""),
    (506, 507, "UDInt", "L3 current", "x 0.01 A", "", ""),
    (508, 509, "UDInt", "Ground current", "mA", "", ""),
    (510, 510, "UInt", "Controller port ID", "", "", ""),
    (511, 511, "UInt", "Time to trip", "x 1 s", "", ""),
    (512, 512, "UInt", "Motor last start current ratio", "% FLC", "", ""),
    (513, 513, "UInt", "Motor last start duration", "s", "", ""),
    (514, 514, "UInt", "Motor starts per hour count", "", "", ""),
    (515, 515, "Word", "Phase imbalances register", "", "", ""),
    (516, 523, "", "(Reserved)", "", "1", ""),
    (524, 539, "", "(Forbidden)", "", "1", ""),  # L4006
    # configuration, 0x2005/0x2006, read/write (L4030-4720)
    (540, 540, "UInt", "Motor operating mode", "", "B", ""),  # L4030, values in OperatingMode
    (541, 541, "UInt", "Motor transition timeout", "s", "", ""),
    (542, 544, "", "(Reserved)", "", "", ""),
    (545, 545, "Word", "Controller AC inputs setting register", "", "", ""),
    (546, 546, "UInt", "Thermal overload setting", "", "B", ""),
    (547, 547, "UInt", "Thermal overload trip definite timeout", "s", "", ""),
    (548, 548, "", "(Reserved)", "", "", ""),
    (549, 549, "UInt", "Motor temperature sensor trip threshold", "x 0.1 Ω", "", ""),
    (550, 550, "UInt", "Motor temperature sensor alarm threshold", "x 0.1 Ω", "", ""),
    (551, 551, "UInt", "Motor temperature sensor trip threshold degree", "°C", "", ""),
    (552, 552, "UInt", "Motor temperature sensor alarm threshold degree", "°C", "", ""),
    (553, 553, "UInt", "Rapid cycle lockout timeout", "s", "", ""),
    (554, 554, "", "(Reserved)", "", "", ""),
    (555, 555, "UInt", "Current phase loss timeout", "x 0.1 s", "", ""),
    (556, 556, "UInt", "Overcurrent trip timeout", "s", "", ""),
    (557, 557, "UInt", "Overcurrent trip threshold", "% FLC", "", ""),
    (558, 558, "UInt", "Overcurrent alarm threshold", "% FLC", "", ""),
    (559, 559, "Word", "Ground current trip configuration", "", "B", ""),
    # 560/561 and 628/629 are printed "client"/"server": primary/secondary (A18, MANUAL_NAMES)
    (560, 560, "UInt", "Ground current sensor primary", "", "", ""),
    (561, 561, "UInt", "Ground current sensor secondary", "", "", ""),
    (562, 562, "UInt", "External ground current trip timeout", "x 0.01 s", "", ""),
    (563, 563, "UInt", "External ground current trip threshold", "x 0.01 A", "", ""),
    (564, 564, "UInt", "External ground current alarm threshold", "x 0.01 A", "", ""),
    (565, 565, "UInt", "Motor nominal voltage", "V", "1", ""),
    (566, 566, "UInt", "Voltage phase imbalance trip timeout starting", "x 0.1 s", "1", ""),
    (567, 567, "UInt", "Voltage phase imbalance trip timeout running", "x 0.1 s", "1", ""),
    (568, 568, "UInt", "Voltage phase imbalance trip threshold", "% imb", "1", ""),
    (569, 569, "UInt", "Voltage phase imbalance alarm threshold", "% imb", "1", ""),
    (570, 570, "UInt", "Overvoltage trip timeout", "x 0.1 s", "1", ""),
    (571, 571, "UInt", "Overvoltage trip threshold", "x Vnom", "1", ""),
    (572, 572, "UInt", "Overvoltage alarm threshold", "x Vnom", "1", ""),
    (573, 573, "UInt", "Undervoltage trip timeout", "x 0.1 s", "1", ""),
    (574, 574, "UInt", "Undervoltage trip threshold", "x Vnom", "1", ""),
    (575, 575, "UInt", "Undervoltage alarm threshold", "x Vnom", "1", ""),
    (576, 576, "UInt", "Voltage phase loss trip timeout", "x 0.1 s", "1", ""),
    (577, 577, "Word", "Voltage dip setting", "", "1", ""),
    (578, 578, "UInt", "Load shedding timeout", "s", "1", ""),
    (579, 579, "UInt", "Voltage dip threshold", "% Vnom", "1", ""),
    (580, 580, "UInt", "Voltage dip restart timeout", "s", "1", ""),
    (581, 581, "UInt", "Voltage dip restart threshold", "% Vnom", "1", ""),
    (582, 582, "UInt", "Auto restart immediate timeout", "x 0.1 s", "", ""),
    (583, 583, "UInt", "Motor nominal power", "x 0.1 kW", "1", ""),
    (584, 584, "UInt", "Overpower trip timeout", "s", "1", ""),
    (585, 585, "UInt", "Overpower trip threshold", "% Pnom", "1", ""),
    (586, 586, "UInt", "Overpower alarm threshold", "% Pnom", "1", ""),
    (587, 587, "UInt", "Underpower trip timeout", "s", "1", ""),
    (588, 588, "UInt", "Underpower trip threshold", "% Pnom", "1", ""),
    (589, 589, "UInt", "Underpower alarm threshold", "% Pnom", "1", ""),
    (590, 590, "UInt", "Under power factor trip timeout", "x 0.1 s", "1", ""),
    (591, 591, "UInt", "Under power factor trip threshold", "x 0.01 PF", "1", ""),
    (592, 592, "UInt", "Under power factor alarm threshold", "x 0.01 PF", "1", ""),
    (593, 593, "UInt", "Over power factor trip timeout", "x 0.1 s", "1", ""),
    (594, 594, "UInt", "Over power factor trip threshold", "x 0.01 PF", "1", ""),
    (595, 595, "UInt", "Over power factor alarm threshold", "x 0.01 PF", "1", ""),
    (596, 596, "UInt", "Auto restart delayed timeout", "s", "", ""),  # type not printed: UInt (A17)
    (597, 599, "", "(Reserved)", "", "", ""),
    (600, 600, "", "(Not significant)", "", "", ""),
    (601, 601, "Word", "General configuration register 1", "", "", ""),  # per-bit notes: BIT_NOTES
    (602, 602, "Word", "General configuration register 2", "", "", ""),
    (603, 603, "UInt", "HMI port address setting", "", "", ""),
    (604, 604, "UInt", "HMI port baud rate setting", "Baud", "", ""),
    (605, 605, "", "(Reserved)", "", "", ""),
    (606, 606, "UInt", "Motor trip class", "s", "", ""),
    (607, 607, "", "(Reserved)", "", "", ""),
    (608, 608, "UInt", "Thermal overload trip reset threshold", "% trip level", "", ""),
    (609, 609, "UInt", "Thermal overload alarm threshold", "% trip level", "", ""),
    (610, 610, "UInt", "Internal ground current trip timeout", "x 0.1 s", "", ""),
    (611, 611, "UInt", "Internal ground current trip threshold", "% FLCmin", "", ""),
    (612, 612, "UInt", "Internal ground current alarm threshold", "% FLCmin", "", ""),
    (613, 613, "UInt", "Current phase imbalance trip timeout starting", "x 0.1 s", "", ""),
    (614, 614, "UInt", "Current phase imbalance trip timeout running", "x 0.1 s", "", ""),
    (615, 615, "UInt", "Current phase imbalance trip threshold", "% imb", "", ""),
    (616, 616, "UInt", "Current phase imbalance alarm threshold", "% imb", "", ""),
    (617, 617, "UInt", "Jam trip timeout", "s", "", ""),
    (618, 618, "UInt", "Jam trip threshold", "% FLC", "", ""),
    (619, 619, "UInt", "Jam alarm threshold", "% FLC", "", ""),
    (620, 620, "UInt", "Undercurrent trip timeout", "s", "", ""),
    (621, 621, "UInt", "Undercurrent trip threshold", "% FLC", "", ""),
    (622, 622, "UInt", "Undercurrent alarm threshold", "% FLC", "", ""),
    (623, 623, "UInt", "Long start trip timeout", "s", "", ""),
    (624, 624, "UInt", "Long start trip threshold", "% FLC", "", ""),
    (625, 625, "", "(Reserved)", "", "", ""),
    (626, 626, "UInt", "HMI display contrast setting", "", "", ""),
    (627, 627, "UInt", "Contactor rating", "0.1 A", "", ""),
    (628, 628, "UInt", "Load CT primary", "", "B", ""),
    (629, 629, "UInt", "Load CT secondary", "", "B", ""),
    (630, 630, "UInt", "Load CT multiple passes", "passes", "B", ""),
    (631, 631, "Word", "Trip enable register 1", "", "", ""),
    (632, 632, "Word", "Alarm enable register 1", "", "", ""),
    (633, 633, "Word", "Trip enable register 2", "", "", ""),
    (634, 634, "Word", "Alarm enable register 2", "", "", ""),
    (635, 636, "", "(Reserved)", "", "", ""),
    (637, 637, "UInt", "Auto-reset attempts group 1 setting", "", "", ""),
    (638, 638, "UInt", "Auto-reset group 1 timeout", "", "", ""),
    (639, 639, "UInt", "Auto-reset attempts group 2 setting", "", "", ""),
    (640, 640, "UInt", "Auto-reset group 2 timeout", "", "", ""),
    (641, 641, "UInt", "Auto-reset attempts group 3 setting", "", "", ""),
    (642, 642, "UInt", "Auto-reset group 3 timeout", "", "", ""),
    (643, 643, "UInt", "Motor step 1 to 2 timeout", "", "", ""),
    (644, 644, "UInt", "Motor step 1 to 2 threshold", "", "", ""),
    (645, 645, "UInt", "HMI port fallback setting", "", "", "DT_OutputFallbackStrategy"),
    (646, 649, "", "(Reserved)", "", "", ""),
    # setting, 0x2007, read/write (L4724-4895)
    (650, 650, "Word", "HMI language setting register", "", "", ""),
    (651, 651, "Word", "HMI display items register 1", "", "", ""),
    (652, 652, "UInt", "Motor full load current ratio, FLC1", "% FLCmax", "", ""),
    (653, 653, "UInt", "Motor high speed full load current ratio, FLC2", "% FLCmax", "", ""),
    (654, 654, "Word", "HMI display items register 2", "", "", ""),
    (655, 658, "Word[4]", "Date and time setting", "", "", "DT_DateTime"),
    (659, 659, "Word", "HMI display items register 3", "", "", ""),
    (660, 681, "", "(Reserved)", "", "", ""),
    (682, 682, "UInt", "Network port fallback setting", "", "", "DT_OutputFallbackStrategy"),
    (683, 683, "Word", "Control setting register", "", "", ""),
    (684, 694, "", "(Reserved)", "", "", ""),  # L4880 printed "684-692" for 2007:23-2D (A9)
    (695, 695, "UInt", "Network port baud rate setting", "", "", "DT_ExtBaudRate"),  # a code, not baud (A20)
    (696, 696, "UInt", "Network port address setting", "", "", ""),
    (697, 699, "", "(Not significant)", "", "", ""),
    # command, 0x2008, read/write (L4908-4960)
    (700, 700, "Word", "Custom logic command register", "", "", ""),  # "available to remotely write commands ..."
    (701, 703, "", "(Reserved)", "", "", ""),
    (704, 704, "Word", "Control register 1", "", "", ""),
    (705, 705, "Word", "Control register 2", "", "", ""),
    (706, 709, "", "(Reserved)", "", "", ""),
    (710, 799, "", "(Forbidden)", "", "", ""),  # L4960 printed "707-799" for 2008:0B-64 (A9)
    # custom logic, 0x200D, tables headed "Read-only Variables" (L4963-5098)
    (1200, 1200, "Word", "Custom logic status register", "", "", ""),
    (1201, 1201, "Word", "Custom logic version", "", "", ""),
    (1202, 1202, "Word", "Custom logic memory space", "", "", ""),
    (1203, 1203, "Word", "Custom logic memory used", "", "", ""),
    (1204, 1204, "Word", "Custom logic temporary space", "", "", ""),
    (1205, 1205, "Word", "Custom logic non volatile space", "", "", ""),
    (1206, 1249, "", "(Reserved)", "", "", ""),
    (1250, 1250, "Word", "Custom logic setting register 1", "", "", ""),
    (1251, 1269, "", "(Reserved)", "", "", ""),
    (1270, 1270, "Word", "Custom logic command register 1", "", "", ""),
    (1271, 1279, "", "(Reserved)", "", "", ""),
    (1280, 1280, "Word", "Custom logic monitoring register 1", "", "", ""),
    (1281, 1300, "", "(Reserved)", "", "", ""),
    (1301, 1399, "Word[99]", "General purpose registers for logic functions", "", "", ""),  # L5096
)

# The manual's own words where this table renames (A18) or shortens
MANUAL_NAMES = {
    560: "Ground current sensor client",
    561: "Ground current sensor server",
    628: "Load CT client",
    629: "Load CT server",
    700: "Register available to remotely write commands that can be processed in a specific custom logic",
}

# Notes that the manual gives per bit, not per register (L4330-4378)
BIT_NOTES = {
    601: {0: "A", 11: "B", 13: "B", 14: "B"},
    602: {0: "C", 1: "C", 2: "C"},
}


def trip_history_base(k: int) -> tuple:
    """(main, extension) first registers of trip n-k, k = 0 (last trip) .. 4:
    main block 150 + 30k in 0x2002, extension 300 + 30k in 0x2003 (L2400-2425)."""
    if not 0 <= k <= 4:
        raise ValueError(f"the LTMR keeps trips n-0 .. n-4, not n-{k}")
    return 150 + 30 * k, 300 + 30 * k


# Offsets inside one trip history table; the five tables differ only in "n-k"
# (n-0 at L2655-2755, extension L3210-3235).
_TRIP_HISTORY_MAIN = (
    (0, 0, "UInt", "Trip code", "", "", "DT_FaultCode"),
    (1, 1, "UInt", "Motor full load current ratio", "% FLC max", "", ""),
    (2, 2, "UInt", "Thermal capacity level", "% trip level", "", ""),
    (3, 3, "UInt", "Average current ratio", "% FLC", "", ""),
    (4, 4, "UInt", "L1 current ratio", "% FLC", "", ""),
    (5, 5, "UInt", "L2 current ratio", "% FLC", "", ""),
    (6, 6, "UInt", "L3 current ratio", "% FLC", "", ""),
    (7, 7, "UInt", "Ground current ratio", "x 0.1 % FLC min", "", ""),
    (8, 8, "UInt", "Full load current max", "x 0.1 A", "", ""),
    (9, 9, "UInt", "Current phase imbalance", "%", "", ""),
    (10, 10, "UInt", "Frequency", "x 0.1 Hz", "2", ""),  # 0.1 Hz here, 0.01 Hz live (474), A19
    (11, 11, "UInt", "Motor temperature sensor", "x 0.1 Ω", "", ""),
    (12, 15, "Word[4]", "Date and time", "", "", "DT_DateTime"),
    (16, 16, "UInt", "Average voltage", "V", "1", ""),
    (17, 17, "UInt", "L3-L1 voltage", "V", "1", ""),
    (18, 18, "UInt", "L1-L2 voltage", "V", "1", ""),
    (19, 19, "UInt", "L2-L3 voltage", "V", "1", ""),
    (20, 20, "UInt", "Voltage phase imbalance", "%", "1", ""),
    (21, 21, "UInt", "Active power", "x 0.1 kWh", "1", ""),  # an energy unit for a power, as printed (A19)
    (22, 22, "UInt", "Power factor", "x 0.01", "1", ""),
    (23, 29, "", "(Not significant)", "", "", ""),
)
_TRIP_HISTORY_EXTENSION = (
    (0, 1, "UDInt", "Average current", "x 0.01 A", "", ""),
    (2, 3, "UDInt", "L1 current", "x 0.01 A", "", ""),
    (4, 5, "UDInt", "L2 current", "x 0.01 A", "", ""),
    (6, 7, "UDInt", "L3 current", "x 0.01 A", "", ""),
    (8, 9, "UDInt", "Ground current", "mA", "", ""),
    (10, 10, "UInt", "Motor temperature sensor degree", "°C", "", ""),
    (11, 29, "", "(Not significant)", "", "", ""),  # mapped (0x2003) but not listed (A17)
)


def _trip_history_rows():
    for k in range(5):
        main, extension = trip_history_base(k)
        for base, table in ((main, _TRIP_HISTORY_MAIN), (extension, _TRIP_HISTORY_EXTENSION)):
            for first, last, type_, name, unit, notes, fmt in table:
                if not name.startswith("("):
                    name = f"{name} n-{k}"
                yield base + first, base + last, type_, name, unit, notes, fmt


_KINDS = {"(Reserved)": "reserved", "(Not significant)": "not significant", "(Forbidden)": "forbidden"}
_UNIT_WITH_SCALE = re.compile(r"^(?:x\s*)?(\d+(?:\.\d+)?)\s*(.*)$")


def _scale_and_unit(printed: str) -> tuple:
    """'x 0.01 A' -> (0.01, 'A'); '0.1 %' -> (0.1, '%'); '% FLC' -> (1, '% FLC')."""
    match = _UNIT_WITH_SCALE.match(printed)
    if match:
        return float(match.group(1)), match.group(2)
    return 1, printed


def _access(reg: int) -> str:
    return "rw" if 540 <= reg <= 799 else "ro"  # §5.3: 0-539 and custom logic are read-only tables


def _build_registers() -> dict:
    registers = {}
    rows = sorted((*_TABLE, *_trip_history_rows()))
    for first, last, type_, name, unit, notes, fmt in rows:
        kind = _KINDS.get(name, "value")
        scale, unit = _scale_and_unit(unit)
        words = last - first + 1 if kind == "value" else 1
        for reg in range(first, last + 1):
            part = reg - first
            if kind != "value":
                label, start = name, reg
            else:
                label, start = (name if part == 0 else f"{name} (word {part + 1})"), first
            registers[reg] = Register(
                number=reg,
                name=label,
                type=type_,
                access=_access(reg),
                scale=scale,
                unit=unit,
                notes=notes,
                kind=kind,
                format=fmt,
                first=start,
                words=words,
            )
    return registers


REGISTERS: dict = _build_registers()


def register_label(reg: int) -> str:
    """A unique, readable name for one register, e.g. for an EDS sub-entry:
    'System status register 1 [455]' (the manual labels PDO entries "Reg [455]")."""
    return f"{REGISTERS[reg].name} [{reg}]"


def scaled_value(reg: int, raw: int) -> float:
    """The physical value of a one-word register (scale applied, Int signed)."""
    register = REGISTERS[reg]
    value = int16(raw) if register.type == "Int" else raw & 0xFFFF
    return value * register.scale


# ---------------------------------------------------------------------------
# Register numbers the runtime uses by name
# ---------------------------------------------------------------------------

REG_CONTROLLER_COMMERCIAL_REFERENCE = 64
REG_CONTROLLER_FIRMWARE_VERSION = 76
REG_FLC_MAX = 96  # x 0.1 A
REG_MOTOR_STARTS_COUNT = 117  # UDInt 117-118
REG_MIN_WAIT_TIME = 450
REG_TRIP_CODE = 451
REG_TRIP_REGISTER_1 = 452
REG_TRIP_REGISTER_2 = 453
REG_TRIP_REGISTER_3 = 454
REG_STATUS_1 = 455
REG_STATUS_2 = 456
REG_LOGIC_INPUTS = 457
REG_LOGIC_OUTPUTS = 458
REG_IO_STATUS = 459
REG_ALARM_CODE = 460
REG_ALARM_REGISTER_1 = 461
REG_ALARM_REGISTER_2 = 462
REG_ALARM_REGISTER_3 = 463
REG_THERMAL_CAPACITY = 465
REG_AVERAGE_CURRENT_RATIO = 466
REG_L1_CURRENT_RATIO = 467
REG_L2_CURRENT_RATIO = 468
REG_L3_CURRENT_RATIO = 469
REG_CONTROLLER_TEMPERATURE = 472  # Int
REG_FREQUENCY = 474  # x 0.01 Hz
REG_NETWORK_PORT_STATUS = 490
REG_NETWORK_BAUD_RATE = 491
REG_AVERAGE_CURRENT = 500  # UDInt 500-501, x 0.01 A
REG_L1_CURRENT = 502
REG_L2_CURRENT = 504
REG_L3_CURRENT = 506
REG_GROUND_CURRENT = 508  # UDInt, mA
REG_TIME_TO_TRIP = 511
REG_OPERATING_MODE = 540
REG_THERMAL_OVERLOAD_SETTING = 546
REG_GENERAL_CONFIG_1 = 601
REG_GENERAL_CONFIG_2 = 602
REG_TRIP_CLASS = 606
REG_THERMAL_RESET_THRESHOLD = 608
REG_THERMAL_ALARM_THRESHOLD = 609
REG_TRIP_ENABLE_1 = 631
REG_ALARM_ENABLE_1 = 632
REG_TRIP_ENABLE_2 = 633
REG_ALARM_ENABLE_2 = 634
REG_HMI_FALLBACK = 645
REG_FLC1 = 652  # % of FLC max (96)
REG_FLC2 = 653
REG_DATE_TIME = 655  # Word[4] 655-658
REG_NETWORK_FALLBACK = 682
REG_CONTROL_SETTING = 683
REG_BAUD_RATE = 695
REG_NODE_ADDRESS = 696
REG_CUSTOM_COMMAND = 700
REG_CONTROL_1 = 704
REG_CONTROL_2 = 705
REG_CUSTOM_LOGIC_STATUS = 1200
