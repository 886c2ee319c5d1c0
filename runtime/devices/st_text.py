"""Generated ST text for device libraries: string literals and the files
a generator writes (fblocks/vendor/*_codes.st from a device's tables)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

TEXT_LENGTH = 80


def vendor_file(name: str) -> Path:
    """The path of a file of the vendor ST library (fblocks/vendor/), where
    the package is installed (the source tree in a development install)."""
    return Path(str(resources.files("softplc.fblocks.vendor").joinpath(name)))


def st_string(text: str, length: int = TEXT_LENGTH) -> str:
    """A single-quoted ST string literal ($ and ' escaped)."""
    if len(text) > length:
        raise ValueError(f"text longer than STRING[{length}]: {text!r}")
    return "'" + text.replace("$", "$$").replace("'", "$'") + "'"
