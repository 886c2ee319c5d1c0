"""`softplc run`: load the configuration, build and start the engine, show
its status, handle signals and commands, stop cleanly, write the results.

Exit codes: 0 stopped cleanly, 1 compile errors, 2 bad configuration or
option, 3 a runtime fault happened during the run.
"""

from __future__ import annotations

import json
import logging
import signal
import sys
import threading
from collections.abc import Callable
from contextlib import ExitStack
from pathlib import Path

EXIT_OK, EXIT_COMPILE, EXIT_CONFIG, EXIT_FAULT = 0, 1, 2, 3

log = logging.getLogger("softplc")


class _LineFormatter(logging.Formatter):
    """Log lines that do not run into a status line being rewritten in place."""

    def __init__(self, tty: bool) -> None:
        super().__init__(
            "%(asctime)s softplc %(levelname)s: %(message)s" if not tty else "softplc %(levelname)s: %(message)s"
        )
        self.prefix = "\r\x1b[K" if tty else ""

    def format(self, record) -> str:
        return self.prefix + super().format(record)


def _setup_logging(tty: bool) -> logging.Handler:
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(_LineFormatter(tty))
    log.addHandler(handler)
    log.setLevel(logging.INFO)
    log.propagate = False
    return handler


def _fail(message: str, code: int) -> int:
    sys.stderr.write(f"softplc: {message}\n")
    return code


def run_plc(
    config: str | None,
    *,
    virtual_time: bool,
    duration_ns: int | None,
    cycles: int | None,
    watch: list,
    trace: str | None,
    final_json: str | None,
    start_mode: str | None,
    report_compile_errors: Callable,
) -> int:
    from .config import ConfigError, default_config_path, load_config
    from .engine.build import build_engine
    from .engine.monitor import StatusReporter, TraceWriter, Watch
    from .engine.scan import EngineError
    from .engine.tasks import TaskSetupError
    from .image.memory import AddressError
    from .plugin.driver import DriverError
    from .st.diagnostics import CompileError
    from .st.faults import STFault

    tty = sys.stderr.isatty()
    handler = _setup_logging(tty)
    try:
        path = Path(config) if config else default_config_path()
        try:
            cfg = load_config(path)
        except ConfigError as e:
            return _fail(str(e), EXIT_CONFIG)
        for warning in cfg.warnings:
            log.warning("%s", warning)
        try:
            engine = build_engine(cfg, virtual_time=virtual_time, start_mode=start_mode)
        except CompileError as e:
            report_compile_errors(e)
            return EXIT_COMPILE
        except (TaskSetupError, DriverError) as e:
            return _fail(str(e), EXIT_CONFIG)
        log.info("%s: %s start, %s clock", path, engine.start_mode, "virtual" if virtual_time else "real")
        try:
            engine.start()
        except STFault as e:
            return _fail(f"initial values: {e}", EXIT_FAULT)
        except (EngineError, DriverError) as e:
            return _fail(str(e), EXIT_CONFIG)
        with ExitStack() as cleanup:
            cleanup.callback(engine.stop)
            try:
                watched = Watch(engine, watch)
            except (KeyError, AddressError) as e:
                return _fail(f"--watch: {e.args[0] if e.args else e}", EXIT_CONFIG)
            if trace:
                try:
                    stream = cleanup.enter_context(open(trace, "w", newline="", encoding="utf-8"))
                except OSError as e:
                    return _fail(f"--trace: cannot write {trace}: {e.strerror or e}", EXIT_CONFIG)
                engine.after_tick.append(TraceWriter(stream, watched))
            engine.after_tick.append(_announce_first_scan)
            reporter = StatusReporter(engine, sys.stderr, watched, tty)
            cleanup.enter_context(_signals(engine))
            _start_console_commands(engine)
            reporter.start()
            cleanup.callback(reporter.stop)
            engine.run(cycles=cycles, duration_ns=duration_ns)
        log.info(
            "stopped after %d scans: outputs safe%s",
            engine.cycle,
            ", retained data saved" if engine.retain_store is not None else "",
        )
        if final_json:
            text = json.dumps(engine.dump(), indent=2, ensure_ascii=False) + "\n"
            if final_json == "-":
                sys.stdout.write(text)
            else:
                try:
                    Path(final_json).write_text(text, encoding="utf-8")
                except OSError as e:
                    return _fail(f"--final-json: cannot write {final_json}: {e.strerror or e}", EXIT_CONFIG)
        if engine.faults:
            log.error("%d runtime fault(s) during the run; the first: %s", len(engine.faults), engine.faults[0])
            return EXIT_FAULT
        return EXIT_OK
    finally:
        log.removeHandler(handler)


def _announce_first_scan(engine) -> None:
    """Log once that the scan is under way (the first cycle went through)."""
    engine.after_tick.remove(_announce_first_scan)
    log.info("running; Ctrl-C or SIGTERM stops, SIGUSR1 restarts faulted tasks")


class _signals:
    """SIGINT/SIGTERM stop the engine after the current scan; SIGUSR1
    restarts faulted tasks. The handlers only set flags the scan reads."""

    def __init__(self, engine) -> None:
        self.engine = engine
        self.previous: dict = {}

    def __enter__(self):
        if threading.current_thread() is not threading.main_thread():
            return self  # signals can only be handled in the main thread
        stop = lambda *_: self.engine.request_stop()  # noqa: E731
        for sig, handler in (
            (signal.SIGINT, stop),
            (signal.SIGTERM, stop),
            (signal.SIGUSR1, lambda *_: self.engine.request_restart()),
        ):
            self.previous[sig] = signal.signal(sig, handler)
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
                engine.request_stop()
                return

    threading.Thread(target=read, name="softplc-console", daemon=True).start()
