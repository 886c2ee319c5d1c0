"""The MPU2-S parameters (manual 004 ch. 4 "Parametrier-ID's", digest 004
§3): the 170 sub-sections 4.2.1-4.2.170 as data, in parameters.csv, and
their conversion between values and the raw words on the bus.

    p = parameter("sync_df_max")           # or "4.2.47", or its German or English name
    encode(p, 0.20)                         # 51: 0.20 Hz·256 = 51.2 (V8)
    frames.write_request(1, p.id, encode(p, 0.20))
    decode(p, 51)                           # 0.19921875 Hz
    by_id(19)                               # the five controller switches in ID 19
    merge(parameter("black_start"), word, True)     # read-modify-write of a bit field
    encode(parameter("gen_rated_voltage"), 400, factor=kwugnsek, variant=400)

parameters.csv, one row per sub-section:

    section      4.2.n
    key          a short name of this module's (stable, for programs)
    id           the parameter ID (bytes 2/3); the first of 3 or 8 for words3/words8
    kind         word, bit, double_bit, half_byte, words3 (relay manager), words8 (fault text)
    bits         the bits of a bit kind, high first: "15+14", "11+10+9+8", "3"
    raw_min/max  the documented raw range ("Wertebereich"); of the 100 V device where
                 the manual gives two; for the voltage families the U of "U·K/400"
    raw_min_400/raw_max_400   the 400 V device's range, where it differs
    family       a scaling family (scaling.py) or flag (0/1), switch (00/11), code
                 (an integer code), di_delay, fault_class, text, relay (codewords.py)
    unit         the value's unit
    signed       1: the word is two's complement (A4, A34)
    name_de      the heading, as printed (three corrected, below)
    name_en      an English name

The raw ranges are binding: "Die vorgegebenen Grenzen sind unbedingt
einzuhalten" (4.1.3). encode() refuses a value whose raw value is outside,
naming the parameter, the value, the raw value and the range; decode()
converts whatever the device sends. Bit, double-bit and half-byte
parameters share words: write them by read-modify-write, "immer zuerst das
gesamte Wort ... auslesen" (4.2.13 ff.), with merge(), which keeps every
other bit (also those the manual does not document). The voltage
parameters need the factor read from ID 507 (KWUGNSEK) or 508 (KWUNTSEK),
again after any change to the transformer parameters (4.2.10).

The table was extracted from digest 004 §3.2 and checked against every
ID, bit and range of the manual's sub-sections; tests read it back against
the digest's index §3.9.

Decided where the manual is unclear (digest 004 §7):
- Device variants: the 100 V and the 400 V device have different ranges
  for the VT secondaries and the voltage set points and limits (4.2.4 ff.).
  encode() takes variant=100 or 400; without it, a value must be valid on
  both (the overlap of the ranges), so nothing outside either is written.
- Voltage limits "25·KWUGNSEK/400 bis 125·KWUGNSEK/400": each limit is
  rounded as a value is (half away from zero), so the documented end
  values themselves always pass.
- A20: 4.2.73 (ID 118) is headed "Überstrom 2 Ansprechwert" like 4.2.75;
  its delay 4.2.74 is "Überstrom 1": it is stage 1, named so here.
- A21: the bits 1 and 0 of ID 310 (4.2.94, 4.2.99) are the voltage
  monitorings, whatever their value text says.
- A22: the battery under-voltage delay (ID 419) is raw 1..4950 as printed,
  though "0 s" is given for raw 1.
- A23: "Stillsetzen" (4.2.168) is printed at bit "1 1" of ID 201: bit 11,
  read as a broken "11" (a bit 1 would need no second digit). To be
  confirmed on a device before it is written.
- A24: the analog output sources (IDs 192, 195) are "0 – 23" but the list
  of ch. 5 ends at 22: 0..22.
- A29: 4.2.3 is the rated frequency "Generatornennfrequenz" (the TOC),
  not the body's "Generatorkennfrequenz".
- A33: 4.2.53 (ID 21 bit 0) lacks the read-modify-write note; it shares
  ID 21, so it is a bit parameter like the others.
- A34: signedness is per parameter: IDs 13, 69, 70, 114, 193, 194, 196,
  197 are signed, the others unsigned (VT primaries go to 65000).
- A35: the reverse-power pickup (ID 114) is signed, -99..99 %, as printed.
- 4.2.78 (ID 298) codes 00 normal, 01 very, 10 extremely inverse and 11
  "nicht definiert": 11 is refused.
- The cos φ set point (ID 13) is "-70 bis -99; 100; 70 bis 99": -69..69 is
  refused as well.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction
from importlib import resources
from typing import NoReturn

from . import codewords, scaling
from .codewords import RelayEvent
from .frames import to_word
from .scaling import KWUGNSEK_ID, KWUNTSEK_ID

__all__ = [
    "KWUGNSEK_ID",
    "KWUNTSEK_ID",
    "PARAMETERS",
    "Parameter",
    "all_ids",
    "by_id",
    "decode",
    "decode_words",
    "encode",
    "encode_words",
    "extract",
    "merge",
    "parameter",
    "raw_range",
    "Value",
]

CSV_FILE = "parameters.csv"
VARIANTS = (100, 400)  # the 100 V and the 400 V device (4.2.4 a.) / b.))
KINDS = ("word", "bit", "double_bit", "half_byte", "words3", "words8")
BIT_KINDS = ("bit", "double_bit", "half_byte")
WORDS_OF_KIND = {"words3": codewords.RELAY_IDS, "words8": codewords.TEXT_WORDS}
CODED_FAMILIES = ("flag", "switch", "code", "di_delay", "fault_class", "text", "relay")
SWITCH_ON, SWITCH_OFF = 0b11, 0b00  # "00 = aus, 11 = ein" (4.2.18, E11)
COS_PHI_MIN_MAGNITUDE = 70  # 4.2.30: -70..-99, 100, 70..99
RANGE_RULE = "Die vorgegebenen Grenzen sind unbedingt einzuhalten (4.1.3)"

#: what decode() gives: a number, a flag (None: a switch reading 01/10), digits
Value = float | int | bool | tuple[float, ...] | tuple[int, ...] | None


@dataclass(frozen=True)
class Parameter:
    section: str
    key: str
    id: int
    kind: str
    bits: tuple[int, ...]  # high first; () for words
    raw_min: int | None  # None: no numeric range (texts, relay words)
    raw_max: int | None
    raw_min_400: int | None  # the 400 V device's, where it differs
    raw_max_400: int | None
    family: str
    unit: str
    signed: bool
    name_de: str
    name_en: str

    @property
    def ids(self) -> tuple[int, ...]:
        """Every ID the parameter occupies: one, or 3 (relay) or 8 (text)."""
        return tuple(range(self.id, self.id + WORDS_OF_KIND.get(self.kind, 1)))

    @property
    def shift(self) -> int:
        """The lowest bit of a bit kind (0 for words)."""
        return min(self.bits, default=0)

    @property
    def mask(self) -> int:
        """The bits of the word the parameter owns (FFFFh for a word)."""
        if not self.bits:
            return 0xFFFF
        return sum(1 << b for b in self.bits)

    @property
    def factor_id(self) -> int | None:
        """The ID of the voltage factor the conversion needs (507, 508), or None."""
        return scaling.FACTOR_IDS.get(self.family)

    @property
    def variants(self) -> bool:
        """The 100 V and the 400 V device have different ranges."""
        return self.raw_min_400 is not None

    def __str__(self) -> str:
        return f"{self.section} {self.name_de} (ID {self.id})"


def _int_or_none(text: str) -> int | None:
    return int(text) if text.strip() else None


def _bits(text: str) -> tuple[int, ...]:
    bits = tuple(int(b) for b in text.split("+")) if text.strip() else ()
    if list(bits) != sorted(bits, reverse=True) or any(not 0 <= b <= 15 for b in bits):
        raise ValueError(f"bits {text!r} are not 15..0, high first")
    return bits


def _row(row: Mapping[str, str]) -> Parameter:
    p = Parameter(
        section=row["section"],
        key=row["key"],
        id=int(row["id"]),
        kind=row["kind"],
        bits=_bits(row["bits"]),
        raw_min=_int_or_none(row["raw_min"]),
        raw_max=_int_or_none(row["raw_max"]),
        raw_min_400=_int_or_none(row["raw_min_400"]),
        raw_max_400=_int_or_none(row["raw_max_400"]),
        family=row["family"],
        unit=row["unit"],
        signed=row["signed"] == "1",
        name_de=row["name_de"],
        name_en=row["name_en"],
    )
    if p.kind not in KINDS:
        raise ValueError(f"{p.section}: unknown kind {p.kind!r}")
    if p.family not in CODED_FAMILIES and p.family not in scaling.FAMILIES and p.family not in scaling.FACTOR_IDS:
        raise ValueError(f"{p.section}: unknown family {p.family!r}")
    if (p.kind in BIT_KINDS) != bool(p.bits):
        raise ValueError(f"{p.section}: a {p.kind} parameter {'needs' if p.kind in BIT_KINDS else 'has no'} bits")
    return p


def load(text: str) -> tuple[Parameter, ...]:
    """The parameters of a parameters.csv text."""
    return tuple(_row(row) for row in csv.DictReader(io.StringIO(text)))


PARAMETERS: tuple[Parameter, ...] = load(
    resources.files(__name__.rpartition(".")[0]).joinpath(CSV_FILE).read_text("utf-8")
)


def _index() -> tuple[dict[int, list[Parameter]], dict[str, list[Parameter]]]:
    by_id: dict[int, list[Parameter]] = {}
    by_name: dict[str, list[Parameter]] = {}
    for p in PARAMETERS:
        for i in p.ids:
            by_id.setdefault(i, []).append(p)
        for name in {p.section, p.key, p.name_de.casefold(), p.name_en.casefold()}:
            by_name.setdefault(name, []).append(p)
    return by_id, by_name


_BY_ID, _BY_NAME = _index()


def parameter(section_or_name: str) -> Parameter:
    """A parameter by its section ("4.2.47"), its key ("sync_df_max") or its
    German or English name (any case); ValueError if none or several match."""
    found = _BY_NAME.get(section_or_name) or _BY_NAME.get(section_or_name.strip().casefold(), [])
    if len(found) != 1:
        what = "several: " + ", ".join(p.section for p in found) if found else "no MPU2-S parameter"
        raise ValueError(f"{section_or_name!r}: {what}")
    return found[0]


def by_id(param_id: int) -> list[Parameter]:
    """Every parameter in the word at param_id (several share a bit word); [] if none."""
    return list(_BY_ID.get(param_id, []))


def all_ids() -> list[int]:
    """Every ID of the table, sorted."""
    return sorted(_BY_ID)


# ------------------------------------------------------------------ ranges


def raw_range(p: Parameter, *, factor: int | None = None, variant: int | None = None) -> tuple[int, int]:
    """The documented raw range (signed for a signed parameter; the field's
    for a bit kind): of the variant (100 or 400 V), or the overlap of both."""
    if p.raw_min is None or p.raw_max is None:
        raise ValueError(f"{p}: a {p.kind} parameter has no numeric range")
    if variant is not None and variant not in VARIANTS:
        raise ValueError(f"the MPU2-S is a 100 V or a 400 V device, not {variant!r}")
    lo, hi = p.raw_min, p.raw_max
    if p.raw_min_400 is not None and p.raw_max_400 is not None:
        if variant == 400:
            lo, hi = p.raw_min_400, p.raw_max_400
        elif variant is None:
            lo, hi = max(lo, p.raw_min_400), min(hi, p.raw_max_400)
    if p.factor_id is not None:
        scale = scaling.family(p.family, factor)
        lo, hi = scale.to_raw(lo), scale.to_raw(hi)
    elif factor is not None:
        raise ValueError(f"{p}: takes no voltage factor")
    return lo, hi


def _refuse(p: Parameter, value: object, raw: int, lo: int, hi: int, variant: int | None, why: str = "") -> NoReturn:
    unit = f" {p.unit}" if p.unit else ""
    hint = ""
    if p.variants:
        hint = (
            f" on the {variant} V device"
            if variant
            else " on both the 100 V and the 400 V device (say variant=100 or 400)"
        )
    raise ValueError(
        f"{p}: {value}{unit} is raw {raw}, outside the documented raw range {lo}..{hi}{hint}{why}. {RANGE_RULE}"
    )


def _check(p: Parameter, value: object, raw: int, factor: int | None, variant: int | None) -> int:
    lo, hi = raw_range(p, factor=factor, variant=variant)
    if not lo <= raw <= hi:
        _refuse(p, value, raw, lo, hi, variant)
    if p.family == "cos_phi" and abs(raw) < COS_PHI_MIN_MAGNITUDE:
        _refuse(p, value, raw, lo, hi, variant, " (-99..-70, 70..100: |cos φ| >= 0.70)")
    if p.family == "switch" and raw not in (SWITCH_OFF, SWITCH_ON):
        _refuse(p, value, raw, lo, hi, variant, " (00 off or 11 on)")
    return raw


# ------------------------------------------------------------------ values


def _code(p: Parameter, value: object) -> int:
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(f"{p}: a code is an integer, not {value!r}")
    return value


def _flag(p: Parameter, value: object) -> int:
    if value not in (True, False) or not isinstance(value, bool | int):
        raise ValueError(f"{p}: a {p.family} is True or False (or 1/0), not {value!r}")
    return int(bool(value))


def encode(p: Parameter, value: object, *, factor: int | None = None, variant: int | None = None) -> int:
    """A value -> the raw word to write (0..FFFFh, two's complement when
    signed), range-checked. For a bit kind it is the field's value, not yet
    shifted: write merge(p, word_read, value). Values by family: a number in
    the unit (scaled families), True/False (flag, switch), an int (code), 4
    delays in s (di_delay), 4 classes 0..3 (fault_class). Texts and relay
    chains: encode_words()."""
    if p.kind in WORDS_OF_KIND:
        raise ValueError(f"{p}: {p.kind} takes encode_words()")
    _no_factor(p, factor)
    if p.family in ("flag", "switch"):
        raw = _flag(p, value) * (SWITCH_ON if p.family == "switch" else 1)
    elif p.family == "code":
        raw = _code(p, value)
    elif p.family == "di_delay":
        raw = codewords.di_delay_word(_sequence(p, value))
    elif p.family == "fault_class":
        raw = codewords.fault_class_word(_sequence(p, value))
    else:
        if isinstance(value, bool) or not isinstance(value, int | float | Fraction | Decimal):
            raise ValueError(f"{p}: a value in {p.unit or 'its unit'}, not {value!r}")
        raw = scaling.family(p.family, factor).to_raw(value)
    _check(p, value, raw, factor, variant)
    return to_word(raw) if p.kind == "word" else raw


def _no_factor(p: Parameter, factor: int | None) -> None:
    if factor is not None and p.factor_id is None:
        raise ValueError(f"{p}: takes no voltage factor")


def _sequence(p: Parameter, value: object) -> Sequence:
    if isinstance(value, str) or not isinstance(value, Sequence):
        raise ValueError(f"{p}: four values, one per input, not {value!r}")
    return value


def decode(p: Parameter, raw: int, *, factor: int | None = None) -> Value:
    """A raw word read from the device (for a bit kind: the field, as
    extract() gives it) -> the value: float (int for ·1 families), bool
    (flag; switch: None for 01/10), int (code), tuple (digit words). Not
    range-checked."""
    if p.kind in WORDS_OF_KIND:
        raise ValueError(f"{p}: {p.kind} takes decode_words()")
    _no_factor(p, factor)
    limit = (1 << len(p.bits)) - 1 if p.bits else 0xFFFF
    if not 0 <= raw <= limit:
        raise ValueError(f"{p}: raw {raw} is outside 0..{limit}")
    if p.family == "flag":
        return bool(raw)
    if p.family == "switch":
        return {SWITCH_ON: True, SWITCH_OFF: False}.get(raw)
    if p.family == "di_delay":
        return codewords.di_delays(raw)
    if p.family == "fault_class":
        return codewords.fault_classes(raw)
    value = raw - 0x10000 if p.signed and raw & 0x8000 else raw
    if p.family == "code":
        return value
    scale = scaling.family(p.family, factor)
    return value if scale.per_unit == 1 else scale.from_raw(value)


def merge(p: Parameter, word: int, value: object) -> int:
    """The word read from p.id with p's bits set to value, every other bit
    kept (read-modify-write, 4.2.13 ff.)."""
    if p.kind not in BIT_KINDS:
        raise ValueError(f"{p}: a {p.kind} parameter is written whole, not merged")
    if not 0 <= word <= 0xFFFF:
        raise ValueError(f"{word} is no 16-bit word")
    return (word & ~p.mask & 0xFFFF) | encode(p, value) << p.shift


def extract(p: Parameter, word: int) -> Value:
    """p's value in the word read from p.id."""
    if p.kind not in BIT_KINDS:
        raise ValueError(f"{p}: a {p.kind} parameter is a whole word: decode()")
    return decode(p, (word & p.mask) >> p.shift)


def encode_words(p: Parameter, value: str | Iterable[RelayEvent]) -> dict[int, int]:
    """A fault text (words8) or a relay chain of 1..3 RelayEvents (words3)
    -> {ID: word}, each ID to be written on its own (4.2.160: "Jede ID ist
    einzeln zu berechnen und zu senden")."""
    if p.family == "text" and isinstance(value, str):
        return dict(zip(p.ids, codewords.text_words(value)))
    if p.family == "relay" and not isinstance(value, str):
        return dict(zip(p.ids, codewords.relay_words(list(value))))
    raise ValueError(f"{p}: encode_words() takes a text (words8) or RelayEvents (words3), not {value!r}")


def decode_words(p: Parameter, words: Mapping[int, int]) -> str | tuple[RelayEvent, ...]:
    """{ID: word} as read -> the text, or the relay chain up to the word
    that ends it (the IDs after it need not be there)."""
    if p.kind not in WORDS_OF_KIND:
        raise ValueError(f"{p}: a {p.kind} parameter: decode()")
    chain: list[int] = []
    for i in p.ids:
        if i not in words:
            raise ValueError(f"{p}: ID {i} not read" + (", and the chain does not end before it" if chain else ""))
        chain.append(words[i])
        if p.family == "relay" and words[i] & codewords.RELAY_END:
            break
    return codewords.text_of(chain) if p.family == "text" else codewords.relay_events(chain)
