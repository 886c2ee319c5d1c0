#!/usr/bin/env python3
"""Benchmarks of the Structured Text compiler (see benchmarks/README.md).

    python benchmarks/bench_language.py           # full run, about 40 s
    python benchmarks/bench_language.py --quick   # smoke run, about 4 s
    python benchmarks/bench_language.py --part 1  # only the generated code vs hand-written
    python benchmarks/bench_language.py --part 1 --processes 5   # part 1 in five processes

Part 1 runs four ST programs (numeric loops, bit/word manipulation, 100 FB
instances, 100 method calls through an interface) and a hand-written Python implementation of the same logic, checks
that both end in the same state and prints us/cycle and the ratio
generated / hand-written (issue 32's target: within 1.10x; a ratio
of two times taken on the same host, so the host's timeit factor, printed
first, does not scale it). The ratio moves from one process to the next by
more than within one (the same code ran 28.9 and 31.0 us a cycle in two
processes, the hand-written twin 27.5 in both): part 1 runs in --processes
fresh processes (3, quick 1), and the verdict is the median of their ratios,
printed with their range.

Part 2 generates a 10,000-line ST file and times the front end phase by phase
and compile_files() end to end (target: 10,000 lines/s, i.e. under 1 s).

Nothing here is asserted: the script prints figures measured in this run.
"""

from __future__ import annotations

import argparse
import gc
import json
import random
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from host import timeit_factor  # benchmarks/, beside this script
from language_hand import BitsHand, NumericHand, OopHand, TimersHand, s32

from softplc.runtime.program import compile as loader
from softplc.runtime.program import compile_files
from softplc.runtime.st.check.checker import Checker
from softplc.runtime.st.codegen.codegen import CodeGen
from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.profile import get_profile
from softplc.runtime.st.syntax.parser import parse_source

HERE = Path(__file__).resolve().parent
RATIO_TARGET = 1.10
FRONT_END_TARGET_LINES_S = 10_000
FRONT_END_LINES = 10_000


# =====================================================================
# Running and timing
# =====================================================================

CYCLE_MS = 10


class Bench:
    """One program: the compiled ST (a runner) and the hand-written twin,
    each driven by an equally bare loop."""

    def __init__(self, name: str, st_path: Path, entry: str, hand_cls, clocked: bool):
        self.name = name
        self.prog = compile_files([str(st_path)])
        self.runner = self.prog.runner(entry, cycle_time_ms=CYCLE_MS)
        self.hand = hand_cls()
        self.clocked = clocked
        self.hand_now_ns = 0

    def run_generated(self, cycles: int) -> None:
        inst, ctx = self.runner.instance, self.runner.ctx
        step = self.runner.cycle_ns
        if self.clocked:
            for _ in range(cycles):
                inst()
                ctx.set_time(ctx.now_ns + step)
        else:
            for _ in range(cycles):
                inst()
            ctx.set_time(ctx.now_ns + step * cycles)
        self.runner.cycles += cycles

    def run_hand(self, cycles: int) -> None:
        hand = self.hand
        step = CYCLE_MS * 1_000_000
        if self.clocked:
            now_ns = self.hand_now_ns
            for _ in range(cycles):
                hand(s32(now_ns // 1_000_000))  # TIME(): ms, wraps like DINT
                now_ns += step
            self.hand_now_ns = now_ns
        else:
            for _ in range(cycles):
                hand()

    def compare(self) -> list:
        """Variables whose values differ between the two sides."""
        return [key for key, want in self.hand.state().items() if self.runner.get(key) != want]


def timed(fn, cycles: int) -> float:
    """Seconds for fn(cycles), with the garbage collector off."""
    gc.collect()
    gc.disable()
    try:
        t0 = time.perf_counter()
        fn(cycles)
        return time.perf_counter() - t0
    finally:
        gc.enable()


def bench_runtime(benches: list, cycles: dict, rounds: int) -> list:
    """Per program: `rounds` rounds, each timing a chunk of cycles of the
    generated code (bare loop) and of the hand-written code back to back
    (alternating which goes first), then of the generated code under
    Runner.run. Reported: the fastest chunk of each side, and the median over
    the rounds of generated / hand-written within a round: the two chunks ran
    back to back, so a slow spell of the machine mostly hits both, and this
    ratio is far steadier than one of single timings."""
    rows = []
    for b in benches:
        n = cycles[b.name]
        b.run_generated(n)  # warm up, and leave the all-zero start
        b.run_hand(n)
        times = {"gen": [], "hand": [], "runner": []}
        pair = [("gen", b.run_generated), ("hand", b.run_hand)]
        for r in range(rounds):
            for key, fn in pair if r % 2 == 0 else pair[::-1]:  # back to back, alternating
                times[key].append(timed(fn, n))
            times["runner"].append(timed(b.runner.run, n))
            b.run_hand(n)  # the generated side ran twice: keep both at the same cycle
        diff = b.compare()
        us = {key: min(t) / n * 1e6 for key, t in times.items()}
        rows.append(
            {
                "name": b.name,
                "cycles": n,
                "gen_us": us["gen"],
                "hand_us": us["hand"],
                "runner_us": us["runner"],
                "ratio": statistics.median(g / h for g, h in zip(times["gen"], times["hand"])),
                "min_ratio": us["gen"] / us["hand"],
                "same": not diff,
                "diff": diff,
                "total_cycles": b.runner.cycles,
            }
        )
    return rows


# =====================================================================
# Front end: a generated 10,000-line ST file
# =====================================================================


def generate_st(target_lines: int, seed: int = 61131) -> str:
    """A deterministic, realistic ST file: enums, structs, functions, function
    blocks with timers and state machines, and programs instantiating them."""
    rnd = random.Random(seed)
    out: list = []

    def emit(*lines: str) -> None:
        out.extend(lines)

    emit("(* Generated by benchmarks/bench_language.py for the front-end benchmark. *)", "")
    n = 0
    fb_names: list = []
    fn_names: list = []
    while len(out) < target_lines:
        n += 1
        # --- types -----------------------------------------------------
        emit(f"TYPE E_Mode{n} : (Off{n}, Manual{n}, Auto{n}, Fault{n}); END_TYPE", "")
        emit(
            f"TYPE ST_Axis{n} :",
            "STRUCT",
            "    enabled : BOOL;",
            "    position : REAL;         (* mm *)",
            "    velocity : REAL := 10.0; (* mm/s *)",
            "    errors : UINT;",
            "    status : WORD;",
            "    history : ARRAY[0..7] OF INT;",
            "END_STRUCT",
            "END_TYPE",
            "",
        )

        # --- a scaling function ---------------------------------------
        fn = f"F_Scale{n}"
        fn_names.append(fn)
        emit(
            f"FUNCTION {fn} : REAL",
            "(* Linear scaling of a raw analog value with clamping. *)",
            "VAR_INPUT",
            "    raw : INT;",
            f"    lo : REAL := {rnd.randint(-50, 0)}.0;",
            f"    hi : REAL := {rnd.randint(100, 500)}.0;",
            "END_VAR",
            "VAR",
            "    t : REAL;",
            "END_VAR",
            "t := INT_TO_REAL(raw) / 27648.0;",
            "IF t < 0.0 THEN",
            "    t := 0.0;",
            "ELSIF t > 1.0 THEN",
            "    t := 1.0;",
            "END_IF",
            f"{fn} := lo + t * (hi - lo);",
            "END_FUNCTION",
            "",
        )

        # --- an integer function with a loop ---------------------------
        fn2 = f"F_Checksum{n}"
        fn_names.append(fn2)
        emit(
            f"FUNCTION {fn2} : DINT",
            "VAR_INPUT",
            "    seed : DINT;",
            "    count : INT;",
            "END_VAR",
            "VAR",
            "    i : INT;",
            "    acc : DINT;",
            "END_VAR",
            "acc := seed;",
            "FOR i := 1 TO count DO",
            f"    acc := acc * {rnd.choice([31, 33, 37])} + i MOD {rnd.randint(3, 9)};",
            "    IF acc < 0 THEN",
            "        acc := -acc;",
            "    END_IF",
            "END_FOR",
            f"{fn2} := acc;",
            "END_FUNCTION",
            "",
        )

        # --- a function block: axis state machine ----------------------
        fb = f"FB_Axis{n}"
        fb_names.append(fb)
        emit(
            f"FUNCTION_BLOCK {fb}",
            "(* One axis: mode state machine, ramp, timers and bit status. *)",
            "VAR_INPUT",
            "    start : BOOL;",
            "    stop : BOOL;",
            "    rawSetpoint : INT;",
            f"    mode : E_Mode{n};",
            "END_VAR",
            "VAR_OUTPUT",
            "    busy : BOOL;",
            "    done : BOOL;",
            "    actual : REAL;",
            "    statusWord : WORD;",
            "END_VAR",
            "VAR",
            f"    axis : ST_Axis{n};",
            "    startDelay : TON;",
            "    faultTimer : TON;",
            "    edge : R_TRIG;",
            "    moves : CTU;",
            "    target : REAL;",
            "    step : INT;",
            "    k : INT;",
            "    bits : BYTE;",
            f"    state : E_Mode{n};",
            "END_VAR",
            "",
            "edge(CLK := start);",
            f"startDelay(IN := start AND NOT stop, PT := T#{rnd.choice([100, 200, 500])}ms);",
            f"faultTimer(IN := busy AND NOT done, PT := T#{rnd.randint(2, 9)}s);",
            "moves(CU := edge.Q, R := stop, PV := 100);",
            f"target := {fn}(raw := rawSetpoint, lo := 0.0, hi := {rnd.randint(200, 900)}.0);",
            "",
            "IF faultTimer.Q THEN",
            f"    state := Fault{n};",
            "ELSE",
            "    state := mode;",
            "END_IF",
            "CASE state OF",
            f"    Off{n}:",
            "        busy := FALSE;",
            "        axis.enabled := FALSE;",
            f"    Manual{n}:",
            "        axis.enabled := TRUE;",
            "        IF start THEN",
            "            actual := actual + axis.velocity * 0.01;",
            "        END_IF",
            f"    Auto{n}:",
            "        axis.enabled := TRUE;",
            "        IF startDelay.Q AND NOT done THEN",
            "            busy := TRUE;",
            "            IF ABS(target - actual) < 0.5 THEN",
            "                actual := target;",
            "                done := TRUE;",
            "                busy := FALSE;",
            "            ELSIF target > actual THEN",
            "                actual := actual + MIN(axis.velocity * 0.01, target - actual);",
            "            ELSE",
            "                actual := actual - MIN(axis.velocity * 0.01, actual - target);",
            "            END_IF",
            "        END_IF",
            f"    Fault{n}:",
            "        busy := FALSE;",
            "        axis.errors := axis.errors + 1;",
            "ELSE",
            "    step := 0;",
            "END_CASE",
            "",
            "IF stop THEN",
            "    done := FALSE;",
            "    step := 0;",
            "END_IF",
            "",
            "(* keep a short history of the position *)",
            "FOR k := 7 TO 1 BY -1 DO",
            "    axis.history[k] := axis.history[k - 1];",
            "END_FOR",
            "axis.history[0] := REAL_TO_INT(actual);",
            "axis.position := actual;",
            "",
            "bits := 0;",
            "bits.0 := busy;",
            "bits.1 := done;",
            "bits.2 := axis.enabled;",
            "bits.7 := faultTimer.Q;",
            "statusWord := SHL(BYTE_TO_WORD(bits), 8) OR INT_TO_WORD(moves.CV);",
            "axis.status := statusWord;",
            "END_FUNCTION_BLOCK",
            "",
        )

        # --- a function block: filter with WHILE / REPEAT --------------
        fb2 = f"FB_Filter{n}"
        emit(
            f"FUNCTION_BLOCK {fb2}",
            "VAR_INPUT",
            "    x : REAL;",
            f"    alpha : REAL := 0.{rnd.randint(1, 9)};",
            "END_VAR",
            "VAR_OUTPUT",
            "    y : REAL;",
            "    peak : REAL;",
            "END_VAR",
            "VAR",
            "    buf : ARRAY[1..16] OF REAL;",
            "    idx : INT := 1;",
            "    n : INT;",
            "    sum : REAL;",
            "END_VAR",
            "y := y + alpha * (x - y);",
            "buf[idx] := y;",
            "idx := idx MOD 16 + 1;",
            "sum := 0.0;",
            "n := 1;",
            "WHILE n <= 16 DO",
            "    sum := sum + buf[n];",
            "    n := n + 1;",
            "END_WHILE",
            "peak := 0.0;",
            "n := 0;",
            "REPEAT",
            "    n := n + 1;",
            "    IF buf[n] > peak THEN",
            "        peak := buf[n];",
            "    END_IF",
            "UNTIL n >= 16",
            "END_REPEAT",
            "END_FUNCTION_BLOCK",
            "",
        )

        # --- a program every few rounds, using the recent blocks -------
        if n % 3 == 0:
            m = n // 3
            axes = fb_names[-3:]
            emit(
                f"PROGRAM P_Cell{m}",
                "VAR",
                *[f"    axis{j} : {fb};" for j, fb in enumerate(axes)],
                f"    filter : FB_Filter{n};",
                "    cycleCount : UDINT;",
                "    raw : INT;",
                "    check : DINT;",
                "    run : BOOL;",
                f"    alarms : ARRAY[0..{rnd.randint(7, 31)}] OF BOOL;",
                "    text : STRING[40] := 'cell';",
                "    i : INT;",
                "END_VAR",
                "cycleCount := cycleCount + 1;",
                "raw := UDINT_TO_INT(cycleCount MOD 27648);",
                "run := (cycleCount / 100) MOD 2 = 0;",
            )
            for j, fb in enumerate(axes):
                mode_n = fb[len("FB_Axis") :]
                emit(f"axis{j}(start := run, stop := NOT run, rawSetpoint := raw + {j * 100}, mode := Auto{mode_n});")
            emit(
                "filter(x := axis0.actual);",
                f"check := {fn_names[-1]}(seed := UDINT_TO_DINT(cycleCount), count := {rnd.randint(3, 12)});",
                "FOR i := 0 TO 7 DO",
                "    alarms[i] := axis0.statusWord.0 AND (check MOD (i + 2) = 0);",
                "END_FOR",
                "IF filter.peak > 100.0 THEN",
                "    text := CONCAT('cell ', 'peak');",
                "ELSE",
                "    text := 'cell';",
                "END_IF",
                "END_PROGRAM",
                "",
            )
    return "\n".join(out) + "\n"


def bench_front_end(repeats: int) -> dict:
    text = generate_st(FRONT_END_LINES)
    lines = text.count("\n")
    profile = get_profile("codesys")
    # the library files compile_files() takes for this text (not every device's)
    words = {w.upper() for w in loader._WORD.findall(text)}
    library_texts = loader._needed_library(loader._always_sources(), loader._on_demand_sources(), words)
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "generated_10k.st"
        path.write_text(text, encoding="utf-8")
        best: dict = {}
        for _ in range(repeats):
            gc.collect()
            t0 = time.perf_counter()
            diags = DiagnosticBag()
            user = parse_source(path.read_text(encoding="utf-8"), str(path), diags)
            t1 = time.perf_counter()
            library = [parse_source(lt, ln, DiagnosticBag()) for ln, lt in library_texts]
            t2 = time.perf_counter()
            checked = Checker(profile, diags, loader._std_functions(), loader._natives()).run(
                library + [user], library_files=tuple(sf.path for sf in library)
            )
            t3 = time.perf_counter()
            gen = CodeGen(checked, profile).generate()
            t4 = time.perf_counter()
            compile(gen.source, "<bench>", "exec")
            t5 = time.perf_counter()
            errors = [d for d in diags.items if d.is_error]
            if errors:
                raise SystemExit(f"the generated ST file does not compile: {errors[:3]}")
            t = {
                "parse": t1 - t0,
                "parse library": t2 - t1,
                "check": t3 - t2,
                "codegen": t4 - t3,
                "python compile": t5 - t4,
                "total": t5 - t0,
            }
            if not best or t["total"] < best["total"]:
                best = t
        # the public API end to end, best of repeats (parts 1 and the phases
        # above have loaded the registry and analysed the grammar)
        for _ in range(repeats):
            gc.collect()
            t0 = time.perf_counter()
            compile_files([str(path)])
            t = time.perf_counter() - t0
            best["compile_files()"] = min(t, best.get("compile_files()", t))
    best["lines"] = lines
    best["python lines"] = gen.source.count("\n")
    best["pous"] = sum(1 for line in text.splitlines() if line.startswith(("FUNCTION ", "FUNCTION_BLOCK ", "PROGRAM ")))
    return best


# =====================================================================
# Main
# =====================================================================


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--quick", action="store_true", help="a smoke run: three rounds, one front-end pass")
    ap.add_argument(
        "--rounds",
        type=int,
        default=None,
        help="timing rounds per program, the minimum is reported (default 40, quick 3)",
    )
    ap.add_argument("--part", type=int, choices=(1, 2), default=None, help="run only part 1 or part 2")
    ap.add_argument("--processes", type=int, default=None, help="fresh processes for part 1 (default 3, quick 1)")
    ap.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args()
    rounds = args.rounds or (3 if args.quick else 40)
    # cycles per timed chunk, about 10 ms each: short chunks are less often
    # interrupted by other processes, so the minimum is a clean run
    cycles = {"a numeric": 4, "b bits": 16, "c timers": 200, "d methods": 50}
    if args.child:  # one process of part 1: its table, then its rows as JSON
        print(json.dumps(run_part1(cycles, rounds)))
        return 0
    processes = args.processes or (1 if args.quick else 3)

    print(
        f"softplc ST benchmarks  (Python {sys.version.split()[0]}, "
        f"{'quick' if args.quick else 'full'} run, {rounds} timing rounds)"
    )
    print(timeit_factor().line() + "\n")
    rows: list = []
    if args.part in (None, 1):
        rows = run_part1(cycles, rounds) if processes == 1 else run_part1_apart(rounds, processes)
    fe = run_part2(args.quick) if args.part in (None, 2) else None
    print_summary(rows, fe)
    return 0


def run_part1(cycles: dict, rounds: int) -> list:
    benches = [
        Bench("a numeric", HERE / "numeric.st", "NumericMain", NumericHand, clocked=False),
        Bench("b bits", HERE / "bits.st", "BitsMain", BitsHand, clocked=False),
        Bench("c timers", HERE / "timers.st", "TimersMain", TimersHand, clocked=True),
        Bench("d methods", HERE / "oop.st", "OopMain", OopHand, clocked=False),
    ]
    print("1. Generated code vs hand-written Python: the same logic for the same cycles")
    print(f"   {'program':<10} {'generated':>12} {'hand':>12} {'ratio':>7} {'(of mins)':>9} {'Runner.run':>12}  check")
    rows = bench_runtime(benches, cycles, rounds)
    for r in rows:
        check = "same state" if r["same"] else f"DIFFERENT: {', '.join(r['diff'][:5])}"
        print(
            f"   {r['name']:<10} {r['gen_us']:>9.1f} us {r['hand_us']:>9.1f} us {r['ratio']:>6.2f}x "
            f"{r['min_ratio']:>8.2f}x {r['runner_us']:>9.1f} us  {check} after {r['total_cycles']} cycles"
        )
    print(
        f"   (us per cycle: the fastest of {rounds} chunks of "
        f"{', '.join(f'{n} {k[2:]}' for k, n in cycles.items())} cycles;\n"
        "    ratio: the median over the rounds of generated / hand-written timed back to back;\n"
        "    (of mins): the ratio of the two fastest chunks; Runner.run: the generated program\n"
        "    under the real Runner, which also arms the watchdog every cycle)\n"
    )
    return rows


def run_part1_apart(rounds: int, processes: int) -> list:
    """Part 1 in fresh processes, one after the other: each prints its
    table; the rows returned carry the median of their ratios (the
    verdict), and the range of those ratios is printed."""
    runs = []
    for n in range(1, processes + 1):
        print(f"-- process {n} of {processes}")
        done = subprocess.run(
            [sys.executable, __file__, "--child", "--rounds", str(rounds)], capture_output=True, text=True
        )
        if done.returncode != 0:
            raise SystemExit(f"part 1 in process {n} failed:\n{done.stderr}")
        table, _, last = done.stdout.rstrip().rpartition("\n")
        print(table)
        runs.append(json.loads(last))
    rows = []
    print(f"   over the {processes} processes: the median ratio (the verdict), and their range")
    for same_program in zip(*runs, strict=True):
        ratios = [r["ratio"] for r in same_program]
        row = dict(same_program[0])
        row["ratio"] = statistics.median(ratios)
        row["same"] = all(r["same"] for r in same_program)
        rows.append(row)
        print(f"   {row['name']:<10} {row['ratio']:>6.2f}x  ({min(ratios):.2f}x .. {max(ratios):.2f}x)")
    print()
    return rows


def run_part2(quick: bool) -> dict:
    print(f"2. Front end on a generated {FRONT_END_LINES:,}-line ST file")
    fe = bench_front_end(1 if quick else 3)
    print(f"   {fe['lines']:,} ST lines, {fe['pous']} POUs -> {fe['python lines']:,} Python lines")
    phases = ("parse", "parse library", "check", "codegen", "python compile", "total")
    for phase in (*phases, "compile_files()"):
        print(f"   {phase:<21} {fe[phase]:7.3f} s  {fe['lines'] / fe[phase]:>10,.0f} lines/s")
    print()
    return fe


def print_summary(rows: list, fe: dict | None) -> None:
    print("Summary")
    print(f"   {'measure':<36} {'value':>10}  {'target':>10}  result")
    for r in rows:
        ok = r["ratio"] <= RATIO_TARGET and r["same"]
        print(
            f"   {r['name'] + ': generated / hand-written':<36} {r['ratio']:>9.2f}x  "
            f"{f'<= {RATIO_TARGET:.2f}x':>10}  {'met' if ok else 'MISSED'}"
            f"{'' if r['same'] else ' (results differ)'}"
        )
    if fe is None:
        return
    speed = fe["lines"] / fe["compile_files()"]
    ok = speed >= FRONT_END_TARGET_LINES_S
    target = f">= {FRONT_END_TARGET_LINES_S:,}"
    print(f"   {'compile_files(), 10k lines (lines/s)':<36} {speed:>10,.0f}  {target:>10}  {'met' if ok else 'MISSED'}")


if __name__ == "__main__":
    sys.exit(main())
