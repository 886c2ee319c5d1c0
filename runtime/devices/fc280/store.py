"""The FC 280's parameter memory: the values the drive works with (RAM), the
non-volatile copy a power-up loads them from, what a write may set, and
saving (1010h, 10-31, 10-33) and restoring the factory settings (1011h).
Pure: no bus, no clock.

    store = ParameterStore({"8-03": 50})        # presets: as if saved before
    store.set("8-04", 5)                        # Refused(HIGH) for 6
    store.save({DRIVE})                         # 1010h sub 4 "save"
    store.restore({DRIVE})                      # 1011h sub 4 "load": at the next power-up
    store.power_up()                            # True: Alarm 80 "drive initialised"

Manual 003 (shared/manuals/003_*.txt) §3.1.5 (Tabellen 3.9, 3.10), §7.1.9,
§7.1.10, chapter 6 (Tabelle 6.1); digest 003 §1.11, §5.
"""

from __future__ import annotations

import enum
from collections.abc import Iterable, Mapping, Sequence

from .parameters import BAUD_CODES, PARAMETERS, TYPES, Parameter, parameter

# Sections of the non-volatile memory (Tabelle 3.9: 1010h sub 1 = all, 2 =
# communication, 4 = drive parameters). DRIVE is the parameters of
# parameters.PARAMETERS; the others are object values the simulator keeps
# here opaquely: COMMUNICATION the objects 1000h-1FFFh, PROFILE the CiA 402
# settings 6046h-604Ch (saved with the drive parameters: simulator choice).
DRIVE = "drive"
COMMUNICATION = "communication"
PROFILE = "profile"
SECTIONS_OF_SUB = {1: {DRIVE, COMMUNICATION, PROFILE}, 2: {COMMUNICATION}, 4: {DRIVE, PROFILE}}  # 3: reserved

# Readouts: the status parameters (brief; Tabelle 6.1 lists 16-84 and 16-9x);
# 15-40 and 15-49 too, which 1008h and 100Ah show read-only (Tabelle 7.1):
# simulator choice.
READ_ONLY = frozenset({"15-40", "15-49", "16-03", "16-05", "16-84", "16-90", "16-91", "16-92", "16-93", "16-97"})
# The texts of the VisStr parameters (simulator choice: 1008h, 100Ah show them, §7.1.5-7.1.6)
TEXTS = {"15-40": "FC 280", "15-49": "1.1"}
# Objects a PDO may carry: the FC profile's words (§4.4) and the alarm and warning words
PDO_MAPPABLE = frozenset({"16-03", "16-05", "16-80", "16-82", "16-90", "16-91", "16-92", "16-93"})

# Raw values a write may set, where the manual (chapter 6) or the simulator
# narrows the type's range: (lowest, highest) or the set of options.
RANGES: dict[str, tuple[int, int] | frozenset[int]] = {
    "0-10": frozenset({1, 2, 3, 4, 9}),  # set-ups 1-4, [9] Externe Anwahl (§4.4.2 bits 13/14); choice
    "0-11": frozenset({1, 2, 3, 4, 9}),  # simulator choice
    "1-23": (1, 1000),  # Hz, simulator choice (0 would leave RPM <-> Hz undefined)
    "1-25": (1, 60000),  # RPM, simulator choice
    "3-00": frozenset({0, 1}),  # [0] Min-Max, [1] -Max-+Max (§4.4.4)
    "3-10": (-10000, 10000),  # -100.00..100.00 %, simulator choice
    "8-01": (0, 2),  # chapter 6
    "8-02": (0, 3),
    "8-03": (1, 0xFFFF),  # 0.1 s and up; 18000 s does not fit the UInt16 (A27)
    "8-04": (0, 5),
    "8-07": (0, 2),
    "8-10": frozenset({0, 7}),  # [0] FC-Profil, [7] CANopen DSP 402 (A16)
    "8-14": frozenset({0, 1, 2, 4, 5, 6}),  # no [3] (A30)
    **{f"8-5{n}": (0, 3) for n in range(7)},
    "10-01": frozenset(BAUD_CODES),  # no [19] (A33)
    "10-02": (1, 127),
    "10-31": frozenset({0, 2, 3}),
    "10-33": (0, 1),
}


class Refusal(enum.Enum):
    HIGH = "too high"
    LOW = "too low"
    RANGE = "not an allowed value"
    READ_ONLY = "read-only"
    STATE = "not now"  # the drive's state does not allow it
    NO_ELEMENT = "no such element"
    NOT_STORED = "cannot be stored"


class Refused(Exception):
    """A write the drive does not take; the simulator answers it with the
    SDO abort code of the reason (Tabelle 8.8)."""

    def __init__(self, reason: Refusal, message: str) -> None:
        super().__init__(message)
        self.reason = reason


def limits(p: Parameter) -> tuple[int, int]:
    """The lowest and highest raw value a write may set."""
    allowed = RANGES.get(p.number)
    if isinstance(allowed, tuple):
        return allowed
    if isinstance(allowed, frozenset):
        return min(allowed), max(allowed)
    _size, lo, hi = TYPES[p.type]
    return lo, hi


def check(p: Parameter, raw: int) -> None:
    """Refused(HIGH / LOW / RANGE) for a raw value a write may not set."""
    lo, hi = limits(p)
    if raw > hi:
        raise Refused(Refusal.HIGH, f"{p.number}: {raw} is above {hi}")
    if raw < lo:
        raise Refused(Refusal.LOW, f"{p.number}: {raw} is below {lo}")
    allowed = RANGES.get(p.number)
    if isinstance(allowed, frozenset) and raw not in allowed:
        raise Refused(Refusal.RANGE, f"{p.number}: {raw} is none of {sorted(allowed)}")


Value = int | str | list[int]


def factory_value(p: Parameter) -> Value:
    """A parameter's factory setting (parameters.py), as the store holds it."""
    if p.type == "VisStr":
        return TEXTS.get(p.number, "")
    if p.elements:
        return [p.default] * p.elements
    return p.default


def _copy(values: Mapping[str, Value]) -> dict[str, Value]:
    return {number: list(v) if isinstance(v, list) else v for number, v in values.items()}


class ParameterStore:
    """RAM and non-volatile memory of the drive's parameters (raw values by
    number, arrays as lists). presets are written to both, as values saved
    before the first power-up; kept are values a restore does not touch (the
    node id and bit rate of the simulator's configuration)."""

    def __init__(
        self, presets: Mapping[str, int | Sequence[int]] | None = None, kept: Mapping[str, int] | None = None
    ) -> None:
        self.factory: dict[str, Value] = {number: factory_value(p) for number, p in PARAMETERS.items()}
        for number, raw in (kept or {}).items():
            self.factory[parameter(number).number] = raw
        self.values = _copy(self.factory)
        for number, preset in (presets or {}).items():
            p = parameter(number)
            if p.number in READ_ONLY or p.type == "VisStr":
                raise ValueError(f"{p.number} {p.name} is a readout: it takes no preset")
            items = list(preset) if isinstance(preset, Sequence) else [preset]
            if len(items) > max(p.elements, 1) or (p.elements == 0 and isinstance(preset, Sequence)):
                raise ValueError(f"{p.number} {p.name} has {p.elements or 'no'} elements")
            for sub, raw in enumerate(items):
                try:
                    check(p, raw)
                except Refused as exc:
                    raise ValueError(str(exc)) from None
                self._put(p, raw, sub)
        self.saved: dict[str, Value] = _copy(self.values)  # non-volatile ("EEPROM")
        #: counts the changes of RAM values a write or power-up makes (not the readouts show() updates)
        self.version = 0
        self.saved_objects: dict[str, dict] = {}  # section -> the simulator's object values
        self.pending_restore: set[str] = set()

    # ------------------------------------------------------------------ values

    def get(self, number: str, sub: int = 0) -> int | str:
        p = parameter(number)
        value = self.values[p.number]
        if isinstance(value, list):
            if not 0 <= sub < len(value):
                raise Refused(Refusal.NO_ELEMENT, f"{p.number} has elements 0..{len(value) - 1}, not {sub}")
            return value[sub]
        return value

    def set(self, number: str, raw: int, sub: int = 0) -> None:
        """A checked write of a raw value (RAM; also non-volatile with 10-33 = [1])."""
        p = parameter(number)
        if p.number in READ_ONLY or p.type == "VisStr":
            raise Refused(Refusal.READ_ONLY, f"{p.number} {p.name} is read-only")
        if p.elements and not 0 <= sub < p.elements:
            raise Refused(Refusal.NO_ELEMENT, f"{p.number} has elements 0..{p.elements - 1}, not {sub}")
        check(p, raw)
        if self.get(p.number, sub) != raw:
            self.version += 1
        self._put(p, raw, sub)
        if self.values["10-33"] == 1:  # "Immer speichern" [1]: received data go to the EEPROM (chapter 6)
            self._put(p, raw, sub, self.saved)

    def show(self, number: str, raw: int) -> None:
        """A readout the drive itself updates (status and alarm words): no checks."""
        self.values[parameter(number).number] = raw

    def _put(self, p: Parameter, raw: int, sub: int, into: dict | None = None) -> None:
        target = self.values if into is None else into
        if p.elements:
            value = target[p.number]
            assert isinstance(value, list)
            value[sub] = raw
        else:
            target[p.number] = raw

    # ------------------------------------------------------------------ save and restore

    def save(self, sections: Iterable[str], objects: Mapping[str, dict] | None = None) -> None:
        """Copy RAM to the non-volatile memory: DRIVE the parameters, the other
        sections the object values given (Tabelle 3.9)."""
        for section in sections:
            if section == DRIVE:
                self.saved = _copy(self.values)
            elif objects is not None and section in objects:
                self.saved_objects[section] = dict(objects[section])

    def restore(self, sections: Iterable[str]) -> None:
        """Factory settings at the next power-up (§7.1.10: "nach dem nächsten
        Aus- und Einschaltzyklus"); RAM keeps its values until then."""
        self.pending_restore |= set(sections)

    def power_up(self) -> bool:
        """RAM from the non-volatile memory, after a pending restore; True when
        the drive parameters went back to their factory settings (Alarm 80)."""
        pending, self.pending_restore = self.pending_restore, set()
        if DRIVE in pending:
            self.saved = _copy(self.factory)
        for section in pending - {DRIVE}:
            self.saved_objects.pop(section, None)
        self.values = _copy(self.saved)
        self.version += 1
        return DRIVE in pending
