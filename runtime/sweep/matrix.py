"""A sweep file: which scenarios of a configuration to run, and what each
one's result is.

    duration = "20s"                     # engine time each scenario runs (virtual)
    seed = 1                             # the random draws' (and nothing else's)

    [matrix]                             # every combination (cartesian product)
    "sim.mpu2s1.slip" = [0.1, 0.2, 0.3]
    "sim.mpu2s1.closing_time" = ["40ms", "80ms", "150ms"]

    # or a list of scenarios, each a table of the same keys:
    # [[scenario]]
    # "sim.mpu2s1.slip" = 0.1
    #
    # or draws = N random scenarios, each key a distribution:
    # [random]
    # draws = 100
    # "sim.mpu2s1.slip" = { uniform = [0.05, 0.35] }
    # "sim.mpu2s1.closing_time" = { choice = ["40ms", "80ms", "150ms"] }
    # "init.Genset.Target" = { normal = [250.0, 20.0] }   # mean, standard deviation

    [result]
    values = ["records.mpu2s1.closes[0].phase_deg", "Genset.State"]
    expect = ["Genset.State == 'Running'", "abs(records.mpu2s1.closes[0].phase_deg) < 10"]
    plot = { x = "sim.mpu2s1.slip", y = "records.mpu2s1.closes[0].phase_deg", hue = "sim.mpu2s1.closing_time" }

A key is where the value goes in the configuration (scenario.py applies
it): `sim.NAME.KEY` a key of the [[sim]] device of that name (its `name`,
or the default the status line and --final-json use: mpu2s1, ltmr40),
`init.PATH` an initial value of the [init] table (an ST path), any other
dotted key a key of the file's tables, a table of an array chosen by its
`name` or its number (`task.Main.interval`, `can.0.bitrate`).

Values and expectations are expressions (expr.py). Random draws come from
one random.Random(seed), in scenario order, before any scenario runs: the
same scenarios wherever they run.
"""

from __future__ import annotations

import itertools
import random
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..durations import parse_duration_ns
from .expr import ExpressionError, parse_expression

DEFAULT_DURATION = "10s"
DISTRIBUTIONS = ("uniform", "normal", "choice", "integers")
TOP_KEYS = ("duration", "seed", "matrix", "scenario", "random", "result")
RESULT_KEYS = ("values", "expect", "plot")
PLOT_KEYS = ("x", "y", "hue")


class SweepError(Exception):
    """What is wrong with a sweep file: its name, the key, the message."""

    def __init__(self, file: str, key: str, message: str) -> None:
        super().__init__(f"{file}: {key}: {message}" if key else f"{file}: {message}")
        self.file, self.key, self.message = file, key, message


@dataclass(frozen=True)
class Scenario:
    """One run of the sweep: its number (from 0, in the file's order) and
    its parameters (key -> value, in the file's key order)."""

    index: int
    params: dict

    @property
    def id(self) -> str:
        """A short name (pytest's id): the keys' last parts and the values."""
        return "-".join(f"{k.rpartition('.')[2]}={v}" for k, v in self.params.items()) or f"s{self.index}"


@dataclass(frozen=True)
class Sweep:
    file: str
    duration_ns: int
    seed: int
    scenarios: tuple
    values: tuple = ()  # expressions: a column each
    expect: tuple = ()  # expressions that must be true for the scenario to pass
    plot: dict = field(default_factory=dict)  # x, y (and hue): keys or value expressions

    @property
    def keys(self) -> list:
        return list(self.scenarios[0].params) if self.scenarios else []


def load_sweep(path: str | Path) -> Sweep:
    """The sweep file read and checked; SweepError names the file and the key."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as e:
        raise SweepError(str(path), "", f"cannot read: {e.strerror or e}") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as e:
        raise SweepError(str(path), "", f"not TOML: {e}") from None
    return sweep_from_dict(data, str(path))


def sweep_from_dict(data: dict, file: str = "<sweep>") -> Sweep:
    def fail(key: str, message: str) -> SweepError:
        return SweepError(file, key, message)

    unknown = [k for k in data if k not in TOP_KEYS]
    if unknown:
        raise fail(unknown[0], f"not a key of a sweep file (it has: {', '.join(TOP_KEYS)})")
    kinds = [k for k in ("matrix", "scenario", "random") if k in data]
    if len(kinds) != 1:
        found = f" (found {', '.join(kinds)})" if kinds else ""
        raise fail("", f"give exactly one of [matrix], [[scenario]] and [random]{found}")
    duration = data.get("duration", DEFAULT_DURATION)
    try:
        duration_ns = parse_duration_ns(duration)
    except (TypeError, ValueError) as e:
        raise fail("duration", str(e)) from None
    if not duration_ns or duration_ns <= 0:
        raise fail("duration", f'{duration!r} is not a positive duration such as "20s"')
    seed = data.get("seed", 0)
    if not isinstance(seed, int) or isinstance(seed, bool):
        raise fail("seed", f"{seed!r} is not a whole number")
    kind = kinds[0]
    if kind == "matrix":
        scenarios = _matrix(data["matrix"], fail)
    elif kind == "scenario":
        scenarios = _listed(data["scenario"], fail)
    else:
        scenarios = _drawn(data["random"], seed, fail)
    values, expect, plot = _result(data.get("result", {}), scenarios, fail)
    return Sweep(file, duration_ns, seed, tuple(scenarios), values, expect, plot)


def _matrix(table: Any, fail) -> list:
    if not isinstance(table, dict) or not table:
        raise fail("matrix", "a table of keys, each with a list of values")
    for key, values in table.items():
        if not isinstance(values, list) or not values:
            raise fail(f"matrix.{key}", "a list of the values to try, e.g. [0.1, 0.2]")
    keys = list(table)
    combos = itertools.product(*(table[k] for k in keys))
    return [Scenario(i, dict(zip(keys, combo))) for i, combo in enumerate(combos)]


def _listed(tables: Any, fail) -> list:
    if not isinstance(tables, list) or not tables or not all(isinstance(t, dict) for t in tables):
        raise fail("scenario", "an array of tables ([[scenario]]), each the keys of one scenario")
    keys = list(tables[0])
    for i, table in enumerate(tables):
        if list(table) != keys:
            raise fail(f"scenario[{i}]", f"has the keys {list(table)}, scenario[0] has {keys}: give every one the same")
    return [Scenario(i, dict(t)) for i, t in enumerate(tables)]


def _drawn(table: Any, seed: int, fail) -> list:
    if not isinstance(table, dict):
        raise fail("random", "a table: draws = N and a distribution per key")
    draws = table.get("draws")
    if not isinstance(draws, int) or isinstance(draws, bool) or draws < 1:
        raise fail("random.draws", f"{draws!r}: how many scenarios to draw, a whole number from 1")
    specs = {k: v for k, v in table.items() if k != "draws"}
    if not specs:
        raise fail("random", 'no key to draw: add one, e.g. "sim.gen.slip" = { uniform = [0.05, 0.3] }')
    for key, spec in specs.items():
        _check_distribution(f"random.{key}", spec, fail)
    rng = random.Random(seed)
    return [Scenario(i, {k: _draw(rng, s) for k, s in specs.items()}) for i in range(draws)]


def _check_distribution(key: str, spec: Any, fail) -> None:
    if not isinstance(spec, dict) or len(spec) != 1 or next(iter(spec)) not in DISTRIBUTIONS:
        raise fail(key, f"one of {{ {' | '.join(f'{d} = [...]' for d in DISTRIBUTIONS)} }}")
    ((kind, args),) = spec.items()
    if not isinstance(args, list) or not args:
        raise fail(f"{key}.{kind}", "a list")
    if kind == "choice":
        return
    if len(args) != 2 or not all(isinstance(a, int | float) and not isinstance(a, bool) for a in args):
        what = "[mean, standard deviation]" if kind == "normal" else "[low, high]"
        raise fail(f"{key}.{kind}", f"two numbers, {what}")
    if kind == "integers" and not all(isinstance(a, int) for a in args):
        raise fail(f"{key}.{kind}", "two whole numbers, [low, high] (both included)")


def _draw(rng: random.Random, spec: dict) -> Any:
    ((kind, args),) = spec.items()
    if kind == "uniform":
        return rng.uniform(args[0], args[1])
    if kind == "normal":
        return rng.gauss(args[0], args[1])
    if kind == "integers":
        return rng.randint(args[0], args[1])
    return rng.choice(args)


def _result(table: Any, scenarios: list, fail) -> tuple:
    if not isinstance(table, dict):
        raise fail("result", "a table: values, expect, plot")
    unknown = [k for k in table if k not in RESULT_KEYS]
    if unknown:
        raise fail(f"result.{unknown[0]}", f"not a key of [result] (it has: {', '.join(RESULT_KEYS)})")
    found = []
    for name in ("values", "expect"):
        texts = table.get(name, [])
        if not isinstance(texts, list) or not all(isinstance(t, str) for t in texts):
            raise fail(f"result.{name}", "a list of expressions (strings)")
        for i, text in enumerate(texts):
            try:
                parse_expression(text)
            except ExpressionError as e:
                raise fail(f"result.{name}[{i}]", str(e)) from None
        found.append(tuple(texts))
    plot = table.get("plot", {})
    if not isinstance(plot, dict) or (plot and ("x" not in plot or "y" not in plot)):
        raise fail("result.plot", "a table { x = KEY, y = VALUE } (and hue = KEY)")
    keys = scenarios[0].params if scenarios else {}
    for axis, what in plot.items():
        if axis not in PLOT_KEYS:
            raise fail(f"result.plot.{axis}", f"not a key of the plot (it has: {', '.join(PLOT_KEYS)})")
        if what not in keys and what not in found[0]:
            raise fail(f"result.plot.{axis}", f"{what!r} is neither a key of the scenarios nor one of result.values")
    return found[0], found[1], dict(plot)
