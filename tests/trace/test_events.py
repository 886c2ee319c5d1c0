"""What simulated devices record, in the trace files (trace/events.py): a
CSV's last column "[[sim]]", a VCD's string variables under the top scope
`sim`, a plot's marks; read back as the Trace's marks. The device here is a
SimulatedDevice that records what the test tells it to (the real ones, the
MPU2-S's breaker and the CANopen devices' EMCYs, are in
tests/test_launch_records.py)."""

from __future__ import annotations

from softplc.runtime.engine.monitor import TraceWriter, Watch
from softplc.runtime.sim.base import SimulatedDevice
from softplc.runtime.trace.events import EVENTS_COLUMN, SimEvents, csv_column, records_events, timed, untimed
from softplc.runtime.trace.series import Recorder, read_csv
from softplc.runtime.trace.vcd import VcdTraceWriter, read_vcd

from ..test_cli import softplc
from .conftest import MS, SRC, task
from .test_plot_marks import marks_in
from .test_vcd import _parse


class Recording(SimulatedDevice):
    """Keeps the (t_ns, text) the test gives it: as a device's own thread would, in real time."""

    def __init__(self, name: str, clock) -> None:
        super().__init__(name, clock=clock)
        self.kept: list = []

    def service(self, now_ns: int) -> None:
        pass

    def events_since(self, t_ns: int) -> list:
        return [e for e in self.kept if e[0] > t_ns]


def _run(engines, writer_of, plan: dict, ticks: int = 6):
    """plan: scan number -> the events the device records during that scan (before its trace row)."""
    e = engines(SRC, [task("Main", 10, "Main")])
    device = Recording("gen", e.clock)
    watch = Watch(e, ["Main.n"])

    def record(engine) -> None:  # before the writers: what the device recorded during this scan
        device.kept += plan.get(engine.cycle, [])

    writer = writer_of(watch, {"gen": device, "quiet": Quiet("quiet", clock=e.clock)})
    e.after_tick += [record, writer]
    e.run(duration_ns=ticks * 10 * MS)
    return e, writer


class Quiet(SimulatedDevice):
    """A device that records nothing (the DA1's simulator, say): no column, no variable of its own."""

    def service(self, now_ns: int) -> None:
        pass


# the scans run at 0, 10, 20 ... ms (scan n at (n - 1) * 10 ms)
PLAN = {
    3: [(12 * MS, "breaker closed: phase 3.2 deg")],
    5: [(31 * MS, "EMCY 1000h Thermal overload"), (31 * MS, "EMCY 0000h error reset")],
}


def test_only_a_device_that_records_has_a_place_in_the_trace(engines):
    e = engines(SRC, [task("Main", 10, "Main")])
    assert records_events(Recording("gen", e.clock))
    assert not records_events(Quiet("quiet", clock=e.clock))
    assert not SimEvents({"quiet": Quiet("quiet", clock=e.clock)}).sources


def test_a_csv_trace_has_the_events_in_a_last_column_and_reads_them_back_as_marks(engines, tmp_path):
    path = tmp_path / "run.csv"
    with path.open("w", newline="", encoding="utf-8") as f:
        _run(engines, lambda watch, sims: TraceWriter(f, watch, csv_column(sims)), PLAN)
    lines = path.read_text(encoding="utf-8").splitlines()
    assert lines[0] == f"time_ms,cycle,Main.n,{EVENTS_COLUMN}"
    rows = {int(line.split(",")[1]): line for line in lines[1:]}
    assert rows[3].endswith(",gen 0.012000 s: breaker closed: phase 3.2 deg")
    assert rows[5].endswith(",gen 0.031000 s: EMCY 1000h Thermal overload | gen 0.031000 s: EMCY 0000h error reset")
    assert rows[4].endswith(",")  # nothing recorded during that scan
    trace = read_csv(path)
    assert trace.names() == ["Main.n"]  # the events are no signal
    assert trace.marks == [
        (0.012, "gen: breaker closed: phase 3.2 deg"),
        (0.031, "gen: EMCY 1000h Thermal overload"),
        (0.031, "gen: EMCY 0000h error reset"),
    ]


def test_a_vcd_trace_has_a_string_per_recording_device_at_the_events_own_times(engines, tmp_path):
    path = tmp_path / "run.vcd"
    with path.open("w", encoding="utf-8") as f:
        e, writer = _run(engines, lambda watch, sims: VcdTraceWriter(f, watch, SimEvents(sims)), PLAN)
        writer.close(e.clock.now_ns())
    decls, changes, _timescale, _end = _parse(path)
    assert decls["sim.gen"] == ("string", 1)
    assert not any(name.startswith("sim.quiet") for name in decls)
    # scan 3 writes its values at 20 ms; the close at 12 ms is written at its own time (before them)
    events = [(t, v) for t, v in changes["sim.gen"] if v]
    assert events[0][0] == 12 * MS
    assert events[1][0] == 31 * MS  # both EMCYs of one time stamp, joined
    trace = read_vcd(path)
    assert trace.marks == [
        (0.012, "gen: breaker closed: phase 3.2 deg"),
        (0.031, "gen: EMCY 1000h Thermal overload"),
        (0.031, "gen: EMCY 0000h error reset"),
    ]
    assert "sim.gen" not in trace.names()


def test_an_event_that_came_after_its_scan_s_row_was_written_keeps_its_time_in_the_text(engines, tmp_path):
    # real time: a device's thread stamps an event at 15 ms that the writer sees only at scan 4 (30 ms),
    # after it wrote the values of 20 ms: the VCD's time stamps cannot go back, the text keeps 15 ms;
    # and one stamped at 45 ms, after the time scan 5 read (40 ms), waits for scan 6
    late = {4: [(15 * MS, "breaker closed: dead bus")], 5: [(45 * MS, "breaker closed: dead bus")]}
    path = tmp_path / "late.vcd"
    with path.open("w", encoding="utf-8") as f:
        e, writer = _run(engines, lambda watch, sims: VcdTraceWriter(f, watch, SimEvents(sims)), late)
        writer.close(e.clock.now_ns())
    _decls, changes, _timescale, _end = _parse(path)
    assert [t for t, v in changes["sim.gen"] if v] == [20 * MS, 45 * MS]  # the last time stamp written; its own
    assert read_vcd(path).marks == [(0.015, "gen: breaker closed: dead bus"), (0.045, "gen: breaker closed: dead bus")]


def test_a_plot_s_recorder_takes_the_events_as_marks(engines):
    _e, recorder = _run(engines, lambda watch, sims: Recorder(watch, SimEvents(sims)), PLAN)
    assert recorder.trace().marks == [
        (0.012, "gen: breaker closed: phase 3.2 deg"),
        (0.031, "gen: EMCY 1000h Thermal overload"),
        (0.031, "gen: EMCY 0000h error reset"),
    ]


def test_a_timed_text_reads_back_and_another_text_is_no_mark():
    assert untimed(timed(1_234_567_000, "EMCY 1000h", "ltmr")) == (1.234567, "ltmr: EMCY 1000h")
    assert untimed(timed(2_000_000_000, "a: b"), "gen") == (2.0, "gen: a: b")
    assert untimed("hello") is None


def test_softplc_plot_draws_a_trace_s_events_as_marks(engines, tmp_path):
    path = tmp_path / "run.csv"
    with path.open("w", newline="", encoding="utf-8") as f:
        _run(engines, lambda watch, sims: TraceWriter(f, watch, csv_column(sims)), PLAN)
    done = softplc("plot", path, "-o", tmp_path / "run.svg")
    assert done.returncode == 0, done.stderr
    svg = (tmp_path / "run.svg").read_text(encoding="utf-8")
    assert marks_in(svg) == {0, 1, 2}
    assert "breaker closed: phase 3.2 deg" in svg
