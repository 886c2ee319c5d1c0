#!/usr/bin/env python3
"""The cost of the cooperative watchdog on loop back-edges (see
benchmarks/README.md).

    python benchmarks/bench_loops.py           # about 30 s
    python benchmarks/bench_loops.py --quick   # smoke run, a few seconds

Every program is compiled twice from the same ST: as softplc compiles it
(FOR loops charge their length to the loop budget, WHILE and REPEAT count it
down, the watchdog's clock is read every 1024 passes) and with the checks
left out (the baseline: CodeGen.watchdog_checks = False). Both are called by
the same bare loop; chunks of cycles of the two run back to back, alternating
which goes first, and the ratio is the median over the rounds of checked /
unchecked. A chunk is timed in this thread's CPU time, so that another
process taking the core (a loaded machine) does not count. Both watchdog
clocks are measured: the real clock's perf_counter and virtual time's
thread CPU time. Both sides must end in the same state.

Nothing here is asserted: the script prints figures measured in this run.
"""

from __future__ import annotations

import argparse
import gc
import statistics
import sys
import time
from pathlib import Path

from softplc.runtime.program import compile_files
from softplc.runtime.program.loaded import Program
from softplc.runtime.st.codegen.codegen import CodeGen

HERE = Path(__file__).resolve().parent

# (file, PROGRAM, cycles per timed chunk: about 5 ms each)
PROGRAMS = [
    ("loops.st", "ForTight", 100),
    ("loops.st", "ForShort", 100),
    ("loops.st", "ForLong", 1),
    ("loops.st", "WhileTight", 60),
    ("loops.st", "RepeatTight", 60),
    ("numeric.st", "NumericMain", 4),
    ("bits.st", "BitsMain", 16),
]


class _Unchecked(CodeGen):
    watchdog_checks = False


def _unchecked(program: Program) -> Program:
    """The same checked program, generated without the watchdog's checks."""
    gen = _Unchecked(program.checked, program.profile).generate()
    filename = program.filename + "-unchecked"
    code = compile(gen.source, filename, "exec")
    return Program(program.profile, program.checked, gen, code, filename, [], program.sources, program.pous)


def _instance(program: Program, entry: str, timer):
    runner = program.runner(entry)
    runner.ctx.timer = timer
    runner.ctx.watchdog_s = 3600.0  # never reached: every check reads the clock and goes on
    runner.ctx.arm_watchdog()  # as the engine arms it for a task's cycle
    return runner, runner.instance


def _timed(call, cycles: int) -> float:
    """CPU seconds of this thread for `cycles` calls, the garbage collector off."""
    gc.collect()
    gc.disable()
    try:
        t0 = time.thread_time()
        for _ in range(cycles):
            call()
        return time.thread_time() - t0
    finally:
        gc.enable()


def measure(path: Path, entry: str, cycles: int, rounds: int, timer) -> dict:
    checked = compile_files([str(path)])
    plain = _unchecked(checked)
    sides = {"checked": _instance(checked, entry, timer), "unchecked": _instance(plain, entry, timer)}
    for _runner, inst in sides.values():  # warm up
        _timed(inst, cycles)
    times: dict = {"checked": [], "unchecked": []}
    order = list(sides)
    for r in range(rounds):
        for key in order if r % 2 == 0 else order[::-1]:
            times[key].append(_timed(sides[key][1], cycles))
    return {
        "us": {key: min(t) / cycles * 1e6 for key, t in times.items()},
        "ratio": statistics.median(c / u for c, u in zip(times["checked"], times["unchecked"])),
        "ratios": sorted(c / u for c, u in zip(times["checked"], times["unchecked"])),
        "same": _state(sides["checked"][0]) == _state(sides["unchecked"][0]),
        "cycles": (1 + rounds) * cycles,
    }


def _state(runner) -> dict:
    """Every variable of the program instance."""
    inst = runner.instance
    return {slot: repr(getattr(inst, slot)) for slot in type(inst).__slots__}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="a smoke run: 5 rounds")
    ap.add_argument("--rounds", type=int, default=None, help="timing rounds per program (default 40, quick 5)")
    args = ap.parse_args()
    rounds = args.rounds or (5 if args.quick else 40)
    print(f"the watchdog's loop checks  (Python {sys.version.split()[0]}, {rounds} rounds per figure)\n")
    clocks = [("real clock (perf_counter)", time.perf_counter), ("virtual time (thread CPU time)", time.thread_time)]
    for label, timer in clocks:
        print(f"watchdog clock: {label}")
        print(f"   {'program':<22} {'checked':>11} {'unchecked':>11} {'ratio':>7} {'(q10..q90)':>13}  check")
        for file, entry, cycles in PROGRAMS:
            m = measure(HERE / file, entry, cycles, rounds, timer)
            q = m["ratios"]
            lo, hi = q[len(q) // 10], q[min(len(q) - 1, len(q) * 9 // 10)]
            print(
                f"   {file[:-3] + '/' + entry:<22} {m['us']['checked']:>8.1f} us {m['us']['unchecked']:>8.1f} us "
                f"{m['ratio']:>6.3f}x {lo:>6.3f}..{hi:<6.3f} "
                f"{'same state' if m['same'] else 'DIFFERENT STATE'} after {m['cycles']} cycles"
            )
        print()
    print(
        "us per cycle (thread CPU time): the fastest chunk of each side; ratio: the median over\n"
        "the rounds of checked / unchecked timed back to back, with the 10th and 90th percentiles\n"
        "of those ratios"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
