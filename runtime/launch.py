"""`softplc run`: load the configuration, build and start the engine, show
its status, handle signals and commands, stop cleanly, write the results.

Exit codes: 0 stopped cleanly, 1 compile errors, 2 bad configuration or
option, 3 a runtime fault happened during the run, or the retained data
could not be saved at the stop.
"""

from __future__ import annotations

import gc
import logging
import signal
import sys
import threading
from collections.abc import Callable
from contextlib import ExitStack
from pathlib import Path

EXIT_OK, EXIT_COMPILE, EXIT_CONFIG, EXIT_FAULT = 0, 1, 2, 3
PLOT_SUFFIXES = (".png", ".svg", ".pdf")
TRACE_SUFFIXES = (".csv", ".vcd", *PLOT_SUFFIXES)

log = logging.getLogger("softplc")


#: --final-json's key of the simulators' records: no ST name can be it
RECORDS_KEY = "[[sim]]"  # the CSV trace's column of their events too (trace/events.py)


def final_data(engine) -> dict:
    """--final-json: every program instance's variables and the globals
    (Engine.dump), and under RECORDS_KEY each simulated device's records by
    its [[sim]] name (what a simulator's records() gives: the MPU2-S's
    breaker closes, the EMCYs a CANopen device sent ...), when one has any."""
    from .sim.base import records_of

    data = engine.dump()
    records = records_of(engine.simulators)
    if records:
        data[RECORDS_KEY] = records
    return data


def settle_heap() -> None:
    """Before the first scan: collect the garbage of the start-up, then move
    what is alive (the libraries, the servers, the program) out of the
    garbage collector's sight (gc.freeze). A full collection holds the
    interpreter lock, and with it the scan, for as long as it walks every
    object: 40 to 160 ms for the default plant on a 2-core machine, and the
    compile of an online change set one off every few changes (a scan 470 ms
    late). Frozen, that walk covers only what came since. The program alive
    now stays in memory after an online change replaces it (once: a few MB;
    the later ones are collected as before)."""
    gc.collect()
    gc.freeze()


class _EngineTime(logging.Filter):
    """Gives every log record the engine time (`t=12.340s `) once there is
    an engine: the clock of the status line, the traces and TIME()."""

    def __init__(self) -> None:
        super().__init__()
        self.clock = None

    def filter(self, record: logging.LogRecord) -> bool:
        record.engine_time = f"t={self.clock.now_ns() / 1e9:.3f}s " if self.clock is not None else ""
        return True


class _LineFormatter(logging.Formatter):
    """Wall time, engine time, level, message; on a terminal the line first
    clears the status line being rewritten in place, so they do not run
    into each other."""

    def __init__(self, tty: bool) -> None:
        super().__init__("%(asctime)s %(engine_time)ssoftplc %(levelname)s: %(message)s")
        self.prefix = "\r\x1b[K" if tty else ""

    def format(self, record) -> str:
        return self.prefix + super().format(record)


def _setup_logging(tty: bool, stream=None) -> tuple:
    handler = logging.StreamHandler(stream if stream is not None else sys.stderr)
    handler.setFormatter(_LineFormatter(tty))
    engine_time = _EngineTime()
    handler.addFilter(engine_time)
    log.addHandler(handler)
    log.setLevel(logging.INFO)
    log.propagate = False
    return handler, engine_time


def _log_file(path: str, max_bytes: int, backups: int, engine_time: _EngineTime) -> logging.Handler:
    """The log also to a file (``--log-file``), the stderr lines without the
    status line, renamed to PATH.1 .. PATH.<backups> when it reaches
    max_bytes (0: never), the oldest dropped; OSError if it cannot be written."""
    from logging.handlers import RotatingFileHandler

    handler = RotatingFileHandler(path, maxBytes=max_bytes, backupCount=backups, encoding="utf-8")
    handler.setFormatter(_LineFormatter(tty=False))
    handler.addFilter(engine_time)
    log.addHandler(handler)
    return handler


def _fail(message: str, code: int) -> int:
    from .config.values import cut

    # a long value or path in it (an option, a name in a driver's error) is cut, as in a configuration error
    sys.stderr.write("softplc: " + "\n".join(cut(line) for line in message.split("\n")) + "\n")
    return code


def run_plc(
    config: str | None,
    *,
    virtual_time: bool,
    duration_ns: int | None,
    cycles: int | None,
    watch: list,
    traces: list,
    units: list,
    final_json: str | None,
    start_mode: str | None,
    report_compile_errors: Callable,
    online_change: bool | None = None,
    web: str | None = None,
    log_file: str | None = None,
    log_max_bytes: int = 10_000_000,
    log_backups: int = 5,
    prepared: tuple | None = None,
    sets: list | None = None,
    bus_log: str | None = None,
) -> int:
    """Run the PLC of config (a TOML file; None: the embedded default), or
    of prepared: (PlcConfig, Program) a project gave (softplc run PROJECT)."""
    from .config import ConfigError, default_config_path, load_config
    from .config.scenario import with_sets
    from .config.servers import web_option
    from .engine.build import build_engine
    from .engine.libc_heap import steady_malloc
    from .engine.monitor import StatusReporter, Watch
    from .engine.scan import EngineError
    from .engine.tasks import TaskSetupError
    from .image.memory import AddressError
    from .plugin.driver import DriverError
    from .st.diagnostics import CompileError
    from .st.faults import STFault
    from .st.valuejson import json_text
    from .surfaces.host import SurfaceError, Surfaces
    from .surfaces.pipe import SERVERS
    from .trace.plot import PlotUnavailable, parse_units, plot

    steady_malloc()  # before its threads start: each would have an arena of its own
    plots = [t for t in traces if Path(t).suffix.lower() in PLOT_SUFFIXES]
    for t in traces:
        if Path(t).suffix.lower() not in TRACE_SUFFIXES:
            return _fail(f"--trace {t}: say which trace by the name's ending: {', '.join(TRACE_SUFFIXES)}", EXIT_CONFIG)
    try:
        unit_of = parse_units(units)
    except ValueError as e:
        return _fail(f"--unit {e}", EXIT_CONFIG)
    if plots:
        try:
            from .trace.plot import require

            require()
        except PlotUnavailable as e:
            return _fail(f"--trace {plots[0]}: {e}", EXIT_CONFIG)
    tty = sys.stderr.isatty()
    handler, engine_time = _setup_logging(tty)
    file_handler = None
    try:
        if log_file:
            try:
                file_handler = _log_file(log_file, log_max_bytes, log_backups, engine_time)
            except OSError as e:
                return _fail(f"--log-file: cannot write {log_file}: {e.strerror or e}", EXIT_CONFIG)
        program = None
        if prepared is not None:
            cfg, program = prepared
            path = cfg.path
        else:
            path = Path(config) if config else default_config_path()
            try:
                cfg = load_config(path)
            except ConfigError as e:
                return _fail(str(e), EXIT_CONFIG)
        for warning in cfg.warnings:
            log.warning("%s", warning)
        if sets:
            try:
                cfg = with_sets(cfg, sets)
            except ValueError as e:
                return _fail(f"--set {e}", EXIT_CONFIG)
        servers = {key: cfg.sections.get(key) for key in SERVERS}
        if web is not None:  # --web [HOST:]PORT: the page without a [web] section, or on another port
            try:
                servers["web"] = web_option(web, servers["web"])
            except ValueError as e:
                return _fail(f"--web: {e}", EXIT_CONFIG)
        try:
            engine = build_engine(
                cfg,
                virtual_time=virtual_time,
                start_mode=start_mode,
                program=program,
                bus_log=Path(bus_log) if bus_log else None,
            )
        except CompileError as e:
            report_compile_errors(e)
            return EXIT_COMPILE
        except (TaskSetupError, DriverError, ConfigError) as e:
            return _fail(str(e), EXIT_CONFIG)
        engine_time.clock = engine.clock
        log.info("%s: %s start, %s clock", path, engine.start_mode, "virtual" if virtual_time else "real")
        try:
            engine.load()
        except STFault as e:
            return _fail(f"initial values: {e}", EXIT_FAULT)
        except EngineError as e:
            return _fail(str(e), EXIT_CONFIG)
        # The servers start before the engine does, so that the first scans
        # run at their release times, not late by a server's start-up.
        surfaces = Surfaces(engine, servers)
        # made before the servers start, so that a page loaded at once offers its button
        changer = _online_change(engine, cfg, online_change, virtual_time)
        surfaces.online_change = changer  # the web page's "Online change" button
        try:
            surfaces.start()
        except SurfaceError as e:  # "[opcua] ...": the section of the file that cannot start
            return _fail(f"{path}: {e}", EXIT_CONFIG)
        settle_heap()
        try:
            engine.start()
        except STFault as e:
            surfaces.stop()
            return _fail(f"initial values: {e}", EXIT_FAULT)
        except (EngineError, DriverError) as e:
            surfaces.stop()
            return _fail(str(e), EXIT_CONFIG)
        with ExitStack() as cleanup:
            cleanup.callback(surfaces.stop)  # after the engine stopped
            cleanup.callback(engine.stop)
            try:
                watched = Watch(engine, watch)
            except (KeyError, AddressError) as e:
                return _fail(f"--watch: {e.args[0] if e.args else e}", EXIT_CONFIG)
            unknown = [p for p in unit_of if p not in watched.paths]
            if unknown:
                return _fail(f"--unit {', '.join(unknown)}: not watched (add --watch {unknown[0]})", EXIT_CONFIG)
            try:
                recorder = _open_traces(traces, watched, engine, cleanup)
            except OSError as e:
                return _fail(f"--trace: cannot write {e.filename}: {e.strerror or e}", EXIT_CONFIG)
            engine.after_tick.append(_announce_first_scan)
            reporter = StatusReporter(engine, sys.stderr, watched, tty, hub=surfaces.hub)
            if changer is not None:  # its file watcher
                changer.start()
                cleanup.callback(changer.stop)
            cleanup.enter_context(_signals(engine, changer))
            _start_console_commands(engine)
            reporter.start()
            cleanup.callback(reporter.stop)
            run_for(engine, cycles=cycles, duration_ns=duration_ns)
        store = engine.retain_store
        log.info(
            "stopped%s after %d scans: outputs safe%s",
            f" by {engine.stop_reason}" if engine.stop_reason else "",
            engine.cycle,
            ", retained data saved" if store is not None and store.last_error is None else "",
        )
        # the last write, at the stop, failed: the file holds the last good save (never a torn one)
        retain_lost = store is not None and store.last_error is not None
        if retain_lost:
            log.error(
                "retained data NOT saved: %s; %d of %d writes failed during the run, the file holds the last good one",
                store.last_error,
                store.errors,
                store.errors + store.writes,
            )
        if final_json:
            text = json_text(final_data(engine), indent=2) + "\n"
            if final_json == "-":
                sys.stdout.write(text)
            else:
                try:
                    Path(final_json).write_text(text, encoding="utf-8")
                except OSError as e:
                    return _fail(f"--final-json: cannot write {final_json}: {e.strerror or e}", EXIT_CONFIG)
        if recorder is not None:
            trace = recorder.trace("softplc run")
            for out in plots:
                try:
                    left_out = plot(trace, out, unit_of, title=f"softplc run {path.name}", marks=trace.marks)
                except OSError as e:
                    return _fail(f"--trace: cannot write {out}: {e.strerror or e}", EXIT_CONFIG)
                except ValueError as e:
                    log.warning("--trace %s: %s", out, e)
                    continue
                log.info("wrote %s%s", out, f" (text not drawn: {', '.join(left_out)})" if left_out else "")
        if engine.faults:
            log.error("%d runtime fault(s) during the run; the first: %s", len(engine.faults), engine.faults[0])
            return EXIT_FAULT
        return EXIT_FAULT if retain_lost else EXIT_OK
    finally:
        log.removeHandler(handler)
        if file_handler is not None:
            log.removeHandler(file_handler)
            file_handler.close()


def run_for(engine, cycles: int | None, duration_ns: int | None) -> int:
    """engine.run until --cycles scans ran or the engine clock reads
    --duration. The duration counts from engine time zero, the moment the
    engine was built, as the status line's t= and the traces do: on the
    real clock the start-up (drivers, bus start) is part of it, so
    `--duration 5s` ends at t=5.00s, not 5 s after the first scan."""
    if duration_ns is not None:
        duration_ns = max(duration_ns - engine.clock.now_ns(), 0)
    return engine.run(cycles=cycles, duration_ns=duration_ns)


def _open_traces(traces: list, watched, engine, cleanup: ExitStack):
    """Open every --trace file (OSError with its filename when one cannot be
    written) and hook its writer into the scan; returns the Recorder for
    the plots, or None."""
    from .engine.monitor import TraceWriter
    from .trace.events import SimEvents, csv_column
    from .trace.series import Recorder
    from .trace.vcd import VcdTraceWriter

    recorder = None
    for trace in traces:
        suffix = Path(trace).suffix.lower()
        if suffix in PLOT_SUFFIXES:
            if not Path(trace).resolve().parent.is_dir():
                raise FileNotFoundError(2, "No such directory", trace)
            if recorder is None:
                recorder = Recorder(watched, SimEvents(engine.simulators))
                engine.after_tick.append(recorder)
            continue
        stream = cleanup.enter_context(open(trace, "w", newline="", encoding="utf-8"))
        if suffix == ".csv":
            engine.after_tick.append(TraceWriter(stream, watched, csv_column(engine.simulators)))
        else:
            vcd_writer = VcdTraceWriter(stream, watched, SimEvents(engine.simulators))
            cleanup.callback(_close_vcd, vcd_writer, engine)
            engine.after_tick.append(vcd_writer)
    return recorder


def _close_vcd(writer, engine) -> None:
    writer.close(engine.clock.now_ns())


def _online_change(engine, cfg, wanted: bool | None, virtual_time: bool):
    """The online change (docs/guide/running.md "Online change"), its file watcher not
    started yet, or None. On by default in real time, where the PLC runs a
    machine and is edited while it runs; off by default in virtual time,
    where a run is a simulation that must give the same result each time
    (--online-change turns it on)."""
    if not (wanted if wanted is not None else not virtual_time):
        return None
    from .engine.online_change import OnlineChange

    return OnlineChange(engine, cfg)


def _announce_first_scan(engine) -> None:
    """Log once that the scan is under way (the first cycle went through)."""
    engine.after_tick.remove(_announce_first_scan)
    log.info("running; Ctrl-C or SIGTERM stops, SIGUSR1 restarts faulted tasks")


class _signals:
    """SIGINT/SIGTERM stop the engine after the current scan (a task in a
    loop ends its cycle at the loop's next watchdog check); SIGUSR1 restarts
    faulted tasks; SIGHUP asks the online change (if on) to compile and swap
    in the ST files now. The handlers only set flags the scan reads."""

    def __init__(self, engine, changer=None) -> None:
        self.engine = engine
        self.changer = changer
        self.previous: dict = {}

    def __enter__(self):
        if threading.current_thread() is not threading.main_thread():
            return self  # signals can only be handled in the main thread
        stop = lambda signum, _frame: self.engine.request_stop(signal.Signals(signum).name)  # noqa: E731
        for sig, handler in (
            (signal.SIGINT, stop),
            (signal.SIGTERM, stop),
            (signal.SIGUSR1, lambda *_: self.engine.request_restart()),
        ):
            self.previous[sig] = signal.signal(sig, handler)
        if self.changer is not None and hasattr(signal, "SIGHUP"):
            changer = self.changer
            self.previous[signal.SIGHUP] = signal.signal(signal.SIGHUP, lambda *_: changer.wake("SIGHUP"))
        return self

    def __exit__(self, *exc) -> None:
        for sig, handler in self.previous.items():
            signal.signal(sig, handler)


def _start_console_commands(engine) -> None:
    """On a terminal, `restart` (or r) and `quit` (or q) typed on stdin."""
    if not sys.stdin or not sys.stdin.isatty():
        return

    def read() -> None:
        for line in sys.stdin:
            word = line.strip().lower()
            if word in ("r", "restart"):
                engine.request_restart()
            elif word in ("q", "quit", "stop"):
                engine.request_stop(f"'{word}' typed on the terminal")
                return

    threading.Thread(target=read, name="softplc-console", daemon=True).start()
