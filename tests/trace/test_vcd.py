"""The VCD trace, read back with pyvcd's own tokenizer (what GTKWave reads)
and with read_vcd (what `softplc plot` reads)."""

from __future__ import annotations

import pytest
from vcd.reader import TokenKind, tokenize

from softplc.runtime.engine.monitor import Watch
from softplc.runtime.trace.series import Recorder, TraceFileError
from softplc.runtime.trace.vcd import VcdTraceWriter, read_vcd

from .conftest import MS, SRC, WATCHED, task


def _run(engines, path, cycles=4):
    e = engines(SRC, [task("Main", 10, "Main")])
    watch = Watch(e, WATCHED)
    recorder = Recorder(watch)
    with open(path, "w", encoding="utf-8") as f:
        writer = VcdTraceWriter(f, watch)
        e.after_tick += [writer, recorder]
        e.run(duration_ns=cycles * 10 * MS)
        writer.close(e.clock.now_ns())
    return recorder.trace()


def _parse(path) -> tuple:
    """{dotted name: (var type, size)}, {dotted name: [(time, value)]}, timescale, last time."""
    decls, changes, scopes, names = {}, {}, [], {}
    timescale, now = None, 0
    with open(path, "rb") as f:
        for token in tokenize(f):
            if token.kind is TokenKind.TIMESCALE:
                timescale = (token.data.magnitude, token.data.unit.value)
            elif token.kind is TokenKind.SCOPE:
                scopes.append(token.data.ident)
            elif token.kind is TokenKind.UPSCOPE:
                scopes.pop()
            elif token.kind is TokenKind.VAR:
                name = ".".join([*scopes, token.data.reference])
                decls[name] = (token.data.type_.value, token.data.size)
                names[token.data.id_code] = name
                changes[name] = []
            elif token.kind is TokenKind.CHANGE_TIME:
                now = token.data
            elif token.kind in (
                TokenKind.CHANGE_SCALAR,
                TokenKind.CHANGE_VECTOR,
                TokenKind.CHANGE_REAL,
                TokenKind.CHANGE_STRING,
            ):
                changes[names[token.data.id_code]].append((now, token.data.value))
    return decls, changes, timescale, now


def test_vcd_holds_every_watched_signal_with_its_type(engines, tmp_path):
    _run(engines, tmp_path / "run.vcd")
    decls, _changes, timescale, _end = _parse(tmp_path / "run.vcd")
    assert timescale == (1, "ns")
    assert decls == {
        "softplc.Main.n": ("integer", 16),
        "softplc.Main.on": ("wire", 1),
        "softplc.Main.mode": ("string", 1),
        "softplc.Main.x": ("real", 64),
        "softplc.Main.t": ("integer", 32),
        "softplc.total": ("integer", 32),
        "softplc.%QW1": ("reg", 16),
        "softplc.Main.name": ("string", 1),
    }


def test_vcd_values_change_at_the_scans_in_engine_time(engines, tmp_path):
    _run(engines, tmp_path / "run.vcd")
    _decls, changes, _ts, end = _parse(tmp_path / "run.vcd")
    ms = 1_000_000
    # pyvcd puts the value at time 0 into $dumpvars; the changes follow at each scan
    assert changes["softplc.Main.on"] == [(0, "1"), (10 * ms, "0"), (20 * ms, "1"), (30 * ms, "0")]
    twos = [(t, v - (1 << 16) if v >= 1 << 15 else v) for t, v in changes["softplc.Main.n"]]
    assert twos == [(0, -3), (10 * ms, -6), (20 * ms, -9), (30 * ms, -12)]
    assert changes["softplc.Main.mode"] == [(0, "Auto"), (20 * ms, "Manual")]  # by name, only when it changes
    assert changes["softplc.Main.x"] == [(0, 0.5), (10 * ms, 1.0), (20 * ms, 1.5), (30 * ms, 2.0)]
    assert changes["softplc.Main.t"] == [(0, 0), (10 * ms, 10), (20 * ms, 20), (30 * ms, 30)]  # TIME in ms
    assert changes["softplc.total"] == [(0, 1), (10 * ms, 2), (20 * ms, 3), (30 * ms, 4)]
    assert changes["softplc.%QW1"] == [(0, 0xFF00)]
    assert [v for _t, v in changes["softplc.Main.name"]] in (["a\\x20b"], ["a b"])  # pyvcd escapes the blank
    assert end == 40 * ms  # the trace ends where the run did


def test_read_vcd_gives_back_what_the_run_recorded(engines, tmp_path):
    recorded = _run(engines, tmp_path / "run.vcd", cycles=30)
    read = read_vcd(tmp_path / "run.vcd")
    assert sorted(read.names()) == sorted(WATCHED)
    by_name = {s.name: s for s in read.series}
    for want in recorded.series:
        got = by_name[want.name]
        assert got.kind == ("enum" if want.kind == "text" else want.kind)  # a VCD string is drawn as levels
        if want.kind == "text":
            continue
        assert _changes(got) == _changes(want), want.name
        assert got.times[-1] == 0.3  # held to the end of the trace
    assert by_name["Main.mode"].levels == ("Auto", "Manual")  # in order of appearance


def _changes(series) -> list:
    out: list = []
    for t, v in zip(series.times, series.values):
        if not out or out[-1][1] != v:
            out.append((round(t, 9), v))
    return out


def test_read_vcd_refuses_a_file_that_is_not_vcd(tmp_path):
    bad = tmp_path / "x.vcd"
    bad.write_text("$var wire 1 ! a $end\n#zz\n")
    with pytest.raises(TraceFileError, match=r"x\.vcd: not a VCD file"):
        read_vcd(bad)
    with pytest.raises(TraceFileError, match="cannot read"):
        read_vcd(tmp_path / "missing.vcd")
