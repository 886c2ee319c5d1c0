#!/usr/bin/env python3
"""How fast `softplc check` goes, start-up included (see benchmarks/README.md).

    python benchmarks/bench_check.py                        # the generated clean 10,000-line file
    python benchmarks/bench_check.py PROJECT... --runs 5    # and real projects (folders, files)
    python benchmarks/bench_check.py PROJECT --baseline DIR # against another softplc, paired

Part 1 times `softplc check` as a subprocess (the user's wait: start-up,
parse, check, the re-checks under the other profiles) of the generated
10,000-line ST file of bench_language.py and of each project given, best and
median of --runs, and prints lines per second here and scaled to the
reference host (issue 32's targets: 20,000 lines/s for a real project with
thousands of errors, 40,000 for the clean file). Lines are those of the
project's source files. With --baseline DIR (a folder holding another
softplc package, e.g. `git archive main | tar -x -C DIR/softplc`), the two
run in turn, A B A B, and the ratio is the median of the pairs.

Part 2 times the "did you mean" hints alone: unknown names, each repeated,
looked up among a few thousand known names, the way the checker does now
(hints.NameIndex, a search per name) and the old way (difflib per error,
kept here as the baseline), with their answers compared.

Nothing is asserted: the script prints figures measured in this run.
"""

from __future__ import annotations

import argparse
import difflib
import os
import random
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from bench_language import FRONT_END_LINES, generate_st  # noqa: E402
from host import timeit_factor  # noqa: E402

from softplc.runtime.project import open_projects  # noqa: E402
from softplc.runtime.st.hints import NameIndex  # noqa: E402

CLEAN_TARGET = 40_000
ERRORS_TARGET = 20_000


def source_lines(path: str) -> int:
    """Lines of the source files `softplc check PATH` reads."""
    total = 0
    for project in open_projects([path]):
        for f in project.files:
            with open(f, "rb") as fh:
                total += fh.read().count(b"\n")
    return total


def check_once(path: str, pythonpath: str | None) -> float:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # an installed softplc has its bytecode: let it be written
    if pythonpath:
        env["PYTHONPATH"] = pythonpath + os.pathsep + env.get("PYTHONPATH", "")
    t0 = time.perf_counter()
    subprocess.run(
        [sys.executable, "-m", "softplc.runtime.cli", "check", path],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        check=False,
    )
    return time.perf_counter() - t0


def bench_path(name: str, path: str, runs: int, baseline: str | None, factor: float) -> None:
    lines = source_lines(path)
    mine: list = []
    theirs: list = []
    for pp in (None, baseline) if baseline else (None,):
        check_once(path, pp)  # a warm-up, not counted: the bytecode written, the files in the page cache
    for i in range(runs):
        order = [(mine, None), (theirs, baseline)] if baseline else [(mine, None)]
        if i % 2:
            order.reverse()
        for into, pp in order:
            into.append(check_once(path, pp))
    best = min(mine)
    print(
        f"{name}: {lines} lines; check {best:.2f} s best, {statistics.median(mine):.2f} s median of {runs}; "
        f"{lines / best:,.0f} lines/s here, {lines / best * factor:,.0f} lines/s scaled"
    )
    if baseline:
        ratio = statistics.median(a / b for a, b in zip(mine, theirs, strict=True))
        b = min(theirs)
        print(
            f"  baseline: {b:.2f} s best, {statistics.median(theirs):.2f} s median; "
            f"{lines / b:,.0f} lines/s here, {lines / b * factor:,.0f} scaled; "
            f"this / baseline {ratio:.2f} (median of pairs)"
        )


def old_suggest(key: str, names: list) -> str | None:
    """The hint as the checker computed it before hints.py: difflib on every error."""
    close = difflib.get_close_matches(key, [n.upper() for n in names], n=1, cutoff=0.75)
    if close:
        return next((n for n in names if n.upper() == close[0]), close[0])
    return None


def new_suggest(indexes: dict, key: str, names: list) -> str | None:
    """The hint as checker_base._suggest computes it now."""
    listed = tuple(names)
    index = indexes.get(listed)
    if index is None:
        index = indexes[listed] = NameIndex(listed)
    return index.closest(key, 0.75)


def bench_hints(known: int, unknown: int, repeats: int) -> None:
    rng = random.Random(32)
    parts = [
        "Motor",
        "Valve",
        "Pump",
        "Alarm",
        "Timer",
        "Count",
        "Speed",
        "Level",
        "Temp",
        "Cmd",
        "State",
        "Fb",
        "Get",
        "Set",
    ]
    names = sorted({"_".join(rng.sample(parts, rng.randint(1, 3))) + str(rng.randint(0, 99)) for _ in range(known)})
    keys = [rng.choice(names).upper()[:-1] + "X" for _ in range(unknown // 2)]  # misspelt: a hint
    keys += ["FB_" + "".join(rng.choice("ABCDEFGHIJ") for _ in range(10)) for _ in range(unknown - len(keys))]  # none
    errors = [k for k in keys for _ in range(repeats)]
    rng.shuffle(errors)
    t0 = time.perf_counter()
    old = [old_suggest(k, list(names)) for k in errors]
    t_old = time.perf_counter() - t0
    indexes: dict = {}
    t0 = time.perf_counter()
    new = [new_suggest(indexes, k, list(names)) for k in errors]
    t_new = time.perf_counter() - t0
    same = "same answers" if old == new else f"{sum(a != b for a, b in zip(old, new, strict=True))} answers DIFFER"
    print(
        f"hints: {len(errors)} errors ({unknown} unknown names x {repeats}) among {len(names)} names: "
        f"difflib per error {t_old:.2f} s, index {t_new * 1000:.1f} ms ({t_old / t_new:.0f}x); {same}"
    )


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("paths", nargs="*", help="projects to check: folders, project files, source files")
    ap.add_argument("--runs", type=int, default=3, help="checks of each (best and median are printed)")
    ap.add_argument(
        "--baseline", metavar="DIR", help="a folder with another softplc package, run in turn with this one"
    )
    args = ap.parse_args()
    host = timeit_factor()
    print(host.line())
    with tempfile.TemporaryDirectory() as tmp:
        clean = Path(tmp) / "generated_10k.st"
        clean.write_text(generate_st(FRONT_END_LINES), encoding="utf-8")
        print(f"targets (reference host): {CLEAN_TARGET:,} lines/s clean, {ERRORS_TARGET:,} lines/s with errors")
        bench_path("generated clean file", str(clean), args.runs, args.baseline, host.factor)
        for p in args.paths:
            bench_path(p, p, args.runs, args.baseline, host.factor)
    bench_hints(known=2000, unknown=200, repeats=10)
    return 0


if __name__ == "__main__":
    sys.exit(main())
