"""Parse speed of a generated, realistic ~10,000-line ST file.

    /tmp/venv/bin/python tests/st/parse_bench.py [lines]

Prints the time; not a test (timings are for people, not for CI).
"""

from __future__ import annotations

import sys
import time

from softplc.runtime.st.diagnostics import DiagnosticBag
from softplc.runtime.st.syntax.parser import parse_source

FB = """(* Motor control block {n}: start/stop with interlocks, ramp and fault handling *)
FUNCTION_BLOCK Motor{n}
VAR_INPUT
    Start, Stop : BOOL;          // commands
    Setpoint : REAL := 50.0;     (* % of nominal speed *)
    Mode : INT;
END_VAR
VAR_OUTPUT
    Running : BOOL;
    Speed : REAL;
    Fault : WORD := 16#0000;
END_VAR
VAR
    state : INT := 0;
    timer : TON;
    edge : R_TRIG;
    history : ARRAY[0..9] OF REAL := [10(0.0)];
    i : INT;
    msg : STRING[80] := 'idle';
END_VAR
edge(CLK := Start);
IF edge.Q AND NOT Stop THEN
    state := 1;
    msg := 'starting';
ELSIF Stop OR Fault <> 0 THEN
    state := 0;
END_IF;
CASE state OF
    0:
        Running := FALSE;
        Speed := 0.0;
    1:
        timer(IN := TRUE, PT := T#2s500ms);
        IF timer.Q THEN
            state := 2;
            timer(IN := FALSE);
        END_IF;
    2, 3:
        Running := TRUE;
        Speed := Speed + (Setpoint - Speed) * 0.1;
        IF ABS(Speed - Setpoint) < 0.5 THEN
            Speed := Setpoint;
        END_IF;
ELSE
    Fault := Fault OR 16#0001;
END_CASE;
FOR i := 9 TO 1 BY -1 DO
    history[i] := history[i - 1];
END_FOR;
history[0] := Speed;
WHILE i < 5 AND Mode > 0 DO
    i := i + 1;
END_WHILE;
Fault.3 := Speed > 100.0 * 1.1;
END_FUNCTION_BLOCK

"""


def generate(lines: int) -> str:
    parts, n, total = [], 0, 0
    per = FB.count("\n")
    while total < lines:
        parts.append(FB.format(n=n))
        n += 1
        total += per
    return "".join(parts)


def main() -> None:
    lines = int(sys.argv[1]) if len(sys.argv) > 1 else 10_000
    text = generate(lines)
    for run in ("first", "best of 5"):
        wall = cpu = float("inf")
        for _ in range(1 if run == "first" else 5):
            diags = DiagnosticBag()
            w0, c0 = time.perf_counter(), time.process_time()
            sf = parse_source(text, "bench.st", diags)
            wall = min(wall, time.perf_counter() - w0)
            cpu = min(cpu, time.process_time() - c0)
            assert not diags.items, [d.format() for d in diags.items[:3]]
        print(
            f"{run:9s}: parsed {text.count(chr(10))} lines ({len(text)} chars, {len(sf.decls)} POUs) "
            f"in {wall * 1000:.0f} ms wall, {cpu * 1000:.0f} ms CPU"
        )


if __name__ == "__main__":
    main()
