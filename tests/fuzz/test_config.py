"""Configurations into config loading: a ConfigError naming the file and the
key of every error, or a valid configuration, never a traceback, within the
harness's bounds.

  * the shipped files load as they are;
  * mutated documents (configs.mutated_documents) go to config_from_dict,
    as load_config hands a parsed file on; mutated texts
    (configs.mutated_texts) go to load_config. Both live in a copy of
    io_config/ in a temporary directory (its ST programs and EDS files
    linked), so that relative paths resolve and nothing is written beside
    the shipped files;
  * the mutated documents that load are built into an engine and run for a
    few scans in virtual time, as `softplc run` would: the errors it reports
    (compile errors, driver and task set-up errors, a runtime fault of the
    initial values) are answers; any other exception, or a traceback in the
    log, is a crash.
"""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import pytest
from hypothesis import given

from softplc.runtime.config import ConfigError, PlcConfig, config_from_dict, load_config
from softplc.runtime.config.errors import SHOWN
from softplc.runtime.engine.build import build_engine
from softplc.runtime.engine.scan import EngineError
from softplc.runtime.engine.tasks import TaskSetupError
from softplc.runtime.plugin.driver import DriverError
from softplc.runtime.st.diagnostics import CompileError
from softplc.runtime.st.faults import STFault

from .configs import CONFIG_DIR, ROOT, huge_texts, mutated_documents, mutated_texts, shipped
from .support import LogWatch, assert_no_tracebacks, bounded, fuzz, long, short

# The longest error line a mutation may give: a message says what is wrong
# and where, and cuts what it echoes (configs.LONG).
ECHO_LIMIT = 1000


def check_outcome(label: str, load) -> str:
    """load() must give a PlcConfig or raise a ConfigError naming label and,
    for every error not about the whole file, its key."""
    try:
        with bounded(f"loading {label}"):
            cfg = load()
    except ConfigError as exc:
        assert exc.file == label, f"the error names {exc.file!r}, not the file {label!r}"
        assert exc.errors, "a ConfigError with no error in it"
        for key, message in exc.errors:
            assert isinstance(message, str) and message.strip(), f"an empty message for {key!r}"
            assert "Traceback" not in message, message
            if not key:
                # a message about the whole file: it cannot be read, or is no TOML
                assert exc.position is not None or _about_the_file(message), (
                    f"{label}: an error that names no key: {message}"
                )
        assert len(str(exc).splitlines()) <= SHOWN + 1, "more than SHOWN errors and the count"
        for line in exc.lines():
            assert line.startswith(label), line
            assert len(line) <= ECHO_LIMIT, f"an error line of {len(line)} characters: {line[:200]}..."
        return "config error"
    assert isinstance(cfg, PlcConfig)
    for warning in cfg.warnings:
        assert warning.startswith(label), warning
    return "valid"


def _about_the_file(message: str) -> bool:
    return message.startswith(
        ("invalid TOML", "not UTF-8", "no such configuration file", "cannot read", "expected a", "tables, arrays or")
    )


@pytest.mark.parametrize("name", sorted(shipped()))
def test_the_shipped_configurations_load(name):
    path, _text, data = shipped()[name]
    assert check_outcome(str(path), lambda: load_config(path)) == "valid"
    assert check_outcome(str(path), lambda: config_from_dict(data, path)) == "valid"


class _Mirror:
    """io_config/ in a temporary directory: the files are written there, the
    ST programs and EDS files are links to the real ones."""

    def __init__(self) -> None:
        self.root = Path(tempfile.mkdtemp(prefix="softplc-fuzz-config-"))
        (self.root / "io_config" / "examples").mkdir(parents=True)
        os.symlink(ROOT / "st_programs", self.root / "st_programs")
        os.symlink(CONFIG_DIR / "eds", self.root / "io_config" / "eds")

    def path(self, name: str) -> Path:
        return self.root / "io_config" / name

    def check_text(self, case) -> str:
        name, text = case
        path = self.path(name)
        path.write_text(text, "utf-8", errors="surrogatepass")
        return check_outcome(str(path), lambda: load_config(path))

    def check_document(self, case, build: bool = False) -> str:
        name, data = case
        path = self.path(name)
        holder: list = []
        outcome = check_outcome(str(path), lambda: holder.append(config_from_dict(data, path)) or holder[0])
        if outcome == "valid" and build:
            outcome = run_briefly(holder[0])
        return outcome

    def close(self) -> None:
        shutil.rmtree(self.root, ignore_errors=True)


# What `softplc run` reports as an error of the configuration or the program
# (launch.run_plc), not a crash.
ANSWERS = (CompileError, DriverError, TaskSetupError, EngineError, STFault)


def run_briefly(cfg: PlcConfig) -> str:
    """Build the engine as `softplc run --virtual-time` does, start it, run
    three scans, stop it."""
    for table in cfg.raw.get("modbus", []):
        if table.get("host", "127.0.0.1") not in ("127.0.0.1", "localhost"):
            return "valid, not built"  # a mutated host would be looked up and called: this harness calls no one
    engine = None
    with LogWatch() as watch:
        try:
            with bounded("building and running a configuration"):
                engine = build_engine(cfg, virtual_time=True)
                engine.start()
                engine.run(cycles=3)
        except ANSWERS:
            return "refused at build"
        finally:
            if engine is not None:
                engine.stop()
    assert_no_tracebacks(watch, "a configuration built and run")
    return "ran"


@pytest.fixture(scope="module")
def mirror():
    made = _Mirror()
    yield made
    made.close()


@short(40)
@given(case=mutated_documents())
def test_mutated_documents_give_config_errors_or_load(mirror, case):
    mirror.check_document(case)


@short(30)
@given(case=mutated_texts())
def test_mutated_files_give_config_errors_or_load(mirror, case):
    mirror.check_text(case)


@short(5)
@given(case=huge_texts(most=2000))
def test_huge_files_give_a_bounded_message(mirror, case):
    assert mirror.check_text(case) == "config error"


@pytest.mark.slow  # whole plants or buses
@short(6)
@given(case=mutated_documents())
def test_mutated_documents_that_load_build_and_run(mirror, case):
    mirror.check_document(case, build=True)


@fuzz
def test_long_mutated_documents(tally, mirror, shard):
    counts = tally("configs")

    @long("configs", 0.59, shard)
    @given(mutated_documents())
    def run(case):
        counts.add(mirror.check_document(case))

    run()


@fuzz
def test_long_mutated_files(tally, mirror, shard):
    counts = tally("configs")

    @long("configs", 0.3, shard)
    @given(mutated_texts())
    def run(case):
        counts.add(mirror.check_text(case))

    run()


@fuzz
def test_long_mutated_documents_built(tally, mirror, shard):
    counts = tally("configs")

    @long("configs", 0.1, shard)
    @given(mutated_documents())
    def run(case):
        counts.add(mirror.check_document(case, build=True))

    run()


@fuzz
def test_long_huge_files(tally, mirror, shard):
    counts = tally("configs")

    @long("configs", 0.01, shard)
    @given(huge_texts(most=10_000))
    def run(case):
        counts.add(mirror.check_text(case))

    run()
