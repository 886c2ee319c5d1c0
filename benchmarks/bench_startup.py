"""Start-up: how long a user waits for softplc to start, against the time
Python takes to import the libraries softplc is built on (issue 32, row 2:
the target is at most 2x that import).

    python benchmarks/bench_startup.py          # N=9 rounds, about 2 minutes on 2 busy cores
    python benchmarks/bench_startup.py -n 3     # a smoke run
    python benchmarks/bench_startup.py --against OTHER/.venv/bin/python
                                                # also every softplc command of another
                                                # checkout (before/after), in the same rounds

Every figure is a whole process, started from this script:

  baseline    python -c "import lark, canopen, can, pymodbus, pydantic, click"
  exec        softplc exec tiny.st                  (a 4-line PROGRAM, one cycle)
  check       softplc check tiny.st
  test        softplc test test_tiny.st             (one ST test, no configuration)
  pytest      python -m pytest test_tiny.py         (one test using the plc fixture)
  pytest-0    python -m pytest test_none.py         (one test without it: pytest's own start)

each with a cold cache (an empty cache folder each run: SOFTPLC_CACHE) and a
warm one (a folder a first run filled). In each round the commands run one
after the other, the order rotated from round to round; printed are the
median wall and CPU (user + system) seconds and the ratios of the medians to
the baseline's, and for the fixture the pytest run less pytest-0. Python
writes and reads its .pyc files here as on an installed softplc
(PYTHONDONTWRITEBYTECODE is dropped from the children's environment; one
run of each command before the rounds writes them).
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from host import timeit_factor

BASELINE = "import lark, canopen, can, pymodbus, pydantic, click"
CLI = "import sys; from softplc.runtime.cli import main; sys.argv[0] = 'softplc'; main()"

TINY_ST = """PROGRAM Main
VAR x : INT; END_VAR
x := x + 1;
END_PROGRAM
"""
TEST_ST = """FUNCTION_BLOCK TEST_Add
VAR n : INT; END_VAR
n := n + 1;
ASSERT_EQUAL(n, 1, 'one');
TEST_FINISHED();
END_FUNCTION_BLOCK
"""
TEST_PY = '''import pytest

PROGRAM = """PROGRAM Main
VAR x : INT; END_VAR
x := x + 1;
END_PROGRAM
"""


@pytest.mark.softplc(st=PROGRAM)
def test_tiny(plc):
    plc.step(1)
    assert plc["Main.x"] == 1
'''
TEST_NONE = """def test_none():
    assert 1 + 1 == 2
"""


def _commands(work: Path, py: str, tag: str = "") -> dict[str, list[str]]:
    pytest = [py, "-m", "pytest", "-q", "-p", "no:cacheprovider", "-p", "no:randomly", "-p", "no:xdist"]
    return {
        "exec" + tag: [py, "-c", CLI, "exec", str(work / "tiny.st")],
        "check" + tag: [py, "-c", CLI, "check", str(work / "tiny.st")],
        "test" + tag: [py, "-c", CLI, "test", str(work / "test_tiny.st")],
        "pytest" + tag: [*pytest, str(work / "test_tiny.py")],
        "pytest-0" + tag: [*pytest, str(work / "test_none.py")],
    }


def _run(cmd: list[str], env: dict, cwd: Path) -> tuple[float, float]:
    """(wall, cpu) seconds of one whole process; a failing command stops the benchmark."""
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    out = proc.stdout.read() if proc.stdout else b""
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({proc.returncode}):\n{out.decode(errors='replace')}")
    return wall, usage.ru_utime + usage.ru_stime


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("-n", type=int, default=9, help="rounds (default 9)")
    ap.add_argument("--against", metavar="PYTHON", help="another softplc's Python: its commands too, tagged '@'")
    args = ap.parse_args()
    host = timeit_factor()
    work = Path(tempfile.mkdtemp(prefix="softplc-startup-"))
    try:
        (work / "tiny.st").write_text(TINY_ST)
        (work / "test_tiny.st").write_text(TEST_ST)
        (work / "test_tiny.py").write_text(TEST_PY)
        (work / "test_none.py").write_text(TEST_NONE)
        warm_dir = work / "warm-cache"
        env = {k: v for k, v in os.environ.items() if k not in ("PYTHONDONTWRITEBYTECODE", "SOFTPLC_NO_CACHE")}
        commands = {"baseline": [sys.executable, "-c", BASELINE], **_commands(work, sys.executable)}
        if args.against:
            commands.update(_commands(work, args.against, "@"))
        cases = [("baseline", "-")]
        cases += [(name, cache) for name in commands if name != "baseline" for cache in ("cold", "warm")]
        for cmd in commands.values():  # .pyc files written, the warm cache filled
            _run(cmd, {**env, "SOFTPLC_CACHE": str(warm_dir)}, work)
        times: dict = {case: [] for case in cases}
        for r in range(args.n):
            order = cases[r % len(cases) :] + cases[: r % len(cases)]
            for name, cache in order:
                if cache == "cold":
                    cold_dir = work / f"cold-{r}-{name}"
                    run_env = {**env, "SOFTPLC_CACHE": str(cold_dir)}
                else:
                    run_env = {**env, "SOFTPLC_CACHE": str(warm_dir)}
                times[(name, cache)].append(_run(commands[name], run_env, work))
                if cache == "cold":
                    shutil.rmtree(work / f"cold-{r}-{name}", ignore_errors=True)
        _report(times, args.n, host)
    finally:
        shutil.rmtree(work, ignore_errors=True)


def _report(times: dict, rounds: int, host) -> None:
    med = {case: (statistics.median(t[0] for t in v), statistics.median(t[1] for t in v)) for case, v in times.items()}
    base_wall, base_cpu = med[("baseline", "-")]
    print(host.line())
    print(f"medians of {rounds} rounds, whole processes; ratio = the command's median / the baseline's")
    print("(a name with @: the commands of --against's Python)")
    print(f"{'command':<10} {'cache':<5} {'wall s':>7} {'ratio':>6} {'cpu s':>7} {'ratio':>6}")
    for (name, cache), (wall, cpu) in med.items():
        print(f"{name:<10} {cache:<5} {wall:7.3f} {wall / base_wall:6.2f} {cpu:7.3f} {cpu / base_cpu:6.2f}")
    for tag in ("", "@"):
        for cache in ("cold", "warm"):
            if ("pytest" + tag, cache) not in med:
                continue
            wall = med[("pytest" + tag, cache)][0] - med[("pytest-0" + tag, cache)][0]
            cpu = med[("pytest" + tag, cache)][1] - med[("pytest-0" + tag, cache)][1]
            print(
                f"the plc fixture{tag} ({cache}: pytest less pytest-0): wall {wall:.3f} s = {wall / base_wall:.2f}x, "
                f"cpu {cpu:.3f} s = {cpu / base_cpu:.2f}x the baseline"
            )
    print(f"baseline on the reference host: wall {host.scaled(base_wall):.3f} s, cpu {host.scaled(base_cpu):.3f} s")


if __name__ == "__main__":
    main()
