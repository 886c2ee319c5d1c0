"""The pytest plugin softplc installs (entry point pytest11 "softplc"):

    @pytest.mark.softplc(config="io_config/default.toml", watch=["Motor.state"])
    def test_motor(plc):                      # a started-on-demand PLC, stopped after the test
        plc.run_until("Motor.ltmr.Running", timeout="2s")

    def test_two(plc_factory):                # any number of PLCs, each stopped after the test
        a = plc_factory(st="PROGRAM Main ... END_PROGRAM", cycle="5ms")
        b = plc_factory(config="plant.toml", watch=["Line.state"])

The marker takes the arguments of plc_factory: config (a path, relative to
the test file's folder if not found from the current directory, the TOML
tables as a dict, or None: the embedded default plant), or st (ST files or texts, with tasks, cycle,
profile, tables), plus watch, virtual_time (default True), edit, start_mode. A
failed test that used a PLC shows the rows of its trace around the end in
the report ("softplc trace"). SOFTPLC_NO_CACHE=1 in the environment keeps
the PLCs' compilations off softplc's cache (docs/reference/commands.md "The cache"), as
``softplc --no-cache`` does.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import pytest

if TYPE_CHECKING:  # the engine is imported when a test asks for a PLC, not by every pytest run
    from .plc import PLC

MARKER = "softplc"


def pytest_configure(config: pytest.Config) -> None:
    config.addinivalue_line(
        "markers",
        f"{MARKER}(config=None, st=None, watch=(), **options): the PLC the `plc` fixture builds "
        "(a configuration file, or ST files or texts; virtual time unless virtual_time=False)",
    )


def _build(where: Path, *, config=None, st=None, watch=(), **options: Any) -> PLC:
    from ..collector import collector_off

    with collector_off():  # the imports, the compile and the engine's build
        return _built(where, config=config, st=st, watch=watch, **options)


def _built(where: Path, *, config=None, st=None, watch=(), **options: Any) -> PLC:
    from .plc import PLC

    if config is not None and st is not None:
        raise pytest.UsageError("softplc: give config or st, not both")
    if st is not None:
        plc = PLC.from_st(st, **options)
    else:
        if isinstance(config, (str, Path)):
            path = Path(config)
            if not path.is_absolute() and not path.exists() and (where / path).exists():
                config = where / path
        plc = PLC.from_config(config, **options)
    if watch:
        plc.watch(*([watch] if isinstance(watch, str) else watch))
    return plc


@pytest.fixture
def plc_factory(request: pytest.FixtureRequest):
    """plc_factory(config=... | st=..., watch=[...], **options) -> PLC; every PLC made is stopped after the test."""
    made: list[PLC] = []
    where = Path(str(request.node.path)).parent

    def factory(**kwargs: Any) -> PLC:
        plc = _build(where, **kwargs)
        made.append(plc)
        return plc

    request.node._softplc_plcs = made
    yield factory
    errors = []
    for plc in reversed(made):
        try:
            plc.stop()
        except Exception as exc:  # stop every one, then report
            errors.append(exc)
    if errors:
        raise errors[0]


@pytest.fixture
def plc(request: pytest.FixtureRequest, plc_factory) -> PLC:
    """The PLC of the test's @pytest.mark.softplc(...) (the embedded default plant without one)."""
    marker = request.node.get_closest_marker(MARKER)
    kwargs: dict = {}
    if marker is not None:
        if marker.args:
            kwargs["config"] = marker.args[0]
        kwargs.update(marker.kwargs)
    return plc_factory(**kwargs)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo):
    outcome = yield
    report = outcome.get_result()
    if report.when == "call" and report.failed:
        for i, made in enumerate(getattr(item, "_softplc_plcs", ())):
            if made.trace.paths:
                title = f"softplc trace (PLC {i + 1}, t={made.now_ns / 1e9:.3f}s)"
                report.sections.append((title, made.trace.around()))
