"""The fuzz harness's bounds: a runaway input becomes a Hang, whether it
spins (CPU time) or blocks (the wall-time backstop), and the limits are gone
after the block."""

from __future__ import annotations

import signal
import time

import pytest

from tests.fuzz.support import Hang, bounded


def test_a_spinning_input_is_a_hang_of_cpu_time():
    with (
        pytest.raises(Hang, match=r"spin: not done within 0.2 s of CPU time"),
        bounded("spin", limit_s=0.2, wall_factor=1e4),
    ):
        while True:
            pass
    assert signal.getitimer(signal.ITIMER_PROF) == (0.0, 0.0)
    assert signal.getitimer(signal.ITIMER_REAL) == (0.0, 0.0)


def test_a_blocked_input_is_a_hang_of_wall_time():
    with pytest.raises(Hang, match=r"block: not done within 0.5 s of wall time"):
        with bounded("block", limit_s=0.05, wall_factor=10):
            time.sleep(3600)


def test_a_caught_hang_is_still_a_hang():
    with pytest.raises(Hang, match="of CPU time"), bounded("swallow", limit_s=0.2, wall_factor=1e4):
        try:
            while True:
                pass
        except Hang:
            raise RuntimeError("the code under test went on") from None
