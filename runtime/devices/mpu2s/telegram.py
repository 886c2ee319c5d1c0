"""The MPU2-S send telegram (manual 004 ch. 3, digest 004 §2): its 69 words as
data, how each is decoded, the named bits of the status words, and an
assembler that gathers the 23 mux frames into one image. Pure: the caller
passes the time (nanoseconds, any monotonic clock).

    t = TelegramAssembler()
    device, mux, words = frames.decode_telegram(can_id, data)
    t.feed(mux, words, now_ns)
    t.words[2]                    # Nr 2, the raw generator frequency word (index = Nr)
    t.values()["f_gen"]           # 50.0 (Hz), None until Nr 2 came
    double_bit(t.words[10], ControlRegister2.T5_GCB_CLOSED)   # True / False / None
    t.stale(now_ns, 5_000_000_000)

The telegram is 23 frames, mux 0..22, three words each (§2.1); word Nr =
3·mux + word (1..3), so Nr runs 1..69 and is the index into ``words``
(``words[0]`` is unused). Frames come about every 100 ms (§1.1), so one
value is refreshed about every 2.3 s: the telegram is no source for
phase-accurate closing (A38).

Decoding (units as printed in §2.1):
- frequencies Nr 2, 32, 39: 1/100 Hz;
- voltages, currents, powers: raw·10^EXPO, the exponent from another word
  (the table's ``exponent``); an exponent byte is a signed int8 (A4);
  PGNEXPO and UGNEXPO in Nr 4 (mux 1), IGNEXPO in Nr 31 (mux 10), UNTEXPO
  in Nr 43, USSEXPO in Nr 44 (mux 14). The assembler caches them as they
  come; a value is None while its exponent has not come yet;
- Nr 5, the current active-power set point: raw·(PGNWWD/2800)·10^PGNEXPO W,
  PGNWWD being Nr 6;
- cos φ Nr 26: signed, /100, negative = capacitive (§2.3, E4);
- double-bit words Nr 9, 10, 12, 53-59 and single-bit words 13, 14, 60
  (§2.2): see the IntEnums below, whose values are bit numbers (the high
  bit of a pair);
- state bytes Nr 30, 33: FFh present, 00h not present (E10);
- hours Nr 45/46 and energy Nr 50/51: high·65536 + low (§1.6);
- battery Nr 52: 1/10 V; analog inputs Nr 61-68: the raw value, its
  meaning set on the device ("Skalierbar").

Decided where the manual is silent or contradicts itself (digest 004 §7):
- A3: Nr 1 "Kennung" is printed „1301“; 1301 (0515h) and 1301h are both
  taken (IDENTS); the assembler does not check it.
- A4: signed (two's complement) are the words that can be negative: active
  power Nr 3, the set point Nr 5, reactive power Nr 25, cos φ Nr 26 (the
  only one the manual proves), and the analog inputs Nr 61-68 (freely
  scaled, the analog-output limits of the same values go to -9999, 4.2.154).
  Every other word is unsigned; the exponent bytes are signed int8.
- A5: Nr 25 names QGNEXPO, which no word carries; PGNEXPO is applied, as
  the sister GCP-30 does. The reactive power shares the active power's
  range, so its exponent is the natural stand-in; to be checked on a device.
- A6: Nr 31 "IGNEXPO (Leistung)": the current exponent, used for Nr 22-24.
- A7: Nr 5 "PGNWWD/2800 (10^PGNEXPO) W" is taken literally,
  raw·PGNWWD/2800·10^PGNEXPO.
- A8: double bits in the telegram are not defined; 11 is TRUE, 00 FALSE,
  01 and 10 None (invalid or in transition), as the GCP-30 reads them.
- A27: Nr 10 bits 7+6 "Klemme 4: LS ist aus" says no breaker; it is
  T4_BREAKER_OPEN, whose breaker the application decides.
- A37: Nr 69 is internal (its remark repeats the analog-input sentence).
- A40: all four fault classes F0..F3 of Nr 9 are decoded.
"""

from __future__ import annotations

import enum
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

MUXES = 23  # mux 0..22 (ch. 3)
WORDS = 69  # Nr 1..69
IDENTS = (1301, 0x1301)  # Nr 1 „1301“, decimal or hex (A3)
PGNWWD_DIVISOR = 2800  # Nr 5 "PGNWWD/2800"


class Coding(enum.Enum):
    """How a telegram word is decoded."""

    IDENT = "ident"  # Nr 1 Kennung
    FREQUENCY = "frequency"  # 1/100 Hz
    SCALED = "scaled"  # raw·10^exponent
    SETPOINT = "setpoint"  # Nr 5: raw·PGNWWD/2800·10^PGNEXPO (A7)
    FACTOR = "factor"  # Nr 6: PGNWWD
    EXPONENTS = "exponents"  # int8 bytes (A4)
    COS_PHI = "cos_phi"  # signed /100
    DOUBLE_BITS = "double_bits"
    BITS = "bits"
    STATES = "states"  # FFh / 00h bytes
    COUNT = "count"
    HIGH = "high"  # high word of a 32-bit value (·65536)
    LOW = "low"
    BATTERY = "battery"  # 1/10 V
    ANALOG = "analog"  # "Skalierbar"
    INTERNAL = "internal"


@dataclass(frozen=True)
class Word:
    nr: int
    key: str
    german: str  # INHALT, as printed
    english: str
    unit: str  # Einheit, as printed
    coding: Coding
    exponent: str | None = None  # PGNEXPO ... for Coding.SCALED / SETPOINT
    signed: bool = False  # A4

    @property
    def mux(self) -> int:
        return (self.nr - 1) // 3

    @property
    def word(self) -> int:
        """1, 2 or 3: the word within its frame (bytes 2/3, 4/5, 6/7)."""
        return (self.nr - 1) % 3 + 1


C = Coding
_U_GEN, _U_MAINS = ("(10^UGNEXPO) V", "UGNEXPO"), ("(10^UNTEXPO) V", "UNTEXPO")


def _w(nr, key, german, english, unit, coding, exponent=None, signed=False) -> Word:
    return Word(nr, key, german, english, unit, coding, exponent, signed)


def _internal(nr: int) -> Word:
    return _w(nr, f"internal_{nr}", "Intern", "internal", "Intern", C.INTERNAL)


def _scaled(nr, key, german, english, unit_exponent, signed=False) -> Word:
    return _w(nr, key, german, english, unit_exponent[0], C.SCALED, unit_exponent[1], signed)


#: digest §2.1, in Nr order; WORD_TABLE[nr - 1].nr == nr
WORD_TABLE: tuple[Word, ...] = (
    _w(1, "ident", "Kennung", "identifier (telegram type)", "1301", C.IDENT),
    _w(2, "f_gen", "Gen-Frequenz L1/L2", "generator frequency L1/L2", "1/100 Hz", C.FREQUENCY),
    _scaled(3, "p_gen", "Gen-Wirkleistung", "generator active power", ("(10^PGNEXPO) W", "PGNEXPO"), True),
    _w(4, "exponents_p_u", "Exponenten", "exponents: high PGNEXPO, low UGNEXPO", "1", C.EXPONENTS),
    _w(
        5,
        "p_set",
        "Aktueller Wirkleistungssollwert",
        "current active-power set point",
        "(PGNWWD/2800)·(10^PGNEXPO) W",
        C.SETPOINT,
        "PGNEXPO",
        True,
    ),
    _w(6, "pgnwwd", "Umrechnungsfaktor", "conversion factor PGNWWD", "1", C.FACTOR),
    _scaled(7, "u_bus_l12", "Sammelschienenenspannung L1 L2", "busbar voltage L1-L2", ("(10^USSEXPO) V", "USSEXPO")),
    _scaled(8, "u_mains_l12", "Netzspannung L1 L2", "mains voltage L1-L2", _U_MAINS),
    _w(9, "fault_classes", "Anliegende Fehlerklassen", "present fault classes", "Doppelbits", C.DOUBLE_BITS),
    _w(10, "control_register_2", "Interne Steuerregister 2", "control register 2", "Doppelbits", C.DOUBLE_BITS),
    _internal(11),
    _w(12, "control_register_1", "Interne Steuerregister 1", "control register 1", "Doppelbits", C.DOUBLE_BITS),
    _w(13, "faults_8", "Interne Fehler 8", "internal faults 8", "Bits", C.BITS),
    _w(14, "faults_6", "Interne Fehler 6", "internal faults 6", "Bits", C.BITS),
    _scaled(15, "u_gen_l23", "Gen.-Spannung L2 L3", "generator voltage L2-L3", _U_GEN),
    _scaled(16, "u_gen_l31", "Gen.-Spannung L3 L1", "generator voltage L3-L1", _U_GEN),
    _scaled(17, "u_gen_l1n", "Gen.-Spannung L1 N", "generator voltage L1-N", _U_GEN),
    _scaled(18, "u_gen_l2n", "Gen.-Spannung L2 N", "generator voltage L2-N", _U_GEN),
    _scaled(19, "u_gen_l3n", "Gen.-Spannung L3 N", "generator voltage L3-N", _U_GEN),
    _scaled(20, "u_gen_l12", "Gen.-Spannung L1 L2", "generator voltage L1-L2", _U_GEN),
    _internal(21),
    _scaled(22, "i_gen_l1", "Gen.-Strom L1", "generator current L1", ("(10^IGNEXPO) A", "IGNEXPO")),
    _scaled(23, "i_gen_l2", "Gen.-Strom L2", "generator current L2", ("(10^IGNEXPO) A", "IGNEXPO")),
    _scaled(24, "i_gen_l3", "Gen.-Strom L3", "generator current L3", ("(10^IGNEXPO) A", "IGNEXPO")),
    # printed (10^QGNEXPO) var; no word carries QGNEXPO: PGNEXPO (A5)
    _scaled(25, "q_gen", "Gen.-Blindleistung", "generator reactive power", ("(10^QGNEXPO) var", "PGNEXPO"), True),
    _w(26, "cos_phi", "Gen.-cosϕ", "generator power factor", "1/100", C.COS_PHI, signed=True),
    _internal(27),
    _internal(28),
    _w(29, "participants", "Anzahl Teilnehmer Verteilung", "participants in load sharing", "1", C.COUNT),
    _w(30, "states_mains_gen", "Zustand Netz / Zustand Generator", "mains state, generator state", "Byte", C.STATES),
    _w(31, "exponent_i", "Exponenten", "exponents: high IGNEXPO, low reserve", "1", C.EXPONENTS),
    _w(32, "f_bus", "Sammelschienenfrequenz", "busbar frequency", "1/100 Hz", C.FREQUENCY),
    _w(33, "state_busbar", "Zustand Sammelschiene / Reserve", "busbar state", "1", C.STATES),
    _scaled(34, "u_mains_l23", "Netzspannung L2 L3", "mains voltage L2-L3", _U_MAINS),
    _scaled(35, "u_mains_l31", "Netzspannung L3 L1", "mains voltage L3-L1", _U_MAINS),
    _scaled(36, "u_mains_l1n", "Netzspannung L1 N", "mains voltage L1-N", _U_MAINS),
    _scaled(37, "u_mains_l2n", "Netzspannung L2 N", "mains voltage L2-N", _U_MAINS),
    _scaled(38, "u_mains_l3n", "Netzspannung L3 N", "mains voltage L3-N", _U_MAINS),
    _w(39, "f_mains", "Netzfrequenz aus L1 L2 L3", "mains frequency", "1/100 Hz", C.FREQUENCY),
    _internal(40),
    _internal(41),
    _internal(42),
    _w(43, "exponent_mains", "Exponenten", "exponents: high free, low UNTEXPO", "1", C.EXPONENTS),
    _w(44, "exponent_bus", "Exponenten", "exponents: high free, low USSEXPO", "1", C.EXPONENTS),
    _w(45, "hours_high", "Betriebsstunden Highwort", "operating hours, high word", "2^16 h", C.HIGH),
    _w(46, "hours_low", "Betriebsstunden Lowwort", "operating hours, low word", "h", C.LOW),
    _w(47, "hours_to_maintenance", "Stunden bis Wartung", "hours until maintenance", "h", C.COUNT),
    _w(48, "starts", "Aggregatstartzähler", "genset start counter", "1", C.COUNT),
    _internal(49),
    _w(50, "energy_high", "Gen.-Wirkarbeit Highwort", "generator active energy, high word", "2^16 kWh", C.HIGH),
    _w(51, "energy_low", "Gen.-Wirkarbeit Lowwort", "generator active energy, low word", "kWh", C.LOW),
    _w(52, "battery", "Batteriespannung", "battery voltage", "1/10 V", C.BATTERY),
    _w(53, "faults_1", "Interne Fehler 1", "internal faults 1", "Doppelbits", C.DOUBLE_BITS),
    _w(54, "faults_2", "Interne Fehler 2", "internal faults 2", "Doppelbits", C.DOUBLE_BITS),
    _w(55, "faults_3", "Interne Fehler 3", "internal faults 3", "Doppelbits", C.DOUBLE_BITS),
    _w(56, "faults_4", "Interne Fehler 4", "internal faults 4", "Doppelbits", C.DOUBLE_BITS),
    _w(57, "faults_5", "Interne Fehler 5", "internal faults 5", "Doppelbits", C.DOUBLE_BITS),
    _w(58, "di_faults_1_8", "Fehler DI's 1-8", "discrete-input faults DI 1-8", "Doppelbits", C.DOUBLE_BITS),
    _w(59, "di_faults_9_16", "Fehler DI's 9-16", "discrete-input faults DI 9-16", "Doppelbits", C.DOUBLE_BITS),
    _w(60, "faults_7", "Interne Fehler 7", "internal faults 7", "Bits", C.BITS),
    *(
        _w(60 + n, f"analog_{n}", f"Analogeingang {n}", f"analog input {n}", "Skalierbar", C.ANALOG, None, True)
        for n in range(1, 9)
    ),
    _internal(69),
)

WORDS_BY_KEY: dict[str, Word] = {w.key: w for w in WORD_TABLE}

#: where each exponent is: (Nr, shift of its byte) (§2.1 summary)
EXPONENTS: dict[str, tuple[int, int]] = {
    "PGNEXPO": (4, 8),  # Mux 1 W1 high byte
    "UGNEXPO": (4, 0),  # Mux 1 W1 low byte
    "IGNEXPO": (31, 8),  # Mux 10 W1 high byte (A6)
    "UNTEXPO": (43, 0),  # Mux 14 W1 low byte
    "USSEXPO": (44, 0),  # Mux 14 W2 low byte
}

#: the 32-bit values: key -> (Nr of the high word, Nr of the low word)
LONG_VALUES: dict[str, tuple[int, int]] = {"hours": (45, 46), "energy_kwh": (50, 51)}

#: the state bytes: key -> (Nr, shift) (§2.1 Nr 30, 33; E10)
STATE_BYTES: dict[str, tuple[int, int]] = {
    "mains_present": (30, 8),
    "generator_present": (30, 0),
    "busbar_present": (33, 8),
}
STATE_PRESENT, STATE_ABSENT = 0xFF, 0x00


# ------------------------------------------------------------------ bits (§2.2)


class FaultClass(enum.IntEnum):
    """Nr 9 "Anliegende Fehlerklassen", double bits (bits 15..8 internal, A40)."""

    F3 = 7
    F2 = 5
    F1 = 3
    F0 = 1


class ControlRegister2(enum.IntEnum):
    """Nr 10 "Interne Steuerregister 2", the terminals, double bits (11+10, 9+8, 1+0 internal)."""

    T3_GCB_RELEASE = 15  # Klemme 3: Freigabe GLS
    T5_GCB_CLOSED = 13  # Klemme 5: GLS ist ein
    T4_BREAKER_OPEN = 7  # Klemme 4: LS ist aus (which breaker: A27)
    T54_MAINS_PARALLEL = 5  # Klemme 54: Netzparallel
    T6_SYNC_ON = 3  # Klemme 6: Sync. ein


class ControlRegister1(enum.IntEnum):
    """Nr 12 "Interne Steuerregister 1", double bits (the others internal)."""

    ACK_F2_F3 = 11  # Quittierung F2/F3
    ACK_F1 = 9  # Quittierung F1


class Faults8(enum.IntEnum):
    """Nr 13 "Interne Fehler 8", single bits (9..0 free)."""

    GEN_OVERFREQUENCY_2 = 15
    GEN_UNDERFREQUENCY_2 = 14
    GEN_OVERVOLTAGE_2 = 13
    GEN_UNDERVOLTAGE_2 = 12
    REACTIVE_INDUCTIVE = 11
    REACTIVE_CAPACITIVE = 10


class Faults6(enum.IntEnum):
    """Nr 14 "Interne Fehler 6", single bits: analog input wire break (15..8 internal)."""

    AI8_WIRE_BREAK = 7
    AI7_WIRE_BREAK = 6
    AI6_WIRE_BREAK = 5
    AI5_WIRE_BREAK = 4
    AI4_WIRE_BREAK = 3
    AI3_WIRE_BREAK = 2
    AI2_WIRE_BREAK = 1
    AI1_WIRE_BREAK = 0


class Faults1(enum.IntEnum):
    """Nr 53 "Interne Fehler 1", double bits (7+6 internal)."""

    GEN_OVERFREQUENCY_1 = 15
    GEN_UNDERFREQUENCY_1 = 13
    GEN_OVERVOLTAGE_1 = 11
    GEN_UNDERVOLTAGE_1 = 9
    BATTERY_UNDERVOLTAGE = 5
    OVERLOAD = 3
    REVERSE_POWER = 1


class Faults2(enum.IntEnum):
    """Nr 54 "Interne Fehler 2", double bits (5+4 free)."""

    MAINS_OVERFREQUENCY = 15
    MAINS_UNDERFREQUENCY = 13
    MAINS_OVERVOLTAGE = 11
    MAINS_UNDERVOLTAGE = 9
    INTERFACE_X1_X5 = 7
    DF_DT = 3
    PHASE_JUMP = 1


class Faults3(enum.IntEnum):
    """Nr 55 "Interne Fehler 3", double bits (13+12, 11+10, 1+0 internal)."""

    OVERCURRENT_1 = 15  # G-Überstrom (UMZ) Stufe 1
    UNBALANCED_LOAD = 9
    OVERCURRENT_2 = 7
    INTERFACE_Y1_Y5 = 5
    MAINTENANCE_CALL = 3


class Faults4(enum.IntEnum):
    """Nr 56 "Interne Fehler 4", double bits: analog inputs 1-4, stages 1 and 2."""

    AI1_STAGE_1 = 15
    AI1_STAGE_2 = 13
    AI2_STAGE_1 = 11
    AI2_STAGE_2 = 9
    AI3_STAGE_1 = 7
    AI3_STAGE_2 = 5
    AI4_STAGE_1 = 3
    AI4_STAGE_2 = 1


class Faults5(enum.IntEnum):
    """Nr 57 "Interne Fehler 5", double bits: analog inputs 5-8, stages 1 and 2."""

    AI5_STAGE_1 = 15
    AI5_STAGE_2 = 13
    AI6_STAGE_1 = 11
    AI6_STAGE_2 = 9
    AI7_STAGE_1 = 7
    AI7_STAGE_2 = 5
    AI8_STAGE_1 = 3
    AI8_STAGE_2 = 1


class DiFaults1To8(enum.IntEnum):
    """Nr 58 "Fehler DI's 1-8", double bits: DI 1 = 15+14 ... DI 8 = 1+0."""

    DI1 = 15
    DI2 = 13
    DI3 = 11
    DI4 = 9
    DI5 = 7
    DI6 = 5
    DI7 = 3
    DI8 = 1


class DiFaults9To16(enum.IntEnum):
    """Nr 59 "Fehler DI's 9-16", double bits: DI 9 = 15+14 ... DI 16 = 1+0."""

    DI9 = 15
    DI10 = 13
    DI11 = 11
    DI12 = 9
    DI13 = 7
    DI14 = 5
    DI15 = 3
    DI16 = 1


class Faults7(enum.IntEnum):
    """Nr 60 "Interne Fehler 7", single bits (the others internal)."""

    EARTH_FAULT = 13  # Erdschluss
    OVERCURRENT_IEC255 = 12  # Überstrom AMZ nach IEC255


#: Nr -> (its bit names, True for double bits)
BIT_WORDS: dict[int, tuple[type[enum.IntEnum], bool]] = {
    9: (FaultClass, True),
    10: (ControlRegister2, True),
    12: (ControlRegister1, True),
    13: (Faults8, False),
    14: (Faults6, False),
    53: (Faults1, True),
    54: (Faults2, True),
    55: (Faults3, True),
    56: (Faults4, True),
    57: (Faults5, True),
    58: (DiFaults1To8, True),
    59: (DiFaults9To16, True),
    60: (Faults7, False),
}


def double_bit_mask(high_bit: int) -> int:
    """The mask of the pair high_bit + high_bit - 1 (high_bit odd, 1..15)."""
    if high_bit not in range(1, 16, 2):
        raise ValueError(f"a double bit's high bit is odd, 1..15, not {high_bit}")
    return 0b11 << (high_bit - 1)


def double_bit(word: int, high_bit: int) -> bool | None:
    """The pair high_bit + high_bit - 1 of word: 11 True, 00 False, 01 or 10
    None, invalid (A8)."""
    pair = (word & double_bit_mask(high_bit)) >> (high_bit - 1)
    return {0b11: True, 0b00: False}.get(pair)


def bit(word: int, n: int) -> bool:
    """Single bit n (0 = LSB, "Zählung bei 0 beginnend", §1.6)."""
    if not 0 <= n <= 15:
        raise ValueError(f"a bit of a word is 0..15, not {n}")
    return bool(word >> n & 1)


def decode_bits(nr: int, word: int) -> dict[str, bool | None]:
    """The named bits of status word Nr (9, 10, 12, 13, 14, 53-60) -> name: value."""
    if nr not in BIT_WORDS:
        raise ValueError(f"Nr {nr} is no bit word (§2.2: 9, 10, 12, 13, 14, 53-60)")
    names, double = BIT_WORDS[nr]
    return {m.name: (double_bit(word, m.value) if double else bit(word, m.value)) for m in names}


def _int8(byte: int) -> int:
    return byte - 0x100 if byte & 0x80 else byte


def _int16(word: int) -> int:
    return word - 0x10000 if word & 0x8000 else word


def _state(byte: int) -> bool | None:
    return {STATE_PRESENT: True, STATE_ABSENT: False}.get(byte)


class TelegramAssembler:
    """The 69 words of one device's telegram as its frames come.

    ``words[nr]`` is the last raw word Nr (None until it came; index 0 is
    unused), ``received_ns[nr]`` when; ``exponents`` the exponents seen so
    far (signed); ``version`` counts the changes (every feed() and clear()),
    so a reader can keep what it computed from the words until it moves.
    Not thread-safe: one owner feeds and reads it."""

    def __init__(self) -> None:
        self.version = 0
        self.clear()

    def clear(self) -> None:
        """Forget everything (the device went away)."""
        self.version += 1
        self.words: list[int | None] = [None] * (WORDS + 1)
        self.received_ns: list[int | None] = [None] * (WORDS + 1)
        self.exponents: dict[str, int] = {}
        self._muxes: set[int] = set()

    def feed(self, mux: int, words: Sequence[int], now_ns: int) -> None:
        """Store frame mux's three words (as frames.decode_telegram gives them)."""
        if not 0 <= mux < MUXES:
            raise ValueError(f"mux {mux} is outside 0..{MUXES - 1}")
        if len(words) != 3 or not all(0 <= w <= 0xFFFF for w in words):
            raise ValueError(f"a telegram frame carries three words 0..FFFFh, not {words!r}")
        self.version += 1
        for i, word in enumerate(words):
            nr = 3 * mux + i + 1
            self.words[nr] = word
            self.received_ns[nr] = now_ns
        self._muxes.add(mux)
        for name, (nr, shift) in EXPONENTS.items():
            if 3 * mux < nr <= 3 * mux + 3:
                self.exponents[name] = _int8(words[nr - 3 * mux - 1] >> shift & 0xFF)

    @property
    def complete(self) -> bool:
        """Every mux 0..22 came at least once since clear()."""
        return len(self._muxes) == MUXES

    def age_ns(self, nr: int, now_ns: int) -> int | None:
        """How long ago word Nr came; None if it never did."""
        if not 1 <= nr <= WORDS:
            raise ValueError(f"Nr {nr} is outside 1..{WORDS}")
        at = self.received_ns[nr]
        return None if at is None else now_ns - at

    def stale(self, now_ns: int, limit_ns: int) -> bool:
        """True until the telegram is complete, and when any word is older
        than limit_ns (no full cycle in that time; a cycle is about 2.3 s)."""
        if not self.complete:
            return True
        return any(now_ns - at > limit_ns for at in self.received_ns[1:] if at is not None)

    def value(self, key: str) -> float | int | bool | None:
        """One engineering value of values(), or None while its words (or
        its exponent) have not come."""
        if key in LONG_VALUES:
            high, low = (self.words[nr] for nr in LONG_VALUES[key])
            return None if high is None or low is None else high * 0x10000 + low
        if key in STATE_BYTES:
            nr, shift = STATE_BYTES[key]
            word = self.words[nr]
            return None if word is None else _state(word >> shift & 0xFF)
        w = WORDS_BY_KEY.get(key)
        if w is None or w.coding not in _VALUE_CODINGS:
            raise KeyError(key)
        raw = self.words[w.nr]
        if raw is None:
            return None
        if w.coding in FIXED_CODINGS:
            return fixed_value(w, raw)
        signed = _int16(raw) if w.signed else raw
        assert w.exponent is not None
        exponent = self.exponents.get(w.exponent)
        if exponent is None:
            return None
        scaled = Fraction(signed) * Fraction(10) ** exponent
        if w.coding is C.SETPOINT:
            factor = self.words[6]
            if factor is None:
                return None
            scaled = scaled * factor / PGNWWD_DIVISOR
        return float(scaled)

    def values(self) -> dict[str, float | int | bool | None]:
        """Every engineering value by key: frequencies in Hz, voltages V,
        currents A, powers W and var, cos φ, hours h, energy_kwh kWh,
        battery V, counts, the *_present states, the raw analog inputs."""
        return {key: self.value(key) for key in VALUE_KEYS}


_VALUE_CODINGS = {C.IDENT, C.FREQUENCY, C.SCALED, C.SETPOINT, C.COS_PHI, C.COUNT, C.BATTERY, C.ANALOG}
#: the codings whose value is the word alone, no exponent or factor of the telegram: fixed_value()
FIXED_CODINGS = {C.FREQUENCY: 100, C.COS_PHI: 100, C.BATTERY: 10, C.COUNT: 1, C.IDENT: 1, C.ANALOG: 1}


def fixed_value(w: Word, raw: int) -> float | int:
    """The engineering value of a word of FIXED_CODINGS (1/100 Hz, 1/100,
    1/10 V, or the number itself), from its raw word; signed where A4 says."""
    signed = _int16(raw) if w.signed else raw
    divisor = FIXED_CODINGS[w.coding]
    return float(Fraction(signed, divisor)) if divisor != 1 else signed


def _value_keys() -> tuple[str, ...]:
    keys: list[str] = []
    for w in WORD_TABLE:
        if w.coding in _VALUE_CODINGS:
            keys.append(w.key)
        keys += [key for key, (nr, _shift) in STATE_BYTES.items() if nr == w.nr]
        keys += [key for key, (high, _low) in LONG_VALUES.items() if high == w.nr]
    return tuple(keys)


#: the keys of TelegramAssembler.values(), in Nr order
VALUE_KEYS = _value_keys()
