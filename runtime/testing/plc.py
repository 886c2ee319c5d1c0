"""PLC: a whole soft-PLC in a test — a configuration or ST files, run in
virtual time, its variables read and written by ST path with ST types, its
simulated devices at hand, a trace of watched values.

    from softplc.testing import PLC

    with PLC.from_config("io_config/default.toml") as plc:   # virtual time
        plc.watch("Motor.state", "Motor.ltmr.Running")
        plc.write("Motor.Auto", False)
        plc.force("Motor.CmdForward", True)
        plc.run_until("Motor.ltmr.Running", timeout="2s")
        plc.fault("ltmr40", "load", 400)                     # a jam
        plc.run_until(lambda: plc["Motor.state"] == "Tripped", timeout="10s")

docs/guide/testing.md "Testing a sequence offline (Python and pytest)" is the guide.
"""

from __future__ import annotations

import copy
import heapq
import itertools
import logging
import tomllib
from collections.abc import Callable, Iterable
from datetime import timedelta
from importlib import resources
from pathlib import Path
from typing import Any

from ..config import PlcConfig, config_from_dict, default_config_path
from ..engine.access import Access, Permission
from ..engine.build import build_engine
from ..engine.places import PathError
from ..engine.scan import Engine
from ..engine.values import duration_value_ns
from ..plugin.registry import registry
from ..program import compile_files
from ..st.importers import is_source
from .trace import Trace

log = logging.getLogger("softplc.testing")

Duration = str | timedelta | int  # '2s', 'T#250ms', timedelta(seconds=2), or int nanoseconds


def duration_ns(value: Duration, what: str = "duration") -> int:
    """Nanoseconds of '2s' / 'T#1m30s' / timedelta / int (nanoseconds). ValueError otherwise."""
    if isinstance(value, int) and not isinstance(value, bool):
        ns: int | None = value
    elif isinstance(value, (str, timedelta)):
        ns = duration_value_ns(value)
    else:
        ns = None
    if ns is None or ns < 0:
        raise ValueError(f"{what}: expected a duration such as '2s', 'T#250ms', a timedelta or int ns, got {value!r}")
    return ns


class EngineTime(timedelta):
    """An engine time: a timedelta (T#... in a message, arithmetic with
    other durations) with .ns, the integer nanoseconds of the trace's times
    (trace.changes, trace.rows), so that the two compare exactly:

        t = plc.run_until("Motor.ltmr.Running")
        assert plc.trace.changes("Motor.state")[-1][0] <= t.ns
    """

    ns: int

    def __new__(cls, ns: int) -> EngineTime:
        self = super().__new__(cls, microseconds=ns / 1000)
        self.ns = ns
        return self

    def __reduce__(self):
        return (EngineTime, (self.ns,))


class PLC:
    """A soft-PLC under test. Build one with ``PLC.from_config`` or
    ``PLC.from_st``; it starts with the first run (variables can be read and
    written before), and ``stop()`` (or the ``with`` block) shuts it down:
    outputs safe, drivers and simulators closed, no thread left behind."""

    def __init__(self, engine: Engine, config=None) -> None:
        self.engine = engine
        self.config = config
        self.trace = Trace()
        self._watched: list[str] = []
        self._due: list = []  # heap of (time_ns, order, action, text)
        self._order = itertools.count()
        self._places: dict = {}  # watched path -> Place, while the instances stay the same
        self._generation = engine.generation
        engine.load()
        #: the engine's one write/force API (engine/access.py); a test may change anything
        self.access = Access(engine, {"test": Permission(("*",), non_finite=True)})
        engine.after_tick.append(self._after_tick)

    # ------------------------------------------------------------ construction

    @classmethod
    def from_config(
        cls,
        config: str | Path | dict | PlcConfig | None = None,
        *,
        virtual_time: bool = True,
        start_mode: str | None = None,
        edit: Callable[[dict], None] | None = None,
        base_dir: str | Path | None = None,
        bus_log: str | Path | None = None,
    ) -> PLC:
        """The PLC of a configuration, with its drivers and [[sim]] devices,
        on the virtual clock unless virtual_time=False. config: a TOML file
        (default: the embedded default plant, io_config/default.toml), its
        tables as a dict (relative paths from base_dir, default the current
        directory) or a loaded PlcConfig. edit gets the TOML tables to change
        before they are checked (a channel of its own, one more [[sim]] ...).
        bus_log: record the wire there (`softplc run --bus-log`: CAN frames
        in python-can's format of its ending, Modbus frames in
        STEM.modbus.log beside it), complete once the PLC stops.
        Raises ConfigError, CompileError or TaskSetupError with their usual
        messages."""
        if isinstance(config, PlcConfig):
            if edit is not None:
                raise ValueError("edit needs the configuration's tables: give a path or a dict, not a PlcConfig")
            cfg = config
        else:
            where = None
            if isinstance(config, dict):
                data = copy.deepcopy(config)
            else:
                where = Path(config) if config is not None else default_config_path()
                data = tomllib.loads(where.read_text(encoding="utf-8"))
            if edit is not None:
                edit(data)
            base = base_dir if base_dir is not None else (None if where is not None else Path.cwd())
            cfg = config_from_dict(data, where, base_dir=base)
        log = Path(bus_log) if bus_log is not None else None
        return cls(build_engine(cfg, virtual_time=virtual_time, start_mode=start_mode, bus_log=log), cfg)

    @classmethod
    def from_st(
        cls,
        sources: str | Path | Iterable[str | Path],
        *,
        tasks: list[dict] | None = None,
        cycle: Duration = "10ms",
        profile: str = "codesys",
        tables: dict | None = None,
        virtual_time: bool = True,
        bus_log: str | Path | None = None,
    ) -> PLC:
        """A PLC of ST sources: each a Path or a str ending in '.st' (a file;
        also a PLCopen .xml, TwinCAT .TcPOU ... and .plcproj)
        or ST text. Without tasks, every PROGRAM runs in one task of period
        cycle (unless the sources declare a CONFIGURATION); tasks are
        [[task]] tables as dicts ({"name": "Fast", "interval": "5ms",
        "programs": ["Main"]}). tables: more TOML tables as a dict
        ([[loopback]], [outputs], [[sim]] ...); bus_log as from_config's."""
        items = [sources] if isinstance(sources, (str, Path)) else list(sources)
        files: list = []
        texts: dict = {}
        for i, item in enumerate(items):
            if isinstance(item, Path) or (isinstance(item, str) and "\n" not in item and is_source(item)):
                files.append(Path(item))
            elif isinstance(item, str):
                texts[f"<st {i + 1}>.st" if len(items) > 1 else "<st>.st"] = item
            else:
                raise TypeError(f"an ST source is a file path or ST text, not {item!r}")
        program = compile_files(files, profile=profile, texts=texts)
        cycle_ns = duration_ns(cycle, "cycle")
        data: dict = {
            "plc": {"profile": profile, "programs": [str(f) for f in files] or [_placeholder()]},
            **(tables or {}),
        }
        if tasks:
            data["task"] = tasks
        elif not program.checked.configurations:
            names = [name for name, kind in program.pous.items() if kind == "PROGRAM"]
            data["task"] = [{"name": "MainTask", "interval": f"{cycle_ns}ns", "programs": names}]
        cfg = config_from_dict(data, base_dir=Path.cwd())
        log = Path(bus_log) if bus_log is not None else None
        engine = build_engine(cfg, virtual_time=virtual_time, program=program, bus_log=log)
        return cls(engine, cfg)

    # ------------------------------------------------------------ time

    @property
    def now(self) -> EngineTime:
        """The engine time (since the start of the run): a timedelta, and
        its .ns in the trace's unit."""
        return EngineTime(self.engine.now_ns())

    @property
    def now_ns(self) -> int:
        return self.engine.now_ns()

    @property
    def cycles(self) -> int:
        """Scans run so far."""
        return self.engine.cycle

    def start(self) -> None:
        """Start the drivers and simulators (run_for, run_until and step do it themselves)."""
        self.engine.start()

    def step(self, n: int = 1) -> None:
        """Run n scans (ticks of the engine: each runs the tasks due then)."""
        if n < 0:
            raise ValueError(f"step: n is a number of scans >= 0, not {n}")
        for _ in range(n):
            self._tick()

    def run_for(self, duration: Duration) -> None:
        """Run the scans released in the next `duration` of engine time; now advances by duration."""
        end = self.engine.now_ns() + duration_ns(duration)
        self.engine.start()
        while self.engine.next_release() < end:
            self._tick()
        self.engine.clock.sleep_until(end)
        self._fire(end)

    def run_until(
        self, condition: str | Callable[[], Any], timeout: Duration = "5s", what: str | None = None
    ) -> EngineTime:
        """Run scan by scan until condition holds; returns the engine time
        then (a timedelta; .ns: integer nanoseconds, as trace.changes
        gives). condition: a callable, or the ST path of a BOOL (watched from
        now on). Checked before the first scan and after each. On timeout an
        AssertionError names the condition and shows the trace around it."""
        if isinstance(condition, str):
            path = condition
            self.access.place(path)  # a wrong path fails now, not at the timeout
            if path not in self._watched:
                self.watch(path)

            def check() -> Any:
                return self.read(path)

            text = what or path
        else:
            check = condition
            name = getattr(condition, "__name__", "<lambda>")
            text = what or ("the condition" if name == "<lambda>" else name)
        end = self.engine.now_ns() + duration_ns(timeout, "timeout")
        self.engine.start()
        start = self.engine.now_ns()
        while not check():
            if self.engine.next_release() > end:
                raise AssertionError(
                    f"{text} did not become true within {_fmt_ns(end - start)} "
                    f"(from t={_fmt_ns(start)} to t={_fmt_ns(self.engine.now_ns())})\n{self.trace.around(rows=10)}"
                )
            self._tick()
        return self.now

    def _tick(self) -> None:
        engine = self.engine
        engine.start()
        release = engine.next_release()
        if self._due and self._due[0][0] <= release:
            engine.clock.sleep_until(release)  # what is due then sees now = its time
            self._fire(release)
        engine.run(cycles=1)

    # ------------------------------------------------------------ variables

    def read(self, path: str) -> Any:
        """The value at path with its ST type (values.py): enums as EnumValue
        (equal to 'Running'), TIME as timedelta, structs as dicts, arrays as
        lists. A wrong path raises KeyError naming it."""
        return self.access.place(path).read()

    def __getitem__(self, path: str) -> Any:
        return self.read(path)

    def __setitem__(self, path: str, value: Any) -> None:
        self.write(path, value)

    def write(self, path: str, value: Any) -> None:
        """Store value once (the program and the buses may change it at the
        next scan). Checked against the ST type: ValueError names the path,
        its type and what it takes."""
        self.access.write(path, value, surface="test")

    def force(self, path: str, value: Any) -> None:
        """Hold path at value against the program and the buses: stored now,
        and in every scan after the inputs are read and again after the
        tasks ran, until unforce. A forced output reaches its bus as forced."""
        self.access.force(path, value, surface="test")

    def unforce(self, path: str) -> None:
        """Release a force; the variable keeps its value until written."""
        self.access.unforce(path, surface="test")

    def unforce_all(self) -> None:
        self.access.unforce_all(surface="test")

    @property
    def forced(self) -> dict:
        """The forced paths and their values."""
        return self.access.forced

    # ------------------------------------------------------------ simulated devices

    @property
    def sims(self) -> dict:
        """Every simulated device by its [[sim]] name (the model a test drives)."""
        return dict(self.engine.simulators)

    def sim(self, name: str) -> Any:
        """The simulated device called name in [[sim]] (its inject() and its own helpers)."""
        for key, sim in self.engine.simulators.items():
            if key.upper() == name.upper():
                return sim
        raise KeyError(f"no simulated device {name!r} (there are: {', '.join(self.engine.simulators) or 'none'})")

    @property
    def records(self) -> dict:
        """What the simulated devices recorded, by [[sim]] name (those with
        any): an MPU2-S's breaker closes, a CANopen device's EMCYs sent; what
        softplc run --final-json writes under "[[sim]]"."""
        from ..sim.base import records_of

        return records_of(self.engine.simulators)

    def faults_of(self, name: str) -> dict:
        """The faults the device called name takes: fault name -> SimFault (description, value, lasting)."""
        self.sim(name)
        for sim in getattr(self.config, "sims", ()):
            if sim.name.upper() == name.upper():
                device = registry().sim_types().get(sim.type)
                if device is not None:
                    return {f.name: f for f in device.sim_faults}
        return {}

    def fault(self, sim: str, fault: str, value: Any = None, duration: Duration | None = None) -> None:
        """Inject fault into the simulated device sim now (its argument value
        where it takes one); a lasting fault is undone duration later in
        engine time, or by clear_fault. As [[sim]] faults = [...] does."""
        target = self.sim(sim)
        offered = self.faults_of(sim)
        spec = offered.get(fault.lower())
        if offered and spec is None:
            raise ValueError(f"{sim} has no fault {fault!r}; it has {', '.join(offered)}")
        if spec is not None:
            if spec.value and value is None:
                raise ValueError(f"fault {spec.name} of {sim} needs a value: {spec.value}")
            if not spec.value and value is not None:
                raise ValueError(f"fault {spec.name} of {sim} takes no value")
            if not spec.lasting and duration is not None:
                raise ValueError(f"fault {spec.name} of {sim} does not last: it takes no duration")
        name = fault.lower()
        log.info("sim %s: fault %s on at %s", sim, name, _fmt_ns(self.now_ns))
        target.inject(name, value, True)
        if duration is not None:
            self.at(self.now_ns + duration_ns(duration), lambda: target.inject(name, value, False), f"{sim} {name} off")

    def clear_fault(self, sim: str, fault: str, value: Any = None) -> None:
        """Undo a lasting fault now (the cable back in, the unit answering again)."""
        self.sim(sim).inject(fault.lower(), value, False)

    # ------------------------------------------------------------ scripts

    def at(self, when: Duration, action: Callable[[], Any], text: str = "") -> None:
        """Call action at engine time `when` (from the start of the run), before the scan released then."""
        heapq.heappush(self._due, (duration_ns(when, "time"), next(self._order), action, text))

    def script(self, events: Iterable[tuple]) -> None:
        """Write inputs over time: (time, path, value) each, applied at that
        engine time before the scan released then. value is checked now."""
        for event in events:
            try:
                when, path, value = event
            except (TypeError, ValueError):
                raise ValueError(f"script: each event is (time, path, value), not {event!r}") from None
            self.at(when, self.access.place(path).writer(value), f"{path} := {value!r}")

    def _fire(self, now_ns: int) -> None:
        while self._due and self._due[0][0] <= now_ns:
            _t, _o, action, _text = heapq.heappop(self._due)
            action()

    # ------------------------------------------------------------ trace

    def watch(self, *paths: str) -> None:
        """Record these paths' values after every scan in plc.trace (a row when one changes)."""
        for path in paths:
            self.access.place(path)  # a wrong path fails here
            if path not in self._watched:
                self._watched.append(path)
        self.trace.paths = list(self._watched)
        self._record()

    def _record(self) -> None:
        if not self._watched:
            return
        if self._generation != self.engine.generation:  # restarted tasks or a new program: new instances
            self._places.clear()
            self._generation = self.engine.generation
        places = self._places
        for p in self._watched:
            if p not in places:
                places[p] = self.access.place(p)
        values = {p: places[p].read() for p in self._watched}
        if values:
            self.trace.record(self.engine.now_ns(), self.engine.cycle, values)

    def _after_tick(self, _engine: Engine) -> None:
        self._record()

    def expect(self, condition: bool | Callable[[], Any], message: str = "expectation failed") -> None:
        """assert condition, with the trace of watched values in the message."""
        ok = condition() if callable(condition) else condition
        if not ok:
            raise AssertionError(f"{message} at t={_fmt_ns(self.now_ns)}\n{self.trace.around(rows=10)}")

    # ------------------------------------------------------------ shutdown

    def stop(self) -> None:
        """Outputs safe, drivers and simulators stopped (their threads, ports and buses closed)."""
        self.engine.stop()

    def __enter__(self) -> PLC:
        return self

    def __exit__(self, *exc) -> None:
        self.stop()

    def __repr__(self) -> str:
        return f"<PLC t={_fmt_ns(self.now_ns)} cycles={self.cycles} sims={list(self.engine.simulators)}>"


def _fmt_ns(ns: int) -> str:
    return f"{ns / 1e9:.3f}s"


def _placeholder() -> str:
    """A file for [plc] programs when every source is text (the program is compiled already)."""
    return str(resources.files("softplc.st_programs").joinpath("conveyor.st"))


__all__ = ["PLC", "PathError", "duration_ns"]
