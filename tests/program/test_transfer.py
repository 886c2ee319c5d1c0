"""program/transfer.py: a compiled Program as bytes and back, as the
online change's compile process sends it: read back, it runs as the one
compiled here, with this process's type objects."""

from __future__ import annotations

import gc

from softplc.runtime.program import compile_files, transfer
from softplc.runtime.st import types as T
from softplc.runtime.st.ast import Pos

SOURCE = """
TYPE Mode : (IDLE, RUN, STOP); END_TYPE
TYPE Pair : STRUCT a : USINT; b : REAL; END_STRUCT END_TYPE
PROGRAM Main
VAR
    u : USINT := 250;
    s : SINT := 120;
    r : REAL;
    t : TIME := T#1s;
    txt : STRING[5];
    m : Mode := RUN;
    p : Pair;
    ton1 : TON;
    k : DINT;
END_VAR
u := u + 3;
s := s + 10;
r := r + 0.1;
t := t + T#250ms;
txt := CONCAT(txt, 'ab');
p.a := p.a + 100;
k := REAL_TO_DINT(r * 10.0);
ton1(IN := TRUE, PT := T#35ms);
END_PROGRAM
"""

NAMES = ["u", "s", "r", "t", "txt", "m", "p.a", "ton1.Q", "k"]


def test_a_program_read_back_runs_as_the_one_compiled_here():
    program = compile_files([], texts={"main.st": SOURCE})
    again = transfer.loads(transfer.dumps(program))
    assert again is not program and again.python_source == program.python_source
    here, there = program.runner("Main", cycle_time_ms=10), again.runner("Main", cycle_time_ms=10)
    for _ in range(6):
        here.run()
        there.run()
        assert [there.get(n) for n in NAMES] == [here.get(n) for n in NAMES]
    assert there.get("u") == (250 + 18) % 256 and there.get("txt") == "ababa"


def test_its_elementary_types_are_this_process_s_own_objects():
    program = compile_files([], texts={"main.st": SOURCE})
    again = transfer.loads(transfer.dumps(program))
    declared = {v.name: v.type for v in again.pou("Main").vars.values()}
    assert declared["u"] is T.USINT and declared["r"] is T.REAL and declared["t"] is T.TIME


def test_the_read_back_calls_its_pace_every_64_source_positions():
    # what lets the PLC's process read a program back step by step, in the
    # scan's idle (engine/lock_share.pause), not in one call of 35 ms
    program = compile_files([], texts={"main.st": SOURCE})
    data = transfer.dumps(program)
    before = [o for o in gc.get_objects() if type(o) is Pos]  # kept alive: their ids stay theirs
    known = {id(o) for o in before}
    paces: list = []
    again = transfer.loads(data, lambda: paces.append(len(paces)))
    made = sum(1 for o in gc.get_objects() if type(o) is Pos and id(o) not in known)
    assert made >= 2 * transfer.PACE_EVERY, made  # enough positions to pace a few times
    assert len(paces) == made // transfer.PACE_EVERY
    assert again.python_source == program.python_source
    transfer.loads(data)  # without a pace: the last one is not called again
    assert len(paces) == made // transfer.PACE_EVERY
