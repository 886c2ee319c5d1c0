"""Emergencies in the log (runtime/io/canopen/emcy_log.py): in the device's
words, one line per node and code at most every interval, the lines held
back counted, an all-zero EMCY logged as the end of the emergency."""

from __future__ import annotations

import logging

from softplc.runtime.io.canopen.emcy_log import EmcyLog

S = 1_000_000_000


def _lines(caplog) -> list:
    return [r.getMessage() for r in caplog.records if r.name.endswith("emcy_log")]


def test_one_line_per_code_and_interval_with_what_was_held_back(caplog):
    caplog.set_level(logging.INFO)
    emcy = EmcyLog(interval_ns=10 * S)
    text = lambda code, register, data: f"words for {code:04X}"  # noqa: E731
    assert emcy.emergency("pump", 5, 0x8130, 0x01, b"\x01\0\0\0\0", 0, text)
    assert not emcy.emergency("pump", 5, 0x8130, 0x01, b"\x01\0\0\0\0", 1 * S, text)
    assert not emcy.emergency("pump", 5, 0x8130, 0x01, b"\x01\0\0\0\0", 9 * S, text)
    assert emcy.emergency("pump", 5, 0x2310, 0x01, b"\x01\0\0\0\0", 9 * S, text)  # another code: at once
    assert emcy.emergency("pump", 5, 0x8130, 0x01, b"\x01\0\0\0\0", 10 * S, text)
    assert emcy.emergency("pump", 5, 0x0000, 0x00, bytes(5), 11 * S, text)
    assert _lines(caplog) == [
        "canopen: node pump (5) emergency 0x8130, error register 0x01, data 01 00 00 00 00: words for 8130",
        "canopen: node pump (5) emergency 0x2310, error register 0x01, data 01 00 00 00 00: words for 2310",
        "canopen: node pump (5) emergency 0x8130, error register 0x01, data 01 00 00 00 00: words for 8130 "
        "(2 more since the last line)",
        "canopen: node pump (5): emergency cleared",
    ]


def test_without_the_device_s_words(caplog):
    caplog.set_level(logging.INFO)
    EmcyLog().emergency("motor", 40, 0x1000, 0x01, b"\x04\0\0\0\0", 0, None)
    assert _lines(caplog) == ["canopen: node motor (40) emergency 0x1000, error register 0x01, data 04 00 00 00 00"]
