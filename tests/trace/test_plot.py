"""Plots of traces: real PNG and SVG files drawn by matplotlib (Agg)."""

from __future__ import annotations

import sys

import pytest
from matplotlib import image

from softplc.runtime.trace.plot import DPI, WIDTH_IN, PlotUnavailable, parse_units, plot
from softplc.runtime.trace.series import Series, Trace


def _series(name, kind, samples, **kw) -> Series:
    s = Series(name, kind, **kw)
    for t, v in samples:
        s.add(t, v)
    s.finish()
    return s


def _trace() -> Trace:
    ts = [i * 0.01 for i in range(200)]
    return Trace(
        [
            _series("Main.run", "bool", [(t, int(0.5 < t < 1.2)) for t in ts], type_name="BOOL"),
            _series("Main.fault", "bool", [(t, int(t > 1.5)) for t in ts], type_name="BOOL"),
            _series(
                "Main.state",
                "enum",
                [(t, "Run" if 0.5 < t < 1.2 else "Idle") for t in ts],
                levels=("Idle", "Run", "Stop"),
            ),
            _series("Main.speed", "real", [(t, 50.0 * min(t, 1.0)) for t in ts], type_name="REAL"),
            _series("Main.setpoint", "real", [(t, 50.0) for t in ts], type_name="REAL"),
            _series("Main.count", "int", [(t, int(t * 10)) for t in ts], type_name="INT"),
            _series("Main.name", "text", [(0.0, "a b")]),
        ],
        "run.csv",
    )


def test_plot_writes_a_png_of_every_drawable_signal(tmp_path):
    out = tmp_path / "run.png"
    left_out = plot(_trace(), out)
    assert left_out == ["Main.name"]
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    pixels = image.imread(out)
    height, width = pixels.shape[:2]
    assert width == round(WIDTH_IN * DPI)
    assert 4 * DPI < height < 12 * DPI  # 2 BOOL lanes, an enum, 3 number axes: a screenful
    # something is drawn: far more than the white background and black frames
    assert len({tuple(p) for p in pixels.reshape(-1, pixels.shape[2])[::7].tolist()}) > 50


def test_signals_with_the_same_unit_share_an_axis(tmp_path):
    own, shared = tmp_path / "own.png", tmp_path / "shared.png"
    plot(_trace(), own)
    plot(_trace(), shared, {"Main.speed": "rpm", "Main.setpoint": "rpm"})
    # one number axis fewer
    assert image.imread(own).shape[0] - image.imread(shared).shape[0] == round(1.9 * DPI)


def test_svg_by_the_ending(tmp_path):
    out = tmp_path / "run.svg"
    plot(_trace(), out)
    text = out.read_text()
    assert "<svg" in text and "Main.speed" in text and "engine time [s]" in text


def test_a_unit_for_a_signal_the_trace_lacks_is_refused(tmp_path):
    with pytest.raises(KeyError, match=r"--unit Main\.nope: no such signal"):
        plot(_trace(), tmp_path / "x.png", {"Main.nope": "Hz"})


def test_nothing_to_plot(tmp_path):
    with pytest.raises(ValueError, match="nothing to plot in t.csv"):
        plot(Trace([_series("Main.name", "text", [(0.0, "x")])], "t.csv"), tmp_path / "x.png")


def test_parse_units():
    assert parse_units(["Main.speed=rpm", " f = Hz "]) == {"Main.speed": "rpm", "f": "Hz"}
    with pytest.raises(ValueError, match="write PATH=UNIT"):
        parse_units(["Main.speed"])


def test_without_matplotlib_the_error_says_how_to_install_it(tmp_path, monkeypatch):
    monkeypatch.setitem(sys.modules, "matplotlib", None)  # as if not installed
    with pytest.raises(PlotUnavailable, match=r"pip install 'softplc\[plot\]'"):
        plot(_trace(), tmp_path / "x.png")
