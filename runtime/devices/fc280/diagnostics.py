"""What an FC 280 says is wrong: its emergency messages (EMCY) and its alarm
and warning words. Pure: no bus.

    decode_emcy(bytes.fromhex("3081010100000000"))   # Emcy(code=0x8130, ..., text='Life guard ...')
    emcy_text(0x8130, 0x01, b"\\x01\\0\\0\\0\\0")       # one line for a log
    alarm_texts(0x00400010)                         # ['Control word timeout', 'Fieldbus fault']

Sources (manual 003, digest 003):
- EMCY layout, §3.1.4 "Notfallobjekt", Tabellen 3.3 and 3.4: always 8 bytes;
  the drive sends one when an alarm comes (8-07 chooses which) and one "with
  the content 0" when it is gone.
- EMCY codes, §8.2.7 Tabelle 8.9 (German texts in the comments).
- Error register 1001h, §7.1.3 Tabelle 7.3: only bit 0, generic error.
- Alarm word 16-90, alarm word 2 16-91, warning word 16-92, warning word 2
  16-93: §8.1, Tabellen 8.1-8.4. Alarm word 3 (16-97) is not tabulated.

Decided where the manual is unclear (digest 003 §10):
- A5: Tabelle 3.3 is mis-extracted and names OD 1003[1]; the CiA 301 layout
  is taken: bytes 0-1 the code (little endian), byte 2 the error register
  (1001h), byte 3 the flags of Tabelle 3.4, bytes 4-7 vendor data the
  manual does not describe (kept as they came). The manual maps no alarm
  to an EMCY code. Tabelle 8.9 names 2130h and 2240h both "Kurzschluss":
  2240h is read as the earth fault (see EMCY_EARTH_FAULT).
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

# ---------------------------------------------------------------- EMCY codes, Tabelle 8.9

EMCY_NO_ERROR = 0x0000
EMCY_GENERIC = 0x1000
# Tabelle 8.9 prints "Kurzschluss" for both 2130h and 2240h and has no row for an earth
# fault (16-90 bit 2 "Erdschluss"): decided (docs/contradictions.md, A5) 2130h short circuit, 2240h earth
# fault, as CiA 402 names 2240h "earth leakage (device internal)" and 2130h "short circuit"
EMCY_SHORT_CIRCUIT = 0x2130
EMCY_SWITCH_ON_OVERCURRENT = 0x2213
EMCY_EARTH_FAULT = 0x2240
EMCY_CONTINUOUS_OVERCURRENT = 0x2310
EMCY_DEVICE_CURRENT = 0x2311
EMCY_MAINS_VOLTAGE = 0x3100
EMCY_PHASE_FAILURE = 0x3130
EMCY_DEVICE_OVERVOLTAGE = 0x3210
EMCY_DEVICE_UNDERVOLTAGE = 0x3220
EMCY_OUTPUT_VOLTAGE = 0x3300
EMCY_DEVICE_TEMPERATURE = 0x4210
EMCY_DRIVE_TEMPERATURE = 0x4310
EMCY_LOW_SUPPLY_VOLTAGE = 0x5110
EMCY_SUPPLY_24V = 0x5112
EMCY_MEASUREMENT_CIRCUIT = 0x5210
EMCY_SOFTWARE = 0x6100
EMCY_BRAKE_CHOPPER = 0x7110
EMCY_COMMUNICATION = 0x8100
EMCY_CAN_OVERRUN = 0x8110
EMCY_CAN_ERROR_PASSIVE = 0x8120
EMCY_LIFE_GUARD = 0x8130
EMCY_BUS_OFF_RECOVERED = 0x8140
EMCY_COB_ID_COLLISION = 0x8150
EMCY_PDO_LENGTH_ERROR = 0x8210
EMCY_PDO_LENGTH_EXCEEDED = 0x8220
EMCY_TORQUE_LIMITED = 0x8302
EMCY_MANUFACTURER = 0xFF00  # FFxx: the high byte FF, any low byte

EMCY_CODES: dict[int, str] = {
    EMCY_NO_ERROR: "No error",  # Kein Fehler
    EMCY_GENERIC: "Generic error",  # Allgemeiner Fehler
    EMCY_SHORT_CIRCUIT: "Short circuit",  # Kurzschluss
    EMCY_SWITCH_ON_OVERCURRENT: "Over-current at switch-on",  # Überstrom bei Einschaltung
    EMCY_EARTH_FAULT: "Earth fault",  # "Kurzschluss" in Tabelle 8.9 (see above), Erdschluss in 8.1
    EMCY_CONTINUOUS_OVERCURRENT: "Continuous over-current",  # Kontinuierlicher Überstrom
    EMCY_DEVICE_CURRENT: "Current inside the device",  # Strom im Gerät
    EMCY_MAINS_VOLTAGE: "Mains voltage",  # Netzspannung
    EMCY_PHASE_FAILURE: "Phase failure",  # Phasenausfall
    EMCY_DEVICE_OVERVOLTAGE: "Over-voltage inside the device",  # Überspannung im Gerät
    EMCY_DEVICE_UNDERVOLTAGE: "Under-voltage inside the device",  # Unterspannung im Gerät
    EMCY_OUTPUT_VOLTAGE: "Output voltage",  # Ausgangsspannung
    EMCY_DEVICE_TEMPERATURE: "Excess device temperature",  # Überschreiten der Gerätetemperatur
    EMCY_DRIVE_TEMPERATURE: "Excess drive temperature",  # Überschreiten der Frequenzumrichter-temperatur
    EMCY_LOW_SUPPLY_VOLTAGE: "Low supply voltage",  # Niedrige Spannungsversorgung
    EMCY_SUPPLY_24V: "24 V supply",  # 24-V-Versorgung
    EMCY_MEASUREMENT_CIRCUIT: "Measurement circuit",  # Messkreis
    EMCY_SOFTWARE: "Internal software error",  # Interner Softwarefehler
    EMCY_BRAKE_CHOPPER: "Brake chopper",  # Bremschopper
    EMCY_COMMUNICATION: "Communication",  # Kommunikation
    EMCY_CAN_OVERRUN: "CAN overrun (objects lost)",  # CAN-Überlauf (Objekte verloren)
    EMCY_CAN_ERROR_PASSIVE: "CAN in error passive mode",  # CAN fehlerhaft (passiver Modus)
    EMCY_LIFE_GUARD: "Life guard error or heartbeat error",  # Life Guard-Fehler oder Heartbeat-Fehler
    EMCY_BUS_OFF_RECOVERED: "Recovered from bus off",  # Zustand „Bus aus“ konnte verlassen werden
    EMCY_COB_ID_COLLISION: "COB-ID collision on transmit",  # Kollision bei Übertragung der COB-ID
    EMCY_PDO_LENGTH_ERROR: "PDO not processed due to length error",  # PDO aufgrund eines Längenfehlers nicht ...
    EMCY_PDO_LENGTH_EXCEEDED: "PDO length exceeded",  # PDO-Länge überschritten
    EMCY_TORQUE_LIMITED: "Torque limited",  # Drehmoment begrenzt
}
MANUFACTURER_TEXT = "Manufacturer-specific"  # FFxx: Herstellerspezifisch
UNKNOWN_EMCY_TEXT = "Unknown EMCY code"

# ---------------------------------------------------------------- error register and byte 3

#: 1001h, Tabelle 7.3: "Nur Bit 0 wird unterstützt" (allgemeiner Fehler)
ERROR_REGISTER_GENERIC = 0x01


class EmcyFlags(enum.IntFlag):
    """EMCY byte 3 (Tabelle 3.4): which alarm or warning word has a bit set. Bits 5-7 reserved, 0."""

    ALARM_WORD = 0x01  # 16-90 Alarmwort
    ALARM_WORD_2 = 0x02  # 16-91 Alarmwort 2
    ALARM_WORD_3 = 0x04  # 16-97 Alarm Word 3
    WARNING_WORD = 0x08  # 16-92 Warnwort
    WARNING_WORD_2 = 0x10  # 16-93 Warnwort 2


ALARM_FLAGS = EmcyFlags.ALARM_WORD | EmcyFlags.ALARM_WORD_2 | EmcyFlags.ALARM_WORD_3
WARNING_FLAGS = EmcyFlags.WARNING_WORD | EmcyFlags.WARNING_WORD_2

_FLAG_NAMES = {
    EmcyFlags.ALARM_WORD: "alarm word 16-90",
    EmcyFlags.ALARM_WORD_2: "alarm word 2 16-91",
    EmcyFlags.ALARM_WORD_3: "alarm word 3 16-97",
    EmcyFlags.WARNING_WORD: "warning word 16-92",
    EmcyFlags.WARNING_WORD_2: "warning word 2 16-93",
}

EMCY_LENGTH = 8  # Tabelle 3.3: "besteht immer aus 8 Bytes"


@dataclass(frozen=True)
class Emcy:
    """One decoded emergency message."""

    code: int  # Tabelle 8.9
    register: int  # 1001h
    flags: EmcyFlags  # byte 3, Tabelle 3.4
    vendor: bytes  # bytes 4-7, undocumented (A5)
    text: str  # the code's text
    cleared: bool  # all eight bytes 0: the alarm is gone (§3.1.4)

    @property
    def alarm(self) -> bool:
        """An alarm word has a bit set (byte 3 bits 0-2)."""
        return bool(self.flags & ALARM_FLAGS)

    @property
    def warning(self) -> bool:
        """A warning word has a bit set (byte 3 bits 3-4)."""
        return bool(self.flags & WARNING_FLAGS)


def emcy_code_text(code: int) -> str:
    """The text of an EMCY code (Tabelle 8.9); FFxx is manufacturer-specific."""
    if code in EMCY_CODES:
        return EMCY_CODES[code]
    if code & 0xFF00 == EMCY_MANUFACTURER:
        return MANUFACTURER_TEXT
    return UNKNOWN_EMCY_TEXT


def decode_emcy(data: bytes) -> Emcy:
    """An EMCY frame's data (up to 8 bytes; fewer are taken as padded with 0)."""
    if len(data) > EMCY_LENGTH:
        raise ValueError(f"an EMCY carries {EMCY_LENGTH} bytes, not {len(data)}")
    frame = bytes(data).ljust(EMCY_LENGTH, b"\0")
    code = int.from_bytes(frame[0:2], "little")
    return Emcy(
        code=code,
        register=frame[2],
        flags=EmcyFlags(frame[3]),
        vendor=frame[4:8],
        text=emcy_code_text(code),
        cleared=not any(frame),
    )


def emcy_text(code: int, register: int, data: bytes = b"") -> str:
    """One line for a log. data: the manufacturer-specific bytes (frame bytes
    3-7, as the CANopen master keeps them), byte 3 first."""
    flags = data[0] if data else 0
    vendor = bytes(data[1:5])
    if code == 0 and register == 0 and flags == 0 and not any(vendor):
        return "EMCY 0000h no error: the alarm is gone"
    line = f"EMCY {code:04X}h {emcy_code_text(code)}, error register {register:02X}h"
    if register & ERROR_REGISTER_GENERIC:
        line += " (generic error)"
    active = [name for flag, name in _FLAG_NAMES.items() if flags & flag]
    if active:
        line += "; active: " + ", ".join(active)
    if flags & ~0x1F:
        line += f"; reserved byte-3 bits {flags & ~0x1F:02X}h"
    if any(vendor):
        line += "; vendor bytes " + vendor.hex(" ").upper()
    return line


# ---------------------------------------------------------------- alarm and warning words, §8.1

#: Tabelle 8.1, parameter 16-90 Alarmwort
ALARM_WORD: dict[int, str] = {
    0x00000001: "Brake resistor test",  # Bremswiderstandstest
    0x00000002: "Power card over-temperature",  # Leistungskarte Übertemperatur
    0x00000004: "Earth fault",  # Erdschluss
    0x00000008: "Control card over-temperature",  # Steuerkartenübertemperatur
    0x00000010: "Control word timeout",  # Steuerwort-Timeout
    0x00000020: "Over-current",  # Überstrom
    0x00000040: "Torque limit",  # Drehmomentgrenze
    0x00000080: "Motor thermistor over-temperature",  # Übertemperatur des Motor-Thermistors
    0x00000100: "Motor ETR over-temperature",  # Motortemperatur ETR
    0x00000200: "Inverter overload",  # Wechselrichterüberlastung
    0x00000400: "DC-link under-voltage",  # Zwischenkreisunterspannung
    0x00000800: "DC-link over-voltage",  # Zwischenkreisüberspannung
    0x00001000: "Short circuit",  # Kurzschluss
    0x00002000: "Inrush fault",  # Einschaltstrom-Fehler
    0x00004000: "Mains phase imbalance",  # Netzasymmetrie
    0x00008000: "AMA not OK",  # AMA nicht OK
    0x00010000: "Live zero error",  # Signalfehler
    0x00020000: "Internal fault",  # Interner Fehler
    0x00040000: "Brake overload",  # Bremsüberlast
    0x00080000: "Motor phase U missing",  # Die Motorphase U fehlt
    0x00100000: "Motor phase V missing",  # Die Motorphase V fehlt
    0x00200000: "Motor phase W missing",  # Die Motorphase W fehlt
    0x00400000: "Fieldbus fault",  # Feldbus-Fehl.
    0x00800000: "24 V supply fault",  # 24 V Versorgung fehlerhaft
    0x01000000: "Mains failure",  # Netzausfall
    0x02000000: "1.8 V supply fault",  # 1,8 V Spannungsversorgungsfehler
    0x04000000: "Brake resistor short circuit",  # Bremswiderstand Kurzschluss
    0x08000000: "Brake chopper fault",  # Bremschopperfehler
    0x10000000: "Option change",  # Optionen neu
    0x20000000: "Drive initialised",  # Frequenzumrichter initialisiert (alarm 80, after 1011h)
    0x40000000: "Safe Torque Off",  # Safe Torque Off
    0x80000000: "Mechanical brake low",  # Mechanische Bremse zu niedrig
}

#: Tabelle 8.2, parameter 16-91 Alarmwort 2 (the bits it leaves out are "Reserviert")
ALARM_WORD_2: dict[int, str] = {
    0x00000001: "Service trip, read/write",  # Serviceabschaltung, Lesen/Schreiben
    0x00000004: "Service trip, type code/spare part",  # Serviceabschaltung, Typencode/Ersatzteil
    0x00000020: "No flow",  # Kein Durchfluss
    0x00000040: "Dry pump",  # Trockenlauf
    0x00000080: "End of curve",  # Kennlinienende
    0x00000100: "Broken belt",  # Riemenbruch
    0x00000200: "Discharge high",  # Entladung hoch
    0x00000400: "Start failed",  # Startfehler
    0x00000800: "Speed limit",  # Drehzahlgrenze
    0x00020000: "KTY error",  # KTY-Fehler
    0x00040000: "Fan error",  # Lüfterfehler
    0x00080000: "ECB error",  # ECB-Fehler
    0x40000000: "PTC thermistor",  # PTC-Thermistor
    0x80000000: "Dangerous failure",  # Gefährl. Fehler
}

#: Tabelle 8.3, parameter 16-92 Warnwort
WARNING_WORD: dict[int, str] = {
    0x00000001: "Brake resistor test",  # Bremswiderstandstest
    0x00000002: "Power card over-temperature",  # Leistungskarte Übertemperatur
    0x00000004: "Earth fault",  # Erdschluss
    0x00000008: "Control card over-temperature",  # Steuerkartenübertemperatur
    0x00000010: "Control word timeout",  # Steuerwort-Timeout
    0x00000020: "Over-current",  # Überstrom
    0x00000040: "Torque limit",  # Drehmomentgrenze
    0x00000080: "Motor thermistor over-temperature",  # Übertemperatur des Motor-Thermistors
    0x00000100: "Motor ETR over-temperature",  # Motortemperatur ETR
    0x00000200: "Inverter overload",  # Wechselrichterüberlastung
    0x00000400: "DC-link under-voltage",  # Zwischenkreisunterspannung
    0x00000800: "DC-link over-voltage",  # Zwischenkreisüberspannung
    0x00001000: "DC-link voltage low",  # Zwischenkreisspannung niedrig
    0x00002000: "DC-link voltage high",  # Zwischenkreisspannung hoch
    0x00004000: "Mains phase imbalance",  # Netzasyymetrie (sic)
    0x00008000: "No motor",  # Kein Motor
    0x00010000: "Live zero error",  # Signalfehler
    0x00020000: "10 V low",  # 10 V niedrig
    0x00040000: "Brake resistor power low",  # Bremswiderstandsleistung niedrig
    0x00080000: "Brake resistor short circuit",  # Bremswiderstand Kurzschluss
    0x00100000: "Brake chopper fault",  # Bremschopperfehler
    0x00200000: "Speed limit",  # Drehzahlgrenze
    0x00400000: "Fieldbus fault",  # Feldbus-Fehler (warning 34: bus off, guarding timeout)
    0x00800000: "24 V supply fault",  # 24 V Versorgung fehlerhaft
    0x01000000: "Mains failure",  # Netzausfall
    0x02000000: "Current limit",  # Stromgrenze
    0x04000000: "Low temperature",  # Niedrige Temperatur
    0x08000000: "Voltage limit",  # Spannungsgrenze
    0x10000000: "Encoder fault",  # Drehgeber-Fehler
    0x20000000: "Output frequency limit",  # Ausgangsfrequenzgrenze
    0x40000000: "Safe Torque Off",  # Safe Torque Off
    0x80000000: "Extended status word",  # Erweitertes Zustandswort
}

#: Tabelle 8.4, parameter 16-93 Warnwort 2 (the bits it leaves out are "Reserviert")
WARNING_WORD_2: dict[int, str] = {
    0x00000001: "Start delayed",  # Startverzögerung
    0x00000002: "Stop delayed",  # Stoppverzögerung
    0x00000004: "Clock fault",  # Uhrfehler
    0x00000008: "Fire mode was active",  # Notfallbetrieb war aktiv
    0x00000020: "No flow",  # Kein Durchfluss
    0x00000040: "Dry pump",  # Trockenlauf
    0x00000080: "End of curve",  # Kennlinienende
    0x00000100: "Broken belt",  # Riemenbruch
    0x00000200: "Discharge high",  # Entladung hoch
    0x00020000: "KTY error",  # KTY-Fehler
    0x00040000: "Fan warning",  # Lüfterwarnung
    0x00080000: "ECB error",  # ECB-Fehler
    0x40000000: "PTC thermistor",  # PTC-Thermistor
}

#: the four words by parameter: (table, its name in a log)
WORDS = {
    "16-90": ALARM_WORD,
    "16-91": ALARM_WORD_2,
    "16-92": WARNING_WORD,
    "16-93": WARNING_WORD_2,
}


def bit_text(table: dict[int, str], bit: int) -> str:
    """The text of one bit of a word; a bit the table leaves out is reserved."""
    return table.get(bit, f"Reserved ({bit:08X}h)")


def word_texts(table: dict[int, str], word: int) -> list[str]:
    """The texts of the set bits of a 32-bit word, lowest bit first."""
    return [bit_text(table, 1 << n) for n in range(32) if word >> n & 1]


def alarm_texts(word: int) -> list[str]:
    """Alarm word 16-90 (Tabelle 8.1)."""
    return word_texts(ALARM_WORD, word)


def alarm2_texts(word: int) -> list[str]:
    """Alarm word 2 16-91 (Tabelle 8.2)."""
    return word_texts(ALARM_WORD_2, word)


def warning_texts(word: int) -> list[str]:
    """Warning word 16-92 (Tabelle 8.3)."""
    return word_texts(WARNING_WORD, word)


def warning2_texts(word: int) -> list[str]:
    """Warning word 2 16-93 (Tabelle 8.4)."""
    return word_texts(WARNING_WORD_2, word)
