"""The FC 280's emergency messages (manual 003 §3.1.4 "Notfallobjekt",
Tabellen 3.3, 3.4, 8.9; digest 003 §1.7, A5): which alarms and warnings
8-07 lets through, and the 8 bytes of one.

    payload("16-90", 0x00400000, words)   # (0x8130, 0x01, b"\\x01\\x00\\x00\\x40\\x00")

Byte 0-1 the error code (little endian), byte 2 the error register 1001h
(only bit 0, "Allgemeiner Fehler", Tabelle 7.3: set while an alarm is
active), byte 3 the words that hold an alarm or warning (Tabelle 3.4), and
bytes 4-7, which the manual leaves undocumented: the simulator's choice,
the word (16-90, 16-91, 16-97, 16-92 or 16-93) of the event, little endian.
The manual maps no alarm to an error code: the codes below are the
simulator's choice from Tabelle 8.9 (2240h, printed "Kurzschluss" like 2130h,
taken as the earth fault: diagnostics.EMCY_EARTH_FAULT), 1000h "Allgemeiner
Fehler" for the others. The end of the last event is the all-zero EMCY ("mit dem Inhalt 0").
"""

from __future__ import annotations

from collections.abc import Mapping

from .model import ALARM_WORDS, WARNING_WORDS

GENERIC = 0x1000
DIAGNOSIS_OFF, DIAGNOSIS_ALARMS, DIAGNOSIS_ALARMS_AND_WARNINGS = range(3)  # 8-07 (chapter 6)
ERROR_REGISTER_GENERIC = 0x01

# Tabelle 3.4: the bit of byte 3 for each word
WORD_FLAGS = {"16-90": 0x01, "16-91": 0x02, "16-97": 0x04, "16-92": 0x08, "16-93": 0x10}

# Alarm word 16-90 (Tabelle 8.1) -> Tabelle 8.9
ALARM_CODES = {
    0x00000001: 0x7110,  # brake resistor test: brake chopper
    0x00000002: 0x4310,  # power card over-temperature: drive temperature
    0x00000004: 0x2240,  # earth fault (2240h, decided in diagnostics.py: A5)
    0x00000008: 0x4210,  # control card over-temperature: device temperature
    0x00000010: 0x8100,  # control word timeout: communication
    0x00000020: 0x2310,  # over-current: continuous over-current
    0x00000040: 0x8302,  # torque limit: torque limited
    0x00000200: 0x2311,  # inverter overload: current inside the device
    0x00000400: 0x3220,  # DC link under-voltage
    0x00000800: 0x3210,  # DC link over-voltage
    0x00001000: 0x2130,  # short circuit
    0x00002000: 0x2213,  # inrush fault: over-current at switch-on
    0x00004000: 0x3130,  # mains phase imbalance: phase failure
    0x00020000: 0x6100,  # internal fault: internal software error
    0x00040000: 0x7110,  # brake overload: brake chopper
    0x00080000: 0x3300,  # motor phase U missing: output voltage
    0x00100000: 0x3300,  # motor phase V missing
    0x00200000: 0x3300,  # motor phase W missing
    0x00400000: 0x8130,  # fieldbus fault: life guard error (digest 003 D29)
    0x00800000: 0x5112,  # 24 V supply fault
    0x01000000: 0x3100,  # mains failure: mains voltage
    0x02000000: 0x5110,  # 1.8 V supply fault: low supply voltage
    0x04000000: 0x7110,  # brake resistor short circuit
    0x08000000: 0x7110,  # brake chopper fault
}
# Warning word 16-92 (Tabelle 8.3) -> Tabelle 8.9; bits 0-11 mean what they mean in 16-90
WARNING_CODES = {
    **{bit: code for bit, code in ALARM_CODES.items() if bit < 0x00001000},
    0x00001000: 0x3220,  # DC link voltage low
    0x00002000: 0x3210,  # DC link voltage high
    0x00004000: 0x3130,  # mains phase imbalance
    0x00080000: 0x7110,  # brake resistor short circuit
    0x00100000: 0x7110,  # brake chopper fault
    0x00400000: 0x8130,  # fieldbus fault (warning 34)
    0x00800000: 0x5112,  # 24 V supply fault
    0x01000000: 0x3100,  # mains failure
    0x02000000: 0x2310,  # current limit
    0x08000000: 0x3210,  # voltage limit
}


def watched_words(trigger: int) -> tuple[str, ...]:
    """The words 8-07 sends emergencies for: [1] alarms, [2] alarms and warnings."""
    if trigger == DIAGNOSIS_ALARMS:
        return ALARM_WORDS
    if trigger == DIAGNOSIS_ALARMS_AND_WARNINGS:
        return ALARM_WORDS + WARNING_WORDS
    return ()


def events(words: Mapping[str, int], watched: tuple[str, ...]) -> list[tuple[str, int]]:
    """The active (word, bit) pairs of the watched words, in word order, lowest bit first."""
    return [(word, 1 << n) for word in watched for n in range(32) if words.get(word, 0) >> n & 1]


def code_of(word: str, bit: int) -> int:
    if word == "16-90":
        return ALARM_CODES.get(bit, GENERIC)
    if word == "16-92":
        return WARNING_CODES.get(bit, GENERIC)
    return GENERIC


def payload(word: str, bit: int, words: Mapping[str, int]) -> tuple[int, int, bytes]:
    """(error code, error register, the 5 manufacturer bytes 3-7) of the EMCY for one event."""
    register = ERROR_REGISTER_GENERIC if any(words.get(w, 0) for w in ALARM_WORDS) else 0
    flags = 0
    for name, flag in WORD_FLAGS.items():
        if words.get(name, 0):
            flags |= flag
    return code_of(word, bit), register, bytes([flags]) + words.get(word, 0).to_bytes(4, "little")
