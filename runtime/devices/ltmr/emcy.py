"""The LTMR's emergency messages (EMCY), what the simulator sends and the
line the CANopen master logs for one. Pure: no bus.

    emcy_text(0x1000, 0x01, bytes.fromhex("04 00 00 00 00"))
    # 'EMCY 1000h generic error, error register 01h detected error;
    #  trip code 4 Thermal overload (register 451)'

Manuals 000/001 give no EMCY codes and no manufacturer bytes (digest 001
A22, digest 000 #23): only the error register 1001h, "Detected error (1) or
no detected error (0)" (manual 001 L806), and the error history 1003h, "bits
00-15 = code of the detected error" (manual 000 L1070). Decided (docs/contradictions.md,
A22): CiA 301's layout and codes, 1000h "generic error" for a trip and
0000h "error reset or no error" for its reset; the manufacturer bytes carry
the trip code (register 451 "Trip code", DT_FaultCode, L2043-2145) as a U16
in bytes 3-4, named here by the manual's DT_FaultCode text.
"""

from __future__ import annotations

from .codes import TRIP_CODES
from .registers import REG_TRIP_CODE

EMCY_TRIP = 0x1000  # CiA 301 "generic error"
EMCY_RESET = 0x0000  # CiA 301 "error reset or no error"
ERROR_REGISTER_DETECTED = 0x01  # 1001h: "Detected error (1) or no detected error (0)"

CODE_TEXTS = {EMCY_TRIP: "generic error", EMCY_RESET: "error reset or no error"}


def trip_payload(trip_code: int) -> bytes:
    """The manufacturer bytes of a trip's EMCY: the trip code, U16 little endian."""
    return trip_code.to_bytes(2, "little")


def emcy_text(code: int, register: int, data: bytes = b"") -> str:
    """One line for a log. data: the manufacturer bytes (frame bytes 3-7, as
    the CANopen master keeps them)."""
    detected = "detected error" if register & ERROR_REGISTER_DETECTED else "no detected error"
    if code == EMCY_RESET and register == 0 and not any(data):
        return f"EMCY 0000h {CODE_TEXTS[EMCY_RESET]}: {detected}"
    name = CODE_TEXTS.get(code, "not a code the LTMR sends")
    line = f"EMCY {code:04X}h {name}, error register {register:02X}h {detected}"
    if code == EMCY_TRIP and len(data) >= 2:
        trip = int.from_bytes(data[:2], "little")
        text = TRIP_CODES.get(trip, "not in DT_FaultCode")
        line += f"; trip code {trip} {text} (register {REG_TRIP_CODE})"
    elif any(data):
        line += "; manufacturer bytes " + bytes(data).hex(" ").upper()
    return line
