"""Reproducers of what OSCAT BASIC's port to Beremiz needs of the matiec
profile (oscat_port/: our own ST written in the port's style, one file per
construct that failed before): they compile and run under matiec with the
values the code means, and name their codes under iec, which has none of
these rules. The port itself is tested in test_oscat.py when its folder is
given."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from softplc.runtime.program import check_files, compile_files

HERE = Path(__file__).parent / "oscat_port"

MAIN = """
PROGRAM Main
VAR
    ramp : RAMP_W;
    steps : INT;
    data : ARRAY[1..10] OF REAL := [2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0];
    sdv : ARRAY_SDV;
    picked : INT;
    utc : UDINT;
    clock : LOCAL_CLOCK;
END_VAR
steps := steps + 1;
ramp(UP := steps <= 5, RATE := 0.25);
sdv(PT := data, SIZE := 8);
picked := PICK(0.5, 10, 20);
utc := LTIME_TO_UTC(LTIME := UDINT#7200, TIME_ZONE_OFFSET := 60);
clock(UDT := UDINT#1000, OFS := 60, DSO := TRUE);
END_PROGRAM
"""


def _files(*names: str) -> list[str]:
    return [str(HERE / n) for n in names]


def test_the_port_style_blocks_run_under_matiec():
    prog = compile_files(_files("ramp.st", "array_stats.st", "time_zone.st"), texts={"main.st": MAIN}, profile="matiec")
    r = prog.runner("Main", cycle_time_ms=10)
    r.run(1)
    # ramp: a quarter of full scale a cycle, read back through rmp.RMP
    assert (r.get("ramp.OUT"), r.get("ramp.LOW")) == (16383, False)
    r.run(4)
    assert (r.get("ramp.OUT"), r.get("ramp.HIGH")) == (65535, True)  # the fifth step up clamped
    r.run(5)  # down from cycle 6 on: 65535 - 5 * 16383 < 0, clamped
    assert (r.get("ramp.OUT"), r.get("ramp.LOW")) == (0, True)
    # the sample standard deviation of 2, 4, 4, 4, 5, 5, 7, 9 (SIZE 8 of 10)
    assert math.isclose(r.get("sdv._ARRAY_SDV"), math.sqrt(32 / 7), rel_tol=1e-6)
    assert r.get("data")[:8] == [2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]
    assert r.get("picked") == 15  # TRUNC(0.5 * 11) + 10
    assert r.get("utc") == 3600
    assert r.get("clock.LDT") == 1000 + 120 * 60 and r.get("clock.SETTLE") == 2500


@pytest.mark.parametrize(
    ("name", "codes"),
    [
        # the ramp's input clamped in place, rmp.RMP read from outside
        ("ramp.st", ["E030", "E013"]),
        # SIZE clamped in place, PT set and read on the instance, a call without it, TRUNC into INT
        ("array_stats.st", ["E030", "E013", "E042", "E013", "E021"]),
        # an input named LTIME, an output named LDT (MULTIME is known in every profile)
        ("time_zone.st", ["E011", "E010", "E011", "E010"]),
    ],
)
def test_under_iec_each_rule_the_port_needs_is_an_error(name, codes):
    diags, _ = check_files(_files(name), profile="iec")
    assert [d.code for d in diags if d.is_error] == codes, [d.format() for d in diags]
    diags, _ = check_files(_files(name), profile="matiec")
    assert not any(d.is_error for d in diags), [d.format() for d in diags]
