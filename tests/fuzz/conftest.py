"""The fuzz harness's two runs (support.py): tests marked `fuzz` (the long
run) are left out unless the -m expression names fuzz (`pytest -m fuzz`,
`-m "fuzz and not slow"` ...), so `pytest`, `pytest -m "not slow"` and CI run
only the short, derandomized examples. The `tally` fixture counts the inputs
of a long test by outcome; the counts are printed at the end of the run."""

from __future__ import annotations

from collections import Counter

import pytest

from .support import SHARDS, Shard


def pytest_generate_tests(metafunc):
    """A long test takes `shard`: it runs as SHARDS tests (support.long)."""
    if "shard" in metafunc.fixturenames:
        base = metafunc.config.getoption("--hypothesis-seed", None)
        name = metafunc.function.__name__
        metafunc.parametrize(
            "shard", [Shard(name, i, SHARDS, base) for i in range(SHARDS)], ids=[f"shard{i}" for i in range(SHARDS)]
        )


def pytest_collection_modifyitems(config, items):
    if "fuzz" in (config.option.markexpr or ""):
        return
    left_out = [item for item in items if item.get_closest_marker("fuzz")]
    if left_out:
        items[:] = [item for item in items if not item.get_closest_marker("fuzz")]
        config.hook.pytest_deselected(items=left_out)


class Tally(Counter):
    """A long test's inputs (ST sources, configurations, frames) and its
    outcomes ("diagnostics", "ran", "runtime fault", "config error" ...)."""

    def __init__(self, area: str) -> None:
        super().__init__()
        self.area = area
        self.inputs = 0

    def add(self, outcome: str, inputs: int = 1) -> None:
        self[outcome] += 1
        self.inputs += inputs


@pytest.fixture
def tally(request, record_property):
    made: list[Tally] = []

    def make(area: str) -> Tally:
        t = Tally(area)
        made.append(t)
        return t

    yield make
    for t in made:
        record_property("fuzz_tally", (t.area, t.inputs, dict(t)))


def pytest_terminal_summary(terminalreporter):
    found: dict = {}  # the teardown report carries what the fixture recorded as it finished
    for reports in terminalreporter.stats.values():
        for report in reports:
            for name, value in getattr(report, "user_properties", ()):
                if name == "fuzz_tally":
                    found[(report.nodeid, value[0])] = value[1:]
    rows = sorted((nodeid.split("::")[-1], area, n, counts) for (nodeid, area), (n, counts) in found.items())
    if not rows:
        return
    terminalreporter.section("fuzz: inputs by outcome")
    totals: Counter = Counter()
    for test, area, n, counts in rows:
        totals[area] += n
        detail = ", ".join(f"{k} {v:,}" for k, v in sorted(counts.items()))
        terminalreporter.write_line(f"{test}: {n:,} {area} ({detail})")
    terminalreporter.write_line("total: " + ", ".join(f"{v:,} {k}" for k, v in sorted(totals.items())))
