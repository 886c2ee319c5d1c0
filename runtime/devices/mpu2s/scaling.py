"""The scaling families of the MPU2-S parameters: how a value in its unit
becomes the raw number written to a parameter ID ("Berechnungsformel",
manual 004 ch. 4; digest 004 §3.1). Pure arithmetic; which parameter uses
which family, and its raw range, is parameters.py.

    FREQUENCY.to_raw(70)                  # 17920 (E1)
    FREQUENCY.from_raw(12800)             # 50.0 Hz
    family("voltage_gen", 400).to_raw(230) # 230: U·KWUGNSEK/400 with KWUGNSEK 400

raw = value · per_unit, rounded to the nearest integer, a half away from
zero. The manual prints the endpoints that way (digest §3.1, §5.1): 0.05 Hz
is 13 (12.8), 0.49 Hz is 125 (125.44), 0.02 Hz is 5 (5.12). A float is
taken by its shortest decimal form (0.49, not 0.48999999999999999112), so
what the user wrote is what is rounded; from_raw(to_raw(x)) is x to the
family's resolution, and to_raw(from_raw(raw)) is raw for every word.

The result is an integer that may be negative (cos φ, the power set points,
reverse power): parameters.py checks it against the documented range and
makes the bus word (its two's complement, frames.to_word).

Families (digest §3.1; the IDs using them are in parameters.csv):

    frequency     f[Hz]·256                 1/256 Hz
    ramp          ramp[Hz/s]·102.4          A13, see below
    time          t[s]·50                   20 ms ticks
    seconds       t[s]·1
    milliseconds  t[ms]·1
    pulse         t[ms]·0.5                 2 ms
    percent_40    %·40                      0.025 %  (voltage differences, voltage dead band)
    percent_10    %·10                      0.1 %
    percent_1     %·1 (and %/s)
    gain          Kp·10, factor·10          0.1
    multiple      I/In·1000                 0.001 In
    plain         V, A, kW, °, counts ·1
    voltage_gen   U[V]·KWUGNSEK/400         the factor read from ID 507
    voltage_mains U[V]·KWUNTSEK/400         the factor read from ID 508
    battery       U[V]·10                   0.1 V
    cos_phi       cos φ·100, signed         negative = capacitive (§2.3)

Decided where the manual contradicts itself (digest 004 §7):
- A13: the frequency controller ramp (ID 68) prints the formula
  "Rampe·1024" beside the range "102 bis 5120, dies entspricht 1 Hz/s bis
  50 Hz/s". 1024 reproduces neither endpoint, 102.4 reproduces both
  (1·102.4 = 102.4 -> 102, 50·102.4 = 5120); and the sister GCP-20's
  frequency ramp is 2..50 Hz/s, while 1024 would make the range 0.1..5
  Hz/s. The raw range is what the manual calls binding ("unbedingt
  einzuhalten"), so the factor is 102.4. To be checked on a device.
- A14: whether U in U·KWUGNSEK/400 is the primary or the secondary voltage
  is not said; the family converts what the manual's real ranges are given
  in (25..125 V on the 100 V device), the factor is the device's.
"""

from __future__ import annotations

from dataclasses import dataclass
from decimal import Decimal
from fractions import Fraction

Number = int | float | Fraction | Decimal

FACTOR_DIVISOR = 400  # U·KWUGNSEK/400, U·KWUNTSEK/400 (4.2.10, 4.2.110)
KWUGNSEK_ID = 507  # "Der Faktor ist auf ID 507 des Gerätes zu finden" (4.2.10)
KWUNTSEK_ID = 508  # the mains factor (4.2.110)


def round_half_away(x: Fraction) -> int:
    """x rounded to the nearest integer, a half away from zero (12.5 -> 13, -12.5 -> -13)."""
    whole = int(abs(x) + Fraction(1, 2))
    return whole if x >= 0 else -whole


def exact(value: Number) -> Fraction:
    """A value as an exact fraction; a float by its shortest decimal form."""
    if isinstance(value, bool):
        raise TypeError("a scaled value is a number, not a bool")
    if isinstance(value, float):
        try:
            return Fraction(repr(value))
        except ValueError:
            raise ValueError(f"{value} is no finite number") from None
    if isinstance(value, int | Fraction | Decimal):
        try:
            return Fraction(value)
        except (ValueError, OverflowError):
            raise ValueError(f"{value} is no finite number") from None
    raise TypeError(f"a scaled value is a number, not {type(value).__name__}")


@dataclass(frozen=True)
class Scale:
    """raw = value · per_unit (rounded half away from zero)."""

    name: str
    per_unit: Fraction
    unit: str

    def to_raw(self, value: Number) -> int:
        """A value in the family's unit -> the raw integer (not range-checked)."""
        return round_half_away(exact(value) * self.per_unit)

    def from_raw(self, raw: int) -> float:
        """A raw integer (signed already, where the parameter is) -> the value."""
        return float(Fraction(raw) / self.per_unit)


FREQUENCY = Scale("frequency", Fraction(256), "Hz")  # "f[Hz]·256" (4.2.2; E1: 70 Hz -> 17920)
RAMP = Scale("ramp", Fraction(512, 5), "Hz/s")  # 102.4, not the printed 1024 (4.2.21, A13)
TIME = Scale("time", Fraction(50), "s")  # "t[s]·50" (4.2.20)
SECONDS = Scale("seconds", Fraction(1), "s")  # "t[s]·1/s" (4.2.54, 4.2.58, 4.2.169)
MILLISECONDS = Scale("milliseconds", Fraction(1), "ms")  # "t[ms]·1/ms" (4.2.52)
PULSE = Scale("pulse", Fraction(1, 2), "ms")  # "t[ms]·0,5" (4.2.23, 4.2.27)
PERCENT_40 = Scale("percent_40", Fraction(40), "%")  # "dU[%]·40" (4.2.26, 4.2.49, 4.2.50, 4.2.57)
PERCENT_10 = Scale("percent_10", Fraction(10), "%")  # "%·10" (4.2.31, 4.2.35 ...)
PERCENT_1 = Scale("percent_1", Fraction(1), "%")  # "%·1" (4.2.34 in %/s, 4.2.83)
GAIN = Scale("gain", Fraction(10), "")  # "Kp·10" (4.2.24, 4.2.28, 4.2.32, 4.2.38, 4.2.39)
MULTIPLE = Scale("multiple", Fraction(1000), "In")  # "·1000" (4.2.80, 4.2.81)
PLAIN = Scale("plain", Fraction(1), "")  # V, A, kW, ° ·1 (4.2.4, 4.2.12, 4.2.14, 4.2.116 ...)
BATTERY = Scale("battery", Fraction(10), "V")  # "U[V]·10" (4.2.126)
COS_PHI = Scale("cos_phi", Fraction(100), "")  # "cosφ·100", negative = capacitive (4.2.30, §2.3)

FAMILIES: dict[str, Scale] = {
    s.name: s
    for s in (
        FREQUENCY,
        RAMP,
        TIME,
        SECONDS,
        MILLISECONDS,
        PULSE,
        PERCENT_40,
        PERCENT_10,
        PERCENT_1,
        GAIN,
        MULTIPLE,
        PLAIN,
        BATTERY,
        COS_PHI,
    )
}

#: the voltage families and the ID their factor is read from (4.2.10, 4.2.110)
FACTOR_IDS: dict[str, int] = {"voltage_gen": KWUGNSEK_ID, "voltage_mains": KWUNTSEK_ID}
FACTOR_NAMES: dict[str, str] = {"voltage_gen": "KWUGNSEK", "voltage_mains": "KWUNTSEK"}


def voltage(name: str, factor: int) -> Scale:
    """U[V]·factor/400 (4.2.10), factor the KWUGNSEK or KWUNTSEK word read
    from the device (1..65535)."""
    if isinstance(factor, bool) or not isinstance(factor, int) or not 1 <= factor <= 0xFFFF:
        raise ValueError(f"{FACTOR_NAMES.get(name, name)} is a 16-bit word 1..65535, not {factor!r}")
    return Scale(name, Fraction(factor, FACTOR_DIVISOR), "V")


def family(name: str, factor: int | None = None) -> Scale:
    """The family called name; a voltage family needs the factor read from
    its ID (FACTOR_IDS), the others take none."""
    if name in FACTOR_IDS:
        if factor is None:
            raise ValueError(
                f"{name}: U[V]·{FACTOR_NAMES[name]}/400 needs factor={FACTOR_NAMES[name]},"
                f" read from ID {FACTOR_IDS[name]}"
            )
        return voltage(name, factor)
    if name not in FAMILIES:
        raise ValueError(f"no scaling family {name!r}")
    if factor is not None:
        raise ValueError(f"{name} takes no voltage factor")
    return FAMILIES[name]
