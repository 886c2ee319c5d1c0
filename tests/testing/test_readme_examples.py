"""The manual's complete examples run as they stand: a block of Python in
the README or a page of docs/ that defines test functions is taken out and
its tests run (a manual that drifts from the API fails here)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PAGES = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]

# a whole plant over tens of seconds of virtual time
pytestmark = pytest.mark.slow


def _block(marker: str) -> tuple:
    """The ```python block of the manual that contains marker, and its page."""
    found = [
        (block, page)
        for page in PAGES
        for block in re.findall(r"```python\n(.*?)```", page.read_text(encoding="utf-8"), re.DOTALL)
        if marker in block
    ]
    [(block, page)] = found
    return block, page


def test_the_trip_and_reset_example_of_the_default_plant():
    code, page = _block("def test_a_jam_trips_the_motor_and_a_reset_clears_it")
    scope: dict = {}
    exec(compile(code, f"{page}:trip-and-reset", "exec"), scope)
    scope["test_a_jam_trips_the_motor_and_a_reset_clears_it_once_the_ltmr_allows_it"]()


def test_the_front_page_s_example():
    code, page = _block("def test_the_motor_runs_forward_then_in_reverse")
    assert page.name == "README.md"
    scope: dict = {}
    exec(compile(code, f"{page}:example", "exec"), scope)
    scope["test_the_motor_runs_forward_then_in_reverse"]()
