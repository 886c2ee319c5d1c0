"""A Trace as a figure (PNG, SVG or PDF), with matplotlib (the `plot` extra).

Top to bottom, on one engine-time axis:
  BOOLs        stacked lanes of steps, one lane per signal, named on the left
  enumerations a panel each, steps between the enumerators' names
  numbers      lines (integers as steps); one axis per unit: signals given
               the same unit (--unit Main.speed=rpm) share an axis labelled
               with it, a signal without a unit has an axis of its own
               labelled with its ST type; a legend names the lines
Text (STRINGs, arrays, structs) is not drawn; plot() returns those names.
Marks (the frames of a bus log, `softplc plot --bus-log FILE --mark TEXT`)
are dotted vertical lines through every panel at their engine time, each
labelled on top with its text (the first MARK_LABELS of them; SVG groups
named mark-0, mark-1 ...).
"""

from __future__ import annotations

from pathlib import Path

from .series import ANALOGUE, Trace

FORMATS = (".png", ".svg", ".pdf")
WIDTH_IN = 11.0
DPI = 110
MARK_LABELS = 40  # more labels than this would hide each other: the lines only


class PlotUnavailable(RuntimeError):
    """matplotlib is not installed."""


def require() -> None:
    """Raise PlotUnavailable, saying how to install it, when matplotlib is missing."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        raise PlotUnavailable(
            "plots need matplotlib, which comes with the `plot` extra: pip install 'softplc[plot]'"
        ) from None


def parse_units(items) -> dict:
    """['Main.speed=rpm', ...] -> {'Main.speed': 'rpm'}; ValueError for an item without '='."""
    units = {}
    for item in items:
        path, sep, unit = item.partition("=")
        if not sep or not path.strip() or not unit.strip():
            raise ValueError(f"{item!r}: write PATH=UNIT, e.g. Main.speed=rpm")
        units[path.strip()] = unit.strip()
    return units


def plot(
    trace: Trace,
    out: str | Path,
    units: dict | None = None,
    title: str | None = None,
    marks: list[tuple[float, str]] | None = None,
) -> list:
    """Draw trace into out (its suffix picks the format), with marks
    ((engine seconds, label): see the module's docstring). Returns the names
    of the signals left out (text). KeyError for a unit of a signal the
    trace does not have; OSError when out cannot be written."""
    require()
    from matplotlib.figure import Figure

    units = dict(units or {})
    unknown = [name for name in units if name not in trace.names()]
    if unknown:
        raise KeyError(f"--unit {', '.join(unknown)}: no such signal in the trace (it has: {', '.join(trace.names())})")
    bools = [s for s in trace.series if s.kind == "bool" and s.times]
    enums = [s for s in trace.series if s.kind == "enum" and s.times]
    groups: dict = {}  # axis key -> (label, [series])
    for s in trace.series:
        if s.kind in ANALOGUE and s.times:
            unit = units.get(s.name)
            key = ("unit", unit) if unit else ("signal", s.name)
            label = unit if unit else (s.type_name or "value")
            groups.setdefault(key, (label, []))[1].append(s)
    left_out = [s.name for s in trace.series if s.kind == "text"]

    panels: list = []  # (height in inches, draw function)
    if bools:
        panels.append((0.35 * len(bools) + 0.4, lambda ax: _draw_bools(ax, bools)))
    for s in enums:
        panels.append((0.22 * max(len(s.levels), 2) + 0.5, lambda ax, s=s: _draw_enum(ax, s)))
    for label, members in groups.values():
        panels.append((1.9, lambda ax, label=label, members=members: _draw_numbers(ax, label, members)))
    if not panels:
        raise ValueError(
            f"nothing to plot in {trace.source or 'the trace'}: no sample of a BOOL, number or enumeration"
        )

    heights = [h for h, _ in panels]
    fig = Figure(figsize=(WIDTH_IN, sum(heights) + 1.0), dpi=DPI, layout="constrained")
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False, gridspec_kw={"height_ratios": heights})[:, 0]
    for ax, (_h, draw) in zip(axes, panels):
        draw(ax)
        ax.grid(True, axis="x", color="0.88", linewidth=0.6)
        ax.tick_params(labelsize=8)
        ax.margins(x=0)
    _draw_marks(axes, marks or [])
    axes[-1].set_xlabel("engine time [s]")
    fig.suptitle(title or Path(trace.source).name or "softplc trace", fontsize=10)
    fig.savefig(out)
    return left_out


def _draw_bools(ax, bools: list) -> None:
    """One lane per BOOL, the first on top: a filled step between 0 and 1."""
    n = len(bools)
    for i, s in enumerate(bools):
        base = (n - 1 - i) * 1.5
        ys = [base + v for v in s.values]
        color = f"C{i % 10}"
        ax.step(s.times, ys, where="post", color=color, linewidth=1.2)
        ax.fill_between(s.times, base, ys, step="post", color=color, alpha=0.2, linewidth=0)
    ax.set_yticks([(n - 1 - i) * 1.5 + 0.5 for i in range(n)], [s.name for s in bools])
    ax.set_ylim(-0.3, (n - 1) * 1.5 + 1.3)
    ax.tick_params(axis="y", length=0)


def _draw_enum(ax, s) -> None:
    levels = list(s.levels) or list(dict.fromkeys(s.values))
    for v in s.values:  # a value outside the declared enumerators (after a cast)
        if v not in levels:
            levels.append(v)
    index = {name: i for i, name in enumerate(levels)}
    ax.step(s.times, [index[v] for v in s.values], where="post", color="C4", linewidth=1.4)
    ax.set_yticks(range(len(levels)), [str(v) for v in levels])
    ax.set_ylim(-0.5, len(levels) - 0.5)
    ax.set_ylabel(s.name, fontsize=8)
    ax.grid(True, axis="y", color="0.92", linewidth=0.6)


def _draw_numbers(ax, label: str, members: list) -> None:
    for i, s in enumerate(members):
        style = "steps-post" if s.kind == "int" or s.stepped else "default"
        ax.plot(s.times, s.values, drawstyle=style, color=f"C{i % 10}", linewidth=1.2, label=s.name)
    ax.set_ylabel(label, fontsize=8)
    # above the axis, where it hides no line
    ax.legend(loc="lower left", bbox_to_anchor=(0, 1), ncol=len(members), fontsize=7, frameon=False, borderaxespad=0.1)
    ax.grid(True, axis="y", color="0.92", linewidth=0.6)


def _draw_marks(axes, marks: list) -> None:
    labelled: set = set()
    for i, (t, label) in enumerate(marks):
        for ax in axes:
            ax.axvline(t, color="0.35", linestyle=":", linewidth=0.8, gid=f"mark-{i}")
        if len(labelled) < MARK_LABELS and (t, label) not in labelled:  # one label where two frames coincide
            labelled.add((t, label))
            axes[0].annotate(
                label,
                (t, 1.0),
                xycoords=("data", "axes fraction"),
                rotation=60,
                fontsize=6,
                color="0.25",
                annotation_clip=False,
            )
