"""The whole suite's cache folder: softplc's cache (runtime/cache.py) goes to
a temporary folder of each pytest process, never to the user's own
(~/.cache/softplc); the processes the tests start inherit it."""

from __future__ import annotations

import os
import shutil
import tempfile

_made: list[str] = []


def pytest_configure(config) -> None:
    folder = tempfile.mkdtemp(prefix="softplc-test-cache-")
    _made.append(folder)
    os.environ["SOFTPLC_CACHE"] = folder


def pytest_unconfigure(config) -> None:
    for folder in _made:
        shutil.rmtree(folder, ignore_errors=True)
