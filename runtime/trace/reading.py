"""A trace file read back, whichever its form (`softplc plot`, the tests):
by its ending, a CSV trace (series.read_csv) or a VCD (vcd.read_vcd)."""

from __future__ import annotations

from pathlib import Path

from .series import Trace, TraceFileError, read_csv
from .vcd import read_vcd


def read_trace(path: str | Path) -> Trace:
    """A CSV trace (`--trace FILE.csv`) or a VCD trace; TraceFileError when it cannot be read."""
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".csv":
        return read_csv(path)
    if suffix == ".vcd":
        return read_vcd(path)
    raise TraceFileError(f"{path}: not a trace softplc reads (give a .csv or .vcd file)")
