"""Eaton PowerXL faults: the fault numbers of Tabelle 11, their display codes and causes.

The fault number is bits 8-15 of the ID 6 status word (registers.fault_number).
Source: manual 002 (shared/manuals/002_a23ab2a6587941cb.txt, "L<n>" a line of
that file) and its digest (shared/digests/002_eaton_modbus.md, "§" and the
ambiguities "A<n>").

    fault_display(50), fault_text(50) -> 'SC-F01', 'No valid Modbus telegram received within the set time'
"""

from __future__ import annotations

from dataclasses import dataclass

from .registers import Family

# ---------------------------------------------------------------------------
# Faults (Tabelle 11, L854-916)
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class Fault:
    number: int
    display: str  # the code on the drive's display
    text: str  # "Mögliche Ursache", translated
    families: frozenset


_ALL = frozenset(Family)
_DA1 = frozenset({Family.DA1})
_DA1_DB1_DC1 = frozenset({Family.DA1, Family.DB1, Family.DC1})

# The manual file garbles the seven-segment display texts ("DI-b" for OI-b,
# "I.L-ErrP" for I.t-trP, "Sc-FQ1" for SC-F01, "REf-Q1" for Atf-01); the
# display column holds the reading of digest §3.4. The printed hex column has
# two typos (16 printed "0A", 19 printed "12", A20); the numbers are decimal.
# The first row, "StoP" without a number, is not a fault: the drive is not enabled.
FAULTS = {
    f.number: f
    for f in (
        Fault(0, "no-Flt", "No fault", _ALL),  # L859: P0-13 shows no entry
        Fault(1, "OI-b", "Brake current too high", _ALL),  # L860
        Fault(2, "OL-br", "Brake resistor thermal overload", _ALL),
        Fault(3, "O-I", "Overcurrent at the output", _ALL),
        Fault(4, "I.t-trP", "Motor overload", _ALL),
        Fault(5, "PS-trP", "Overcurrent (hardware)", _ALL),
        Fault(6, "O-Volt", "DC link overvoltage", _ALL),  # L865, printed "UUolt"
        Fault(7, "U-Volt", "DC link undervoltage", _ALL),  # L866, printed "UUolt"
        Fault(8, "O-t", "Heatsink overtemperature", _ALL),
        Fault(9, "U-t", "Undertemperature", _ALL),
        Fault(10, "P-dEF", "Factory default parameters loaded", _ALL),
        Fault(11, "E-trip", "External fault", _ALL),
        Fault(12, "SC-Obs", "Communication fault with the external keypad or PC", _ALL),
        Fault(13, "FLt-dc", "DC link voltage ripple too high", _ALL),
        Fault(14, "P-LOSS", "Loss of a supply phase (three-phase supplied devices only)", _ALL),
        # L874: families printed "DA1, DE1", yet the text names a DC1 meaning too (A20)
        Fault(
            15,
            "h O-I",
            "Overcurrent at the output; DC1: flying start fault",
            frozenset({Family.DA1, Family.DC1, Family.DE1}),
        ),
        Fault(16, "th-Flt", "Heatsink thermistor defective", _ALL),
        Fault(17, "dAtA-F", "Internal memory fault", _ALL),
        Fault(18, "4-20 F", "Analog input current outside the specified range", _ALL),
        Fault(19, "dAtA-E", "Internal memory fault", _DA1_DB1_DC1),
        Fault(20, "U-dEF", "Customer parameter set loaded", _DA1),  # L879
        Fault(21, "F-Ptc", "Motor PTC overtemperature", _DA1_DB1_DC1),  # L887
        Fault(22, "FAn-F", "Internal fan fault", _DA1_DB1_DC1),
        Fault(23, "O-hEAt", "Ambient temperature above the specified value", _DA1_DB1_DC1),
        Fault(24, "O-torq", "Maximum permitted torque exceeded", _DA1),
        Fault(
            25,
            "U-torq",
            "Hoist brake control (P2-18 = 8): torque below the threshold before the brake was released",
            _DA1,
        ),
        Fault(26, "OUt-F", "Fault at the device output", _DA1_DB1_DC1),
        Fault(29, "Sto-F", "STO circuit internal fault", _DA1),  # L893
        Fault(30, "Enc-01", "No communication between the encoder module and the drive", _DA1),
        Fault(31, "Enc-02", "Calculated motor speed differs from the measured speed", _DA1),  # also "SP-Err"
        Fault(32, "Enc-03", "Motor speed and the encoder PPR in P6-06 do not match", _DA1),
        Fault(33, "Enc-04", "Encoder channel A fault", _DA1),
        Fault(34, "Enc-05", "Encoder channel B fault", _DA1),
        Fault(35, "Enc-06", "Encoder channels A and B fault", _DA1),
        Fault(40, "Atf-01", "Motor identification failed", _DA1_DB1_DC1),  # L900
        Fault(41, "Atf-02", "Motor identification failed: measured stator resistance too large", _DA1_DB1_DC1),
        Fault(42, "Atf-03", "Motor identification failed: measured motor inductance too low", _DA1_DB1_DC1),
        Fault(43, "Atf-04", "Motor identification failed: measured motor inductance too large", _DA1_DB1_DC1),
        Fault(44, "Atf-05", "Motor identification failed: measured motor parameters do not match", _DA1_DB1_DC1),
        Fault(49, "OUt-Ph", "A motor phase is not connected or interrupted", _DA1_DB1_DC1),
        # L906: listed for DA1, DB1, DC1 only, although the DE1 trips on a Modbus
        # timeout as well (P-36); the manual names no other fault for it (A20)
        Fault(50, "SC-F01", "No valid Modbus telegram received within the set time", _DA1_DB1_DC1),
        Fault(51, "SC-F02", "No valid CANopen telegram received within the set time", _DA1_DB1_DC1),
        Fault(52, "SC-F03", "Communication with the plugged-in fieldbus option interrupted", _DA1),
        Fault(53, "SC-F04", "Communication with the plugged-in I/O extension interrupted", _DA1),
        Fault(60, "OF-01", "No internal connection to an option card", _DA1),  # L910
        Fault(61, "OF-02", "Option module in an exceptional state", _DA1),
        Fault(70, "PLC-01", "Function block editor: unsupported function block", _DA1),  # L912
        Fault(71, "PLC-02", "Function block editor: program too large", _DA1),
        Fault(72, "PLC-03", "Function block editor: division by zero", _DA1),
        Fault(73, "PLC-04", "Function block editor: lower limit above upper limit", _DA1),
        Fault(74, "PLC-05", "Function block editor: table overflow", _DA1),  # L916
    )
}

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
