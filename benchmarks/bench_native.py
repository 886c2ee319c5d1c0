#!/usr/bin/env python3
"""Where generated Python stands against C (see benchmarks/README.md).

    python benchmarks/bench_native.py            # about 15 s
    python benchmarks/bench_native.py --quick    # smoke run
    python benchmarks/bench_native.py --check 5  # final states only, no timing

The four scan workloads of bench_language.py part 1 (numeric loops, bit/word
manipulation, 100 timer and counter instances, 100 method calls through an
interface) written in C with the same IEC semantics (benchmarks/native/scan.c),
compiled with the system's cc -O2 into a temporary directory. Per workload it
prints us/cycle of C, of the generated Python and of the hand-written Python
(language_hand.py), timed in the same rounds, the ratios Python / C, the host's
timeit factor and the figures scaled to the reference host. No target: a
figure on record for a native back end later.

C and the generated Python must end in the same state: a C program of its own
runs as many cycles as the generated code did, and every variable is compared
(REALs bit for bit); a difference is printed and the exit status is 1. Without
a cc on PATH the script says so and exits 0.
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from bench_language import Bench, timed  # benchmarks/, beside this script
from host import timeit_factor
from language_hand import BitsHand, NumericHand, OopHand, TimersHand

from softplc.runtime.program.variables import locate

HERE = Path(__file__).resolve().parent
C_SOURCE = HERE / "native" / "scan.c"
# -ffp-contract=off: IEC rounds a * b + c twice, and gcc fuses it into one
# FMA rounding by default where the CPU has one (aarch64; x86-64 with -march)
C_FLAGS = ("-O2", "-ffp-contract=off")


class Workload:
    """One ST program, its hand-written twin and its C version, with the
    cycles of one timed chunk on each side (about 3-10 ms each)."""

    def __init__(self, name, st, entry, hand_cls, clocked, py_cycles, c_cycles):
        self.name, self.st, self.entry = name, st, entry
        self.hand_cls, self.clocked = hand_cls, clocked
        self.py_cycles, self.c_cycles = py_cycles, c_cycles

    def bench(self) -> Bench:
        return Bench(self.name, HERE / self.st, self.entry, self.hand_cls, clocked=self.clocked)


WORKLOADS = [
    Workload("numeric", "numeric.st", "NumericMain", NumericHand, False, 4, 1000),
    Workload("bits", "bits.st", "BitsMain", BitsHand, False, 16, 4000),
    Workload("timers", "timers.st", "TimersMain", TimersHand, True, 200, 10000),
    Workload("methods", "oop.st", "OopMain", OopHand, False, 50, 10000),
]


# =====================================================================
# The C side
# =====================================================================


def compile_c(cc: str, source: Path, out_dir: Path) -> Path:
    exe = out_dir / "scan"
    done = subprocess.run([cc, *C_FLAGS, "-o", str(exe), str(source)], capture_output=True, text=True)
    if done.returncode != 0:
        raise SystemExit(f"ERROR: {cc} {' '.join(C_FLAGS)} failed on {source}:\n{done.stderr}")
    return exe


class Native:
    """The compiled C program for one workload, driven over a pipe: it
    times its own cycles (the pipe is outside the timed part)."""

    def __init__(self, exe: Path, workload: str):
        self.proc = subprocess.Popen(
            [str(exe), workload], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, bufsize=1
        )
        self.cycles = 0

    def _ask(self, line: str) -> str:
        assert self.proc.stdin is not None and self.proc.stdout is not None
        self.proc.stdin.write(line + "\n")
        self.proc.stdin.flush()
        answer = self.proc.stdout.readline()
        if not answer:
            raise SystemExit(f"ERROR: the C program stopped (exit {self.proc.wait()}) on {line!r}")
        return answer

    def run(self, cycles: int) -> float:
        """Seconds the C program took for `cycles` cycles."""
        kind, ns = self._ask(f"run {cycles}").split()
        assert kind == "ns"
        self.cycles += cycles
        return int(ns) / 1e9

    def state(self) -> dict:
        """The program's variables; a REAL comes as C's exact hex ("%a")."""
        return {key: _real(value) for key, value in json.loads(self._ask("state")).items()}

    def close(self) -> None:
        if self.proc.stdin:
            self.proc.stdin.close()
        self.proc.wait()


def _real(value):
    if isinstance(value, str):
        return float.fromhex(value)
    if isinstance(value, list):
        return [_real(v) for v in value]
    return value


# =====================================================================
# Comparing final states
# =====================================================================


def generated_value(runner, key: str):
    """The generated program's value of a variable C printed: an ST path
    (`t1.ET`), or `array.member` for a member of every FB of an array
    (`adds.sum`: the sums of adds[1..50], in order)."""
    try:
        return runner.get(key)
    except KeyError:
        name, _, member = key.partition(".")
        return [getattr(*locate(member, (fb,))[:2]) for fb in runner.get(name)]


def differences(c_state: dict, runner) -> list:
    """(key, C's value, generated value) of every variable that differs;
    values compare exactly (a REAL is the same binary32 or differs)."""
    out = []
    for key, want in c_state.items():
        got = generated_value(runner, key)
        if got != want or isinstance(got, bool) is not isinstance(want, bool):
            out.append((key, want, got))
    return out


def first_difference(key: str, want, got) -> str:
    """`key: C ... generated ...`, for an array at its first differing element."""
    if isinstance(want, list) and isinstance(got, list) and len(want) == len(got):
        where = [i for i, (a, b) in enumerate(zip(want, got)) if a != b or type(a) is not type(b)]
        more = f" (and {len(where) - 1} more elements)" if len(where) > 1 else ""
        key, want, got = f"{key}[element {where[0]}]", want[where[0]], got[where[0]]
        return f"{key}: C {want!r}  generated {got!r}{more}"
    return f"{key}: C {str(want)[:100]}  generated {str(got)[:100]}"


def count_values(state: dict) -> int:
    return sum(len(v) if isinstance(v, list) else 1 for v in state.values())


def check_state(exe: Path, w: Workload, b: Bench) -> tuple:
    """A C program of its own runs as many cycles as b's generated code
    has run, from the start; (differences, values compared)."""
    native = Native(exe, w.name)
    try:
        native.run(b.runner.cycles)
        c_state = native.state()
    finally:
        native.close()
    return differences(c_state, b.runner), count_values(c_state)


def report_check(w: Workload, cycles: int, diff: list, n_values: int, hand_diff: list) -> bool:
    if not diff:
        print(f"   {w.name:<8} C and generated Python: same state after {cycles} cycles ({n_values:,} values)")
    else:
        print(f"!!! {w.name}: C AND GENERATED PYTHON DIFFER after {cycles} cycles in {len(diff)} variables:")
        for key, want, got in diff[:8]:
            print(f"!!!   {first_difference(key, want, got)}")
    if hand_diff:
        print(f"!!! {w.name}: hand-written Python differs from the generated in {', '.join(hand_diff[:5])}")
    return not diff and not hand_diff


# =====================================================================
# Timing
# =====================================================================


def bench_workload(exe: Path, w: Workload, rounds: int) -> dict:
    """`rounds` rounds; in each, a chunk of C, of generated Python and of
    hand-written Python back to back, the order rotating. Per side the
    fastest chunk (us/cycle); per ratio the median over the rounds of the
    ratio within a round, and its 10th..90th percentile."""
    b = w.bench()
    native = Native(exe, w.name)
    try:
        sides = {
            "c": lambda: native.run(w.c_cycles) / w.c_cycles,
            "gen": lambda: timed(b.run_generated, w.py_cycles) / w.py_cycles,
            "hand": lambda: timed(b.run_hand, w.py_cycles) / w.py_cycles,
        }
        for fn in sides.values():  # warm up, and leave the all-zero start
            fn()
        per_cycle: dict = {key: [] for key in sides}
        order = list(sides)
        for r in range(rounds):
            for key in order[r % 3 :] + order[: r % 3]:
                per_cycle[key].append(sides[key]())
    finally:
        native.close()
    row = {"workload": w, "bench": b, **{f"{k}_us": min(v) * 1e6 for k, v in per_cycle.items()}}
    for side in ("gen", "hand"):
        ratios = sorted(p / c for p, c in zip(per_cycle[side], per_cycle["c"]))
        row[f"{side}_ratio"] = statistics.median(ratios)
        row[f"{side}_spread"] = (ratios[len(ratios) // 10], ratios[-1 - len(ratios) // 10])
        row[f"{side}_of_mins"] = row[f"{side}_us"] / row["c_us"]
    row["gen_hand"] = statistics.median(g / h for g, h in zip(per_cycle["gen"], per_cycle["hand"]))
    return row


# =====================================================================
# Main
# =====================================================================


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="a smoke run: 3 rounds")
    ap.add_argument("--rounds", type=int, default=None, help="timing rounds per workload (default 40, quick 3)")
    ap.add_argument("--check", type=int, metavar="N", help="no timing: compare the final states after N cycles")
    ap.add_argument("--cc", default="cc", help="the C compiler (default: cc)")
    ap.add_argument("--source", type=Path, default=C_SOURCE, help="the C file (default: native/scan.c)")
    args = ap.parse_args()
    rounds = args.rounds or (3 if args.quick else 40)

    cc = shutil.which(args.cc)
    if cc is None:
        print(f"bench_native: skipped: no C compiler {args.cc!r} on PATH (the C reference needs one)")
        return 0
    version = subprocess.run([cc, "--version"], capture_output=True, text=True).stdout.split("\n")[0]

    with tempfile.TemporaryDirectory(prefix="softplc-native-") as tmp:
        exe = compile_c(cc, args.source, Path(tmp))
        shown = args.source.resolve()
        shown = shown.relative_to(HERE.parent) if shown.is_relative_to(HERE.parent) else shown
        print(f"C: {version}, {args.cc} {' '.join(C_FLAGS)} {shown}")

        if args.check is not None:
            ok = True
            for w in WORKLOADS:
                b = w.bench()
                b.run_generated(args.check)
                b.run_hand(args.check)
                diff, n_values = check_state(exe, w, b)
                ok &= report_check(w, args.check, diff, n_values, b.compare())
            return 0 if ok else 1

        host = timeit_factor()
        print(host.line())
        print(f"Python {sys.version.split()[0]}, {rounds} timing rounds\n")
        rows = [bench_workload(exe, w, rounds) for w in WORKLOADS]
        print_figures(rows, host)
        print("3. Final states")
        ok = True
        for r in rows:
            b = r["bench"]
            diff, n_values = check_state(exe, r["workload"], b)
            ok &= report_check(r["workload"], b.runner.cycles, diff, n_values, b.compare())
        print(f"\n{timeit_factor().line()}  (again, at the end)")
        return 0 if ok else 1


def print_figures(rows: list, host) -> None:
    print("1. us per cycle (the fastest chunk of each side); Python / C: the ratio of the fastest chunks,")
    print("   and the median over the rounds of the ratio within a round with its 10th..90th percentile")
    print(
        f"   {'workload':<9} {'C':>7} {'generated':>10} {'hand':>8}   {'generated / C':<32}"
        f" {'hand / C':<32} {'gen / hand':>10}"
    )
    for r in rows:
        cells = []
        for side in ("gen", "hand"):
            lo, hi = r[f"{side}_spread"]
            cells.append(f"{r[f'{side}_of_mins']:>5.0f}x, median {r[f'{side}_ratio']:>4.0f}x ({lo:.0f}..{hi:.0f})")
        print(
            f"   {r['workload'].name:<9} {r['c_us']:>7.3f} {r['gen_us']:>10.1f} {r['hand_us']:>8.1f}   "
            f"{cells[0]:<32} {cells[1]:<32} {r['gen_hand']:>9.2f}x"
        )
    ws = [r["workload"] for r in rows]
    print(
        f"   (chunks: C {', '.join(str(w.c_cycles) for w in ws)} cycles, Python "
        f"{', '.join(str(w.py_cycles) for w in ws)}; a round runs a chunk of each side, the order rotating;\n"
        "    gen / hand: the median of the rounds' ratios, as bench_language.py has it)\n"
    )
    print(f"2. Scaled to the reference host (÷ timeit factor {host.factor:.2f}), us per cycle")
    print(f"   {'workload':<9} {'C':>7} {'generated':>10} {'hand':>8}")
    for r in rows:
        c, g, h = (host.scaled(r[k]) for k in ("c_us", "gen_us", "hand_us"))
        print(f"   {r['workload'].name:<9} {c:>7.3f} {g:>10.1f} {h:>8.1f}")
    print(
        "   (the factor measures this host's interpreter; C scaled by it assumes that the host's\n"
        "    native speed differs from the reference host's by as much)\n"
    )


if __name__ == "__main__":
    sys.exit(main())
