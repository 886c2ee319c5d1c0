"""A sweep's results: one table (CSV, or Parquet with pyarrow) with a row
per scenario, and a plot of one result over one parameter.

Columns: scenario (its number), the sweep's keys, passed, failed (what
did not hold), fault (the first runtime fault), the [result] values, and
records (what the simulated devices recorded, as JSON).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

from .matrix import Sweep
from .scenario import FAILED, PASSED, RECORDS, SCENARIO

TABLE_SUFFIXES = (".csv", ".parquet")


def columns(sweep: Sweep) -> list:
    return [SCENARIO, *sweep.keys, PASSED, FAILED, "fault", *sweep.values, RECORDS]


def write_table(rows: list, sweep: Sweep, out: str | Path) -> None:
    """rows into out, by its ending; ValueError for another ending, RuntimeError without pyarrow."""
    out = Path(out)
    names = columns(sweep)
    suffix = out.suffix.lower()
    if suffix == ".csv":
        with out.open("w", newline="", encoding="utf-8") as f:
            writer = csv.writer(f)
            writer.writerow(names)
            for row in rows:
                writer.writerow(["" if row.get(n) is None else row.get(n) for n in names])
        return
    if suffix == ".parquet":
        try:
            import pyarrow as pa
            import pyarrow.parquet as pq
        except ImportError:
            raise RuntimeError("a Parquet table needs pyarrow: pip install 'softplc[sweep]'") from None
        table = pa.table({n: [_cell(row.get(n)) for row in rows] for n in names})
        pq.write_table(table, out)
        return
    raise ValueError(f"{out}: the ending says the table's form: {', '.join(TABLE_SUFFIXES)}")


def _cell(value):
    """One type per Parquet column: mixed numbers and text become text."""
    return value if value is None or isinstance(value, bool | int | float) else str(value)


def plot_results(rows: list, sweep: Sweep, out: str | Path) -> None:
    """y over x, a line of markers per hue value (failed scenarios as x);
    PlotUnavailable without matplotlib."""
    from ..trace.plot import require

    require()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    x, y, hue = sweep.plot["x"], sweep.plot["y"], sweep.plot.get("hue")
    groups: dict = {}
    for row in rows:
        groups.setdefault(row.get(hue) if hue else None, []).append(row)
    fig, ax = plt.subplots(figsize=(8, 5), dpi=110)
    for key, members in groups.items():
        points = sorted((r[x], r[y], r["passed"]) for r in members if _number(r.get(x)) and _number(r.get(y)))
        label = f"{hue} = {key}" if hue else None
        line = ax.plot([p[0] for p in points], [p[1] for p in points], "o-", label=label)[0]
        bad = [p for p in points if not p[2]]
        if bad:
            ax.plot([p[0] for p in bad], [p[1] for p in bad], "x", color=line.get_color(), markersize=10)
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    failed = sum(1 for r in rows if not r["passed"])
    ax.set_title(f"{Path(sweep.file).name}: {len(rows)} scenarios, {failed} failed (x)")
    ax.grid(True, alpha=0.3)
    if hue:
        ax.legend()
    fig.tight_layout()
    fig.savefig(out)
    plt.close(fig)


def _number(value) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value)
