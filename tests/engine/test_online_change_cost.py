"""What an online change asks of the scan thread (issue 31: overruns at
every few changes): the compile, the loading and the collector's work in
the requester's thread; in the scan thread only the swap, its copy made
by plans worked out once per type. Counted, never timed (the times are
benchmarks/bench_online_change.py's)."""

from __future__ import annotations

import gc
import threading
import time
from pathlib import Path

from softplc.runtime.engine.carry import Carry, members
from softplc.runtime.engine.clock import RealClock
from softplc.runtime.engine.online_change import ChangeRequest, OnlineChange
from softplc.runtime.launch import settle_heap
from softplc.runtime.program import compile_files, transfer
from softplc.runtime.st import types as T
from softplc.testing import PLC

from .conftest import Scanning, compile_st, task, wait_until

BLOCKS = """
FUNCTION_BLOCK Acc
VAR_INPUT x : INT; END_VAR
VAR sum : DINT; peak : INT; END_VAR
sum := sum + x;
IF x > peak THEN peak := x; END_IF
END_FUNCTION_BLOCK
PROGRAM Main
VAR accs : ARRAY[1..1000] OF Acc; timers : ARRAY[1..1000] OF TON; i : INT; n : DINT; {extra} END_VAR
n := n + 1;
FOR i := 1 TO 1000 DO
    accs[i](x := i);
    timers[i](IN := TRUE, PT := T#1h);
END_FOR
END_PROGRAM
"""


def plant(tmp_path: Path, source: str) -> PLC:
    st = tmp_path / "plant.st"
    st.write_text(source, encoding="utf-8")
    return PLC.from_st([st], cycle="10ms")


def test_the_compile_runs_in_the_requesters_thread_with_the_collector_paused(tmp_path):
    with plant(tmp_path, BLOCKS.format(extra="")) as plc:
        plc.step(3)
        seen: list = []

        def compile_again():
            seen.append((threading.current_thread(), gc.isenabled()))
            return compile_files([tmp_path / "plant.st"])

        (tmp_path / "plant.st").write_text(BLOCKS.format(extra="added : INT := 7;"), encoding="utf-8")
        requester = []

        def request() -> None:
            requester.append(threading.current_thread())
            requester.append(OnlineChange(plc.engine, plc.config, compile=compile_again).submit("test"))

        thread = threading.Thread(target=request)
        thread.start()
        thread.join()
        request_done = requester[1]
        # compiled and loaded in the requester's thread, the collector off meanwhile, then on again
        assert seen == [(requester[0], False)] and gc.isenabled()
        assert not request_done.done.is_set() and len(plc.engine.between_scans) == 1  # the swap waits for a scan
        assert plc["Main.n"] == 3
        plc.step()
        report = request_done.wait(0)
        assert report.applied and report.cycle == 3
        assert plc["Main.n"] == 4 and plc["Main.added"] == 7


def test_an_array_of_a_thousand_blocks_is_carried_whole_by_one_plan(tmp_path):
    with plant(tmp_path, BLOCKS.format(extra="")) as plc:
        plc.step(5)
        (tmp_path / "plant.st").write_text(BLOCKS.format(extra="added : INT := 7;"), encoding="utf-8")
        request = OnlineChange(plc.engine, plc.config).submit("test")
        plc.step()
        report = request.wait(0)
        assert report.applied, report.errors
        # every block went on from where it was: 6 scans, the 6th on the new program
        assert plc["Main.accs[1].sum"] == 6 and plc["Main.accs[1000].sum"] == 6000
        assert plc["Main.accs[1000].peak"] == 1000
        assert plc["Main.timers[500].ET"].total_seconds() == 0.05
        # the arrays are reported as one path each, not element by element
        assert "Main.accs" in report.kept and "Main.timers" in report.kept
        assert not any(p.startswith("Main.accs[") for p in report.kept)


def test_a_plan_is_made_once_per_pair_of_types(tmp_path):
    with plant(tmp_path, BLOCKS.format(extra="")) as plc:
        _name, info, _obj = plc.engine.instances["MAIN"]
        declared = {name: ty for name, _attr, ty in members(None, info).values()}
        accs, timers = T.resolve(declared["accs"]), T.resolve(declared["timers"])
        carry = Carry(frozenset())
        plan = carry.plan(accs, accs)
        assert plan is not None and carry.plan(accs, accs) is plan  # 1,000 blocks: one plan, made once
        assert carry.plan(timers, timers) not in (None, plan)


def test_softplc_run_freezes_the_start_up_heap_out_of_the_collectors_walks():
    try:
        before = gc.get_freeze_count()
        settle_heap()
        assert gc.get_freeze_count() > before  # a full collection later walks only what came since
    finally:
        gc.unfreeze()


SLOW = """
PROGRAM Main
VAR n : DINT; i : DINT; s : DINT; {extra} END_VAR
n := n + 1;
FOR i := 1 TO 200000 DO s := s + 1; END_FOR
END_PROGRAM
"""


def _read_back(source: str, extra: str = ""):
    """A program as the compile process gives it (release() takes such a one apart)."""
    return transfer.loads(transfer.dumps(compile_st(source.replace("{extra}", extra))))


def test_the_replaced_program_is_taken_apart_once_the_scan_has_gone_to_sleep(engines, monkeypatch):
    """The scan a change is applied before runs its tasks; the requester
    takes the replaced program apart (transfer.release, dismantle: some 7 ms
    for the default plant) after that scan, while the scan thread sleeps.
    It did so beside those tasks, as soon as the swap was done, and made
    them late by as much (a live soak: 20 ms, two overruns). Here a scan is
    a long loop, many switch intervals long."""
    engine = engines(_read_back(SLOW), [task("Main", 200, "Main", watchdog_ms=None)], clock=RealClock(spin_ns=0))
    ends: list = []  # (generation, when) at the end of each scan
    engine.after_tick.append(lambda e: ends.append((e.generation, time.perf_counter())))
    torn: list = []
    release = transfer.release

    def recorded(program, *pace) -> bool:
        torn.append(time.perf_counter())
        return release(program, *pace)

    monkeypatch.setattr(transfer, "release", recorded)
    scanning = Scanning(engine, pause_s=0).start()
    try:
        wait_until(lambda: engine.cycle >= 2, "two scans")
        new = _read_back(SLOW, "m : INT := 3;")
        request = ChangeRequest("test", new, new.module(engine.ctx))
        engine.between_scans.append(request)
        report = request.wait(20)
        assert report.applied, report.errors
        swapped_scan_end = next(when for generation, when in ends if generation == 1)
        assert len(torn) == 1 and torn[0] > swapped_scan_end
        assert engine.get("Main.m") == 3
    finally:
        scanning.stop()
