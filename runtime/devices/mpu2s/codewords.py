"""MPU2-S parameter words that carry no scaled number: the fault texts, the
relay-manager event words and the digit-coded words of the discrete inputs
(manual 004 4.2.129-4.2.166, ch. 6; digest 004 §3.5, §3.6, §3.8). Pure;
parameters.py applies them to its table entries.

    text_words("ABCDEFGHIJKLMNOP")   # (0x4F50, 0x4D4E, ... 0x4142): 'OP' first (E5)
    RelayEvent(68, end=True).word     # 0x4404 (V19)
    di_delay_word((0.1, 1, 5, 100))   # 359: digits 0, 3, 5, 9 (E6)
    fault_class_word((3, 3, 3, 3))    # 3333 (E7)

Fault texts (4.2.140-4.2.151): 16 characters, two ASCII codes per word,
the first in the high byte; eight IDs per text, "written backwards": the
first ID holds characters 15-16, the last characters 1-2 (E5).

Relay manager (4.2.160-4.2.166): three IDs per relay, each a word with the
event number (ch. 6) in the high byte and in the low byte bit 2 "end of
chain" (the remaining IDs are ignored), bit 1 "inverted", bit 0 AND (1) or
OR (0) with the next ID; bits 7-3 always 0 (E12). AND binds before OR.

Digit words: one decimal digit per input, 0-9 a delay code (IDs 404-406,
E6), 0-3 a fault class (IDs 130, 135, 136, E7).

Decided where the manual is unclear (digest 004 §7):
- A25: the example text ",ABCDEFGHJKLMNOP'" has 15 characters yet the
  mapping shows 'IJ'; the text is 16 characters, a shorter one is padded
  with spaces at the end, and reading strips the trailing spaces. Only
  printable ASCII (20h-7Eh) is written ("ASCII-Codes").
- A26: which digit belongs to which input is not said, nor whether the
  word is decimal or BCD. The thousands digit is the lowest input (DI 1,
  5 or 9), as the bits of the half-byte parameters put DI 1 at the top
  (4.2.128: bit 11 = DI 1), and the word is the decimal number ("0000 bis
  9999", a decimal range: 3333 is 0D05h, not 3333h). To be checked on a
  device.
- A30: the chain always ends at the third ID; RelayEvent only codes what
  each word says.
"""

from __future__ import annotations

import enum
from collections.abc import Sequence
from dataclasses import dataclass
from fractions import Fraction

from .scaling import Number, exact

TEXT_LENGTH = 16  # "beinhalten immer 16 Zeichen" (4.2.140)
TEXT_WORDS = 8  # "werden pro Text acht ID's verwendet"
TEXT_PAD = " "  # A25
TEXT_TERMINALS = range(62, 74)  # Klemme 62..73, 4.2.140..4.2.151
TEXT_FIRST_ID = 732  # Klemme 62: IDs 732..739; each next terminal 8 IDs on

RELAY_END = 0x04  # low byte bit 2: "Die log. Verknüpfung ist beendet"
RELAY_INVERT = 0x02  # bit 1: "Das Ereignis wird invertiert (logisch NOT)"
RELAY_AND = 0x01  # bit 0: 1 = UND-, 0 = ODER-Verknüpfung mit der nächsten ID
RELAY_IDS = 3  # "Hierzu werden pro Relais drei ID's benötigt"
RELAYS = range(1, 8)  # Relais 1..7, 4.2.160..4.2.166
RELAY_FIRST_ID = 436  # relay r: 436 + 3·(r - 1) .. + 2
EVENT_MIN, EVENT_MAX = 1, 98  # the event list of ch. 6 is 01..98

DIGITS = 4  # four inputs per word: "0000 bis 9999"
#: the delay of each digit 0..9 (4.2.129, E6), seconds
DI_DELAYS: tuple[Fraction, ...] = tuple(
    Fraction(x) for x in ("0.1", "0.2", "0.5", "1", "2", "5", "10", "20", "50", "100")
)
FAULT_CLASS_MAX = 3  # "0000 bis 3333 (Stellenweise 0 bis 3)" (4.2.131, E7)


class Event(enum.IntEnum):
    """The relay-manager events (ch. 6) the genset synchronisation uses."""

    GCB_CONNECT_TIME = 29  # Zuschaltzeitfehler GLS
    GCB_CLOSED = 68  # GLS EIN
    GCB_CLOSE_FAULT = 89  # Störung GLS EIN
    GCB_OPEN_FAULT = 91  # Störung GLS AUF
    BLACK_START_TIME = 94  # Zuschaltzeit außerhalb Grenzen Schwarzstart


# ------------------------------------------------------------------ fault texts


def text_words(text: str) -> tuple[int, ...]:
    """A fault text -> its 8 words in ID order: the first ID carries
    characters 15-16, the last characters 1-2 (E5). Padded with spaces to
    16 characters (A25); ValueError for a longer text or one that is not
    printable ASCII."""
    if len(text) > TEXT_LENGTH:
        raise ValueError(f"a fault text has {TEXT_LENGTH} characters, {text!r} has {len(text)}")
    bad = [c for c in text if not " " <= c <= "~"]
    if bad:
        raise ValueError(f"a fault text is printable ASCII; {text!r} has {''.join(bad)!r}")
    data = text.ljust(TEXT_LENGTH, TEXT_PAD).encode("ascii")
    pairs = [int.from_bytes(data[i : i + 2], "big") for i in range(0, TEXT_LENGTH, 2)]
    return tuple(reversed(pairs))


def text_of(words: Sequence[int]) -> str:
    """The 8 words of a fault text in ID order -> the text, trailing spaces
    stripped. A byte outside printable ASCII is shown as '?'."""
    if len(words) != TEXT_WORDS:
        raise ValueError(f"a fault text is {TEXT_WORDS} words, not {len(words)}")
    data = b"".join(w.to_bytes(2, "big") for w in reversed(words))
    return "".join(chr(b) if 0x20 <= b <= 0x7E else "?" for b in data).rstrip(TEXT_PAD)


def text_ids(terminal: int) -> range:
    """The 8 IDs of the fault text of Klemme 62..73 (4.2.140-4.2.151)."""
    if terminal not in TEXT_TERMINALS:
        raise ValueError(f"fault texts are for terminals 62..73, not {terminal}")
    first = TEXT_FIRST_ID + TEXT_WORDS * (terminal - TEXT_TERMINALS.start)
    return range(first, first + TEXT_WORDS)


# ------------------------------------------------------------------ relay manager


@dataclass(frozen=True)
class RelayEvent:
    """One ID of a relay's event chain (4.2.160, E12)."""

    event: int  # 1..98, the list of ch. 6
    end: bool = False  # bit 2: the chain ends here, the remaining IDs are ignored
    invert: bool = False  # bit 1: NOT
    and_next: bool = False  # bit 0: AND (True) or OR (False) with the next ID

    def __post_init__(self) -> None:
        if isinstance(self.event, bool) or not EVENT_MIN <= self.event <= EVENT_MAX:
            raise ValueError(f"relay-manager events are {EVENT_MIN}..{EVENT_MAX} (ch. 6), not {self.event!r}")

    @property
    def word(self) -> int:
        flags = (RELAY_END if self.end else 0) | (RELAY_INVERT if self.invert else 0)
        return self.event << 8 | flags | (RELAY_AND if self.and_next else 0)

    @classmethod
    def from_word(cls, word: int) -> RelayEvent:
        """ValueError for bits 7-3 set ("werden immer auf Null gesetzt") or
        an event outside 1..98."""
        if not 0 <= word <= 0xFFFF:
            raise ValueError(f"{word} is no 16-bit word")
        if word & 0xF8:
            raise ValueError(f"relay word {word:04X}h has low-byte bits 7-3 set; they are always 0 (E12)")
        return cls(word >> 8, bool(word & RELAY_END), bool(word & RELAY_INVERT), bool(word & RELAY_AND))


def relay_ids(relay: int) -> range:
    """The 3 IDs of relay 1..7 (4.2.160-4.2.166)."""
    if relay not in RELAYS:
        raise ValueError(f"the relay manager has relays 1..7, not {relay}")
    first = RELAY_FIRST_ID + RELAY_IDS * (relay - 1)
    return range(first, first + RELAY_IDS)


def relay_words(events: Sequence[RelayEvent]) -> tuple[int, ...]:
    """A chain of 1..3 events -> their words in ID order. The last one must
    end the chain (bit 2), and only the last one."""
    if not 1 <= len(events) <= RELAY_IDS:
        raise ValueError(f"a relay takes 1..{RELAY_IDS} events, not {len(events)}")
    if not events[-1].end or any(e.end for e in events[:-1]):
        raise ValueError("the last event of a chain, and only it, has end=True (bit 2)")
    return tuple(e.word for e in events)


def relay_events(words: Sequence[int]) -> tuple[RelayEvent, ...]:
    """A relay's words in ID order -> its chain, up to the word that ends it
    (the third at the latest: A30); the words after it are not decoded."""
    chain: list[RelayEvent] = []
    for word in words[:RELAY_IDS]:
        chain.append(RelayEvent.from_word(word))
        if chain[-1].end:
            break
    return tuple(chain)


# ------------------------------------------------------------------ digit words


def digit_word(digits: Sequence[int], highest: int) -> int:
    """Four digits 0..highest, the first for the lowest input (A26) -> the
    decimal word: (1, 2, 3, 0) -> 1230."""
    if len(digits) != DIGITS:
        raise ValueError(f"a digit word codes {DIGITS} inputs, not {len(digits)}")
    for d in digits:
        if isinstance(d, bool) or not isinstance(d, int) or not 0 <= d <= highest:
            raise ValueError(f"each digit is 0..{highest}, not {d!r}")
    word = 0
    for d in digits:
        word = word * 10 + d
    return word


def word_digits(word: int, highest: int) -> tuple[int, ...]:
    """The decimal word -> its four digits, the lowest input first (A26);
    ValueError for a word above 9999 or a digit above highest."""
    if not 0 <= word <= 9999:
        raise ValueError(f"a digit word is 0000..9999, not {word}")
    digits = tuple(int(c) for c in f"{word:04d}")
    if max(digits) > highest:
        raise ValueError(f"word {word:04d} has a digit above {highest}")
    return digits


def di_delay_word(seconds: Sequence[Number]) -> int:
    """The delays of four inputs in seconds, each one of DI_DELAYS -> the
    word of IDs 404-406 (E6)."""
    codes = []
    for s in seconds:
        value = exact(s)
        if value not in DI_DELAYS:
            raise ValueError(f"a DI delay is one of {', '.join(str(float(d)) for d in DI_DELAYS)} s, not {s}")
        codes.append(DI_DELAYS.index(value))
    return digit_word(codes, len(DI_DELAYS) - 1)


def di_delays(word: int) -> tuple[float, ...]:
    """The word of IDs 404-406 -> four delays in seconds."""
    return tuple(float(DI_DELAYS[d]) for d in word_digits(word, len(DI_DELAYS) - 1))


def fault_class_word(classes: Sequence[int]) -> int:
    """The fault classes 0..3 of four inputs -> the word of IDs 130, 135, 136 (E7)."""
    return digit_word(classes, FAULT_CLASS_MAX)


def fault_classes(word: int) -> tuple[int, ...]:
    """The word of IDs 130, 135, 136 -> four fault classes."""
    return word_digits(word, FAULT_CLASS_MAX)
