"""Schneider TeSys T LTMR motor controller on CANopen: everything the manual
says about its registers, in one place.

Source: manual 001 (DOCA0132EN, "Using the CANopen Communication Network",
shared/manuals/001_5287ad2b8a6c20a4.txt; "L<n>" below is a line of that file)
and its digest (shared/digests/001_ltmr_canopen_en.md, "§" and the
ambiguities A1..A26 of its §10). Pure data and pure functions: the simulator,
the CANopen master, the EDS generator and the ST constants all read it.

    register_to_object(455)          -> (0x2004, 0x06)
    REGISTERS[455].name              -> 'System status register 1'
    Status1(0x6083)                  -> READY|ON|RUNNING|IN_REMOTE (+ current ratio 32 = 100 %)
    encode_datetime(datetime(2008, 9, 4, 7, 50, 32)) -> (0x3200, 0x0750, 0x0904, 0x2008)
"""
from __future__ import annotations

import datetime as _dt
import enum
import re
from dataclasses import dataclass

# ---------------------------------------------------------------------------
# Register number <-> CANopen object (digest §5.2; the manual prints no formula)
# ---------------------------------------------------------------------------

# (first register, last register, CANopen index): sub-index = register - first + 1.
# The blocks are irregular (700 -> 0x2008, not 0x2007). 1200-1399 use 0x200D
# with sub-indices 0x01..0xC8 as the detailed tables print them (A8).
REGISTER_BLOCKS = (
    (0, 99, 0x2000),        # identification, L2288-2394
    (100, 149, 0x2001),     # global and LTM monitoring statistics, L2434-2643
    (150, 299, 0x2002),     # trip history n-0..n-4, main tables, L2655-3199
    (300, 449, 0x2003),     # trip history extensions, L3210-3383
    (450, 539, 0x2004),     # monitoring, L3412-4006
    (540, 599, 0x2005),     # configuration, L4030-4322
    (600, 649, 0x2006),     # configuration, L4326-4720
    (650, 699, 0x2007),     # setting, L4724-4895
    (700, 799, 0x2008),     # command, L4908-4960
    (1200, 1399, 0x200D),   # custom logic, L4972-5096 (A8)
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
    raise UnmappedRegisterError(f"LTMR register {reg} has no CANopen address "
                                "(the map covers 0-799 and 1200-1399)")


def object_to_register(index: int, subindex: int, *, split_custom_logic: bool = False) -> int:
    """The register number of a CANopen manufacturer object; the inverse of
    register_to_object, with the same errors."""
    for first, last, block_index in _blocks(split_custom_logic):
        if index == block_index:
            reg = first + subindex - 1
            if not first <= reg <= last:
                raise UnmappedRegisterError(
                    f"LTMR object 0x{index:04X}:{subindex:02X} has no register "
                    f"(sub-index 0x01..0x{last - first + 1:02X})")
            if is_forbidden(reg):
                raise ForbiddenRegisterError(
                    f"LTMR object 0x{index:04X}:{subindex:02X} (register {reg}) is Forbidden (not accessible)")
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
    type: str            # 'UInt', 'Int', 'Word', 'UDInt', 'DInt', 'Word[n]' as printed; '' if unused
    access: str          # 'ro' (0-539, 1200-1399) or 'rw' (540-799), §5.3
    scale: float = 1     # 0.01 for "x 0.01 A"
    unit: str = ""
    notes: str = ""      # 1/2: needs the LTMEV40 expansion; A: motor off; B: config mode; C: no trip
    kind: str = "value"  # 'value', 'reserved', 'not significant', 'forbidden'
    format: str = ""     # the manual's DT_* data type, when it names one
    first: int = -1      # the register where the value starts (= number for one-word values)
    words: int = 1       # how many registers the value spans

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
    (0, 34, "", "(Not significant)", "", "", ""),       # L2288, printed 2000:03-2000:28 (A9)
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
    (82, 94, "", "(Not significant)", "", "", ""),      # L2380, printed 2000:53-2000:58 (A9)
    (95, 95, "UInt", "Load CT ratio", "x 0.1 A", "", ""),
    (96, 96, "UInt", "Full load current max", "x 0.1 A", "", ""),   # L2389: maximum FLC range
    (97, 99, "", "(Forbidden)", "", "", ""),            # L2394
    # global statistics, 0x2001, read-only
    (100, 101, "", "(Not significant)", "", "", ""),
    (102, 102, "UInt", "Ground current trips count", "", "", ""),
    (103, 103, "UInt", "Thermal overload trips count", "", "", ""),
    (104, 104, "UInt", "Long start trips count", "", "", ""),
    (105, 105, "UInt", "Jam trips count", "", "", ""),
    (106, 106, "UInt", "Current phase imbalance trips count", "", "", ""),
    (107, 107, "UInt", "Undercurrent trips count", "", "", ""),
    (108, 108, "", "(Not significant)", "", "", ""),    # not listed at all (A17)
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
    (451, 451, "UInt", "Trip code", "", "", "DT_FaultCode"),   # of the last trip, or of the one that takes priority
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
    (464, 464, "UInt", "Motor temperature sensor degree", "°C", "", ""),   # type not printed: UInt (A17)
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
    (524, 539, "", "(Forbidden)", "", "1", ""),          # L4006
    # configuration, 0x2005/0x2006, read/write (L4030-4720)
    (540, 540, "UInt", "Motor operating mode", "", "B", ""),   # L4030, values in OperatingMode
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
    (596, 596, "UInt", "Auto restart delayed timeout", "s", "", ""),   # type not printed: UInt (A17)
    (597, 599, "", "(Reserved)", "", "", ""),
    (600, 600, "", "(Not significant)", "", "", ""),
    (601, 601, "Word", "General configuration register 1", "", "", ""),   # per-bit notes: BIT_NOTES
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
    (684, 694, "", "(Reserved)", "", "", ""),            # L4880 printed "684-692" for 2007:23-2D (A9)
    (695, 695, "UInt", "Network port baud rate setting", "", "", "DT_ExtBaudRate"),  # a code, not baud (A20)
    (696, 696, "UInt", "Network port address setting", "", "", ""),
    (697, 699, "", "(Not significant)", "", "", ""),
    # command, 0x2008, read/write (L4908-4960)
    (700, 700, "Word", "Custom logic command register", "", "", ""),  # "available to remotely write commands ..."
    (701, 703, "", "(Reserved)", "", "", ""),
    (704, 704, "Word", "Control register 1", "", "", ""),
    (705, 705, "Word", "Control register 2", "", "", ""),
    (706, 709, "", "(Reserved)", "", "", ""),
    (710, 799, "", "(Forbidden)", "", "", ""),           # L4960 printed "707-799" for 2008:0B-64 (A9)
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
    (1301, 1399, "Word[99]", "General purpose registers for logic functions", "", "", ""),   # L5096
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
    (10, 10, "UInt", "Frequency", "x 0.1 Hz", "2", ""),     # 0.1 Hz here, 0.01 Hz live (474), A19
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
    (11, 29, "", "(Not significant)", "", "", ""),   # mapped (0x2003) but not listed (A17)
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
    return "rw" if 540 <= reg <= 799 else "ro"    # §5.3: 0-539 and custom logic are read-only tables


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
            registers[reg] = Register(number=reg, name=label, type=type_, access=_access(reg), scale=scale,
                                      unit=unit, notes=notes, kind=kind, format=fmt, first=start, words=words)
    return registers


REGISTERS: dict = _build_registers()

# ---------------------------------------------------------------------------
# Register numbers the runtime uses by name
# ---------------------------------------------------------------------------

REG_CONTROLLER_COMMERCIAL_REFERENCE = 64
REG_CONTROLLER_FIRMWARE_VERSION = 76
REG_FLC_MAX = 96                 # x 0.1 A
REG_MOTOR_STARTS_COUNT = 117     # UDInt 117-118
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
REG_FREQUENCY = 474               # x 0.01 Hz
REG_NETWORK_PORT_STATUS = 490
REG_NETWORK_BAUD_RATE = 491
REG_AVERAGE_CURRENT = 500         # UDInt 500-501, x 0.01 A
REG_L1_CURRENT = 502
REG_L2_CURRENT = 504
REG_L3_CURRENT = 506
REG_GROUND_CURRENT = 508          # UDInt, mA
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
REG_FLC1 = 652                    # % of FLC max (96)
REG_FLC2 = 653
REG_DATE_TIME = 655               # Word[4] 655-658
REG_NETWORK_FALLBACK = 682
REG_CONTROL_SETTING = 683
REG_BAUD_RATE = 695
REG_NODE_ADDRESS = 696
REG_CUSTOM_COMMAND = 700
REG_CONTROL_1 = 704
REG_CONTROL_2 = 705
REG_CUSTOM_LOGIC_STATUS = 1200

# ---------------------------------------------------------------------------
# Bits
# ---------------------------------------------------------------------------


class Status1(enum.IntFlag):
    """455 System status register 1 (L3516-3543)."""
    READY = 1 << 0
    ON = 1 << 1
    TRIP = 1 << 2
    ALARM = 1 << 3
    TRIPPED = 1 << 4
    RESET_AUTHORIZED = 1 << 5
    CONTROLLER_POWER = 1 << 6     # "(Not significant)" in the Data Formats example; decoded (A13)
    RUNNING = 1 << 7              # current above 10 % FLC
    IN_REMOTE = 1 << 14
    STARTING = 1 << 15


# 455 bits 8-13: motor average current ratio, "32 = 100% FLC - 63 = 200% FLC" (L3538)
STATUS1_CURRENT_SHIFT = 8
STATUS1_CURRENT_MASK = 0x3F


def current_ratio_field(percent: float) -> int:
    """The 6-bit current ratio field of 455 for a current in % FLC:
    percent * 32 / 100, rounded, saturating at 63 (A14: 63 means about 200 %)."""
    return max(0, min(STATUS1_CURRENT_MASK, round(percent * 32 / 100)))


def current_ratio_percent(field: int) -> float:
    """% FLC of the 455 current ratio field (A14: linear, 32 = 100 %)."""
    return (field & STATUS1_CURRENT_MASK) * 100 / 32


class Status2(enum.IntFlag):
    """456 System status register 2 (L3544-3571)."""
    AUTO_RESET_ACTIVE = 1 << 0
    POWER_CYCLE_REQUESTED = 1 << 2
    RESTART_TIME_UNDEFINED = 1 << 3
    RAPID_CYCLE_LOCKOUT = 1 << 4
    LOAD_SHEDDING = 1 << 5        # note 1
    SPEED_FLC2 = 1 << 6           # 0 = FLC1 setting used, 1 = FLC2
    HMI_COMM_LOSS = 1 << 7
    NETWORK_COMM_LOSS = 1 << 8
    TRANSITION_LOCKOUT = 1 << 9


class Control1(enum.IntFlag):
    """704 Control register 1 (L4917-4937). Bits 0 and 1 also drive LO1/LO2 in
    overload mode (German edition L2576, A12)."""
    RUN_FORWARD = 1 << 0
    RUN_REVERSE = 1 << 1
    TRIP_RESET = 1 << 3
    SELF_TEST = 1 << 5
    LOW_SPEED = 1 << 6


class Control2(enum.IntFlag):
    """705 Control register 2 (L4938-4955)."""
    CLEAR_ALL = 1 << 0
    CLEAR_STATISTICS = 1 << 1
    CLEAR_THERMAL_CAPACITY = 1 << 2
    CLEAR_CONTROLLER_SETTINGS = 1 << 3
    CLEAR_NETWORK_SETTINGS = 1 << 4


class TripRegister1(enum.IntFlag):
    """452 Trip register 1 (L3423-3458)."""
    GROUND_CURRENT = 1 << 2
    THERMAL_OVERLOAD = 1 << 3
    LONG_START = 1 << 4
    JAM = 1 << 5
    CURRENT_PHASE_IMBALANCE = 1 << 6
    UNDERCURRENT = 1 << 7
    TEST = 1 << 9
    HMI_PORT = 1 << 10
    CONTROLLER_INTERNAL = 1 << 11
    INTERNAL_PORT = 1 << 12
    NETWORK_PORT_CONFIG = 1 << 14
    NETWORK_PORT = 1 << 15


class TripRegister2(enum.IntFlag):
    """453 Trip register 2 (L3459-3506); bits 6-15 need the LTMEV40."""
    EXTERNAL_SYSTEM = 1 << 0
    DIAGNOSTIC = 1 << 1
    WIRING = 1 << 2
    OVERCURRENT = 1 << 3
    CURRENT_PHASE_LOSS = 1 << 4
    CURRENT_PHASE_REVERSAL = 1 << 5
    MOTOR_TEMPERATURE_SENSOR = 1 << 6
    VOLTAGE_PHASE_IMBALANCE = 1 << 7
    VOLTAGE_PHASE_LOSS = 1 << 8
    VOLTAGE_PHASE_REVERSAL = 1 << 9
    UNDERVOLTAGE = 1 << 10
    OVERVOLTAGE = 1 << 11
    UNDERPOWER = 1 << 12
    OVERPOWER = 1 << 13
    UNDER_POWER_FACTOR = 1 << 14
    OVER_POWER_FACTOR = 1 << 15


class AlarmRegister1(enum.IntFlag):
    """461 Alarm register 1 (L3688-3717)."""
    GROUND_CURRENT = 1 << 2
    THERMAL_OVERLOAD = 1 << 3
    JAM = 1 << 5
    CURRENT_PHASE_IMBALANCE = 1 << 6
    UNDERCURRENT = 1 << 7
    HMI_PORT = 1 << 10
    CONTROLLER_TEMPERATURE = 1 << 11
    NETWORK_PORT = 1 << 15


class AlarmRegister2(enum.IntFlag):
    """462 Alarm register 2 (L3718-3763); bits 7-15 need the LTMEV40."""
    DIAGNOSTIC = 1 << 1
    OVERCURRENT = 1 << 3
    CURRENT_PHASE_LOSS = 1 << 4
    CURRENT_PHASE_REVERSAL = 1 << 5
    MOTOR_TEMPERATURE_SENSOR = 1 << 6
    VOLTAGE_PHASE_IMBALANCE = 1 << 7
    VOLTAGE_PHASE_LOSS = 1 << 8
    UNDERVOLTAGE = 1 << 10
    OVERVOLTAGE = 1 << 11
    UNDERPOWER = 1 << 12
    OVERPOWER = 1 << 13
    UNDER_POWER_FACTOR = 1 << 14
    OVER_POWER_FACTOR = 1 << 15


class NetworkPortStatus(enum.IntFlag):
    """490 Network port status (L3893-3909)."""
    COMMUNICATING = 1 << 0
    CONNECTED = 1 << 1
    SELF_TESTING = 1 << 2
    SELF_DETECTING = 1 << 3
    BAD_CONFIG = 1 << 4


class GeneralConfig1(enum.IntFlag):
    """601 General configuration register 1 (L4330-4357). Bits 8-10 are the
    configuration channels, "one bit is set to 1"."""
    CONFIG_MODE = 1 << 0              # 1 = go to the configuration menu (note A)
    CONFIG_VIA_HMI_KEYPAD = 1 << 8
    CONFIG_VIA_HMI_TOOL = 1 << 9
    CONFIG_VIA_NETWORK = 1 << 10      # factory setting: enabled (L230)
    MOTOR_STAR_DELTA = 1 << 11        # note B
    PHASE_SEQUENCE_ACB = 1 << 12
    AUXILIARY_FAN = 1 << 15


# 601 bits 13-14 motor phases, DT_PhaseNumber (L2195): 1 = 1 phase, 2 = 3 phases
GENERAL_CONFIG1_PHASES_SHIFT = 13
GENERAL_CONFIG1_PHASES_MASK = 0x3
# 602 bits 0-2 trip reset mode, DT_ResetMode (L4358, note C)
GENERAL_CONFIG2_RESET_MODE_MASK = 0x7


class TripEnable1(enum.IntFlag):
    """631 Trip enable register 1 (L4519-4547)."""
    GROUND_CURRENT = 1 << 2
    THERMAL_OVERLOAD = 1 << 3
    LONG_START = 1 << 4
    JAM = 1 << 5
    CURRENT_PHASE_IMBALANCE = 1 << 6
    UNDERCURRENT = 1 << 7
    SELF_TEST = 1 << 9                # factory setting: enabled
    HMI_PORT = 1 << 10
    NETWORK_PORT = 1 << 15


class AlarmEnable1(enum.IntFlag):
    """632 Alarm enable register 1 (L4548-4578)."""
    GROUND_CURRENT = 1 << 2
    THERMAL_OVERLOAD = 1 << 3
    JAM = 1 << 5
    CURRENT_PHASE_IMBALANCE = 1 << 6
    UNDERCURRENT = 1 << 7
    HMI_PORT = 1 << 10
    CONTROLLER_TEMPERATURE = 1 << 11
    NETWORK_PORT = 1 << 15


# The communication-loss trip and alarm enables for the network port: bit 15 of 631 and 632
NETWORK_PORT_TRIP_ENABLE = TripEnable1.NETWORK_PORT
NETWORK_PORT_ALARM_ENABLE = AlarmEnable1.NETWORK_PORT

# Register values the manual states as factory settings; every other register
# starts at 0 here. 601 bit 10 (L230), 602 bit 3 HMI parity even (L4358),
# 631 bit 9 self test (L4519), 650 English (DT_Language5, L2155).
FACTORY_SETTINGS = {
    601: int(GeneralConfig1.CONFIG_VIA_NETWORK),
    602: 1 << 3,
    631: int(TripEnable1.SELF_TEST),
    650: 1,
}

# ---------------------------------------------------------------------------
# Enumerations
# ---------------------------------------------------------------------------


class OperatingMode(enum.IntEnum):
    """540 Motor operating mode (L4030); 256-511 = custom logic program 0-255."""
    OVERLOAD_2W = 2
    OVERLOAD_3W = 3
    INDEPENDENT_2W = 4
    INDEPENDENT_3W = 5
    REVERSER_2W = 6
    REVERSER_3W = 7
    TWO_STEP_2W = 8
    TWO_STEP_3W = 9
    TWO_SPEED_2W = 10
    TWO_SPEED_3W = 11


CUSTOM_LOGIC_FIRST = 256
CUSTOM_LOGIC_LAST = 511


def is_custom_logic(mode: int) -> bool:
    return CUSTOM_LOGIC_FIRST <= mode <= CUSTOM_LOGIC_LAST


def is_valid_operating_mode(mode: int) -> bool:
    return mode in OperatingMode._value2member_map_ or is_custom_logic(mode)


class FallbackStrategy(enum.IntEnum):
    """DT_OutputFallbackStrategy, registers 682 (network) and 645 (HMI), L2171-2194."""
    HOLD = 0        # hold LO1 LO2
    RUN = 1         # 2-step mode only
    OFF = 2         # LO1, LO2 off
    BOTH_ON = 3     # overload, independent and custom modes only
    LO1_ON = 4      # all modes except 2-step
    LO2_ON = 5      # all modes except 2-step


_OVERLOAD = {OperatingMode.OVERLOAD_2W, OperatingMode.OVERLOAD_3W}
_INDEPENDENT = {OperatingMode.INDEPENDENT_2W, OperatingMode.INDEPENDENT_3W}
_TWO_STEP = {OperatingMode.TWO_STEP_2W, OperatingMode.TWO_STEP_3W}


def fallback_allowed(strategy: int, mode: int) -> bool:
    """Whether a fallback strategy may be used with an operating mode, per the
    "Motor Modes" column of DT_OutputFallbackStrategy (L2171-2194)."""
    strategy = FallbackStrategy(strategy)
    if not is_valid_operating_mode(mode):
        raise ValueError(f"{mode} is not an LTMR operating mode (2-11 or 256-511)")
    if strategy in (FallbackStrategy.HOLD, FallbackStrategy.OFF):
        return True
    if strategy == FallbackStrategy.RUN:
        return mode in _TWO_STEP
    if strategy == FallbackStrategy.BOTH_ON:
        return mode in _OVERLOAD or mode in _INDEPENDENT or is_custom_logic(mode)
    return mode not in _TWO_STEP          # LO1_ON, LO2_ON


class ResetMode(enum.IntEnum):
    """DT_ResetMode, register 602 bits 0-2 (L2204-2214)."""
    MANUAL = 1      # manual or HMI
    REMOTE = 2      # remote by network
    AUTOMATIC = 4


class PhaseNumber(enum.IntEnum):
    """DT_PhaseNumber, register 601 bits 13-14 (L2195-2203)."""
    ONE_PHASE = 1
    THREE_PHASES = 2


# DT_CANopenExtBaudRate, register 695 (L183-206, L2003): code -> bit/s; 8 = autobaud.
# 9 "Factory setting" is 250 kbit/s (L206), the same rate as code 4 (A20).
CANOPEN_BAUD_CODES = {0: 10_000, 1: 20_000, 2: 50_000, 3: 125_000, 4: 250_000, 5: 500_000,
                      6: 800_000, 7: 1_000_000, 8: None, 9: 250_000}

# ---------------------------------------------------------------------------
# Trip and alarm codes (DT_FaultCode L2043-2145, DT_WarningCode L2218-2278)
# ---------------------------------------------------------------------------

TRIP_CODES = {
    0: "No detected error",
    3: "Ground current",
    4: "Thermal overload",
    5: "Long start",
    6: "Jam",
    7: "Current phase imbalance",
    8: "Undercurrent",
    10: "Test",
    11: "HMI port detected error",
    12: "HMI port communication loss",
    13: "Network port internal detected error",
    16: "External trip",
    18: "ON-OFF diagnostic",
    19: "Wiring diagnostic",
    20: "Overcurrent",
    21: "Current phase loss",
    22: "Current phase reversal",
    23: "Motor temp sensor",
    24: "Voltage phase imbalance",
    25: "Voltage phase loss",
    26: "Voltage phase reversal",
    27: "Undervoltage",
    28: "Overvoltage",
    29: "Underpower",
    30: "Overpower",
    31: "Under power factor",
    32: "Over power factor",
    33: "LTME configuration",
    34: "Temperature sensor short-circuit",
    35: "Temperature sensor open-circuit",
    36: "CT reversal",
    37: "Out of boundary CT ratio",
    46: "Start check",
    47: "Run checkback",
    48: "Stop check",
    49: "Stop checkback",
    51: "Controller internal temperature detected error",
    55: "Controller internal detected error (Stack overflow)",
    56: "Controller internal detected error (RAM detected error)",
    57: "Controller internal detected error (RAM checksum detected error)",
    58: "Controller internal detected error (Hardware watchdog trip)",
    60: "L2 current detected in single-phase mode",
    64: "Non-volatile memory detected error",
    65: "Expansion module communication detected error",
    66: "Stuck reset button",
    67: "Logic function detected error",
    **{code: "Network port internal detected error" for code in range(100, 105)},   # printed "100-104"
    109: "Network port comm detected error",
    111: "Fast device replacement trip",
    555: "Network port configuration detected error",
}

ALARM_CODES = {
    0: "No alarm",
    3: "Ground current",
    4: "Thermal overload",
    5: "Long start",
    6: "Jam",
    7: "Current phase imbalance",
    8: "Undercurrent",
    10: "HMI port",                       # 10 is "Test" as a trip code
    11: "LTMR internal temperature",      # 11 is "HMI port detected error" as a trip code
    18: "Diagnostic",
    19: "Wiring",
    20: "Overcurrent",
    21: "Current phase loss",
    23: "Motor temp sensor",
    24: "Voltage phase imbalance",
    25: "Voltage phase loss",
    27: "Undervoltage",
    28: "Overvoltage",
    29: "Underpower",
    30: "Overpower",
    31: "Under power factor",
    32: "Over power factor",
    33: "LTME configuration",
    46: "Start check",
    47: "Run checkback",
    48: "Stop check",
    49: "Stop checkback",
    109: "Network port comm loss",
    555: "Network port configuration",
}

TRIP_NONE = 0
TRIP_THERMAL_OVERLOAD = 4
TRIP_TEST = 10
TRIP_NETWORK_COMM = 109
ALARM_NONE = 0
ALARM_THERMAL_OVERLOAD = 4
ALARM_NETWORK_COMM = 109


def trip_text(code: int) -> str:
    return TRIP_CODES.get(code, f"unknown trip code {code}")


def alarm_text(code: int) -> str:
    return ALARM_CODES.get(code, f"unknown alarm code {code}")


# ---------------------------------------------------------------------------
# Data types (§5.4, §5.5)
# ---------------------------------------------------------------------------

DATETIME_MIN = _dt.datetime(2006, 1, 1, 0, 0, 0)       # L1931
DATETIME_MAX = _dt.datetime(2099, 12, 31, 23, 59, 59)  # L1934


def _bcd(value: int) -> int:
    return int(str(value), 16)


def _from_bcd(bits: int, what: str) -> int:
    text = f"{bits:x}"
    if not text.isdigit():
        raise ValueError(f"DT_DateTime {what} 0x{bits:X} is not BCD")
    return int(text)


def encode_datetime(dt: _dt.datetime) -> tuple:
    """DT_DateTime (L1866-1966): four BCD words [SS00, HHmm, MMDD, YYYY], seconds
    in the high byte of the first word. Sub-second parts are dropped."""
    dt = dt.replace(microsecond=0, tzinfo=None)
    if not DATETIME_MIN <= dt <= DATETIME_MAX:
        raise ValueError(f"DT_DateTime {dt} is outside {DATETIME_MIN} .. {DATETIME_MAX}")
    return (_bcd(dt.second) << 8,
            _bcd(dt.hour) << 8 | _bcd(dt.minute),
            _bcd(dt.month) << 8 | _bcd(dt.day),
            _bcd(dt.year))


def decode_datetime(words) -> _dt.datetime:
    """The datetime of four DT_DateTime words; ValueError for a non-BCD digit, an
    impossible date (2007-02-29) or a value outside 2006 .. 2099 ("the system
    will return a detected error", L1936). The low byte of the first word is
    "unused" and ignored."""
    seconds_word, hour_minute, month_day, year = (int(w) & 0xFFFF for w in words)
    parts = dict(year=_from_bcd(year, "year"),
                 month=_from_bcd(month_day >> 8, "month"), day=_from_bcd(month_day & 0xFF, "day"),
                 hour=_from_bcd(hour_minute >> 8, "hour"), minute=_from_bcd(hour_minute & 0xFF, "minute"),
                 second=_from_bcd(seconds_word >> 8, "second"))
    try:
        value = _dt.datetime(**parts)
    except ValueError as exc:
        raise ValueError(f"DT_DateTime {parts} is not a valid date and time: {exc}") from None
    if not DATETIME_MIN <= value <= DATETIME_MAX:
        raise ValueError(f"DT_DateTime {value} is outside {DATETIME_MIN} .. {DATETIME_MAX}")
    return value


COMMERCIAL_REFERENCE_WORDS = 6


def encode_commercial_reference(text: str) -> tuple:
    """DT_CommercialReference (L1817-1865): 12 ASCII characters in 6 words,
    the first character of each pair in the MSB. Short texts are padded with
    spaces (the manual's blank cells, A16)."""
    if len(text) > 2 * COMMERCIAL_REFERENCE_WORDS:
        raise ValueError(f"a commercial reference has at most 12 characters, not {len(text)}: {text!r}")
    data = text.ljust(2 * COMMERCIAL_REFERENCE_WORDS).encode("ascii")
    return tuple(data[i] << 8 | data[i + 1] for i in range(0, len(data), 2))


def decode_commercial_reference(words) -> str:
    """The text of DT_CommercialReference words, trailing spaces and NULs removed
    (whether blank cells are spaces or NULs is not defined, A16)."""
    data = b"".join(bytes(((int(w) >> 8) & 0xFF, int(w) & 0xFF)) for w in words)
    return data.decode("ascii", errors="replace").rstrip(" \x00")


def udint_from_registers(first: int, second: int, msw_first: bool = True) -> int:
    """A UDInt from two consecutive registers. The manual does not state the
    word order; the default takes the lower register as the MSW, like PKW's
    "1st word MSW" (A5)."""
    msw, lsw = (first, second) if msw_first else (second, first)
    return (msw & 0xFFFF) << 16 | (lsw & 0xFFFF)


def udint_to_registers(value: int, msw_first: bool = True) -> tuple:
    if not 0 <= value <= 0xFFFFFFFF:
        raise ValueError(f"{value} does not fit a UDInt")
    msw, lsw = value >> 16, value & 0xFFFF
    return (msw, lsw) if msw_first else (lsw, msw)


def dint_from_registers(first: int, second: int, msw_first: bool = True) -> int:
    value = udint_from_registers(first, second, msw_first)
    return value - (1 << 32) if value & 0x80000000 else value


def int16(word: int) -> int:
    """A signed 'Int' register (e.g. 472 controller temperature): 0xFFF6 -> -10."""
    word &= 0xFFFF
    return word - 0x10000 if word & 0x8000 else word


def full_load_current_amps(flc_max: int, flc_ratio: int) -> float:
    """FLC in A from register 96 (FLC max, x 0.1 A) and 652/653 (% of FLC max)."""
    return flc_max / 10 * flc_ratio / 100


# ---------------------------------------------------------------------------
# PDO defaults and identity (manual §4 object dictionary, digest §2.3, §2.5)
# ---------------------------------------------------------------------------

# 0x1600: 704, then 0x2008:04 (printed "Reg [706]", a reserved word either way: A2), then 700 (L1199-1221)
RPDO1_DEFAULT = (0x20080510, 0x20080410, 0x20080110)
# 0x1A00: 455, 456, 457, 0x2004:0A = 459 I/O status (overview table says 458: A1), L1526-1548
TPDO1_DEFAULT = (0x20040610, 0x20040710, 0x20040810, 0x20040A10)
# 0x1603 / 0x1A03: PKW request 0x3000:01/02, response 0x3000:03/04 (L1304, L1631)
RPDO4_DEFAULT = (0x30000120, 0x30000220)
TPDO4_DEFAULT = (0x30000320, 0x30000420)

PKW_INDEX = 0x3000          # sub 1/2 request (RPDO4), sub 3/4 response (TPDO4)
# The register objects PDOs may map (L253-280): 0x2004 into TPDOs, 0x2007/0x2008 into RPDOs
TPDO_MAPPABLE_INDICES = (0x2004,)
RPDO_MAPPABLE_INDICES = (0x2007, 0x2008)

VENDOR_ID = 0x0300005A       # 0x1018:01, L977
PRODUCT_REVISION = 0x00010001  # 0x1018:03, L991
DEVICE_NAME = "LTM"          # 0x1008, L907
HARDWARE_VERSION = "M1.0-ES1.0"   # 0x1009, L914
SOFTWARE_VERSION = "V01.01"  # 0x100A, L921 ("only an example")

# 0x1018:02 product code (L1034-1050); bit 0 = LTMEV40 present, 0x100 = local configuration (A24)
PRODUCT_CODES = {
    0x030: "TeSys T MMC R (remote configuration)",
    0x031: "TeSys T MMC R EV40 (remote configuration, LTMEV40)",
    0x130: "TeSys T MMC L (local configuration)",
    0x131: "TeSys T MMC L EV40 (local configuration, LTMEV40)",
}
PRODUCT_CODE_REMOTE = 0x030


def pkw_read_only(product_code: int) -> bool:
    """"For TeSys T MMC L and TeSys T MMC L EV40, PKW use is restricted to read
    access" (L343): the local-configuration variants."""
    if product_code not in PRODUCT_CODES:
        raise ValueError(f"0x{product_code:X} is not an LTMR product code ({', '.join(map(hex, PRODUCT_CODES))})")
    return bool(product_code & 0x100)


def has_expansion_module(product_code: int) -> bool:
    return bool(product_code & 0x001)


def register_label(reg: int) -> str:
    """A unique, readable name for one register, e.g. for an EDS sub-entry:
    'System status register 1 [455]' (the manual labels PDO entries "Reg [455]")."""
    return f"{REGISTERS[reg].name} [{reg}]"


def scaled_value(reg: int, raw: int) -> float:
    """The physical value of a one-word register (scale applied, Int signed)."""
    register = REGISTERS[reg]
    value = int16(raw) if register.type == "Int" else raw & 0xFFFF
    return value * register.scale
