"""Every key of the shipped configurations given a hostile value (of the
wrong type, negative, huge, non-finite, empty, too long; mutation_support.py):
the file loads, or every error names the file, and the key, and cuts long
values. The loopback example goes on to the build and two scans, where
what the configuration check cannot see (a task's program, a driver's
limits) must be refused the same way."""

from __future__ import annotations

from pathlib import Path

import pytest

from softplc.runtime.config import ConfigError, config_from_dict, default_config_path
from softplc.runtime.config.errors import key_text
from softplc.runtime.engine.build import build_engine
from softplc.runtime.engine.tasks import TaskSetupError
from softplc.runtime.plugin.driver import DriverError
from softplc.runtime.program import compile_files

from .mutation_support import SAMPLE, check_message, load_mutation, mutations, names_the_key
from .support import EXAMPLES

LOOPBACK = EXAMPLES / "loopback.toml"


def _build_and_scan(cfg, programs: dict) -> None:
    """Compile (once per set of ST files), build, start, two scans, stop."""
    key = (tuple(cfg.programs), cfg.profile)
    if key not in programs:
        programs[key] = compile_files(cfg.programs, profile=cfg.profile)
    engine = build_engine(cfg, virtual_time=True, program=programs[key], retain=False)
    try:
        engine.start()
        engine.run(cycles=2)
    finally:
        engine.stop()


def test_every_key_of_the_loopback_example():
    programs: dict = {}
    refused = loaded = 0
    unnamed = []
    for loc, value, tables in mutations(LOOPBACK):
        err = load_mutation(LOOPBACK, tables)
        if err is not None:
            refused += 1
            if not names_the_key(err.errors, loc):
                unnamed.append(f"{key_text(loc)} = {value}: {err}")
            continue
        cfg = config_from_dict(tables, LOOPBACK)
        try:
            _build_and_scan(cfg, programs)
        except (TaskSetupError, DriverError, ConfigError) as exc:  # ConfigError: an [init] path the program lacks
            refused += 1
            check_message(str(exc), LOOPBACK)
            if f": {key_text(loc)}" not in str(exc):
                unnamed.append(f"{key_text(loc)} = {value}: {exc}")
        else:
            loaded += 1
    assert not unnamed, f"{len(unnamed)} errors name another key or none:\n" + "\n".join(unnamed)
    assert refused > 500 and loaded > 10  # the mutations reached both ends


EVERY_CONFIG = sorted(EXAMPLES.glob("*.toml")) + [default_config_path()]


@pytest.mark.slow
@pytest.mark.parametrize("path", EVERY_CONFIG, ids=lambda p: Path(p).name)
def test_every_key_of_every_shipped_configuration(path):
    """No hostile value (one of each kind) crashes the configuration check;
    each error line names the file and stays short (the key may be another
    one: a relation between two keys is reported at one of them)."""
    refused = 0
    for _loc, _value, tables in mutations(path, values=SAMPLE):
        refused += load_mutation(path, tables) is not None
    assert refused > 100


def test_a_mutated_loopback_table_names_the_table():
    tables = {"plc": {"programs": ["../../st_programs/loopback_echo.st"]}, "loopback": [{"from": "%QB0"}, 7]}
    with pytest.raises(ConfigError) as info:
        config_from_dict(tables, LOOPBACK)
    assert [k for k, _m in info.value.errors] == ["loopback[0].to", "loopback[0].bytes", "loopback[1]"]
