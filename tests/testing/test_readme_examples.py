"""The README's complete examples run as they stand: a block of Python in
the README that defines test functions is taken out and its tests run (a
README that drifts from the API fails here)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[2] / "README.md"

# a whole plant over tens of seconds of virtual time
pytestmark = pytest.mark.slow


def _block(marker: str) -> str:
    """The ```python block of the README that contains marker."""
    blocks = re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.DOTALL)
    [found] = [b for b in blocks if marker in b]
    return found


def test_the_trip_and_reset_example_of_the_default_plant():
    code = _block("def test_a_jam_trips_the_motor_and_a_reset_clears_it")
    scope: dict = {}
    exec(compile(code, f"{README}:trip-and-reset", "exec"), scope)
    scope["test_a_jam_trips_the_motor_and_a_reset_clears_it_once_the_ltmr_allows_it"]()
