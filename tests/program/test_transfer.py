"""program/transfer.py: a compiled Program as bytes and back, as the
online change's compile process sends it: read back, it runs as the one
compiled here, with this process's type objects."""

from __future__ import annotations

import gc

from softplc.runtime.engine.online_change import ChangeReport
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


def test_the_read_back_calls_its_pace_every_64_source_positions_and_asks_room_to_end():
    # what lets the PLC's process read a program back step by step, in the
    # scan's idle (engine/lock_share.pause), not in one call of 35 ms; the
    # unpickler's memo, freed at the end in one go, waits for a window that
    # has room for it (about 4 ms for the default plant's 1.5 MB)
    program = compile_files([], texts={"main.st": SOURCE})
    data = transfer.dumps(program)
    before = [o for o in gc.get_objects() if type(o) is Pos]  # kept alive: their ids stay theirs
    known = {id(o) for o in before}
    calls: list = []
    again = transfer.loads(data, lambda *room: calls.append(room))
    made = sum(1 for o in gc.get_objects() if type(o) is Pos and id(o) not in known)
    assert made >= 2 * transfer.PACE_EVERY, made  # enough positions to pace a few times
    steps, last = calls[:-1], calls[-1]
    assert set(steps) == {()} and len(steps) >= made // transfer.PACE_EVERY
    assert last == (len(data) * transfer.FREE_NS_PER_BYTE,)
    assert again.python_source == program.python_source
    transfer.loads(data)  # without a pace: nothing calls the last one again
    assert len(calls) == len(steps) + 1


def test_a_read_back_without_positions_is_paced_too():
    # the tail of a real read-back (tables, no source positions) was 8-10 ms
    # with no step; every 8th plain softplc instance is a step as well
    inner = [ChangeReport(str(n)) for n in range(64 * 64)]
    outer = ChangeReport("outer", errors=inner)
    calls: list = []
    again = transfer.loads(transfer.dumps(outer), lambda *room: calls.append(room))
    assert [r.reason for r in again.errors] == [str(n) for n in range(64 * 64)]
    made_by_new = (len(inner) + 1) // transfer.ROUTE_EVERY
    assert calls[:-1] == [()] * (made_by_new // transfer.PACE_EVERY)
