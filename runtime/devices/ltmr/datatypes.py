"""LTMR data types: DT_DateTime, DT_CommercialReference, two-word and signed register values.

How a value spread over registers, or packed into one, is encoded. Source:
manual 001 (DOCA0132EN, shared/manuals/001_5287ad2b8a6c20a4.txt; "L<n>" below
is a line of that file) and its digest (shared/digests/001_ltmr_canopen_en.md,
"§" and the ambiguities "A<n>" of its §10).

    encode_datetime(datetime(2008, 9, 4, 7, 50, 32)) -> (0x3200, 0x0750, 0x0904, 0x2008)
"""

from __future__ import annotations

import datetime as _dt

# ---------------------------------------------------------------------------
# Data types (§5.4, §5.5)
# ---------------------------------------------------------------------------

DATETIME_MIN = _dt.datetime(2006, 1, 1, 0, 0, 0)  # L1931
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
    return (
        _bcd(dt.second) << 8,
        _bcd(dt.hour) << 8 | _bcd(dt.minute),
        _bcd(dt.month) << 8 | _bcd(dt.day),
        _bcd(dt.year),
    )


def decode_datetime(words) -> _dt.datetime:
    """The datetime of four DT_DateTime words; ValueError for a non-BCD digit, an
    impossible date (2007-02-29) or a value outside 2006 .. 2099 ("the system
    will return a detected error", L1936). The low byte of the first word is
    "unused" and ignored."""
    seconds_word, hour_minute, month_day, year = (int(w) & 0xFFFF for w in words)
    parts = dict(
        year=_from_bcd(year, "year"),
        month=_from_bcd(month_day >> 8, "month"),
        day=_from_bcd(month_day & 0xFF, "day"),
        hour=_from_bcd(hour_minute >> 8, "hour"),
        minute=_from_bcd(hour_minute & 0xFF, "minute"),
        second=_from_bcd(seconds_word >> 8, "second"),
    )
    try:
        value = _dt.datetime(
            parts["year"], parts["month"], parts["day"], parts["hour"], parts["minute"], parts["second"]
        )
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
