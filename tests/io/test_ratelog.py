"""The rate limiter every bus logs through (runtime/io/ratelog.py): one line
per key and window, at most a budget of lines per interval over all keys,
and a "suppressed N" line when a window that held lines back ends, so that
the numbers always add up. Time is a clock the test moves."""

from __future__ import annotations

import logging
import re

import pytest

from softplc.runtime.io.ratelog import PeerLogFilter, RateLimitedLog

S = 1_000_000_000
NAME = "softplc.test.ratelog"


class Clock:
    def __init__(self) -> None:
        self.now = 0

    def __call__(self) -> int:
        return self.now


@pytest.fixture
def lines(caplog):
    caplog.set_level(logging.DEBUG, logger=NAME)
    return lambda: [r.getMessage() for r in caplog.records if r.name == NAME]


def _suppressed(text: list) -> int:
    return sum(int(m.group(1)) for line in text if (m := re.match(r"suppressed (\d+) ", line)))


def test_a_flood_of_one_message_is_one_line_per_interval_and_the_count_adds_up(lines):
    clock = Clock()
    limited = RateLimitedLog(logging.getLogger(NAME), clock)
    for i in range(10_000):  # one every 0.1 ms: 1 s
        clock.now = i * 100_000
        limited.warning(None, "node %d: emergency 0x%04X", 5, 0x8130)
    assert lines() == ["node 5: emergency 0x8130"]
    limited.flush(9 * S)
    assert len(lines()) == 1  # the window lasts 10 s from its first line
    limited.flush(10 * S)
    assert lines() == [
        "node 5: emergency 0x8130",
        "suppressed 9999 similar messages in 10 s; the last: node 5: emergency 0x8130",
    ]
    assert limited.written == 2 and limited.suppressed == 9999
    limited.flush(30 * S)
    assert len(lines()) == 2  # nothing more to tell


def test_a_continuous_flood_gives_two_lines_per_interval(lines):
    clock = Clock()
    limited = RateLimitedLog(logging.getLogger(NAME), clock)
    calls = 0
    for ms in range(0, 60_000, 1):  # one a millisecond for a minute
        clock.now = ms * 1_000_000
        limited.flush()
        limited.info(None, "frame dropped: %d bytes", ms % 8)
        calls += 1
    limited.flush(70 * S)
    text = lines()
    assert len(text) <= 2 * 7
    assert len([t for t in text if not t.startswith("suppressed")]) + _suppressed(text) == calls


def test_many_keys_are_held_to_the_budget(lines):
    clock = Clock()
    limited = RateLimitedLog(logging.getLogger(NAME), clock, budget=20)
    for code in range(10_000):  # every EMCY with a new code: a new key each time
        clock.now = code * 100_000
        limited.warning(("emcy", 5, code), "node 5: emergency 0x%04X", code)
    limited.flush(20 * S)
    text = lines()
    assert text[:20] == [f"node 5: emergency 0x{code:04X}" for code in range(20)]
    assert text[20:] == [
        "suppressed 9980 more messages (over the limit of this log) in 10 s; the last: node 5: emergency 0x270F"
    ]
    assert 20 + _suppressed(text) == 10_000


def test_keys_apart_are_logged_apart_and_a_burst_is_allowed(lines):
    clock = Clock()
    limited = RateLimitedLog(logging.getLogger(NAME), clock, burst=2)
    for node in (1, 2):
        for _ in range(3):
            limited.info(("lost", node), "node %d lost", node)
    assert lines() == ["node 1 lost", "node 1 lost", "node 2 lost", "node 2 lost"]
    clock.now = 10 * S
    limited.info(("lost", 1), "node %d lost", 1)  # the next line tells first what the ended windows held back
    assert lines()[4:] == [
        "suppressed 1 similar messages in 10 s; the last: node 1 lost",
        "suppressed 1 similar messages in 10 s; the last: node 2 lost",
        "node 1 lost",
    ]


def test_the_summary_has_the_level_of_what_it_held_back(caplog):
    caplog.set_level(logging.INFO, logger=NAME)
    clock = Clock()
    limited = RateLimitedLog(logging.getLogger(NAME), clock)
    limited.info("k", "one")
    limited.error("k", "two")
    limited.flush(10 * S)
    assert [(r.levelname, r.getMessage()) for r in caplog.records] == [
        ("INFO", "one"),
        ("ERROR", "suppressed 1 similar messages in 10 s; the last: two"),
    ]


def test_a_level_the_logger_does_not_write_is_not_counted(caplog):
    caplog.set_level(logging.WARNING, logger=NAME)
    limited = RateLimitedLog(logging.getLogger(NAME), Clock())
    for _ in range(5):
        assert not limited.debug(None, "chatter")
    assert limited.suppressed == 0 and limited.written == 0


def test_a_traceback_only_on_the_lines_written(caplog):
    caplog.set_level(logging.ERROR, logger=NAME)
    clock = Clock()
    limited = RateLimitedLog(logging.getLogger(NAME), clock)
    for _ in range(100):
        try:
            raise struct_error()
        except ValueError:
            limited.exception("handler", "handler failed on frame 0x%03X", 0x85)
    written = [r for r in caplog.records if r.name == NAME]
    assert len(written) == 1 and written[0].exc_info is not None


def struct_error() -> ValueError:
    return ValueError("unpack requires a buffer of 8 bytes")


def test_a_clock_that_starts_again_ends_the_windows(lines):
    """A new engine's virtual clock starts at 0 again."""
    clock = Clock()
    limited = RateLimitedLog(logging.getLogger(NAME), clock)
    clock.now = 50 * S
    limited.info(None, "a")
    limited.info(None, "a")
    clock.now = 0
    limited.flush()
    limited.info(None, "a")
    assert lines() == ["a", "suppressed 1 similar messages in 10 s; the last: a", "a"]


def test_a_peer_log_filter_limits_a_librarys_records_and_drops_their_tracebacks(caplog):
    """As on uvicorn's and asyncua's loggers: 10,000 failures of a client's requests,
    each with a traceback, are a line per window and the count of the rest."""
    name = "softplc.test.peer.library"
    clock = Clock()
    library = logging.getLogger(name)
    quiet = PeerLogFilter(clock)
    library.addFilter(quiet)
    caplog.set_level(logging.DEBUG, logger=name)
    try:
        for i in range(10_000):
            clock.now = i * 100_000
            try:
                raise ValueError("malformed chunk\n" + "x" * 5000)
            except ValueError:
                library.exception("Exception raised while parsing message from client %d", i)
        clock.now = 10 * S
        library.warning("later")  # the window's summary comes with the next line
    finally:
        library.removeFilter(quiet)
    records = [r for r in caplog.records if r.name == name]
    text = [r.getMessage() for r in records]
    assert all(r.exc_info is None and r.exc_text is None and "\n" not in r.getMessage() for r in records)
    assert text[0].startswith("Exception raised while parsing message from client 0: ValueError: malformed chunk x")
    assert "(5000 characters)" in text[0] and len(text[0]) < 200  # the value cut, as in config errors
    assert text[1].startswith("suppressed 9999 similar messages in 10 s; the last: Exception raised")
    assert text[2:] == ["later"] and 1 + _suppressed(text) == 10_000
