"""Emergencies in the log (runtime/io/canopen/emcy_log.py): in the device's
words, one line per node and code at most every interval, the lines held
back counted in a "suppressed" line when the interval ends, an all-zero EMCY
logged as the end of the emergency."""

from __future__ import annotations

import logging

from softplc.runtime.io.canopen.emcy_log import EmcyLog

S = 1_000_000_000


class Clock:
    def __init__(self) -> None:
        self.now = 0

    def __call__(self) -> int:
        return self.now


def _lines(caplog) -> list:
    return [r.getMessage() for r in caplog.records if r.name.endswith("emcy_log")]


def test_one_line_per_code_and_interval_with_what_was_held_back(caplog):
    caplog.set_level(logging.INFO)
    clock = Clock()
    emcy = EmcyLog(interval_ns=10 * S, clock=clock)
    text = lambda code, register, data: f"words for {code:04X}"  # noqa: E731

    def at(t, code, register=0x01, data=b"\x01\0\0\0\0"):
        clock.now = t
        return emcy.emergency("pump", 5, code, register, data, text)

    assert at(0, 0x8130)
    assert not at(1 * S, 0x8130)
    assert not at(9 * S, 0x8130)
    assert at(9 * S, 0x2310)  # another code: at once
    assert at(10 * S, 0x8130)
    assert at(11 * S, 0x0000, 0x00, bytes(5))
    assert _lines(caplog) == [
        "canopen: node pump (5) emergency 0x8130, error register 0x01, data 01 00 00 00 00: words for 8130",
        "canopen: node pump (5) emergency 0x2310, error register 0x01, data 01 00 00 00 00: words for 2310",
        "suppressed 2 similar messages in 10 s; the last: "
        "canopen: node pump (5) emergency 0x8130, error register 0x01, data 01 00 00 00 00: words for 8130",
        "canopen: node pump (5) emergency 0x8130, error register 0x01, data 01 00 00 00 00: words for 8130",
        "canopen: node pump (5): emergency cleared",
    ]


def test_the_lines_held_back_are_told_when_the_interval_ends_without_another(caplog):
    caplog.set_level(logging.INFO)
    clock = Clock()
    emcy = EmcyLog(interval_ns=10 * S, clock=clock)
    for i in range(5):
        clock.now = i * S
        emcy.emergency("pump", 5, 0x8130, 0x01, bytes(5), None)
    emcy.flush(9 * S)
    assert len(_lines(caplog)) == 1
    emcy.flush(10 * S)
    assert _lines(caplog)[1].startswith("suppressed 4 similar messages in 10 s; the last: canopen: node pump (5)")


def test_without_the_device_s_words(caplog):
    caplog.set_level(logging.INFO)
    EmcyLog().emergency("motor", 40, 0x1000, 0x01, b"\x04\0\0\0\0", None)
    assert _lines(caplog) == ["canopen: node motor (40) emergency 0x1000, error register 0x01, data 04 00 00 00 00"]
