"""The whole suite's cache folder: softplc's cache (runtime/cache.py) goes to
a temporary folder of each pytest process, never to the user's own
(~/.cache/softplc); the processes the tests start inherit it. And the cache
tests' fixtures: a folder of a test's own (own_cache), the parser's calls
(parses)."""

from __future__ import annotations

import os
import shutil
import tempfile

import pytest

_made: list[str] = []


def pytest_configure(config) -> None:
    folder = tempfile.mkdtemp(prefix="softplc-test-cache-")
    _made.append(folder)
    os.environ["SOFTPLC_CACHE"] = folder


def pytest_unconfigure(config) -> None:
    for folder in _made:
        shutil.rmtree(folder, ignore_errors=True)


@pytest.fixture
def own_cache(tmp_path, monkeypatch):
    """A cache folder of the test's own, on, and no parse kept in memory
    (the cache tests: pytestmark = pytest.mark.usefixtures("own_cache"))."""
    from softplc.runtime.program import libraries

    monkeypatch.setenv("SOFTPLC_CACHE", str(tmp_path / "cache"))
    monkeypatch.delenv("SOFTPLC_NO_CACHE", raising=False)
    monkeypatch.setattr(libraries, "_PARSES", {})  # (as a new process)


@pytest.fixture
def parses(monkeypatch) -> list:
    """The names parse_source is called with (the parser runs, not the cache)."""
    from softplc.runtime.program import libraries

    calls: list = []
    real = libraries.parse_source

    def counted(text, name, *args, **kwargs):
        calls.append(name)
        return real(text, name, *args, **kwargs)

    monkeypatch.setattr(libraries, "parse_source", counted)
    return calls
